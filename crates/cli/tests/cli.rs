//! The `flexdem` command end to end: every example checks, describes and runs a few steps;
//! bad scenes exit with code 2 and their file:line message; unstable runs with code 1; a run
//! resumed from a checkpoint ends exactly as an uninterrupted one; Ctrl-C writes a
//! checkpoint and exits with 130.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace's folder.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `flexdem` with `args`.
fn flexdem<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexdem")).args(args).output().expect("flexdem starts")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Every `.toml` file in `dir`, sorted.
fn tomls(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

fn examples() -> Vec<PathBuf> {
    let files = tomls(&root().join("examples"));
    assert!(files.len() >= 5, "the examples are missing: {files:?}");
    files
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap();
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}\n{text}", path.display()))
}

/// The value at a `/`-separated path of `json`, which must exist.
fn at<'a>(json: &'a Value, pointer: &str) -> &'a Value {
    json.pointer(pointer).unwrap_or_else(|| panic!("no {pointer} in the summary {json:#}"))
}

#[test]
fn check_accepts_every_example() {
    for scene in examples() {
        let out = flexdem(&["check".as_ref(), scene.as_os_str()]);
        assert!(out.status.success(), "{}: {}", scene.display(), stderr(&out));
        let text = stdout(&out);
        assert!(text.starts_with("ok: "), "{text}");
        assert!(text.contains("dt = "), "{text}");
    }
}

#[test]
fn every_example_runs_a_few_steps_and_writes_its_output_and_summary() {
    let tmp = tempfile::tempdir().unwrap();
    for scene in examples() {
        let name = scene.file_stem().unwrap().to_string_lossy().into_owned();
        let dir = tmp.path().join(&name);
        let summary = tmp.path().join(format!("{name}.json"));
        let out = flexdem(&[
            "run".as_ref(),
            scene.as_os_str(),
            "--steps".as_ref(),
            "5".as_ref(),
            "--output".as_ref(),
            dir.as_os_str(),
            "--summary".as_ref(),
            summary.as_os_str(),
        ]);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        let report = stdout(&out);
        assert!(report.contains("run completed: 5 steps"), "{name}: {report}");
        assert!(report.contains("energy balance"), "{name}: {report}");

        let text = std::fs::read_to_string(&scene).unwrap();
        let configured = |key: &str| text.lines().any(|l| l.trim_start().starts_with(key));
        let pvd = dir.join("flexdem.pvd");
        assert_eq!(pvd.is_file(), configured("vtk_every"), "{name}: {}", pvd.display());
        if configured("vtk_every") {
            assert!(dir.join("particles_000005.vtp").is_file(), "{name}");
            assert!(report.contains(&format!("paraview {}", pvd.display())), "{report}");
        }
        assert_eq!(dir.join("series.csv").is_file(), configured("series_every"), "{name}");
        assert_eq!(dir.join("series.png").is_file(), configured("plot = true"), "{name}");

        let json = read_json(&summary);
        assert_eq!(at(&json, "/status"), "completed");
        assert!(at(&json, "/warnings").is_array(), "{name}");
        assert_eq!(at(&json, "/steps"), 5);
        assert_eq!(at(&json, "/steps_this_run"), 5);
        for key in ["/time", "/dt", "/critical_dt", "/wall_time", "/steps_per_second"] {
            assert!(at(&json, key).as_f64().is_some_and(|x| x > 0.0), "{name} {key}");
        }
        for stage in
            ["collision", "contacts", "links", "loads", "integration", "bookkeeping", "other"]
        {
            assert!(at(&json, &format!("/stages/{stage}")).is_f64(), "{name} {stage}");
        }
        for count in ["particles", "spheres", "nodes", "connections", "pfacets", "walls"] {
            assert!(at(&json, &format!("/counts/{count}")).is_u64(), "{name} {count}");
        }
        for term in [
            "kinetic_translation",
            "elastic_links",
            "friction",
            "contact_damping",
            "stored",
            "balance",
        ] {
            assert!(at(&json, &format!("/energy/{term}")).is_f64(), "{name} {term}");
        }
        // a few steps are too few to judge the balance (works lag a step): only its presence
        assert!(at(&json, "/energy/relative_balance_error").as_f64().is_some_and(f64::is_finite));
        let tracked = at(&json, "/tracked").as_object().unwrap();
        assert_eq!(!tracked.is_empty(), configured("[[output.series]]"), "{name}");
        assert!(tracked.values().all(|s| s.as_object().is_some_and(|c| !c.is_empty())));
        assert_eq!(at(&json, "/output/directory").as_str(), dir.to_str(), "{name}");
    }
}

#[test]
fn info_prints_counts_masses_and_time_step() {
    let scene = root().join("examples/tube_impact_solid.toml");
    let out = flexdem(&["info".as_ref(), scene.as_os_str()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    for expected in [
        "particles: 337 (1 sphere, 336 nodes); connections: 976; PFacets: 640; walls: 0",
        "tube: 336 nodes, 976 connections, 640 PFacets, mass",
        "spheres: 1, mass 1.12115",
        "sphere: E = 1.000e8 Pa",
        "tube: E = 1.000e6 Pa",
        "critical dt: ",
        "dt used: ",
        "run length: 1 s of simulated time = about ",
    ] {
        assert!(text.contains(expected), "missing `{expected}` in\n{text}");
    }
}

/// A scene without spheres printed `mass -0.000000e0 kg` (the sum of nothing in f64 is -0).
#[test]
fn info_prints_zero_masses_without_a_sign() {
    let scene = root().join("examples/cantilever.toml");
    let out = flexdem(&["info".as_ref(), scene.as_os_str()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("(0 spheres, 11 nodes)"), "{text}");
    assert!(text.contains("spheres: 0, mass 0.000000e0 kg"), "{text}");
    assert!(!text.contains("-0.0"), "{text}");
}

/// With dt = "auto" the step count of a duration is known once the simulation is built:
/// 10^300 s used to be accepted (and to run for ever).
#[test]
fn an_endless_duration_with_an_automatic_step_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("examples/cantilever.toml")).unwrap();
    let scene = dir.path().join("endless.toml");
    std::fs::write(&scene, text.replace("duration = 20 ", "duration = 1e300 ")).unwrap();
    for command in ["check", "run", "info"] {
        let out = flexdem(&[command.as_ref(), scene.as_os_str()]);
        let message = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{command}: {message}");
        assert!(message.contains("`simulation.duration`"), "{message}");
        assert!(message.contains("expected at most 1e12"), "{message}");
    }
}

#[test]
fn bad_scenes_exit_with_code_2_and_their_message() {
    let bad = tomls(&root().join("tests/data/scenes/bad"));
    assert!(bad.len() >= 20, "{bad:?}");
    for scene in bad {
        let expected = std::fs::read_to_string(scene.with_extension("expected")).unwrap();
        for command in ["check", "run", "info"] {
            let out = flexdem(&[command.as_ref(), scene.as_os_str()]);
            let message = stderr(&out);
            assert_eq!(out.status.code(), Some(2), "{command} {}: {message}", scene.display());
            assert!(!message.contains("panicked"), "{message}");
            assert!(message.starts_with("error: "), "{message}");
            for line in expected.lines().filter(|l| !l.is_empty()) {
                assert!(message.contains(line), "{}: `{line}` not in {message}", scene.display());
            }
        }
    }
}

#[test]
fn missing_files_and_bad_arguments_exit_with_code_2() {
    let tmp = tempfile::tempdir().unwrap();
    let missing = tmp.path().join("nothing.toml");
    let out = flexdem(&["run".as_ref(), missing.as_os_str()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("nothing.toml"), "{}", stderr(&out));

    let garbage = tmp.path().join("checkpoint.flexdem");
    std::fs::write(&garbage, b"not a checkpoint at all, just some text").unwrap();
    let out = flexdem(&["resume".as_ref(), garbage.as_os_str()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("checkpoint.flexdem"), "{}", stderr(&out));

    let scene = root().join("examples/cantilever.toml");
    let out = flexdem(&["run".as_ref(), scene.as_os_str(), "--steps".as_ref(), "0".as_ref()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

/// A cantilever with a fixed time step 50 times its critical step.
const UNSTABLE: &str = r#"
[simulation]
dt = 0.01
steps = 2000
[materials.bar]
young = 1e8
poisson = 0.3
density = 1000
friction_angle_deg = 30
[[structures]]
name = "beam"
kind = "chain"
material = "bar"
node_radius = 0.01
start = [0, 0, 0]
end = [1, 0, 0]
segments = 10
[[boundary]]
select = { structure = "beam", side = "start" }
block = "xyzXYZ"
[[loads]]
select = { structure = "beam", side = "end" }
force = [0, 0, -0.01]
[output]
series_every = 1
[[output.series]]
name = "tip"
quantity = "position"
of = { structure = "beam", side = "end" }
"#;

#[test]
fn an_unstable_run_exits_with_code_1_and_keeps_its_output() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("unstable.toml");
    std::fs::write(&scene, UNSTABLE).unwrap();
    let summary = tmp.path().join("summary.json");
    let out =
        flexdem(&["run".as_ref(), scene.as_os_str(), "--summary".as_ref(), summary.as_os_str()]);
    let message = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{message}");
    assert!(message.contains("warning: the fixed time step"), "{message}");
    assert!(message.contains("error: particle 10"), "{message}");
    assert!(message.contains("use a smaller dt"), "{message}");
    let csv = std::fs::read_to_string(tmp.path().join("output/series.csv")).unwrap();
    assert!(csv.lines().count() > 2, "{csv}");
    let json = read_json(&summary);
    assert_eq!(at(&json, "/status"), "failed");
    assert!(at(&json, "/error").as_str().unwrap().contains("unstable"));
    let warnings = at(&json, "/warnings").as_array().unwrap();
    assert!(warnings[0].as_str().unwrap().starts_with("the fixed time step"), "{warnings:?}");
}

#[test]
fn no_output_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("tube.toml");
    std::fs::copy(root().join("examples/tube_impact_solid.toml"), &scene).unwrap();
    let summary = tmp.path().join("s.json");
    let out = flexdem(&[
        "run".as_ref(),
        scene.as_os_str(),
        "--steps".as_ref(),
        "2".as_ref(),
        "--no-output".as_ref(),
        "--quiet".as_ref(),
        "--summary".as_ref(),
        summary.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).is_empty(), "--quiet prints no report: {}", stdout(&out));
    assert!(!tmp.path().join("output").exists());
    let json = read_json(&summary);
    assert!(at(&json, "/output").is_null());
    // the tracked quantities are reported all the same
    assert!(at(&json, "/tracked/impactor_position/impactor_position_z_m").is_f64());
}

/// The parts of a summary that describe the simulation's state (not the wall clock).
fn state(json: &Value) -> Vec<(String, Value)> {
    ["/steps", "/time", "/dt", "/critical_dt", "/counts", "/energy", "/tracked"]
        .iter()
        .map(|p| (p.to_string(), at(json, p).clone()))
        .collect()
}

#[test]
fn a_run_resumed_from_a_periodic_checkpoint_ends_as_an_uninterrupted_one() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = root().join("examples/tube_impact_solid.toml");
    let (whole, parts) = (tmp.path().join("whole"), tmp.path().join("parts"));
    let run = |dir: &Path, steps: &str, extra: &[&str]| {
        let summary = dir.with_extension("json");
        let mut args: Vec<std::ffi::OsString> = vec![
            "run".into(),
            scene.clone().into(),
            "--steps".into(),
            steps.into(),
            "--output".into(),
            dir.into(),
            "--summary".into(),
            summary.clone().into(),
        ];
        args.extend(extra.iter().map(Into::into));
        let out = flexdem(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        read_json(&summary)
    };
    let uninterrupted = run(&whole, "40", &[]);
    // 20 steps with a checkpoint at step 20, then 20 more from it
    let first = run(&parts, "20", &["--checkpoint-every", "20"]);
    let checkpoint = parts.join("checkpoint.flexdem");
    assert_eq!(at(&first, "/checkpoint").as_str(), checkpoint.to_str());

    let out = flexdem(&["resume".as_ref(), checkpoint.as_os_str()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("nothing to do"), "{}", stdout(&out));

    let summary = tmp.path().join("resumed.json");
    let out = flexdem(&[
        "resume".as_ref(),
        checkpoint.as_os_str(),
        "--steps".as_ref(),
        "20".as_ref(),
        "--summary".as_ref(),
        summary.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let resumed = read_json(&summary);
    assert_eq!(at(&resumed, "/steps_this_run"), 20);
    assert_eq!(state(&resumed), state(&uninterrupted));
    assert!(at(&resumed, "/counts/contacts").as_u64().unwrap() > 0, "the impact has begun");
    for file in ["series.csv", "flexdem.pvd", "particles_000040.vtp", "contacts_000040.vtp"] {
        let a = std::fs::read(whole.join(file)).unwrap();
        let b = std::fs::read(parts.join(file)).unwrap();
        assert!(a == b, "{file} differs between the uninterrupted and the resumed run");
    }
}

#[cfg(unix)]
#[test]
fn ctrl_c_writes_a_checkpoint_and_exits_with_130() {
    use std::time::{Duration, Instant};
    let tmp = tempfile::tempdir().unwrap();
    let scene = root().join("examples/cantilever.toml"); // 200 000 steps: far more than the wait
    let dir = tmp.path().join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_flexdem"))
        .args(["run".as_ref(), scene.as_os_str(), "--output".as_ref(), dir.as_os_str()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // wait for the run to be under way: a few rows of the series
    let csv = dir.join("series.csv");
    let start = Instant::now();
    while std::fs::read_to_string(&csv).map_or(0, |t| t.lines().count()) < 3 {
        assert!(start.elapsed() < Duration::from_secs(60), "the run does not start");
        std::thread::sleep(Duration::from_millis(10));
    }
    let kill = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    let message = stderr(&out);
    assert_eq!(out.status.code(), Some(130), "{message}");
    let checkpoint = dir.join("checkpoint.flexdem");
    assert!(message.contains(&format!("flexdem resume {}", checkpoint.display())), "{message}");
    // the output is finished, and the run goes on from the checkpoint
    assert!(dir.join("series.png").is_file());
    let out =
        flexdem(&["resume".as_ref(), checkpoint.as_os_str(), "--steps".as_ref(), "5".as_ref()]);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// A chain whose fixed dt is 1.3 times its critical step (6.3246e-4 s): its energy grows from
/// the first steps. The energy watch stops it with exit 1, naming the step and the link that
/// holds the energy; the report does not say "completed".
const CREATES_ENERGY: &str = r#"
[simulation]
dt = 8.2219e-4
steps = 2000
[materials.steel]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30
[[structures]]
name = "cable"
kind = "chain"
material = "steel"
node_radius = 0.01
start = [0, 0, 0]
end = [0.5, 0, 0]
segments = 5
[[boundary]]
select = { structure = "cable", side = "start" }
block = "xyzXYZ"
[[boundary]]
select = { structure = "cable", side = "end" }
velocity = [0, 0, 0.1]
"#;

#[test]
fn a_run_that_creates_energy_exits_with_code_1_and_says_where() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("creates_energy.toml");
    std::fs::write(&scene, CREATES_ENERGY).unwrap();
    let out = flexdem(&["run".as_ref(), scene.as_os_str(), "--no-output".as_ref()]);
    let message = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{message}");
    assert!(message.contains("created energy"), "{message}");
    assert!(message.contains("at step"), "{message}");
    assert!(message.contains("structure \"cable\""), "{message}");
    assert!(message.contains("energy_tolerance"), "{message}");
    assert!(!stdout(&out).contains("run completed"), "{}", stdout(&out));
    // switched off, the same scene runs to its end (and blows up later or not: not our point)
    let off = CREATES_ENERGY.replace("steps = 2000", "steps = 5\nenergy_tolerance = \"off\"");
    std::fs::write(&scene, off).unwrap();
    let out = flexdem(&["run".as_ref(), scene.as_os_str(), "--no-output".as_ref()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

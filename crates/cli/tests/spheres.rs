//! `flexdem spheres`: the free spheres of a scene or a checkpoint written as the CSV file
//! that `[[spheres]] kind = "file"` reads back.

use std::path::PathBuf;
use std::process::{Command, Output};

fn flexdem<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexdem")).args(args).output().expect("flexdem starts")
}

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexdem_spheres_{name}_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const HEAD: &str = r#"
[simulation]
steps = 40
gravity = [0, 0, -9.81]

[materials.m]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "m"

[output]
directory = "out"
"#;

/// Data rows of a sphere CSV.
fn rows(path: &PathBuf) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,radius"));
    lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect()
}

#[test]
fn spheres_of_a_scene_and_of_a_checkpoint_are_written_and_read_back() {
    let dir = folder("roundtrip");
    let packed = dir.join("packed.toml");
    std::fs::write(
        &packed,
        format!(
            "{HEAD}\n[[spheres]]\nkind = \"random\"\nmaterial = \"m\"\nbox = {{ min = [0, 0, 0], max = [0.2, 0.2, 0.2] }}\nradius_range = [0.01, 0.02]\ncount = 30\nseed = 5\n"
        ),
    )
    .unwrap();
    let csv = dir.join("pack.csv");
    let out = flexdem(&["spheres".as_ref(), packed.as_os_str(), "-o".as_ref(), csv.as_os_str()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let first = rows(&csv);
    assert_eq!(first.len(), 30);
    // the input as output, however the path is written: refused, the input kept
    let scene_text = std::fs::read_to_string(&packed).unwrap();
    let same = dir.join(".").join("packed.toml");
    let out = flexdem(&["spheres".as_ref(), packed.as_os_str(), "-o".as_ref(), same.as_os_str()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("input file"));
    assert_eq!(std::fs::read_to_string(&packed).unwrap(), scene_text);

    // a scene that reads them back, run with a checkpoint
    let reused = dir.join("reused.toml");
    std::fs::write(
        &reused,
        format!("{HEAD}\n[[spheres]]\nkind = \"file\"\nmaterial = \"m\"\nfile = \"pack.csv\"\n"),
    )
    .unwrap();
    let again = dir.join("again.csv");
    let out = flexdem(&["spheres".as_ref(), reused.as_os_str(), "-o".as_ref(), again.as_os_str()]);
    assert!(out.status.success());
    assert_eq!(rows(&again), first, "the file kind reads back exactly what was written");
    let checkpoint = dir.join("c.flexdem");
    let out = flexdem(&[
        "run".as_ref(),
        reused.as_os_str(),
        "--quiet".as_ref(),
        "--no-output".as_ref(),
        "--checkpoint-every".as_ref(),
        "40".as_ref(),
        "--checkpoint".as_ref(),
        checkpoint.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let settled = dir.join("settled.csv");
    let out =
        flexdem(&["spheres".as_ref(), checkpoint.as_os_str(), "-o".as_ref(), settled.as_os_str()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let after = rows(&settled);
    assert_eq!(after.len(), 30);
    // gravity moved them down, the radii are the same
    for (a, b) in after.iter().zip(&first) {
        assert!(a[2] < b[2]);
        assert_eq!(a[3], b[3]);
    }
    // not a checkpoint: a clear error, exit code 2
    let out = flexdem(&["spheres".as_ref(), csv.as_os_str(), "-o".as_ref(), settled.as_os_str()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("pack.csv"));
    std::fs::remove_dir_all(&dir).ok();
}

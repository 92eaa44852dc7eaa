//! `flexdem bench`: a quick run prints its table, writes the CSV and finds the state
//! independent of the thread count; bad options exit with code 2.

use std::process::{Command, Output};

fn flexdem<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexdem")).args(args).output().expect("flexdem starts")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn quick_bench_prints_the_table_and_writes_the_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("results/quick.csv");
    let out = flexdem(&[
        "bench".as_ref(),
        "--quick".as_ref(),
        "--scene".as_ref(),
        "membrane,packing".as_ref(),
        "--csv".as_ref(),
        csv.as_os_str(),
    ]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", text(&out.stderr));
    assert!(stdout.starts_with("scene "), "{stdout}");
    assert!(stdout.contains("ns/elem-step"), "{stdout}");
    assert_eq!(stdout.matches("identical").count(), 2, "{stdout}");
    assert!(!stdout.contains("tube_impact"), "{stdout}");
    let table = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines.len(), 5, "{table}");
    let columns = lines[0].split(',').count();
    assert!(lines.iter().all(|l| l.split(',').count() == columns), "{table}");
    assert!(lines[1].starts_with("membrane,200,") && lines[4].starts_with("packing,200,"));
    let column = |name: &str| lines[0].split(',').position(|c| c == name).unwrap();
    let field = |line: &str, name: &str| line.split(',').nth(column(name)).unwrap().to_string();
    assert!(field(lines[2], "vs_first_threads") == "identical", "{table}");
    assert!(field(lines[4], "vs_first_threads") == "identical", "{table}");
    // the heap a scene holds, counted by the binary's allocator, and B/elem from it
    for line in &lines[1..] {
        let heap: u64 = field(line, "heap_delta_bytes").parse().expect("a heap count");
        let per_element: f64 = field(line, "bytes_per_element").parse().unwrap();
        let elements: f64 = field(line, "elements").parse().unwrap();
        assert!(heap > 0 && (per_element - heap as f64 / elements).abs() < 0.1, "{line}");
    }
}

#[test]
fn csv_to_standard_output_and_sizes() {
    let out = flexdem(&[
        "bench",
        "--scene",
        "membrane",
        "--sizes",
        "50",
        "--threads",
        "2",
        "--steps",
        "2",
        "--warmup",
        "1",
        "--csv",
        "-",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("scene,size,elements,"), "{stdout}");
    assert!(stdout.lines().nth(1).unwrap().starts_with("membrane,50,"), "{stdout}");
    assert!(text(&out.stderr).contains("ms/step"), "the table goes to standard error");
}

#[test]
fn bad_options_exit_with_code_2() {
    for (args, message) in [
        (&["bench", "--scene", "tube"][..], "unknown scene \"tube\""),
        (&["bench", "--scene", "packing", "--sizes", "5"][..], "packing: size 5"),
    ] {
        let out = flexdem(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(text(&out.stderr).contains(message), "{args:?}: {}", text(&out.stderr));
    }
    let out = flexdem(&["bench", "--threads", "0"]);
    assert_eq!(out.status.code(), Some(2));
}

/// `flexdem bench` used to write over the committed `bench/results/latest.csv` by default: it
/// now writes under `target/` of the current folder.
#[test]
fn bench_writes_its_csv_under_target_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_flexdem"))
        .args(["bench", "--quick", "--scene", "packing", "--threads", "1"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", text(&out.stderr));
    let csv = dir.path().join("target/flexdem/bench/latest.csv");
    assert!(std::fs::read_to_string(csv).unwrap().contains("packing,200,"), "{stdout}");
    assert!(stdout.contains("CSV: target/flexdem/bench/latest.csv"), "{stdout}");
    let both = flexdem(&["bench", "--update-committed", "--csv", "x.csv"]);
    assert_eq!(both.status.code(), Some(2), "--csv and --update-committed conflict");
}

/// `--step-times` writes every timed step of every run, after the main CSV; a path it cannot
/// write is an error naming it, and the main CSV is written all the same.
#[test]
fn bench_writes_each_steps_time_when_asked() {
    let dir = tempfile::tempdir().unwrap();
    let run = |steps_csv: &str| {
        Command::new(env!("CARGO_BIN_EXE_flexdem"))
            .args(["bench", "--quick", "--scene", "packing", "--threads", "1,2"])
            .args(["--csv", "main.csv", "--step-times", steps_csv])
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    let out = run("steps/times.csv");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let times = std::fs::read_to_string(dir.path().join("steps/times.csv")).unwrap();
    let lines: Vec<&str> = times.lines().collect();
    // --quick: 5 timed steps, at 1 and at 2 threads
    assert_eq!(lines.len(), 1 + 2 * 5, "{times}");
    assert_eq!(lines[0], "scene,size,threads,step,ms");
    assert!(lines[1].starts_with("packing,200,1,0,") && lines[10].starts_with("packing,200,2,4,"));
    std::fs::remove_file(dir.path().join("main.csv")).unwrap();
    // a folder where the file should be
    std::fs::create_dir(dir.path().join("taken")).unwrap();
    let out = run("taken");
    assert!(!out.status.success());
    assert!(text(&out.stderr).contains("cannot write taken"), "{}", text(&out.stderr));
    assert!(dir.path().join("main.csv").is_file());
}

/// `--step-times` on standard output or on the CSV's own file (however it is written) is
/// refused at once, naming it.
#[test]
fn bench_refuses_step_times_over_its_csv() {
    for (args, message) in [
        (&["--csv", "x.csv", "--step-times", "x.csv"][..], "--step-times: x.csv is the CSV's file"),
        (
            &["--csv", "x.csv", "--step-times", "./x.csv"][..],
            "--step-times: ./x.csv is the CSV's file",
        ),
        (&["--step-times", "-"][..], "--step-times: a file, not `-`"),
    ] {
        let out = flexdem(&[&["bench", "--quick", "--scene", "packing"][..], args].concat());
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(text(&out.stderr).contains(message), "{args:?}: {}", text(&out.stderr));
    }
}

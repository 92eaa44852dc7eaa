//! The run driver as a library: stepping in pieces with callbacks, the interrupt flag and its
//! checkpoint, and a run resumed from it ending bit-identically to an uninterrupted one.

use flexdem_integrate::Simulation;
use flexdem_run::{
    NoObserver, Run, RunError, RunLength, RunObserver, RunOptions, Status, Stop, CHECKPOINT_FILE,
};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// An example scene of the workspace.
fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

/// Counts what a run reports.
#[derive(Default)]
struct Counter {
    started: usize,
    steps: u64,
    checkpoints: usize,
    finished: usize,
    /// Sets this flag once this many steps are done.
    interrupt_after: Option<(u64, Arc<AtomicBool>)>,
}

impl RunObserver for Counter {
    fn started(&mut self, _sim: &Simulation, _target: RunLength) {
        self.started += 1;
    }
    fn stepped(&mut self, _sim: &Simulation) {
        self.steps += 1;
        if let Some((n, flag)) = &self.interrupt_after {
            if self.steps >= *n {
                flag.store(true, Ordering::SeqCst);
            }
        }
    }
    fn checkpoint_written(&mut self, _path: &Path) {
        self.checkpoints += 1;
    }
    fn finished(&mut self, _sim: &Simulation) {
        self.finished += 1;
    }
}

/// The output of a resumed run of 40 steps is the uninterrupted run's, byte for byte: the
/// series, the `.pvd` and the last frame.
fn assert_same_output(whole_dir: &Path, parts_dir: &Path) {
    for file in ["series.csv", "flexdem.pvd", "particles_000040.vtp", "contacts_000040.vtp"] {
        let a = std::fs::read(whole_dir.join(file)).unwrap();
        let b = std::fs::read(parts_dir.join(file)).unwrap();
        assert!(a == b, "{file} differs between the uninterrupted and the resumed run");
    }
}

/// The state a run ends in, bit for bit: positions, velocities and energy terms.
fn final_state(run: &Run) -> Vec<u64> {
    let sim = run.sim();
    let p = &sim.model().particles;
    let e = sim.energy();
    p.pos
        .iter()
        .chain(&p.vel)
        .chain(&p.ang_vel)
        .flat_map(|v| [v.x, v.y, v.z])
        .chain([sim.time(), e.kinetic_translation, e.elastic_links, e.elastic_contacts, e.friction])
        .map(f64::to_bits)
        .collect()
}

#[test]
fn advance_steps_in_pieces_with_callbacks_then_finishes_with_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let options = RunOptions {
        steps: Some(30),
        output_directory: Some(dir.path().into()),
        checkpoint_every: Some(10),
        ..RunOptions::default()
    };
    let mut run = Run::from_scene(&example("net_drop.toml"), options).unwrap();
    assert_eq!(run.target(), RunLength::Steps(30));
    let mut counter = Counter::default();
    assert_eq!(run.advance(Some(12), &mut counter).unwrap(), Stop::StepLimit);
    assert_eq!(run.sim().steps(), 12);
    assert_eq!(run.advance(None, &mut counter).unwrap(), Stop::Reached);
    assert!(run.is_done());
    assert_eq!(run.advance(None, &mut counter).unwrap(), Stop::Reached, "nothing more to do");
    let summary = run.finish(&mut counter).unwrap();
    assert_eq!(
        (counter.started, counter.steps, counter.checkpoints, counter.finished),
        (1, 30, 3, 1)
    );
    assert_eq!(summary.status, Status::Completed);
    assert_eq!((summary.steps, summary.steps_this_run), (30, 30));
    assert_eq!(summary.checkpoint.as_deref(), Some(dir.path().join(CHECKPOINT_FILE).as_path()));
    let output = summary.output.expect("the scene writes output");
    assert_eq!(output.directory, dir.path());
    assert!(output.csv.is_some_and(|csv| csv.is_file()));
}

#[test]
fn an_interrupted_run_resumes_to_the_same_end_as_an_uninterrupted_one() {
    let dir = tempfile::tempdir().unwrap();
    let (whole_dir, parts_dir) = (dir.path().join("whole"), dir.path().join("parts"));
    let options = |out: &Path| RunOptions {
        steps: Some(40),
        output_directory: Some(out.into()),
        ..RunOptions::default()
    };
    let scene = example("tube_impact_solid.toml");
    let mut whole = Run::from_scene(&scene, options(&whole_dir)).unwrap();
    let summary = whole.execute(&mut NoObserver).unwrap();
    assert_eq!(summary.status, Status::Completed);

    let flag = Arc::new(AtomicBool::new(false));
    let mut parts = Run::from_scene(
        &scene,
        RunOptions { interrupt: Some(Arc::clone(&flag)), ..options(&parts_dir) },
    )
    .unwrap();
    let mut counter = Counter { interrupt_after: Some((15, flag)), ..Counter::default() };
    let summary = parts.execute(&mut counter).unwrap();
    assert_eq!(summary.status, Status::Interrupted);
    assert_eq!(summary.steps, 15);
    let checkpoint = parts_dir.join(CHECKPOINT_FILE);
    assert_eq!(summary.checkpoint.as_deref(), Some(checkpoint.as_path()));

    let mut resumed = Run::resume(&checkpoint, RunOptions::default()).unwrap();
    assert_eq!(resumed.target(), RunLength::Steps(40));
    assert_eq!(resumed.scene_file(), std::path::absolute(&scene).unwrap());
    let summary = resumed.execute(&mut NoObserver).unwrap();
    assert_eq!((summary.status, summary.steps_this_run), (Status::Completed, 25));
    assert_eq!(final_state(&resumed), final_state(&whole));
    assert_same_output(&whole_dir, &parts_dir);
}

#[test]
fn a_run_resumed_at_its_end_continues_its_output_once_moved_on() {
    let dir = tempfile::tempdir().unwrap();
    let (whole_dir, parts_dir) = (dir.path().join("whole"), dir.path().join("parts"));
    let scene = example("tube_impact_solid.toml");
    let options = |out: &Path, steps| RunOptions {
        steps: Some(steps),
        output_directory: Some(out.into()),
        ..RunOptions::default()
    };
    let mut whole = Run::from_scene(&scene, options(&whole_dir, 40)).unwrap();
    assert_eq!(whole.execute(&mut NoObserver).unwrap().status, Status::Completed);

    // a run of 25 steps with a checkpoint at its last step; its end adds a row and a frame
    // at step 25, off the schedule (rows every 10 steps, frames every 100)
    let first = RunOptions { checkpoint_every: Some(25), ..options(&parts_dir, 25) };
    let mut part = Run::from_scene(&scene, first).unwrap();
    assert_eq!(part.execute(&mut NoObserver).unwrap().status, Status::Completed);
    let csv = parts_dir.join("series.csv");
    let written = std::fs::read(&csv).unwrap();

    // resumed at its end: the output is left as written, and a checkpoint of it keeps the
    // progress of the first
    let mut resumed = Run::resume(&parts_dir.join(CHECKPOINT_FILE), RunOptions::default()).unwrap();
    assert!(resumed.is_done());
    assert_eq!(resumed.advance(None, &mut NoObserver).unwrap(), Stop::Reached);
    assert_eq!(std::fs::read(&csv).unwrap(), written);
    let again = dir.path().join("again.flexdem");
    resumed.set_checkpoint_path(&again);
    resumed.save_checkpoint().unwrap();

    // moved on to step 40: the same files as the uninterrupted run's
    let mut resumed = Run::resume(&again, RunOptions::default()).unwrap();
    resumed.set_target(RunLength::Steps(40));
    let summary = resumed.execute(&mut NoObserver).unwrap();
    assert_eq!((summary.status, summary.steps_this_run), (Status::Completed, 15));
    assert_eq!(final_state(&resumed), final_state(&whole));
    assert_same_output(&whole_dir, &parts_dir);
}

#[test]
fn setup_errors_say_whether_the_input_is_at_fault() {
    let err = Run::from_scene(Path::new("no/such/scene.toml"), RunOptions::default())
        .err()
        .expect("a missing scene is an error");
    assert!(err.is_bad_input(), "{err}");
    let dir = tempfile::tempdir().unwrap();
    let not_a_checkpoint = dir.path().join("x.flexdem");
    std::fs::write(&not_a_checkpoint, b"hello").unwrap();
    let err = Run::resume(&not_a_checkpoint, RunOptions::default()).err().unwrap();
    assert!(matches!(err, RunError::ReadCheckpoint(_)) && err.is_bad_input(), "{err}");
}

#[test]
fn a_script_moves_the_end_of_the_run_and_where_its_checkpoints_go() {
    let dir = tempfile::tempdir().unwrap();
    let options = RunOptions { steps: Some(10), no_output: true, ..RunOptions::default() };
    let mut run = Run::from_scene(&example("cantilever.toml"), options).unwrap();
    assert_eq!(run.advance(None, &mut NoObserver).unwrap(), Stop::Reached);
    assert_eq!(run.sim().steps(), 10);
    // a later stage: 5 steps more
    run.set_target(RunLength::Steps(15));
    assert!(!run.is_done());
    assert_eq!(run.advance(None, &mut NoObserver).unwrap(), Stop::Reached);
    assert_eq!(run.sim().steps(), 15);
    // a checkpoint where the script likes, with the run length set then
    let path = dir.path().join("stage").join("two.flexdem");
    run.set_checkpoint_path(&path);
    assert_eq!(run.checkpoint_path(), path);
    run.save_checkpoint().unwrap();
    let resumed = Run::resume(&path, RunOptions::default()).unwrap();
    assert_eq!(resumed.target(), RunLength::Steps(15));
    assert!(resumed.is_done());
    assert_eq!(final_state(&resumed), final_state(&run));
}

/// A scene with a servo platen on a lattice of spheres, built as `flexdem run` builds it: the
/// platen is under its servo and, at rest, its stress and the Love–Weber stress of the
/// lattice in the series are the target's.
#[test]
fn a_scene_servo_wall_presses_its_sample_to_the_target_stress() {
    let text = r#"
[simulation]
steps = 6000
damping = 0.3

[materials.glass]
young = 1e8
poisson = 0.3
density = 2600
friction_angle_deg = 30

[[spheres]]
kind = "lattice"
material = "glass"
radius = 0.01
spacing = 0.0201
box = { min = [0, 0, 0], max = [0.0603, 0.0603, 0.0603] }

[[walls]]
point = [0, 0, -1e-6]
normal = [0, 0, 1]
material = "glass"

[[walls]]
point = [0, 0, 0.0604]
normal = [0, 0, -1]
material = "glass"
servo = { stress = 1e5, area = 0.00363609, max_speed = 0.05 }

[output]
series_every = 100

[[output.series]]
name = "platen"
quantity = "wall_stress"
wall = 1

[[output.series]]
name = "sample"
quantity = "stress"
box = { min = [0, 0, 0], max = [0.0603, 0.0603, 0.0603] }
"#;
    let scene = flexdem_scene::parse_scene(text, Path::new("servo.toml")).unwrap();
    let (mut sim, rest) = flexdem_run::build_simulation(scene).unwrap();
    assert!(matches!(sim.wall_controls()[1], flexdem_integrate::WallControl::Stress(_)));
    sim.run(6000).unwrap();
    let row = flexdem_output::row_values(&rest.output.series, &sim);
    let (platen, szz) = (row[2], row[5]);
    eprintln!(
        "platen {platen:.6e} Pa, Love–Weber σzz {szz:.6e} Pa, p {:.6e} Pa, q {:.6e} Pa, energy \
         error {:.2e}",
        row[9],
        row[10],
        sim.relative_balance_error()
    );
    assert!((platen / 1e5 - 1.0).abs() < 1e-2, "platen stress {platen}");
    // the box is 60.3 mm high, the columns about 59.9 mm between their wall contacts
    // (three diameters less the overlaps): σzz reads 0.7 % below the platen
    assert!((szz / platen - 1.0).abs() < 1e-2, "σzz {szz} vs {platen}");
    assert!(sim.relative_balance_error().abs() < 1e-3, "{}", sim.relative_balance_error());
}

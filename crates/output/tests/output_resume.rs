//! Continuing the output of a run from a checkpoint: `Output::progress` and `Output::resume`
//! give the same `.pvd` and `series.csv` as a run that was never interrupted, and refuse
//! output folders that do not match the checkpoint.

use flexdem_contact::Material;
use flexdem_elements::builders::{chain, straight_line, StructureOptions};
use flexdem_elements::Model;
use flexdem_geom::Vec3;
use flexdem_integrate::{Settings, Simulation};
use flexdem_output::OutputProgress;
use flexdem_output::{Output, OutputError, OutputSettings, Quantity, SeriesSpec, CSV_FILE};
use std::path::Path;

/// A cable hanging from its first node (blocked) swinging down onto a sphere on a wall.
fn simulation() -> Simulation {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    model.add_sphere(Vec3::new(-0.5, 0.0, 0.9), 0.05, m).unwrap();
    let points = straight_line(Vec3::new(-1.0, 0.0, 1.0), Vec3::new(-0.4, 0.0, 1.0), 4).unwrap();
    chain(&mut model, &points, &StructureOptions::new("cable", 0.01, m)).unwrap();
    model.particles.blocked[1] = flexdem_elements::Dofs::ALL;
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    Simulation::new(model, settings).unwrap()
}

fn settings(dir: &Path) -> OutputSettings {
    OutputSettings {
        directory: dir.to_path_buf(),
        vtk_every: Some(3),
        series_every: Some(2),
        series: vec![
            SeriesSpec { name: "tip".into(), quantity: Quantity::Position(5) },
            SeriesSpec { name: "e".into(), quantity: Quantity::Energy },
            SeriesSpec { name: "cable".into(), quantity: Quantity::ForceOnParticles(vec![2, 3]) },
        ],
        plot: true,
    }
}

/// Steps `sim` to step `end`, recording each step.
fn advance(sim: &mut Simulation, out: &mut Output, end: u64) {
    while sim.steps() < end {
        sim.step().unwrap();
        out.record(sim).unwrap();
    }
}

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap()
}

#[test]
fn a_resumed_output_matches_an_uninterrupted_one() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));

    let mut sim = simulation();
    let mut out = Output::new(&settings(&a), &sim).unwrap();
    out.record(&sim).unwrap();
    advance(&mut sim, &mut out, 10);
    let whole = out.finish(&sim).unwrap();

    let mut sim = simulation();
    let mut out = Output::new(&settings(&b), &sim).unwrap();
    out.record(&sim).unwrap();
    advance(&mut sim, &mut out, 7);
    let progress = out.progress();
    assert_eq!(progress.vtk_frames.iter().map(|f| f.0).collect::<Vec<_>>(), vec![0, 3, 6]);
    assert_eq!(progress.vtk_frames[2].1, out.rows()[3][0]);
    assert_eq!(progress.series_rows, 4); // steps 0, 2, 4, 6
    let saved = sim.state().clone();
    // the first run goes on past the checkpoint and stops off the schedule
    advance(&mut sim, &mut out, 9);
    out.finish(&sim).unwrap();

    let mut sim = Simulation::from_state(saved).unwrap();
    let mut out = Output::resume(&settings(&b), &sim, &progress).unwrap();
    assert_eq!(out.rows().len(), 4);
    advance(&mut sim, &mut out, 10);
    let resumed = out.finish(&sim).unwrap();

    assert_eq!(read(&a, CSV_FILE), read(&b, CSV_FILE));
    assert_eq!(read(&a, "flexdem.pvd"), read(&b, "flexdem.pvd"));
    for file in ["particles_000009.vtp", "connections_000010.vtp", "contacts_000010.vtp"] {
        assert_eq!(read(&a, file), read(&b, file), "{file}");
    }
    assert_eq!(resumed.vtk_frames, whole.vtk_frames);
    assert_eq!(resumed.series_rows, whole.series_rows);
    assert!(b.join("series.png").is_file());
}

/// An output folder written up to step 4 (frames at 0 and 3, rows at 0, 2 and 4).
fn written(dir: &Path) -> (Simulation, OutputProgress) {
    let mut sim = simulation();
    let mut out = Output::new(&settings(dir), &sim).unwrap();
    out.record(&sim).unwrap();
    advance(&mut sim, &mut out, 4);
    let progress = out.progress();
    out.finish(&sim).unwrap();
    (sim, progress)
}

#[test]
fn a_missing_frame_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (sim, progress) = written(tmp.path());
    std::fs::remove_file(tmp.path().join("pfacets_000003.vtp")).unwrap();
    let err = Output::resume(&settings(tmp.path()), &sim, &progress).unwrap_err();
    assert!(
        matches!(&err, OutputError::Resume { path, .. } if path.ends_with("pfacets_000003.vtp")),
        "{err:?}"
    );
}

#[test]
fn a_series_that_does_not_match_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (sim, progress) = written(tmp.path());
    let csv = tmp.path().join(CSV_FILE);
    let text = std::fs::read_to_string(&csv).unwrap();

    // fewer rows than the checkpoint wrote
    let short: Vec<&str> = text.lines().take(2).collect();
    std::fs::write(&csv, short.join("\n") + "\n").unwrap();
    let err = Output::resume(&settings(tmp.path()), &sim, &progress).unwrap_err();
    assert!(err.to_string().contains("rows"), "{err}");

    // another header (the series changed)
    std::fs::write(&csv, text.replacen("tip_x_m", "top_x_m", 1)).unwrap();
    let err = Output::resume(&settings(tmp.path()), &sim, &progress).unwrap_err();
    assert!(matches!(err, OutputError::Resume { .. }) && err.to_string().contains("header"));

    // a damaged row
    std::fs::write(&csv, text.replacen(",0,", ",zero,", 1)).unwrap();
    let err = Output::resume(&settings(tmp.path()), &sim, &progress).unwrap_err();
    assert!(err.to_string().contains("not numbers"), "{err}");

    // missing
    std::fs::remove_file(&csv).unwrap();
    let err = Output::resume(&settings(tmp.path()), &sim, &progress).unwrap_err();
    assert!(matches!(err, OutputError::Resume { .. }), "{err:?}");
}

//! A scene with a `[[pressures]]` table and a `volume` series, run end to end: the pressure
//! reaches the simulation, its work is in the energy terms, and the final enclosed volume is
//! among the summary's tracked values and in the CSV.

use flexdem_run::{NoObserver, Run, RunOptions};
use flexdem_scene::parse_scene;

const SCENE: &str = r#"
[simulation]
steps = 300
dt = "auto"
safety = 0.3

[materials.rubber]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[structures]]
name = "balloon"
kind = "sphere_shell"
material = "rubber"
node_radius = 0.002
center = [0, 0, 0]
radius = 0.1
subdivisions = 2

[[pressures]]
structure = "balloon"
pressure = 2e3
ramp = { start = 0, duration = 2e-3 }

[output]
series_every = 50

[[output.series]]
name = "balloon"
quantity = "volume"
of = { structure = "balloon" }

[[output.series]]
name = "e"
quantity = "energy"
"#;

#[test]
fn a_pressurised_balloon_runs_and_reports_its_volume() {
    let dir = tempfile::tempdir().unwrap();
    let scene = parse_scene(SCENE, &dir.path().join("balloon.toml")).unwrap();
    let v0 = flexdem_elements::structure_volume(&scene.model, 0, &[]).unwrap();
    let options = RunOptions { output_directory: Some(dir.path().into()), ..RunOptions::default() };
    let mut run = Run::new(scene, options).unwrap();
    assert_eq!(run.sim().pressures().len(), 1);
    run.advance(None, &mut NoObserver).unwrap();
    let summary = run.finish(&mut NoObserver).unwrap();
    let volume = summary.tracked["balloon"]["balloon_volume_m3"];
    assert!(volume > v0 * 1.001, "the balloon inflates: {volume} vs {v0}");
    assert!(summary.energy.terms.load_work > 0.0);
    assert!(summary.energy.relative_balance_error.abs() < 1e-3);
    let csv = std::fs::read_to_string(dir.path().join("series.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.split(',').any(|c| c == "balloon_volume_m3"), "{header}");
}

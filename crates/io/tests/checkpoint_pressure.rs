//! A checkpoint keeps the pressures on PFacets (format version 4) and the enclosed-volume
//! series: a shell inflated by a pressure, restored from its checkpoint, continues
//! bit-identically.

use flexdem_contact::Material;
use flexdem_elements::builders::{sphere_shell, ShellBase, StructureOptions};
use flexdem_elements::Model;
use flexdem_geom::Vec3;
use flexdem_integrate::{Pressure, Ramp, Settings, Simulation};
use flexdem_io::checkpoint::{restore_checkpoint, write_checkpoint, Checkpoint, OutputProgress};
use flexdem_io::output::{OutputSettings, Quantity, SeriesSpec};
use flexdem_io::scene::RunLength;
use std::path::PathBuf;

#[test]
fn a_pressurised_shell_continues_bit_identically_from_its_checkpoint() {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let opts = StructureOptions::new("shell", 0.002, m);
    sphere_shell(&mut model, Vec3::zeros(), 0.1, ShellBase::Icosahedron, 1, &opts).unwrap();
    let mut sim = Simulation::new(model, Settings::default()).unwrap();
    let pfacets = (0..sim.model().pfacets.len() as u32).collect();
    let ramp = Ramp::Linear { start: 0.0, duration: 1e-3 };
    sim.add_pressure(Pressure { pfacets, pressure: 1e3, flip: false, ramp }).unwrap();
    sim.run(30).unwrap();
    let series = vec![SeriesSpec {
        name: "shell".into(),
        quantity: Quantity::EnclosedVolume { structure: 0, walls: vec![] },
    }];
    let checkpoint = Checkpoint {
        state: sim.state().clone(),
        run: RunLength::Steps(100),
        threads: None,
        output: OutputSettings {
            directory: PathBuf::from("out"),
            vtk_every: None,
            series_every: Some(10),
            series: series.clone(),
            plot: false,
        },
        scene: PathBuf::from("shell.toml"),
        output_progress: OutputProgress { vtk_frames: vec![], series_rows: 3 },
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("shell.ckp");
    write_checkpoint(&path, &checkpoint).unwrap();
    let (mut resumed, info) = restore_checkpoint(&path).unwrap();
    assert_eq!(info.output.series, series);
    assert_eq!(resumed.pressures(), sim.pressures());
    sim.run(50).unwrap();
    resumed.run(50).unwrap();
    assert_eq!(resumed.model().particles.pos, sim.model().particles.pos);
    assert_eq!(resumed.energy(), sim.energy());
    assert!(sim.energy().load_work > 0.0);
}

//! The enclosed-volume series: one column in m³, the volume of a structure's PFacets closed
//! by walls, and errors naming the series when it cannot be measured.

use flexdem_contact::Material;
use flexdem_elements::builders::{tube, StructureOptions};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation};
use flexdem_output::{series_columns, series_values, validate_series, Quantity, SeriesSpec};
use std::f64::consts::TAU;

const RADIUS: Real = 0.1;
const LENGTH: Real = 0.8;
const AROUND: usize = 16;

/// A tube along z from the origin, walls 0 and 1 on its end rings, walls 2 and 3 a little
/// beyond them.
fn scene() -> Simulation {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let opts = StructureOptions::new("membrane", 0.002, m);
    tube(&mut model, Vec3::zeros(), Vec3::z(), RADIUS, LENGTH, AROUND, 10, &opts).unwrap();
    for (z, n) in [(0.0, 1.0), (LENGTH, -1.0), (-0.1, 1.0), (LENGTH + 0.2, -1.0)] {
        model.add_wall(Vec3::new(0.0, 0.0, z), Vec3::new(0.0, 0.0, n), m).unwrap();
    }
    Simulation::new(model, Settings::default()).unwrap()
}

fn volume_series(walls: Vec<u32>) -> SeriesSpec {
    SeriesSpec { name: "sample".into(), quantity: Quantity::EnclosedVolume { structure: 0, walls } }
}

#[test]
fn the_volume_column_is_the_tube_closed_by_its_walls() {
    let sim = scene();
    let area = 0.5 * AROUND as Real * RADIUS * RADIUS * (TAU / AROUND as Real).sin();
    for (walls, height) in [(vec![0, 1], LENGTH), (vec![3, 2], LENGTH + 0.3)] {
        let spec = volume_series(walls);
        assert_eq!(series_columns(&spec), vec!["sample_volume_m3".to_string()]);
        validate_series(std::slice::from_ref(&spec), &sim).unwrap();
        let mut row = Vec::new();
        series_values(&spec, &sim, &mut row);
        assert_eq!(row.len(), 1);
        assert!((row[0] - area * height).abs() <= 1e-13 * area * height, "{row:?}");
    }
}

#[test]
fn a_volume_that_cannot_be_measured_is_an_error_naming_the_series() {
    let sim = scene();
    let problem = |spec: SeriesSpec| validate_series(&[spec], &sim).unwrap_err().to_string();
    let open = problem(volume_series(vec![]));
    assert!(open.contains("sample") && open.contains("not closed"), "{open}");
    let missing = problem(volume_series(vec![0, 9]));
    assert!(missing.contains("wall 9 does not exist"), "{missing}");
    let structure = problem(SeriesSpec {
        name: "sample".into(),
        quantity: Quantity::EnclosedVolume { structure: 4, walls: vec![] },
    });
    assert!(structure.contains("structure 4 does not exist"), "{structure}");
}

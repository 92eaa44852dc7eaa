//! The CSV series and the PNG plot: header with units, one row per recorded step with the
//! simulation's values, a plot that decodes as a PNG of one panel per series; and the errors.

use flexdem_contact::Material;
use flexdem_elements::builders::{chain, straight_line, StructureOptions};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Region, Settings, Simulation};
use flexdem_output::{format_number, Output, OutputError, OutputSettings, Quantity, SeriesSpec};
use std::path::Path;

/// A cable hanging from its first node (blocked) and a free sphere on a wall.
fn scene() -> Simulation {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let heavy = model.add_material(Material::new(1e7, 0.3, 1e5, 0.5).unwrap()).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, 0.0498), 0.05, heavy).unwrap();
    let points = straight_line(Vec3::new(-1.0, 0.0, 1.0), Vec3::new(-0.4, 0.0, 1.0), 3).unwrap();
    chain(&mut model, &points, &StructureOptions::new("cable", 0.01, m)).unwrap();
    model.particles.blocked[1] = flexdem_elements::Dofs::ALL;
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    Simulation::new(model, settings).unwrap()
}

fn series() -> Vec<SeriesSpec> {
    let spec = |name: &str, quantity| SeriesSpec { name: name.into(), quantity };
    vec![
        spec("tip", Quantity::Position(4)),
        spec("tip_v", Quantity::Velocity(4)),
        spec("spin", Quantity::AngularVelocity(0)),
        spec("e", Quantity::Energy),
        spec("cable", Quantity::ForceOnParticles(vec![2, 3, 4])),
        spec("contacts", Quantity::ContactCount),
        spec("broken", Quantity::BrokenLinks),
    ]
}

fn settings(dir: &Path) -> OutputSettings {
    OutputSettings {
        directory: dir.to_path_buf(),
        vtk_every: None,
        series_every: Some(2),
        series: series(),
        plot: true,
    }
}

/// The values the CSV should hold for `sim` now, computed here from the simulation.
fn expected_row(sim: &Simulation) -> Vec<Real> {
    let p = &sim.model().particles;
    let e = sim.energy();
    let f: Vec3 = [2, 3, 4].iter().map(|&i| sim.forces()[i]).sum();
    let mut row = vec![sim.time(), sim.steps() as Real];
    for v in [p.pos[4], p.vel[4], p.ang_vel[0]] {
        row.extend_from_slice(&[v.x, v.y, v.z]);
    }
    row.extend_from_slice(&[
        e.kinetic_translation,
        e.kinetic_rotation,
        e.elastic_links,
        e.elastic_contacts,
        e.gravity_work,
        e.load_work,
        e.boundary_work,
        e.contact_births,
        e.damping,
        e.links_dissipated,
        e.friction,
        e.contact_damping,
        e.contact_releases,
        e.balance(),
    ]);
    row.extend_from_slice(&[f.x, f.y, f.z, sim.contacts().len() as Real, 0.0]);
    row
}

/// Width and height from a PNG's signature and IHDR chunk (with its CRC checked).
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |k: usize| u32::from_be_bytes(bytes[k..k + 4].try_into().unwrap());
    let crc = crc32(&bytes[12..29]);
    assert_eq!(crc, be(29), "IHDR CRC");
    assert!(bytes.windows(4).any(|w| w == b"IDAT") && bytes.ends_with(&[0xAE, 0x42, 0x60, 0x82]));
    (be(16), be(20))
}

/// CRC-32 (IEEE) as PNG uses it.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

#[test]
fn csv_rows_hold_the_simulation_values_and_the_plot_is_a_png() {
    let mut sim = scene();
    let dir = tempfile::tempdir().unwrap();
    let settings = settings(dir.path());
    let mut output = Output::new(&settings, &sim).unwrap();
    let mut expected = Vec::new();
    output.record(&sim).unwrap();
    expected.push(expected_row(&sim));
    for _ in 0..7 {
        sim.step().unwrap();
        output.record(&sim).unwrap();
        if sim.steps() % 2 == 0 {
            expected.push(expected_row(&sim));
        }
    }
    let report = output.finish(&sim).unwrap();
    expected.push(expected_row(&sim));
    assert_eq!(report.series_rows, 5);
    assert_eq!(report.files, vec![dir.path().join("series.csv"), dir.path().join("series.png")]);
    assert!(sim.contacts().len() == 1, "the sphere rests on the wall");

    let text = std::fs::read_to_string(dir.path().join("series.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let energy = [
        "kinetic_translation",
        "kinetic_rotation",
        "elastic_links",
        "elastic_contacts",
        "gravity_work",
        "load_work",
        "boundary_work",
        "contact_births",
        "damping",
        "links_dissipated",
        "friction",
        "contact_damping",
        "contact_releases",
        "balance",
    ];
    let mut want = vec!["time_s".to_string(), "step".into()];
    want.extend(["x", "y", "z"].map(|c| format!("tip_{c}_m")));
    want.extend(["x", "y", "z"].map(|c| format!("tip_v_v{c}_m_per_s")));
    want.extend(["x", "y", "z"].map(|c| format!("spin_w{c}_rad_per_s")));
    want.extend(energy.map(|t| format!("e_{t}_J")));
    want.extend(["x", "y", "z"].map(|c| format!("cable_f{c}_N")));
    want.extend(["contacts_count".to_string(), "broken_count".into()]);
    assert_eq!(header, want);
    let rows: Vec<Vec<Real>> =
        lines.map(|l| l.split(',').map(|x| x.parse::<Real>().unwrap()).collect()).collect();
    assert_eq!(rows.len(), expected.len());
    for (k, (row, want)) in rows.iter().zip(&expected).enumerate() {
        assert_eq!(row, want, "row {k}");
    }
    let steps: Vec<Real> = rows.iter().map(|r| r[1]).collect();
    assert_eq!(steps, vec![0.0, 2.0, 4.0, 6.0, 7.0]);
    assert!(rows.windows(2).all(|w| w[1][0] > w[0][0]), "times increase");
    assert!(rows.last().unwrap()[5] != 0.0, "the tip falls: vz is not zero");

    let png = std::fs::read(dir.path().join("series.png")).unwrap();
    // FLEXDEM_KEEP_PLOT=/some/file.png keeps a copy of the plot to look at
    if let Ok(keep) = std::env::var("FLEXDEM_KEEP_PLOT") {
        std::fs::copy(dir.path().join("series.png"), keep).unwrap();
    }
    let (w, h) = png_size(&png);
    assert_eq!((w, h), (1100, 320 * 7));
    // no temporary file is left behind
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn numbers_in_the_csv_round_trip_exactly() {
    for x in [
        0.0,
        -0.0,
        1.0,
        123.0,
        0.1,
        1.0 / 3.0,
        -2.5e-7,
        6.02e23,
        1e-300,
        Real::MAX,
        Real::MIN_POSITIVE,
    ] {
        assert_eq!(format_number(x).parse::<Real>().unwrap(), x, "{x}");
    }
    assert_eq!(format_number(42.0), "42");
    assert!(format_number(Real::NAN).parse::<Real>().unwrap().is_nan());
}

#[test]
fn an_output_directory_that_is_a_file_is_an_error_naming_it() {
    let sim = scene();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("taken");
    std::fs::write(&file, "not a folder").unwrap();
    for path in [file.clone(), file.join("below")] {
        let err = Output::new(&settings(&path), &sim).unwrap_err();
        assert!(matches!(err, OutputError::Directory { .. }), "{err:?}");
        assert!(err.to_string().contains(&path.display().to_string()), "{err}");
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a folder");
}

/// The series of walls and samples on the sphere resting on its wall: the wall carries what
/// the sphere's contact puts on it, the sphere's Love–Weber stress over a box is its
/// contact's branch times force over the volume, its solid fraction its volume over the box.
#[test]
fn wall_and_sample_series_give_their_columns_and_values() {
    let mut sim = scene();
    sim.run(50).unwrap();
    let spec = |name: &str, quantity| SeriesSpec { name: name.into(), quantity };
    let block = Region::Box { min: Vec3::repeat(-0.1), max: Vec3::repeat(0.1) };
    let series = vec![
        spec("floor", Quantity::WallForce(0)),
        spec("floor_s", Quantity::WallStress { wall: 0, area: 0.01 }),
        spec("sample", Quantity::Stress { region: block, volume: Some(0.004) }),
        spec("phi", Quantity::SolidFraction(block)),
    ];
    flexdem_output::validate_series(&series, &sim).unwrap();
    let columns = flexdem_output::header_columns(&series);
    assert_eq!(
        columns[2..],
        [
            "floor_fx_N",
            "floor_fy_N",
            "floor_fz_N",
            "floor_s_normal_stress_Pa",
            "sample_sxx_Pa",
            "sample_syy_Pa",
            "sample_szz_Pa",
            "sample_sxy_Pa",
            "sample_sxz_Pa",
            "sample_syz_Pa",
            "sample_mean_stress_Pa",
            "sample_deviator_stress_Pa",
            "phi_solid_fraction",
        ]
    );
    let row = flexdem_output::row_values(&series, &sim);
    assert_eq!(row.len(), columns.len());
    let contact = sim.contacts().into_iter().find(|c| c.site2.nodes[0] == 0).unwrap();
    let force = contact.forces.force_on_2;
    assert!(force.z > 0.0, "the sphere is not pressed on its wall: {force:?}");
    assert_eq!(row[2..5], [-force.x, -force.y, -force.z]);
    assert_eq!(row[5], force.z / 0.01);
    // the sphere's only contact: σzz = −(x_c − x_p)_z·f_z / V, compression positive
    let branch = contact.point - sim.model().particles.pos[0];
    let szz = -branch.z * force.z / 0.004;
    assert!(szz > 0.0 && (row[8] / szz - 1.0).abs() < 1e-12, "{} vs {szz}", row[8]);
    assert!((row[12] - row[8] / 3.0).abs() < 1e-9 * szz, "mean stress {}", row[12]);
    let volume = 4.0 / 3.0 * std::f64::consts::PI * 0.05f64.powi(3);
    assert!((row[14] - volume / 0.008).abs() < 1e-15, "solid fraction {}", row[14]);
}

#[test]
fn bad_settings_and_series_are_errors() {
    let sim = scene();
    let dir = tempfile::tempdir().unwrap();
    let base = settings(dir.path());
    let spec = |name: &str, quantity| SeriesSpec { name: name.into(), quantity };
    let block = Region::Box { min: Vec3::repeat(-1.0), max: Vec3::repeat(1.0) };
    let flat = Region::Box { min: Vec3::repeat(-1.0), max: Vec3::new(1.0, 1.0, -1.0) };
    let cases = [
        OutputSettings { vtk_every: Some(0), ..base.clone() },
        OutputSettings { series_every: Some(0), ..base.clone() },
        OutputSettings { series_every: None, ..base.clone() },
        OutputSettings { series: vec![], ..base.clone() },
        OutputSettings { series: vec![spec("p", Quantity::Position(99))], ..base.clone() },
        OutputSettings {
            series: vec![spec("f", Quantity::ForceOnParticles(vec![]))],
            ..base.clone()
        },
        OutputSettings { series: vec![spec("a,b", Quantity::Energy)], ..base.clone() },
        OutputSettings { series: vec![spec("", Quantity::Energy)], ..base.clone() },
        OutputSettings {
            series: vec![spec("e", Quantity::Energy), spec("e", Quantity::ContactCount)],
            ..base.clone()
        },
        OutputSettings { series: vec![spec("w", Quantity::WallForce(1))], ..base.clone() },
        OutputSettings {
            series: vec![spec("w", Quantity::WallStress { wall: 0, area: 0.0 })],
            ..base.clone()
        },
        OutputSettings {
            series: vec![spec("s", Quantity::Stress { region: flat, volume: None })],
            ..base.clone()
        },
        OutputSettings {
            series: vec![spec("s", Quantity::Stress { region: block, volume: Some(-1.0) })],
            ..base.clone()
        },
        OutputSettings { series: vec![spec("phi", Quantity::SolidFraction(flat))], ..base.clone() },
    ];
    for settings in cases {
        let err = Output::new(&settings, &sim).unwrap_err();
        assert!(matches!(err, OutputError::Setting { .. } | OutputError::Series { .. }), "{err:?}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}

#[test]
fn a_failed_write_keeps_the_files_already_written() {
    let mut sim = scene();
    let dir = tempfile::tempdir().unwrap();
    let settings = OutputSettings { vtk_every: Some(1), plot: false, ..settings(dir.path()) };
    let mut output = Output::new(&settings, &sim).unwrap();
    output.record(&sim).unwrap();
    let pvd = dir.path().join("flexdem.pvd");
    let before = std::fs::read(&pvd).unwrap();
    // the temporary file of the next .pvd cannot be created: a folder is in its way
    std::fs::create_dir(dir.path().join(".flexdem.pvd.tmp")).unwrap();
    sim.step().unwrap();
    let err = output.record(&sim).unwrap_err();
    assert!(matches!(&err, OutputError::Write { path, .. } if path == &pvd), "{err:?}");
    assert!(err.to_string().contains("flexdem.pvd"), "{err}");
    assert_eq!(std::fs::read(&pvd).unwrap(), before, "the old .pvd is intact");
    // the same for a frame file
    std::fs::remove_dir(dir.path().join(".flexdem.pvd.tmp")).unwrap();
    let particles = dir.path().join("particles_000002.vtp");
    std::fs::create_dir(dir.path().join(".particles_000002.vtp.tmp")).unwrap();
    sim.step().unwrap();
    let err = output.record(&sim).unwrap_err();
    assert!(matches!(&err, OutputError::Write { path, .. } if path == &particles), "{err:?}");
    assert!(!particles.exists());
    // the run goes on once the way is clear, and the .pvd lists the frames written
    std::fs::remove_dir(dir.path().join(".particles_000002.vtp.tmp")).unwrap();
    sim.step().unwrap();
    output.record(&sim).unwrap();
    let report = output.finish(&sim).unwrap();
    assert!(report.files.contains(&pvd));
    let text = std::fs::read_to_string(&pvd).unwrap();
    assert!(text.contains("particles_000003.vtp") && text.contains("particles_000001.vtp"));
}

//! The VTK output read back with an independent reader (the `vtkio` crate): every frame's
//! particles, connections, PFacets and contacts match the simulation state they were written
//! from, and the `.pvd` lists every frame with increasing times.

use flexdem_contact::{LinkStatus, Material};
use flexdem_elements::builders::{chain, membrane_rectangle, straight_line, StructureOptions};
use flexdem_elements::{Model, ParticleKind, NO_STRUCTURE};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation};
use flexdem_output::{Output, OutputSettings};
use std::path::Path;
use vtkio::model::{Attribute, DataSet, IOBuffer, Piece, PolyDataPiece, VertexNumbers};

/// A chain hanging in gravity, a membrane with a sphere pressed into it, and a sphere pressed
/// into a wall: links, PFacets and contacts of every kind from the first step.
fn scene() -> Simulation {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    // heavy spheres: their contacts last many steps
    let heavy = model.add_material(Material::new(1e7, 0.3, 1e5, 0.5).unwrap()).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    let on_wall = model.add_sphere(Vec3::new(0.0, 0.0, 0.0498), 0.05, heavy).unwrap();
    model.particles.vel[on_wall as usize] = Vec3::new(0.1, 0.0, 0.0);
    let points = straight_line(Vec3::new(-1.0, 0.0, 1.0), Vec3::new(-0.4, 0.0, 1.0), 3).unwrap();
    chain(&mut model, &points, &StructureOptions::new("cable", 0.01, m)).unwrap();
    let opts = StructureOptions::new("sheet", 0.01, m);
    let (x, y) = (Vec3::x(), Vec3::y());
    membrane_rectangle(&mut model, Vec3::new(1.0, 0.0, 0.2), x, y, 0.4, 0.4, 2, 2, &opts).unwrap();
    let above =
        model.add_sphere(Vec3::new(1.13, 0.11, 0.2 + 0.01 + 0.05 - 0.0002), 0.05, heavy).unwrap();
    model.particles.vel[above as usize] = Vec3::new(0.0, 0.0, -0.2);
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    Simulation::new(model, settings).unwrap()
}

/// What a frame was written from.
struct Snapshot {
    time: Real,
    pos: Vec<Vec3>,
    vel: Vec<Vec3>,
    force: Vec<Vec3>,
    axial: Vec<Real>,
    contacts: Vec<(Vec3, Vec3, Real, Vec3)>,
}

/// The state a frame shows; contacts as (centre 1, centre 2, normal force, force on 2), with
/// the centres computed here from the sites' weights.
fn snapshot(sim: &Simulation) -> Snapshot {
    let pos = sim.model().particles.pos.clone();
    let centre = |site: &flexdem_elements::virtual_sphere::Site, point: Vec3| {
        if site.node_count() == 0 {
            point
        } else {
            (0..site.node_count()).map(|k| site.weights[k] * pos[site.nodes[k] as usize]).sum()
        }
    };
    let contacts = sim
        .contacts()
        .iter()
        .map(|c| {
            (
                centre(&c.site1, c.point),
                centre(&c.site2, c.point),
                c.forces.normal_force,
                c.forces.force_on_2,
            )
        })
        .collect();
    Snapshot {
        time: sim.time(),
        pos: pos.clone(),
        vel: sim.model().particles.vel.clone(),
        force: sim.forces().to_vec(),
        axial: (0..sim.links().len()).map(|k| sim.links().normal_force(k)).collect(),
        contacts,
    }
}

/// The single inline poly data piece of a `.vtp` file, read by vtkio.
fn read_piece(path: &Path) -> PolyDataPiece {
    let vtk = vtkio::Vtk::import(path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let DataSet::PolyData { pieces, .. } = vtk.data else {
        panic!("{}: not poly data", path.display())
    };
    assert_eq!(pieces.len(), 1);
    match pieces.into_iter().next() {
        Some(Piece::Inline(piece)) => *piece,
        _ => panic!("{}: not an inline piece", path.display()),
    }
}

/// A named point or cell array as f64 (integers converted).
fn array(attributes: &[Attribute], name: &str) -> Vec<f64> {
    for a in attributes {
        if let Attribute::DataArray(d) = a {
            if d.name == name {
                return match &d.data {
                    IOBuffer::F64(v) => v.clone(),
                    other => other.cast_into::<f64>().unwrap(),
                };
            }
        }
    }
    panic!("no array {name}")
}

/// Connectivity and offsets of a cell block.
fn cells(block: &Option<VertexNumbers>) -> (Vec<u64>, Vec<u64>) {
    block.clone().map(|b| b.into_xml()).unwrap_or_default()
}

/// Point coordinates of a piece.
fn points(piece: &PolyDataPiece) -> Vec<Vec3> {
    let flat: Vec<f64> = piece.points.cast_into::<f64>().unwrap();
    flat.chunks(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect()
}

/// Relative closeness for values written as Float64 (exact in fact).
fn close(a: Real, b: Real) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300)
}

fn close3(a: &Vec3, b: &Vec3) -> bool {
    (0..3).all(|k| close(a[k], b[k]))
}

/// `<DataSet .../>` entries of a `.pvd` as (timestep, part, file), parsed by hand.
fn pvd_entries(text: &str) -> Vec<(Real, u32, String)> {
    let attr = |element: &str, name: &str| -> String {
        let key = format!(" {name}=\"");
        let start =
            element.find(&key).unwrap_or_else(|| panic!("no {name} in {element}")) + key.len();
        element[start..].split('"').next().unwrap().to_string()
    };
    text.split("<DataSet")
        .skip(1)
        .map(|e| {
            let element = e.split("/>").next().unwrap();
            (
                attr(element, "timestep").parse().unwrap(),
                attr(element, "part").parse().unwrap(),
                attr(element, "file"),
            )
        })
        .collect()
}

#[test]
fn frames_read_back_match_the_simulation_and_the_pvd_lists_them() {
    let mut sim = scene();
    let dir = tempfile::tempdir().unwrap();
    let settings = OutputSettings {
        directory: dir.path().join("out"),
        vtk_every: Some(2),
        series_every: None,
        series: vec![],
        plot: false,
    };
    let mut output = Output::new(&settings, &sim).unwrap();
    let mut snapshots = Vec::new();
    output.record(&sim).unwrap();
    snapshots.push((0, snapshot(&sim)));
    for _ in 0..5 {
        sim.step().unwrap();
        output.record(&sim).unwrap();
        if sim.steps() % 2 == 0 {
            snapshots.push((sim.steps(), snapshot(&sim)));
        }
    }
    let report = output.finish(&sim).unwrap();
    snapshots.push((sim.steps(), snapshot(&sim)));
    assert_eq!(report.vtk_frames, 4);
    assert_eq!(report.files.len(), 4 * 4 + 1);
    assert!(report.files.iter().all(|f| f.exists()), "{:?}", report.files);
    let last = &snapshots.last().unwrap().1;
    assert!(last.contacts.len() >= 2, "the scene has contacts: {}", last.contacts.len());
    assert!(last.axial.iter().any(|&f| f != 0.0), "the links carry forces");

    let p = &sim.model().particles;
    for (step, snap) in &snapshots {
        let file = |part: &str| settings.directory.join(format!("{part}_{step:06}.vtp"));
        // particles: every particle as a vertex with its data
        let piece = read_piece(&file("particles"));
        let n = p.pos.len();
        let (conn, offsets) = cells(&piece.verts);
        assert_eq!(conn, (0..n as u64).collect::<Vec<_>>());
        assert_eq!(offsets.len(), n);
        let xyz = points(&piece);
        assert_eq!(xyz.len(), n);
        let radius = array(&piece.data.point, "radius");
        let velocity = array(&piece.data.point, "velocity");
        let force = array(&piece.data.point, "force");
        let kind = array(&piece.data.point, "kind");
        let structure = array(&piece.data.point, "structure");
        for i in 0..n {
            assert!(close3(&xyz[i], &snap.pos[i]), "step {step} particle {i}");
            assert!(close(radius[i], p.radius[i]));
            assert!(close3(
                &Vec3::new(velocity[3 * i], velocity[3 * i + 1], velocity[3 * i + 2]),
                &snap.vel[i]
            ));
            assert!(close3(
                &Vec3::new(force[3 * i], force[3 * i + 1], force[3 * i + 2]),
                &snap.force[i]
            ));
            assert_eq!(kind[i], if p.kind[i] == ParticleKind::Node { 1.0 } else { 0.0 });
            let s = p.structure[i];
            assert_eq!(structure[i], if s == NO_STRUCTURE { -1.0 } else { s as f64 });
        }
        // connections: one line per connection between its nodes' positions
        let piece = read_piece(&file("connections"));
        let xyz = points(&piece);
        let (conn, offsets) = cells(&piece.lines);
        let ids = array(&piece.data.point, "id");
        let axial = array(&piece.data.cell, "axial_force");
        let radius = array(&piece.data.cell, "radius");
        let broken = array(&piece.data.cell, "broken");
        assert_eq!(offsets.len(), sim.model().connections.len());
        for (c, connection) in sim.model().connections.iter().enumerate() {
            assert_eq!(offsets[c], 2 * (c as u64 + 1));
            for k in 0..2 {
                let point = conn[2 * c + k] as usize;
                assert_eq!(ids[point] as u32, connection.nodes[k]);
                assert!(close3(&xyz[point], &snap.pos[connection.nodes[k] as usize]));
            }
            assert!(close(axial[c], snap.axial[c]), "step {step} link {c}");
            assert!(close(radius[c], connection.radius));
            assert_eq!(
                broken[c],
                f64::from(u8::from(sim.links().state[c].status == LinkStatus::Broken))
            );
        }
        // PFacets: one triangle per PFacet over its nodes
        let piece = read_piece(&file("pfacets"));
        let xyz = points(&piece);
        let (conn, offsets) = cells(&piece.polys);
        let ids = array(&piece.data.point, "id");
        let structure = array(&piece.data.cell, "structure");
        assert_eq!(offsets.len(), sim.model().pfacets.len());
        for (f, pfacet) in sim.model().pfacets.iter().enumerate() {
            for k in 0..3 {
                let point = conn[3 * f + k] as usize;
                assert_eq!(ids[point] as u32, pfacet.nodes[k]);
                assert!(close3(&xyz[point], &snap.pos[pfacet.nodes[k] as usize]));
            }
            assert_eq!(structure[f], pfacet.structure as f64);
        }
        // contacts: a line per contact between the sites' centres with its forces
        let piece = read_piece(&file("contacts"));
        let xyz = points(&piece);
        let (conn, _) = cells(&piece.lines);
        let normal = array(&piece.data.cell, "normal_force");
        let force = array(&piece.data.cell, "force");
        assert_eq!(normal.len(), snap.contacts.len(), "step {step}");
        for (c, (c1, c2, fn_, f2)) in snap.contacts.iter().enumerate() {
            assert!(close3(&xyz[conn[2 * c] as usize], c1));
            assert!(close3(&xyz[conn[2 * c + 1] as usize], c2));
            assert!(close(normal[c], *fn_));
            assert!(close3(&Vec3::new(force[3 * c], force[3 * c + 1], force[3 * c + 2]), f2));
        }
    }

    // the .pvd: four parts per frame, times those of the frames, increasing
    let text = std::fs::read_to_string(settings.directory.join("flexdem.pvd")).unwrap();
    let entries = pvd_entries(&text);
    assert_eq!(entries.len(), 4 * snapshots.len());
    for (k, (step, snap)) in snapshots.iter().enumerate() {
        for (part, name) in ["particles", "connections", "pfacets", "contacts"].iter().enumerate() {
            let (time, p, file) = &entries[4 * k + part];
            assert_eq!(*time, snap.time);
            assert_eq!(*p, part as u32);
            assert_eq!(file, &format!("{name}_{step:06}.vtp"));
            assert!(settings.directory.join(file).exists());
        }
        if k > 0 {
            assert!(entries[4 * k].0 > entries[4 * k - 4].0, "times increase");
        }
    }
}

#[test]
fn a_model_without_structures_or_contacts_writes_empty_parts() {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, 1.0), 0.05, m).unwrap();
    let mut sim = Simulation::new(model, Settings::default()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let settings = OutputSettings {
        directory: dir.path().to_path_buf(),
        vtk_every: Some(1),
        series_every: None,
        series: vec![],
        plot: false,
    };
    let mut output = Output::new(&settings, &sim).unwrap();
    output.record(&sim).unwrap();
    sim.step().unwrap();
    output.record(&sim).unwrap();
    // a second record at the same step writes nothing new
    output.record(&sim).unwrap();
    let report = output.finish(&sim).unwrap();
    assert_eq!(report.vtk_frames, 2);
    for part in ["connections", "pfacets", "contacts"] {
        let piece = read_piece(&dir.path().join(format!("{part}_000001.vtp")));
        assert_eq!(piece.num_points(), 0, "{part}");
        assert_eq!(piece.num_cells(), 0, "{part}");
    }
    assert_eq!(read_piece(&dir.path().join("particles_000001.vtp")).num_points(), 1);
}

#[test]
fn a_frame_written_off_schedule_is_the_outputs_frame_at_that_step() {
    let tmp = tempfile::tempdir().unwrap();
    let (scheduled, mine) = (tmp.path().join("run"), tmp.path().join("mine").join("deeper"));
    let mut sim = scene();
    let settings = OutputSettings {
        directory: scheduled.clone(),
        vtk_every: Some(5),
        series_every: None,
        series: Vec::new(),
        plot: false,
    };
    let mut out = Output::new(&settings, &sim).unwrap();
    while sim.steps() < 10 {
        sim.step().unwrap();
        out.record(&sim).unwrap();
    }
    let written = flexdem_output::write_frame(&mine, &sim).unwrap();
    let names: Vec<String> =
        written.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    assert_eq!(
        names,
        [
            "particles_000010.vtp",
            "connections_000010.vtp",
            "pfacets_000010.vtp",
            "contacts_000010.vtp"
        ]
    );
    for (path, name) in written.iter().zip(&names) {
        assert_eq!(path.parent(), Some(mine.as_path()));
        assert_eq!(std::fs::read(path).unwrap(), std::fs::read(scheduled.join(name)).unwrap());
    }
    // read back by an independent reader: every particle
    assert_eq!(points(&read_piece(&written[0])).len(), sim.model().particles.len());
    // no .pvd of its own
    assert!(!mine.join(flexdem_output::PVD_FILE).exists());
}

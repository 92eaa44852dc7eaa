//! Placement, packings and selections of scene files.

use flexdem_elements::{Dofs, ParticleKind};
use flexdem_geom::Vec3;
use flexdem_scene::packing::{lattice_packing, random_packing, PackingError};
use flexdem_scene::parse_scene;
use std::path::Path;

const HEAD: &str = r#"
[simulation]
steps = 1

[materials.m]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30
"#;

fn scene(body: &str) -> flexdem_scene::Scene {
    parse_scene(&format!("{HEAD}{body}"), Path::new("t.toml")).unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).norm() < 1e-12
}

#[test]
fn placement_scales_rotates_then_translates_a_chain() {
    let s = scene(
        r#"
[[structures]]
name = "c"
kind = "chain"
material = "m"
node_radius = 0.01
points = [[0, 0, 0], [1, 0, 0], [1, 1, 0]]
placement = { scale = 2, axis = [0, 0, 1], angle_deg = 90, translate = [10, 0, 0] }
"#,
    );
    let p = &s.model.particles.pos;
    assert!(close(p[0], Vec3::new(10.0, 0.0, 0.0)));
    assert!(close(p[1], Vec3::new(10.0, 2.0, 0.0)));
    assert!(close(p[2], Vec3::new(8.0, 2.0, 0.0)));
    // rest lengths follow the scale, node radius does not
    assert!((s.model.connections[0].rest_length - 2.0).abs() < 1e-12);
    assert_eq!(s.model.particles.radius[0], 0.01);
}

#[test]
fn euler_placement_moves_a_tube_rigidly() {
    let body = |placement: &str| {
        format!(
            r#"
[[structures]]
name = "t"
kind = "tube"
material = "m"
node_radius = 0.002
radius = 0.1
length = 0.8
around = 8
along = 4
{placement}
"#
        )
    };
    let plain = scene(&body(""));
    let moved = scene(&body("placement = { rotate_deg = [0, -90, 0], translate = [1, 2, 3] }"));
    // rotating x by -90° about y points the axis along +z
    let r = nalgebra::UnitQuaternion::from_euler_angles(0.0, (-90.0f64).to_radians(), 0.0);
    for (a, b) in plain.model.particles.pos.iter().zip(&moved.model.particles.pos) {
        assert!(close(Vec3::new(1.0, 2.0, 3.0) + r * a, *b));
    }
    let last = moved.model.particles.pos.last().unwrap();
    assert!((last.z - 3.8).abs() < 1e-12);
    assert!((plain.model.total_mass() - moved.model.total_mass()).abs() < 1e-15);
}

#[test]
fn random_packing_has_no_overlap_stays_inside_and_is_deterministic() {
    let (lo, hi) = (Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.5));
    let a = random_packing(lo, hi, 0.02, 0.05, 500, 7).unwrap();
    assert_eq!(a.len(), 500);
    for (i, &(c, r)) in a.iter().enumerate() {
        assert!((0.02..=0.05).contains(&r));
        for k in 0..3 {
            assert!(c[k] - r >= lo[k] && c[k] + r <= hi[k], "sphere {i} outside");
        }
        for &(d, s) in &a[..i] {
            assert!((c - d).norm() >= r + s, "overlap with sphere {i}");
        }
    }
    assert_eq!(a, random_packing(lo, hi, 0.02, 0.05, 500, 7).unwrap());
    assert_ne!(a, random_packing(lo, hi, 0.02, 0.05, 500, 8).unwrap());
    let err = random_packing(lo, hi, 0.1, 0.1, 100_000, 1).unwrap_err();
    assert!(matches!(err, PackingError::Saturated { .. }), "{err}");
    assert!(random_packing(hi, lo, 0.1, 0.1, 1, 1).is_err());
    assert!(random_packing(lo, hi, 0.1, 0.05, 1, 1).is_err());
}

#[test]
fn random_packing_is_fast_for_many_spheres() {
    let (lo, hi) = (Vec3::zeros(), Vec3::new(1.0, 1.0, 1.0));
    let start = std::time::Instant::now();
    let a = random_packing(lo, hi, 0.005, 0.005, 200_000, 3).unwrap();
    assert_eq!(a.len(), 200_000);
    assert!(start.elapsed().as_secs_f64() < 20.0, "{:?}", start.elapsed());
}

#[test]
fn lattice_packing_counts_and_bounds() {
    let c = lattice_packing(Vec3::zeros(), Vec3::new(1.0, 0.5, 0.2), 0.05, 0.1).unwrap();
    assert_eq!(c.len(), 10 * 5 * 2);
    assert!(close(c[0], Vec3::new(0.05, 0.05, 0.05)));
    assert!(close(*c.last().unwrap(), Vec3::new(0.95, 0.45, 0.15)));
    assert!(lattice_packing(Vec3::zeros(), Vec3::new(1.0, 1.0, 1.0), 0.1, 0.15).is_err());
    assert!(lattice_packing(Vec3::zeros(), Vec3::new(0.1, 1.0, 1.0), 0.1, 0.2).is_err());
}

#[test]
fn sphere_groups_velocities_and_lattice_in_a_scene() {
    let s = scene(
        r#"
[[spheres]]
name = "grid"
kind = "lattice"
material = "m"
box = { min = [0, 0, 0], max = [0.4, 0.4, 0.2] }
radius = 0.1
velocity = [1, 0, 0]
angular_velocity = [0, 0, 3]

[[boundary]]
select = { spheres = "grid", box = { min = [0, 0, 0], max = [0.15, 1, 1] } }
velocity = [0, 0, -1]
"#,
    );
    let ps = &s.model.particles;
    assert_eq!(ps.len(), 4);
    assert!(ps.kind.iter().all(|&k| k == ParticleKind::Sphere));
    assert_eq!(ps.ang_vel[3], Vec3::new(0.0, 0.0, 3.0));
    // spheres at x = 0.1 get the imposed velocity and blocked translations, the others keep theirs
    for i in 0..4 {
        if ps.pos[i].x < 0.15 {
            assert_eq!((ps.vel[i], ps.blocked[i]), (Vec3::new(0.0, 0.0, -1.0), Dofs::TRANSLATION));
        } else {
            assert_eq!((ps.vel[i], ps.blocked[i]), (Vec3::new(1.0, 0.0, 0.0), Dofs::NONE));
        }
    }
}

#[test]
fn selections_by_side_box_plane_and_ids() {
    let s = scene(
        r#"
[[structures]]
name = "net"
kind = "net"
material = "m"
node_radius = 0.001
size = [1, 2]
cells = [2, 4]

[[structures]]
name = "tube"
kind = "tube"
material = "m"
node_radius = 0.001
start = [5, 0, 0]
radius = 0.1
length = 1
around = 6
along = 3

[[structures]]
name = "disc"
kind = "disc"
material = "m"
node_radius = 0.001
center = [0, 0, 5]
radius = 1
rings = 2

[[loads]]
select = { structure = "net", side = "corners" }
total_force = [0, 0, -4]

[[loads]]
select = { structure = "net", side = "u_max" }
force = [1, 0, 0]

[[loads]]
select = { structure = "tube", side = "end" }
moment = [1, 0, 0]
ramp = { start = 0.1, duration = 0.2 }

[[loads]]
select = { structure = "net", plane = { point = [0, 1, 0], normal = [0, 1, 0] } }
force = [0, 1, 0]

[[loads]]
select = { structure = "disc", side = "boundary" }
force = [0, 0, 1]

[[loads]]
select = { ids = [3, 1, 3] }
force = [0, 0, 1]
"#,
    );
    let l = &s.loads;
    assert_eq!(l[0].particles, vec![0, 2, 12, 14]);
    assert_eq!(l[0].force, Vec3::new(0.0, 0.0, -1.0));
    assert_eq!(l[1].particles, vec![2, 5, 8, 11, 14]);
    let tube_first = 15u32;
    assert_eq!(l[2].particles, (tube_first + 18..tube_first + 24).collect::<Vec<_>>());
    for &p in &l[2].particles {
        assert!((s.model.particles.pos[p as usize].x - 6.0).abs() < 1e-12);
    }
    assert!(
        matches!(l[2].ramp, flexdem_integrate::Ramp::Linear { start, duration } if start == 0.1 && duration == 0.2)
    );
    // the plane y = 1 (tolerance: each node's radius) holds the net's middle row (and a
    // node of the disc, left out by `structure = "net"`)
    assert_eq!(l[3].particles, vec![6, 7, 8]);
    let disc_first = tube_first + 24;
    assert_eq!(l[4].particles, (disc_first + 7..disc_first + 19).collect::<Vec<_>>());
    for &p in &l[4].particles {
        let d = s.model.particles.pos[p as usize] - Vec3::new(0.0, 0.0, 5.0);
        assert!((d.norm() - 1.0).abs() < 1e-12);
    }
    assert_eq!(l[5].particles, vec![1, 3]);
}

#[test]
fn a_mesh_structure_is_read_relative_to_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let meshes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/meshes/cube.obj");
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::copy(meshes, dir.path().join("meshes/cube.obj")).unwrap();
    let text = format!(
        "{HEAD}\n[[structures]]\nname = \"box\"\nkind = \"mesh\"\nmaterial = \"m\"\n\
         node_radius = 0.01\nfile = \"meshes/cube.obj\"\nplacement = {{ scale = 3 }}\n"
    );
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let s = flexdem_scene::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.model.pfacets.len(), 12);
    assert_eq!(s.model.structures[0].nodes.len(), 8);
    assert_eq!(s.output.directory, dir.path().join("output"));
}

/// A servo wall and the series of walls and samples: the controls come one per wall in file
/// order, a wall stress takes its servo's area unless given one, regions are read as written.
#[test]
fn servo_walls_and_sample_measures_are_read() {
    use flexdem_integrate::{Region, StressControl, WallControl};
    use flexdem_output::Quantity;
    let s = scene(
        r#"
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "m"
velocity = [0, 0, 0.01]

[[walls]]
point = [0, 0, 0.2]
normal = [0, 0, -1]
material = "m"
servo = { stress = 1e5, area = 0.01, max_speed = 0.05 }

[[walls]]
point = [0.1, 0, 0]
normal = [-1, 0, 0]
material = "m"
servo = { stress = 5e4, area = 0.02, gain = 1e-6, max_speed = 0.1 }

[output]
series_every = 10

[[output.series]]
name = "top_force"
quantity = "wall_force"
wall = 1

[[output.series]]
name = "top"
quantity = "wall_stress"
wall = 1

[[output.series]]
name = "bottom"
quantity = "wall_stress"
wall = 0
area = 0.04

[[output.series]]
name = "sample"
quantity = "stress"
cylinder = { start = [0, 0, 0], axis = [0, 0, 2], radius = 0.05, length = 0.2 }

[[output.series]]
name = "inner"
quantity = "stress"
box = { min = [-0.05, -0.05, 0], max = [0.05, 0.05, 0.2] }
volume = 0.003

[[output.series]]
name = "phi"
quantity = "solid_fraction"
box = { min = [-0.05, -0.05, 0], max = [0.05, 0.05, 0.2] }
"#,
    );
    let top = StressControl { target: 1e5, area: 0.01, gain: None, max_speed: 0.05, section: None };
    let side =
        StressControl { target: 5e4, area: 0.02, gain: Some(1e-6), max_speed: 0.1, section: None };
    assert_eq!(
        s.wall_controls,
        vec![WallControl::Velocity, WallControl::Stress(top), WallControl::Stress(side)]
    );
    assert_eq!(s.model.walls[0].velocity, Vec3::new(0.0, 0.0, 0.01));
    let q: Vec<&Quantity> = s.output.series.iter().map(|x| &x.quantity).collect();
    let cylinder = Region::Cylinder {
        start: Vec3::zeros(),
        axis: Vec3::new(0.0, 0.0, 2.0),
        radius: 0.05,
        length: 0.2,
    };
    let block = Region::Box { min: Vec3::new(-0.05, -0.05, 0.0), max: Vec3::new(0.05, 0.05, 0.2) };
    assert_eq!(
        q,
        [
            &Quantity::WallForce(1),
            &Quantity::WallStress { wall: 1, area: 0.01 },
            &Quantity::WallStress { wall: 0, area: 0.04 },
            &Quantity::Stress { region: cylinder, volume: None },
            &Quantity::Stress { region: block, volume: Some(0.003) },
            &Quantity::SolidFraction(block),
        ]
    );
}

/// Six walls around a 0.2 × 0.1 × 0.3 box: 0, 1 along z (the platens), 2, 3 along x, 4, 5
/// along y; the top platen's servo is `servo`.
fn six_walls(servo: &str) -> String {
    let wall = |p: &str, n: &str, extra: &str| {
        format!("\n[[walls]]\npoint = {p}\nnormal = {n}\nmaterial = \"m\"\n{extra}\n")
    };
    [
        wall("[0, 0, 0]", "[0, 0, 1]", ""),
        wall("[0, 0, 0.3]", "[0, 0, -1]", servo),
        wall("[-0.1, 0, 0]", "[1, 0, 0]", ""),
        wall("[0.1, 0, 0]", "[-1, 0, 0]", ""),
        wall("[0, -0.05, 0]", "[0, 1, 0]", ""),
        wall("[0, 0.05, 0]", "[0, -1, 0]", ""),
    ]
    .concat()
}

#[test]
fn a_servo_follows_the_section_between_walls_and_refuses_a_bad_one() {
    let s = scene(&six_walls(
        "servo = { stress = 1e5, area_of = { walls = [[2, 3], [4, 5]] }, max_speed = 0.1 }",
    ));
    let flexdem_integrate::WallControl::Stress(servo) = s.wall_controls[1] else {
        panic!("{:?}", s.wall_controls)
    };
    // the area measured at the build: 0.2 m × 0.1 m
    assert!((servo.area - 0.02).abs() < 1e-15, "{}", servo.area);
    assert!(servo.section.is_some());
    let err = |servo: &str| {
        parse_scene(&format!("{HEAD}{}", six_walls(servo)), Path::new("t.toml"))
            .unwrap_err()
            .to_string()
    };
    let e =
        err("servo = { stress = 1e5, area_of = { walls = [[2, 3], [4, 9]] }, max_speed = 0.1 }");
    assert!(e.contains("walls.servo.area_of") && e.contains("wall 9 does not exist"), "{e}");
    let e =
        err("servo = { stress = 1e5, area_of = { walls = [[0, 2], [4, 5]] }, max_speed = 0.1 }");
    assert!(e.contains("must face each other"), "{e}");
    let e = err("servo = { stress = 1e5, max_speed = 0.1 }");
    assert!(e.contains("walls.servo.area") && e.contains("area_of"), "{e}");
    let e = err("servo = { stress = 1e5, area_of = { walls = [[2, 3]] }, max_speed = 0.1 }");
    assert!(e.contains("walls.servo.area_of.walls"), "{e}");
    let e = err("servo = { stress = 1e5, area_of = { membrane = \"tube\", platens = [0, 1] }, max_speed = 0.1 }");
    assert!(e.contains("walls.servo.area_of.membrane"), "{e}");
}

/// `self_contact = false`: the structure's elements never pair, so a chain thicker than its
/// segments (an error with self-contact, see tests/data/scenes/bad) is accepted; a value that
/// is not a boolean is an error naming the key.
#[test]
fn self_contact_off_is_kept_and_allows_a_structure_that_overlaps_itself() {
    let chain = r#"
[[structures]]
name = "cable"
kind = "chain"
material = "m"
node_radius = 0.01
start = [0, 0, 0]
end = [1, 0, 0]
segments = 200
"#;
    let thick = parse_scene(&format!("{HEAD}{chain}"), Path::new("t.toml")).unwrap_err();
    assert!(thick.to_string().contains("overlaps itself"), "{thick}");
    let s = scene(&format!("{chain}self_contact = false\n"));
    assert!(!s.model.structures[0].self_contact);
    assert!(
        scene(chain.replace("segments = 200", "segments = 10").as_str()).model.structures[0]
            .self_contact
    );
    let typo = format!("{HEAD}{chain}self_contact = \"no\"\n");
    let err = parse_scene(&typo, Path::new("t.toml")).unwrap_err().to_string();
    assert!(err.contains("self_contact"), "{err}");
}

/// A direction may have any length: one whose squared length overflows or underflows
/// (1e200, 1e-200) is the same direction as a unit one, not "[0, 0, 0]".
#[test]
fn directions_of_huge_and_tiny_lengths_are_their_direction() {
    for (given, unit) in [
        ("[0, 1e200, 0]", Vec3::y()),
        ("[-1e-200, 0, 0]", -Vec3::x()),
        ("[0, 0, 3]", Vec3::z()),
        ("[1e200, 1e200, 0]", Vec3::new(1.0, 1.0, 0.0).normalize()),
    ] {
        let s =
            scene(&format!("[[walls]]\npoint = [0, 0, 0]\nnormal = {given}\nmaterial = \"m\"\n"));
        let n = s.model.walls[0].normal;
        assert!(close(n, unit) && (n.norm() - 1.0).abs() < 1e-15, "{given}: {n:?}");
    }
    let text =
        format!("{HEAD}[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 0]\nmaterial = \"m\"\n");
    let e = parse_scene(&text, Path::new("s.toml")).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("non-zero direction"), "{e}");
}

//! Dense packings and sphere files from scene files: `[[spheres]] kind = "dense"` and
//! `kind = "file"`.

use flexdem_elements::ParticleKind;
use flexdem_geom::{Real, Vec3};
use flexdem_scene::sphere_file::write_spheres;
use flexdem_scene::{parse_scene, Scene};
use std::f64::consts::PI;
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

fn parse(body: &str) -> Result<Scene, String> {
    parse_scene(&format!("{HEAD}{body}"), Path::new("t.toml")).map_err(|e| e.to_string())
}

fn spheres(s: &Scene) -> Vec<(Vec3, Real)> {
    let p = &s.model.particles;
    (0..p.len())
        .filter(|&i| p.kind[i] == ParticleKind::Sphere)
        .map(|i| (p.pos[i], p.radius[i]))
        .collect()
}

fn solid_volume(s: &[(Vec3, Real)]) -> Real {
    s.iter().map(|(_, r)| 4.0 / 3.0 * PI * r.powi(3)).sum()
}

fn largest_overlap(s: &[(Vec3, Real)]) -> Real {
    let mut largest: Real = 0.0;
    for (i, (c, r)) in s.iter().enumerate() {
        for (c2, r2) in &s[i + 1..] {
            largest = largest.max(r + r2 - (c2 - c).norm());
        }
    }
    largest
}

#[test]
fn a_dense_cylinder_reaches_its_solid_fraction() {
    let s = parse(
        r#"
[[spheres]]
kind = "dense"
material = "m"
cylinder = { start = [0, 0, 0], axis = [0, 0, 2], radius = 0.05, length = 0.2 }
radius_range = [0.0025, 0.005]
solid_fraction = 0.6
seed = 4
"#,
    )
    .unwrap();
    let sp = spheres(&s);
    let volume = PI * 0.05 * 0.05 * 0.2;
    assert!((solid_volume(&sp) / volume - 0.6).abs() < 1e-9);
    let r_min = sp.iter().map(|x| x.1).fold(Real::INFINITY, Real::min);
    assert!(largest_overlap(&sp) <= 1e-3 * r_min * 1.000001);
    for (c, r) in &sp {
        let rho = (c.x * c.x + c.y * c.y).sqrt();
        // inside, to the packing's tolerance (1e-3 of the smallest radius)
        let slack = 1e-3 * r_min * 1.000001;
        assert!(rho + r <= 0.05 + slack && c.z - r >= -slack && c.z + r <= 0.2 + slack);
    }
}

#[test]
fn a_dense_packing_fills_the_inside_of_a_closed_structure() {
    let s = parse(
        r#"
[[structures]]
name = "ball"
kind = "sphere_shell"
material = "m"
node_radius = 0.004
center = [0, 0, 0]
radius = 0.1
subdivisions = 2

[[spheres]]
kind = "dense"
material = "m"
inside = "ball"
radius_range = [0.006, 0.009]
count = 300
solid_fraction = 0.5
"#,
    )
    .unwrap();
    let sp = spheres(&s);
    assert_eq!(sp.len(), 300);
    // every sphere clear of the shell's PFacets: inside the inscribed sphere of the
    // icosahedral mesh less the node radius, or at least inside the circumscribed one
    for (c, r) in &sp {
        assert!(c.norm() + r <= 0.1 - 0.004 + 1e-6, "{c:?} {r}");
    }
}

#[test]
fn spheres_read_from_a_file_are_the_ones_written() {
    let dir = std::env::temp_dir().join(format!("flexdem_sphere_file_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let written = vec![(Vec3::new(0.0, 0.0, 0.1), 0.01), (Vec3::new(0.1, 0.0, 0.1), 0.02)];
    std::fs::write(dir.join("pack.csv"), write_spheres(&written)).unwrap();
    let text =
        format!("{HEAD}\n[[spheres]]\nkind = \"file\"\nmaterial = \"m\"\nfile = \"pack.csv\"\n");
    let s = parse_scene(&text, &dir.join("scene.toml")).unwrap();
    assert_eq!(spheres(&s), written);
    let missing = text.replace("pack.csv", "nothing.csv");
    let e = parse_scene(&missing, &dir.join("scene.toml")).unwrap_err().to_string();
    assert!(e.contains("spheres.file") && e.contains("nothing.csv"), "{e}");
    std::fs::write(dir.join("pack.csv"), "x,y,z,radius\n0,0,0,zero\n").unwrap();
    let e = parse_scene(&text, &dir.join("scene.toml")).unwrap_err().to_string();
    assert!(e.contains("line 2") && e.contains("radius"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_dense_packings_are_located_errors() {
    let base = r#"
[[spheres]]
kind = "dense"
material = "m"
radius = 0.01
"#;
    let e = parse(&format!("{base}box = {{ min = [0, 0, 0], max = [1, 1, 1] }}\n")).unwrap_err();
    assert!(e.contains("solid_fraction"), "{e}");
    let e = parse(&format!("{base}solid_fraction = 0.6\n")).unwrap_err();
    assert!(e.contains("exactly one of `box`, `cylinder` and `inside`"), "{e}");
    let e = parse(&format!(
        "{base}solid_fraction = 0.8\nbox = {{ min = [0, 0, 0], max = [0.2, 0.2, 0.2] }}\n"
    ))
    .unwrap_err();
    assert!(e.contains("solid fraction is 0.8"), "{e}");
    let e = parse(&format!("{base}solid_fraction = 0.6\ninside = \"bal\"\n")).unwrap_err();
    assert!(e.contains("spheres.inside") && e.contains("unknown structure"), "{e}");
    let e = parse(&format!(
        "{base}solid_fraction = 0.6\ncylinder = {{ start = [0, 0, 0], axis = [0, 0, 0], radius = 1, length = 1 }}\n"
    ))
    .unwrap_err();
    assert!(e.contains("spheres.cylinder.axis"), "{e}");
    let e = parse(&format!("{base}solid_fraction = 0.6\nfile = \"a.csv\"\n")).unwrap_err();
    assert!(e.contains("does not apply to kind = \"dense\""), "{e}");
    // a typo of a few zeros: refused before the packing starts (it would run for days)
    let e = parse(&format!(
        "{base}solid_fraction = 0.6\nbox = {{ min = [0, 0, 0], max = [1, 1, 1] }}\nmax_iterations = 2000000000\n"
    ))
    .unwrap_err();
    assert!(e.contains("spheres.max_iterations") && e.contains("at most 1000000"), "{e}");
    // radii whose cube underflows: an error, not an overflow (found by the fuzzer)
    let e = parse(
        &format!(
        "{base}solid_fraction = 0.6\nbox = {{ min = [0, 0, 0], max = [1, 1, 1] }}\ncount = 10\n"
    )
        .replace("radius = 0.01", "radius_range = [6e-300, 1.2e-299]"),
    )
    .unwrap_err();
    assert!(e.contains("scaled radius"), "{e}");
    // a vanishing solid fraction: tiny radii in a grid that must still fit (an overflow of
    // the cell count, found by the fuzzer); built or refused, never a panic
    let _ = parse(&format!(
        "{base}solid_fraction = 0.6e-300\ncylinder = {{ start = [0, 0, 0], axis = [0, 0, 1], radius = 0.05, length = 0.2 }}\ncount = 5000\n"
    ));
    // an open structure cannot hold spheres
    let open = r#"
[[structures]]
name = "sheet"
kind = "membrane"
material = "m"
node_radius = 0.01
origin = [0, 0, 0]
u_dir = [1, 0, 0]
v_dir = [0, 1, 0]
size = [1, 1]
cells = [4, 4]
"#;
    let e = parse(&format!("{open}{base}solid_fraction = 0.3\ninside = \"sheet\"\n")).unwrap_err();
    assert!(e.contains("not closed"), "{e}");
}

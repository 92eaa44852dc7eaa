//! Every format of the unit cube in `tests/data/meshes/` reads to the same surface.

use std::collections::BTreeSet;
use std::path::PathBuf;

use flexdem_geom::{TriMesh, Vec3};
use flexdem_mesh::{read_mesh, MeshError};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/meshes").join(name)
}

fn read(name: &str) -> TriMesh {
    read_mesh(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A triangle as its corner coordinates (scaled to integers: the cube's corners are 0 or 1),
/// rotated so that the smallest corner comes first: equal for the same oriented triangle
/// whatever the vertex numbering.
type Key = [[i64; 3]; 3];

fn surface(mesh: &TriMesh) -> BTreeSet<Key> {
    mesh.triangles
        .iter()
        .map(|t| {
            let corners = t.map(|v| mesh.vertices[v].map(|x| (x * 1000.0).round() as i64).into());
            let first = (0..3).min_by_key(|&k| corners[k]).unwrap();
            [corners[first], corners[(first + 1) % 3], corners[(first + 2) % 3]]
        })
        .collect()
}

/// The cube of `generate.py`: 12 outward triangles.
fn expected_cube() -> BTreeSet<Key> {
    let corners: [[i64; 3]; 8] =
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
    let quads =
        [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [0, 4, 7, 3], [1, 2, 6, 5]];
    let mut triangles = Vec::new();
    for q in quads {
        triangles.push([q[0], q[1], q[2]]);
        triangles.push([q[0], q[2], q[3]]);
    }
    let vertices =
        corners.iter().map(|c| Vec3::new(c[0] as f64, c[1] as f64, c[2] as f64)).collect();
    surface(&TriMesh::new(vertices, triangles))
}

/// Every triangle is outward: its normal points away from the cube's centre.
fn assert_outward(mesh: &TriMesh, name: &str) {
    let centre = Vec3::new(0.5, 0.5, 0.5);
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| mesh.vertices[v]);
        let normal = (b - a).cross(&(c - a));
        assert!(normal.dot(&((a + b + c) / 3.0 - centre)) > 0.0, "{name}: inward triangle {t:?}");
    }
}

const INDEXED: [&str; 7] = [
    "cube_v22_ascii.msh",
    "cube_v22_binary.msh",
    "cube_v41_ascii.msh",
    "cube_v41_binary.msh",
    "cube.obj",
    "cube.gts",
    "cube.mesh",
];

#[test]
fn indexed_formats_give_the_cube_with_8_vertices_and_12_triangles() {
    let expected = expected_cube();
    assert_eq!(expected.len(), 12);
    for name in INDEXED {
        let mesh = read(name);
        assert_eq!(mesh.vertices.len(), 8, "{name}: unused nodes must be dropped");
        assert_eq!(mesh.triangles.len(), 12, "{name}");
        assert_eq!(surface(&mesh), expected, "{name}");
        assert_outward(&mesh, name);
        // Each corner exactly once.
        let corners: BTreeSet<[i64; 3]> =
            mesh.vertices.iter().map(|v| v.map(|x| x.round() as i64).into()).collect();
        assert_eq!(corners.len(), 8, "{name}");
    }
}

#[test]
fn stl_gives_an_unmerged_soup_of_the_cube() {
    let expected = expected_cube();
    for name in ["cube_ascii.stl", "cube_binary.stl"] {
        let mesh = read(name);
        assert_eq!(mesh.vertices.len(), 36, "{name}: 3 vertices per triangle");
        assert_eq!(mesh.triangles.len(), 12, "{name}");
        for (k, t) in mesh.triangles.iter().enumerate() {
            assert_eq!(*t, [3 * k, 3 * k + 1, 3 * k + 2], "{name}");
        }
        assert_eq!(surface(&mesh), expected, "{name}");
        assert_outward(&mesh, name);
    }
}

#[test]
fn binary_stl_whose_header_starts_with_solid_is_read_as_binary() {
    let bytes = std::fs::read(data("cube_binary.stl")).unwrap();
    assert!(bytes.starts_with(b"solid"));
    let mesh = flexdem_mesh::read_stl(&bytes, "cube_binary.stl").unwrap();
    // The first triangle of generate.py: corners 0, 3, 2 of the cube.
    assert_eq!(mesh.vertices[0], Vec3::new(0.0, 0.0, 0.0));
    assert_eq!(mesh.vertices[1], Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(mesh.vertices[2], Vec3::new(1.0, 1.0, 0.0));
}

#[test]
fn vertex_order_and_coordinates_follow_the_file() {
    // msh: nodes in file order, tags 10, 20, ... 80 (non-contiguous) mapped to 0..8; the
    // mid-side nodes of the 6-node triangles and the tetrahedron's centre node are dropped.
    for name in
        ["cube_v22_ascii.msh", "cube_v22_binary.msh", "cube_v41_ascii.msh", "cube_v41_binary.msh"]
    {
        let mesh = read(name);
        assert_eq!(mesh.vertices[1], Vec3::new(1.0, 0.0, 0.0), "{name}");
        assert_eq!(mesh.vertices[6], Vec3::new(1.0, 1.0, 1.0), "{name}");
        assert!(!mesh.vertices.contains(&Vec3::new(0.5, 0.5, 0.5)), "{name}");
    }
    let v22 = read("cube_v22_ascii.msh");
    // Its first two triangles are 6-node ones: corners (10, 40, 30) and (10, 30, 20).
    assert_eq!(v22.triangles[0], [0, 3, 2]);
    assert_eq!(v22.triangles[1], [0, 2, 1]);
    // OBJ: the first quad 1 4 3 2 fans into (1 4 3) and (1 3 2); the relative face
    // -6 -5 -1 -2 is 3 4 8 7.
    let obj = read("cube.obj");
    assert_eq!(obj.triangles[0], [0, 3, 2]);
    assert_eq!(obj.triangles[1], [0, 2, 1]);
    assert_eq!(obj.triangles[6], [2, 3, 7]);
    assert_eq!(obj.triangles[7], [2, 7, 6]);
    // GTS and MEDIT: vertex order of the file, triangles in the generator's order.
    for name in ["cube.gts", "cube.mesh"] {
        let mesh = read(name);
        assert_eq!(mesh.vertices[7], Vec3::new(0.0, 1.0, 1.0), "{name}");
        assert_eq!(mesh.triangles[0], [0, 3, 2], "{name}");
        assert_eq!(mesh.triangles[11], [1, 6, 5], "{name}");
    }
}

#[test]
fn extension_is_case_insensitive_and_unknown_ones_are_listed() {
    let dir = std::env::temp_dir().join(format!("flexdem-io-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let upper = dir.join("CUBE.OBJ");
    std::fs::copy(data("cube.obj"), &upper).unwrap();
    assert_eq!(read_mesh(&upper).unwrap().triangles.len(), 12);
    let unknown = dir.join("cube.ply");
    std::fs::write(&unknown, "ply\n").unwrap();
    let error = read_mesh(&unknown).unwrap_err();
    assert!(matches!(error, MeshError::UnsupportedExtension { .. }));
    let message = error.to_string();
    for extension in [".msh", ".stl", ".obj", ".gts", ".mesh", "cube.ply"] {
        assert!(message.contains(extension), "{message}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_file_is_an_io_error_naming_the_path() {
    let path = data("no_such_cube.stl");
    let error = read_mesh(&path).unwrap_err();
    assert!(matches!(error, MeshError::Io { .. }));
    assert!(error.to_string().contains("no_such_cube.stl"), "{error}");
}

use super::*;
use crate::builders::test_support::*;
use crate::builders::{sphere_shell, ShellBase};

fn opts(mat: u32) -> StructureOptions {
    StructureOptions::new("mesh", 0.01, mat)
}

/// A unit cube as 12 triangles, outward, indexed (8 vertices).
fn cube() -> TriMesh {
    let v = (0..8)
        .map(|i| Vec3::new((i & 1) as Real, ((i >> 1) & 1) as Real, ((i >> 2) & 1) as Real))
        .collect();
    let quads = [
        [0, 2, 3, 1], // z = 0, normal −z
        [4, 5, 7, 6], // z = 1, normal +z
        [0, 1, 5, 4], // y = 0, normal −y
        [2, 6, 7, 3], // y = 1, normal +y
        [0, 4, 6, 2], // x = 0, normal −x
        [1, 3, 7, 5], // x = 1, normal +x
    ];
    let triangles = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
    TriMesh::new(v, triangles)
}

/// The same mesh with every triangle given its own three vertices (an STL-like soup),
/// perturbed by `noise` (relative to size 1).
fn soup(mesh: &TriMesh, noise: Real) -> TriMesh {
    let mut seed = 0x2545F4914F6CDD1Du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as Real / (1u64 << 53) as Real - 0.5
    };
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for t in &mesh.triangles {
        let base = vertices.len();
        for &v in t {
            vertices.push(mesh.vertices[v] + noise * Vec3::new(next(), next(), next()));
        }
        triangles.push([base, base + 1, base + 2]);
    }
    TriMesh::new(vertices, triangles)
}

#[test]
fn closed_cube_mesh_is_a_closed_shell() {
    let (mut model, mat) = model_with_material(1000.0);
    let s = pfacets_from_mesh(&mut model, &cube(), 0.0, &opts(mat)).unwrap();
    let st = model.structure(s).unwrap().clone();
    assert_eq!((st.nodes.len(), st.connections.len(), st.pfacets.len()), (8, 18, 12));
    assert_eq!(euler_characteristic(&model, s), 2);
    assert!(faces_per_connection(&model, s).iter().all(|&k| k == 2));
    for f in st.pfacets.clone() {
        let (n, c) = pfacet_normal_centroid(&model, f as usize);
        assert!(n.dot(&(c - Vec3::repeat(0.5))) > 0.0);
    }
    check_adjacency(&model);
}

#[test]
fn triangle_soup_merges_to_the_indexed_mesh() {
    let (mut model, mat) = model_with_material(1000.0);
    let mesh = soup(&cube(), 1e-9);
    assert_eq!(mesh.vertices.len(), 36);
    let s = pfacets_from_mesh(&mut model, &mesh, 1e-6, &opts(mat)).unwrap();
    let st = model.structure(s).unwrap().clone();
    assert_eq!((st.nodes.len(), st.connections.len(), st.pfacets.len()), (8, 18, 12));
    assert_eq!(euler_characteristic(&model, s), 2);
    // Merged nodes keep the lowest-index vertex's position.
    assert_eq!(model.particles.pos[st.nodes.start as usize], mesh.vertices[0]);
    // Without merging, the soup's 36 vertices stay apart: 12 separate triangles.
    let s2 = pfacets_from_mesh(&mut model, &mesh, 0.0, &opts(mat)).unwrap();
    let st2 = model.structure(s2).unwrap();
    assert_eq!((st2.nodes.len(), st2.connections.len()), (36, 36));
    check_adjacency(&model);
}

#[test]
fn icosphere_soup_round_trips() {
    // Build an icosphere, read it back as a soup, import it: same counts, closed.
    let (mut model, mat) = model_with_material(1000.0);
    let s = sphere_shell(&mut model, Vec3::zeros(), 2.0, ShellBase::Icosahedron, 2, &opts(mat))
        .unwrap();
    let st = model.structure(s).unwrap().clone();
    let mesh = TriMesh::new(
        model.particles.pos[st.nodes.start as usize..st.nodes.end as usize].to_vec(),
        st.pfacets
            .clone()
            .map(|f| model.pfacets[f as usize].nodes.map(|n| (n - st.nodes.start) as usize))
            .collect(),
    );
    let s2 = pfacets_from_mesh(&mut model, &soup(&mesh, 1e-10), 1e-7, &opts(mat)).unwrap();
    let st2 = model.structure(s2).unwrap().clone();
    assert_eq!(st2.nodes.len(), st.nodes.len());
    assert_eq!(st2.connections.len(), st.connections.len());
    assert_eq!(euler_characteristic(&model, s2), 2);
    assert!(faces_per_connection(&model, s2).iter().all(|&k| k == 2));
}

#[test]
fn unused_vertices_are_dropped_and_non_manifold_edges_allowed() {
    let (mut model, mat) = model_with_material(1000.0);
    // Three triangles on the edge (0, 1) (a fin), and an unused NaN vertex.
    let mesh = TriMesh::new(
        vec![Vec3::zeros(), Vec3::x(), Vec3::y(), -Vec3::y(), Vec3::z(), Vec3::repeat(f64::NAN)],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    );
    let s = pfacets_from_mesh(&mut model, &mesh, 1e-9, &opts(mat)).unwrap();
    let st = model.structure(s).unwrap().clone();
    assert_eq!((st.nodes.len(), st.connections.len(), st.pfacets.len()), (5, 7, 3));
    let shared: Vec<usize> = faces_per_connection(&model, s);
    assert_eq!(shared.iter().filter(|&&k| k == 3).count(), 1);
    assert_eq!(model.adjacency().connection_pfacets.get(0), &[0, 1, 2]);
    check_adjacency(&model);
}

/// Checks that importing `mesh` fails, that the message names `triangle`, and that the
/// model is unchanged.
#[track_caller]
fn assert_rejected(mesh: &TriMesh, tolerance: Real, triangle: usize, also: &str) -> BuildError {
    let (mut model, mat) = model_with_material(1000.0);
    let err = pfacets_from_mesh(&mut model, mesh, tolerance, &opts(mat)).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains(&format!("triangle {triangle} ")), "{msg}");
    assert!(msg.contains(also), "{msg}");
    assert_eq!(model.particles.len(), 0);
    assert!(model.structures.is_empty());
    err
}

#[test]
fn bad_meshes_are_rejected_naming_the_triangle() {
    let mut m = cube();
    m.triangles[5] = [1, 1, 2];
    let err = assert_rejected(&m, 0.0, 5, "[1, 1, 2] repeats a vertex index");
    assert!(matches!(err, BuildError::RepeatedIndex { triangle: 5, .. }));

    let mut m = cube();
    m.triangles[7] = [0, 1, 8];
    let err = assert_rejected(&m, 0.0, 7, "vertex index 8 is out of range");
    assert!(matches!(err, BuildError::IndexOutOfRange { triangle: 7, index: 8, .. }));

    let mut m = cube();
    m.vertices[3].y = f64::NAN;
    let err = assert_rejected(&m, 0.0, 0, "vertex 3 is (1, NaN, 0)");
    assert!(matches!(err, BuildError::NonFiniteVertex { vertex: 3, .. }));

    // Zero-length edge: two distinct indices at the same point.
    let mut m = cube();
    m.vertices.push(m.vertices[1]);
    m.triangles.push([0, 1, 8]);
    let err = assert_rejected(&m, 0.0, 12, "edge 1 from vertex 1 to vertex 8 has length 0");
    assert!(matches!(err, BuildError::ZeroLengthEdge { triangle: 12, edge: 1, .. }));

    // Within the merge tolerance counts as zero length too.
    let mut m = cube();
    m.vertices.push(m.vertices[1] + Vec3::new(1e-8, 0.0, 0.0));
    m.triangles.push([1, 8, 4]);
    let err = assert_rejected(&m, 1e-6, 12, "edge 0 from vertex 1 to vertex 8");
    assert!(matches!(err, BuildError::ZeroLengthEdge { .. }));

    // Flat triangle: collinear vertices.
    let mut m = cube();
    m.vertices.push(Vec3::new(0.5, 0.0, 0.0));
    m.triangles.push([0, 8, 1]);
    let err = assert_rejected(&m, 1e-9, 12, "[0, 8, 1] is degenerate");
    assert!(matches!(err, BuildError::DegenerateTriangle { triangle: 12, .. }));

    // Nearly flat (height 1e-12 of the edge) is degenerate as well.
    let mut m = cube();
    m.vertices.push(Vec3::new(0.5, 1e-12, 0.0));
    m.triangles.push([0, 1, 8]);
    assert_rejected(&m, 0.0, 12, "degenerate");

    // Duplicate face, reversed.
    let mut m = cube();
    m.triangles.push([2, 0, 3]);
    let err = assert_rejected(&m, 0.0, 12, "same three vertices as triangle 0");
    assert!(matches!(err, BuildError::DuplicateTriangle { other: 0, .. }));
}

#[test]
fn thin_but_valid_triangles_and_bad_parameters() {
    let (mut model, mat) = model_with_material(1000.0);
    // A sliver with height 1e-6 of its edge is kept.
    let sliver =
        TriMesh::new(vec![Vec3::zeros(), Vec3::x(), Vec3::new(0.5, 1e-6, 0.0)], vec![[0, 1, 2]]);
    pfacets_from_mesh(&mut model, &sliver, 0.0, &opts(mat)).unwrap();
    let empty = TriMesh::new(vec![Vec3::zeros()], vec![]);
    assert!(matches!(
        pfacets_from_mesh(&mut model, &empty, 0.0, &opts(mat)),
        Err(BuildError::EmptyMesh { vertices: 1 })
    ));
    for bad in [-1.0, 0.5, f64::NAN] {
        let err = pfacets_from_mesh(&mut model, &cube(), bad, &opts(mat)).unwrap_err();
        assert!(err.to_string().contains("merge_tolerance"), "{err}");
    }
    assert_eq!(model.structures.len(), 1);
}

#[test]
fn merging_is_linear_not_quadratic_on_a_large_soup() {
    // A 60 × 60 membrane as a soup: 7200 triangles, 21600 vertices, 3721 after merging.
    let n = 60;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let p = |i: usize, j: usize| Vec3::new(i as Real, j as Real, 0.0) / n as Real;
    for j in 0..n {
        for i in 0..n {
            for t in
                [[p(i, j), p(i + 1, j), p(i + 1, j + 1)], [p(i, j), p(i + 1, j + 1), p(i, j + 1)]]
            {
                let b = vertices.len();
                vertices.extend(t);
                triangles.push([b, b + 1, b + 2]);
            }
        }
    }
    let (mut model, mat) = model_with_material(1000.0);
    let mesh = TriMesh::new(vertices, triangles);
    let s = pfacets_from_mesh(&mut model, &mesh, 1e-9, &opts(mat)).unwrap();
    let st = model.structure(s).unwrap();
    assert_eq!(st.nodes.len(), (n + 1) * (n + 1));
    assert_eq!(st.pfacets.len(), 2 * n * n);
    assert_eq!(euler_characteristic(&model, s), 1);
}

//! Helpers shared by the builders' tests.

use crate::{MaterialId, Model, StructureId};
use flexdem_contact::Material;
use flexdem_geom::{Real, Vec3};

/// An empty model with one material of density `density`.
pub(crate) fn model_with_material(density: Real) -> (Model, MaterialId) {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e7, 0.3, density, 0.5).unwrap()).unwrap();
    (model, mat)
}

/// `|a − b| ≤ tol·max(|a|, |b|)`.
#[track_caller]
pub(crate) fn assert_rel(a: Real, b: Real, tol: Real) {
    assert!((a - b).abs() <= tol * a.abs().max(b.abs()), "{a} vs {b} (relative tolerance {tol})");
}

/// V − E + F of a structure, counted from the built model.
pub(crate) fn euler_characteristic(model: &Model, s: StructureId) -> i64 {
    let st = model.structure(s).unwrap();
    st.nodes.len() as i64 - st.connections.len() as i64 + st.pfacets.len() as i64
}

/// How many of the structure's PFacets use each of its connections, from the PFacets alone.
pub(crate) fn faces_per_connection(model: &Model, s: StructureId) -> Vec<usize> {
    let st = model.structure(s).unwrap();
    let mut count = vec![0; model.connections.len()];
    for f in st.pfacets.clone() {
        for c in model.pfacets[f as usize].connections {
            count[c as usize] += 1;
        }
    }
    st.connections.clone().map(|c| count[c as usize]).collect()
}

/// The unnormalized normal (b − a) × (c − a) and centroid of PFacet `f`.
pub(crate) fn pfacet_normal_centroid(model: &Model, f: usize) -> (Vec3, Vec3) {
    let [a, b, c] = model.pfacets[f].nodes.map(|n| model.particles.pos[n as usize]);
    ((b - a).cross(&(c - a)), (a + b + c) / 3.0)
}

/// Checks the model's adjacency against lists computed naively from its elements, and that
/// every PFacet's connections join its edges (via `validate`).
pub(crate) fn check_adjacency(model: &Model) {
    model.validate().unwrap();
    let adj = model.adjacency();
    for n in 0..model.particles.len() as u32 {
        let conns: Vec<u32> = (0..model.connections.len() as u32)
            .filter(|&c| model.connections[c as usize].nodes.contains(&n))
            .collect();
        assert_eq!(adj.node_connections.get(n as usize), conns.as_slice(), "node {n}");
        let facets: Vec<u32> = (0..model.pfacets.len() as u32)
            .filter(|&f| model.pfacets[f as usize].nodes.contains(&n))
            .collect();
        assert_eq!(adj.node_pfacets.get(n as usize), facets.as_slice(), "node {n}");
    }
    for c in 0..model.connections.len() as u32 {
        let facets: Vec<u32> = (0..model.pfacets.len() as u32)
            .filter(|&f| model.pfacets[f as usize].connections.contains(&c))
            .collect();
        assert_eq!(adj.connection_pfacets.get(c as usize), facets.as_slice(), "connection {c}");
    }
}

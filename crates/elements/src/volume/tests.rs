use super::*;
use crate::builders::test_support::{assert_rel, model_with_material};
use crate::builders::{membrane_disc, membrane_rectangle, sphere_shell, tube, ShellBase};
use crate::StructureOptions;
use flexdem_geom::{polygon_vector_area, Vec3};
use std::f64::consts::TAU;

/// Volume of a convex polyhedron whose vertices all lie on the sphere of radius `r` about
/// its centre, from its faces' edge lengths only (independent of the divergence theorem):
/// `Σ_f (1/3)·A_f·h_f`, with `A_f` by Heron's formula, `ρ_f = abc/(4A_f)` the face's
/// circumradius and `h_f = √(r² − ρ_f²)` the distance from the centre to the face's plane.
fn inscribed_polyhedron_volume(model: &Model, s: StructureId, r: Real) -> Real {
    let st = model.structure(s).unwrap();
    st.pfacets
        .clone()
        .map(|f| {
            let x = model.pfacets[f as usize].nodes.map(|n| model.particles.pos[n as usize]);
            let (a, b, c) = ((x[1] - x[0]).norm(), (x[2] - x[1]).norm(), (x[0] - x[2]).norm());
            let s = 0.5 * (a + b + c);
            let area = (s * (s - a) * (s - b) * (s - c)).sqrt();
            let rho = a * b * c / (4.0 * area);
            area * (r * r - rho * rho).sqrt() / 3.0
        })
        .sum()
}

fn opts(mat: u32) -> StructureOptions {
    StructureOptions::new("s", 0.002, mat)
}

#[test]
fn sphere_shells_enclose_their_polyhedron() {
    for base in [ShellBase::Icosahedron, ShellBase::Octahedron] {
        for k in 0..=3 {
            let (mut model, mat) = model_with_material(1000.0);
            let (c, r) = (Vec3::new(3.0, -1.0, 0.5), 0.4);
            let s = sphere_shell(&mut model, c, r, base, k, &opts(mat)).unwrap();
            assert!(boundary_loops(&model, &pfacets_of(&model, s)).unwrap().is_empty());
            let v = structure_volume(&model, s, &[]).unwrap();
            assert_rel(v, inscribed_polyhedron_volume(&model, s, r), 1e-13);
            if base == ShellBase::Octahedron && k == 0 {
                assert_rel(v, 4.0 / 3.0 * r * r * r, 1e-14);
            }
        }
    }
}

fn pfacets_of(model: &Model, s: StructureId) -> Vec<PFacetId> {
    model.structure(s).unwrap().pfacets.clone().collect()
}

#[test]
fn tube_has_two_boundary_loops_running_along_its_pfacets() {
    let (mut model, mat) = model_with_material(1000.0);
    let axis = Vec3::new(1.0, 2.0, -0.5).normalize();
    let s = tube(&mut model, Vec3::new(0.1, 0.2, 0.3), axis, 0.2, 1.0, 9, 4, &opts(mat)).unwrap();
    let pfacets = pfacets_of(&model, s);
    let loops = boundary_loops(&model, &pfacets).unwrap();
    assert_eq!(loops.len(), 2);
    for nodes in &loops {
        assert_eq!(nodes.len(), 9);
        for i in 0..9 {
            let edge = [nodes[i], nodes[(i + 1) % 9]];
            let runs = pfacets
                .iter()
                .filter(|&&f| (0..3).any(|e| model.pfacets[f as usize].edge_nodes(e) == edge));
            assert_eq!(runs.count(), 1, "edge {edge:?}");
        }
        // clockwise seen from outside the open end: the loop's vector area points in
        let points: Vec<Vec3> = nodes.iter().map(|&n| model.particles.pos[n as usize]).collect();
        let centre = points.iter().sum::<Vec3>() / 9.0;
        let middle = Vec3::new(0.1, 0.2, 0.3) + axis * 0.5;
        let outward = (centre - middle).normalize();
        assert!(polygon_vector_area(&points).dot(&outward) < 0.0);
    }
}

#[test]
fn tube_closed_by_two_walls_is_a_prism() {
    let (mut model, mat) = model_with_material(1000.0);
    let (c0, axis, r, l, m) = (Vec3::new(-0.4, 0.0, 1.0), Vec3::new(0.0, 0.6, 0.8), 0.1, 0.8, 16);
    let s = tube(&mut model, c0, axis, r, l, m, 20, &opts(mat)).unwrap();
    let area = 0.5 * m as Real * r * r * (TAU / m as Real).sin();
    let wall = |model: &mut Model, at: Real, n: Vec3| {
        let id = model.add_wall(c0 + axis * at, n, mat).unwrap();
        model.walls[id as usize].plane()
    };
    // platens on the end rings, facing into the sample, given in either order
    let top = wall(&mut model, l, -axis);
    let bottom = wall(&mut model, 0.0, axis);
    assert_rel(structure_volume(&model, s, &[top, bottom]).unwrap(), area * l, 1e-13);
    // platens pulled away from the ends: the ribbons add the gaps
    let below = Plane { point: c0 - axis * 0.05, normal: axis };
    let above = Plane { point: c0 + axis * (l + 0.1), normal: -axis };
    assert_rel(structure_volume(&model, s, &[below, above]).unwrap(), area * (l + 0.15), 1e-13);
}

#[test]
fn disc_closed_by_a_plane_behind_it_is_a_prism() {
    let (mut model, mat) = model_with_material(1000.0);
    let (c, n, r, rings) =
        (Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.3, -0.2, 1.0).normalize(), 0.5, 3);
    let s = membrane_disc(&mut model, c, n, r, rings, &opts(mat)).unwrap();
    let m = 6 * rings;
    let area = 0.5 * m as Real * r * r * (TAU / m as Real).sin();
    let behind = Plane { point: c - n * 0.25, normal: n };
    assert_rel(structure_volume(&model, s, &[behind]).unwrap(), area * 0.25, 1e-13);
    // a plane in front: the disc faces into the closed region, the volume is negative
    let front = Plane { point: c + n * 0.25, normal: n };
    assert_rel(structure_volume(&model, s, &[front]).unwrap(), -area * 0.25, 1e-13);
}

#[test]
fn open_or_over_closed_surfaces_are_errors() {
    let (mut model, mat) = model_with_material(1000.0);
    let t = tube(&mut model, Vec3::zeros(), Vec3::z(), 0.1, 1.0, 8, 3, &opts(mat)).unwrap();
    let err = structure_volume(&model, t, &[]).unwrap_err();
    assert_eq!(err, VolumeError::NotClosed { loops: 2, planes: 0 });
    assert!(err.to_string().contains("2 boundary loops"), "{err}");
    let z = |h: Real| Plane { point: Vec3::new(0.0, 0.0, h), normal: Vec3::z() };
    assert_eq!(
        structure_volume(&model, t, &[z(0.0), z(-0.1)]).unwrap_err(),
        VolumeError::PlaneSharedByLoops { plane: 0, loops: [0, 1] }
    );
    let bad = Plane { point: Vec3::zeros(), normal: Vec3::zeros() };
    assert!(matches!(
        structure_volume(&model, t, &[z(0.0), bad]).unwrap_err(),
        VolumeError::InvalidPlane { index: 1, .. }
    ));
    let shell =
        sphere_shell(&mut model, Vec3::x() * 5.0, 0.3, ShellBase::Octahedron, 1, &opts(mat))
            .unwrap();
    assert_eq!(
        structure_volume(&model, shell, &[z(0.0)]).unwrap_err(),
        VolumeError::TooManyPlanes { loops: 0, planes: 1 }
    );
    assert_eq!(
        structure_volume(&model, 7, &[]).unwrap_err(),
        VolumeError::UnknownStructure { structure: 7, count: 2 }
    );
    assert_eq!(
        pfacets_volume(&model, &[0, 10_000], &[]).unwrap_err(),
        VolumeError::UnknownPFacet { pfacet: 10_000, count: model.pfacets.len() }
    );
    assert!(matches!(pfacets_volume(&model, &[], &[]), Err(VolumeError::NoPFacets { .. })));
}

#[test]
fn bad_topologies_are_errors_not_panics() {
    let (mut model, mat) = model_with_material(1000.0);
    let s = membrane_rectangle(
        &mut model,
        Vec3::zeros(),
        Vec3::x(),
        Vec3::y(),
        1.0,
        1.0,
        2,
        2,
        &opts(mat),
    )
    .unwrap();
    let all = pfacets_of(&model, s);
    assert_eq!(boundary_loops(&model, &all).unwrap().len(), 1);
    // one PFacet turned over
    let mut flipped = model.clone();
    flipped.pfacets[3].nodes.swap(1, 2);
    assert!(matches!(
        boundary_loops(&flipped, &all).unwrap_err(),
        VolumeError::InconsistentOrientation { .. }
    ));
    // PFacet 0 with a turned-over copy (8): a closed two-sided pillow of no volume; with a
    // third copy (9) its edges are on three PFacets
    let mut pillow = model.clone();
    let mut turned = pillow.pfacets[0];
    turned.nodes.swap(1, 2);
    pillow.pfacets.push(turned);
    pillow.pfacets.push(pillow.pfacets[0]);
    assert!(boundary_loops(&pillow, &[0, 8]).unwrap().is_empty());
    assert!(pfacets_volume(&pillow, &[0, 8], &[]).unwrap().abs() < 1e-15);
    assert!(matches!(
        boundary_loops(&pillow, &[0, 8, 9]).unwrap_err(),
        VolumeError::NonManifoldEdge { count: 3, .. }
    ));
    // two PFacets touching at one node only (a bow tie): two boundary edges start there
    let corners: Vec<PFacetId> =
        all.iter().copied().filter(|&f| model.pfacets[f as usize].nodes.contains(&4)).collect();
    let bow_tie = [corners[0], *corners.last().unwrap()];
    let shared: Vec<u32> = model.pfacets[bow_tie[0] as usize]
        .nodes
        .iter()
        .copied()
        .filter(|n| model.pfacets[bow_tie[1] as usize].nodes.contains(n))
        .collect();
    assert_eq!(shared, vec![4], "the two PFacets share node 4 only");
    assert!(matches!(
        boundary_loops(&model, &bow_tie).unwrap_err(),
        VolumeError::UnchainedBoundary { node: 4, .. }
    ));
}

//! Chains, cables and beams from a polyline (YADE's `cylinderConnection`): one node per point,
//! one connection per consecutive pair.

use super::skeleton::{add_skeleton, Skeleton, StructureOptions};
use crate::error::{count, finite_point, positive, BuildError};
use crate::{Model, StructureId};
use flexdem_geom::{Real, Vec3};
use std::f64::consts::TAU;

/// Adds a chain through `points`: node `i` (the structure's `nodes.start + i`) at `points[i]`
/// and connection `i` joining nodes `i` and `i + 1`. The end nodes are the structure's first
/// and last nodes ([`Model::structure_ends`]). Needs at least 2 points, all finite, and no
/// zero-length segment (relative to the polyline's size).
pub fn chain(
    model: &mut Model,
    points: &[Vec3],
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    if points.len() < 2 {
        return Err(BuildError::TooFewPoints { count: points.len() });
    }
    let n = points.len() as u32;
    let skeleton = Skeleton {
        points: points.to_vec(),
        edges: (0..n - 1).map(|i| [i, i + 1]).collect(),
        faces: vec![],
    };
    add_skeleton(model, &skeleton, opts)
}

/// `n_segments + 1` equally spaced points from `a` to `b` (both included).
pub fn straight_line(a: Vec3, b: Vec3, n_segments: usize) -> Result<Vec<Vec3>, BuildError> {
    finite_point("a", a)?;
    finite_point("b", b)?;
    let n = count("n_segments", n_segments, 1)?;
    Ok((0..=n).map(|i| a.lerp(&b, i as Real / n as Real)).collect())
}

/// Points of a helix about the z axis through `center`: point k is
/// `center + (R cos θ, R sin θ, pitch·θ/2π)` with θ = 2π·turns·k/n, n = round(turns ·
/// segments_per_turn) segments (at least 1), so it starts at `center + (R, 0, 0)` and rises
/// by `pitch` per turn (a negative pitch gives a left-handed helix; 0 a circle). Rotate the
/// points for another axis.
pub fn helix(
    center: Vec3,
    radius: Real,
    pitch: Real,
    turns: Real,
    segments_per_turn: usize,
) -> Result<Vec<Vec3>, BuildError> {
    finite_point("center", center)?;
    positive("radius", radius)?;
    positive("turns", turns)?;
    if !pitch.is_finite() {
        return Err(BuildError::InvalidParameter {
            name: "pitch",
            value: pitch.to_string(),
            expected: "a finite value",
        });
    }
    let per_turn = count("segments_per_turn", segments_per_turn, 3)?;
    let n = count(
        "turns · segments_per_turn",
        ((turns * per_turn as Real).round() as usize).max(1),
        1,
    )?;
    Ok((0..=n)
        .map(|k| {
            let theta = TAU * turns * k as Real / n as Real;
            center + Vec3::new(radius * theta.cos(), radius * theta.sin(), pitch * theta / TAU)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support::*;
    use std::f64::consts::PI;

    /// validation.md case 5: a chain of N equal connections has total mass N·πr²L·ρ; end
    /// nodes hold half of an inner node.
    #[test]
    fn validation_case_5_chain_mass() {
        let (mut model, mat) = model_with_material(7850.0);
        let (n, length, r) = (10usize, 1.0, 0.01);
        let pts = straight_line(Vec3::zeros(), Vec3::new(length, 0.0, 0.0), n).unwrap();
        let s = chain(&mut model, &pts, &StructureOptions::new("bar", r, mat)).unwrap();
        let st = model.structure(s).unwrap().clone();
        assert_eq!(st.nodes.len(), n + 1);
        assert_eq!(st.connections.len(), n);
        assert_eq!(st.pfacets.len(), 0);
        let seg = length / n as Real;
        let expected = n as Real * PI * r * r * seg * 7850.0;
        assert_rel(model.total_mass(), expected, 1e-13);
        let m = &model.particles.mass;
        let (first, last) = (st.nodes.start as usize, st.nodes.end as usize - 1);
        for inner in first + 1..last {
            assert_rel(m[first], 0.5 * m[inner], 1e-13);
            assert_rel(m[last], 0.5 * m[inner], 1e-13);
            assert_rel(model.particles.inertia[first], 0.5 * model.particles.inertia[inner], 1e-13);
        }
        assert_eq!(model.structure_ends(s).unwrap(), vec![first as u32, last as u32]);
        for c in &model.connections {
            assert_rel(c.rest_length, seg, 1e-13);
        }
        model.validate().unwrap();
    }

    #[test]
    fn helix_points_lie_on_the_helix() {
        let c = Vec3::new(1.0, 2.0, 3.0);
        let pts = helix(c, 0.5, 0.2, 2.5, 12).unwrap();
        assert_eq!(pts.len(), 31);
        for p in &pts {
            let d = p - c;
            assert_rel((d.x * d.x + d.y * d.y).sqrt(), 0.5, 1e-12);
        }
        assert_rel((pts[0] - c - Vec3::new(0.5, 0.0, 0.0)).norm() + 1.0, 1.0, 1e-12);
        assert_rel(pts[30].z - c.z, 0.5, 1e-12);
        let (mut model, mat) = model_with_material(1000.0);
        let s = chain(&mut model, &pts, &StructureOptions::new("spring", 0.01, mat)).unwrap();
        assert_eq!(model.structure(s).unwrap().connections.len(), 30);
        model.validate().unwrap();
    }

    #[test]
    fn chain_rejects_bad_inputs_and_adds_nothing() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("c", 0.01, mat);
        let one = [Vec3::zeros()];
        assert!(matches!(
            chain(&mut model, &one, &opts),
            Err(BuildError::TooFewPoints { count: 1 })
        ));
        let nan = [Vec3::zeros(), Vec3::new(f64::NAN, 0.0, 0.0)];
        let err = chain(&mut model, &nan, &opts).unwrap_err();
        assert!(matches!(err, BuildError::NonFinitePoint { index: 1, .. }), "{err}");
        let dup = [Vec3::zeros(), Vec3::x(), Vec3::x(), Vec3::new(2.0, 0.0, 0.0)];
        let err = chain(&mut model, &dup, &opts).unwrap_err();
        assert!(matches!(err, BuildError::ZeroLengthSegment { segment: 1, points: [1, 2], .. }));
        assert!(err.to_string().contains("segment 1"), "{err}");
        let bad_r = StructureOptions::new("c", -1.0, mat);
        let err = chain(&mut model, &[Vec3::zeros(), Vec3::x()], &bad_r).unwrap_err();
        assert!(err.to_string().contains("radius = -1"), "{err}");
        let bad_m = StructureOptions::new("c", 0.1, 7);
        let err = chain(&mut model, &[Vec3::zeros(), Vec3::x()], &bad_m).unwrap_err();
        assert!(err.to_string().contains("material 7"), "{err}");
        assert_eq!(model.particles.len(), 0);
        assert!(model.structures.is_empty());
        assert!(straight_line(Vec3::zeros(), Vec3::x(), 0).is_err());
        assert!(helix(Vec3::zeros(), 1.0, 0.1, 1.0, 2).is_err());
        assert!(helix(Vec3::zeros(), 0.0, 0.1, 1.0, 8).is_err());
        assert!(helix(Vec3::zeros(), 1.0, f64::INFINITY, 1.0, 8).is_err());
    }
}

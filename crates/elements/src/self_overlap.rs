//! Structures that overlap themselves: two elements of one structure that share no node (so
//! the engine lets them touch) but whose hulls interpenetrate (a helix of pitch 0, a chain of
//! segments shorter than its diameter, a mesh with nodes thicker than its cells). Built that
//! way, the engine would push them apart from the first step, and the collider would list
//! every such pair as a candidate: a million segments 1 µm long and 1 cm thick overlap
//! 20 000 others each, 2·10¹⁰ pairs (the 16 GiB allocation of issue 13). The scene reader
//! refuses them with [`self_overlap`], naming the two elements and where they are.
//!
//! The search is a cell list over the structure's collidable elements (connections of no
//! PFacet, PFacets, as in the engine's collider) that stops at the first overlap, so a dense
//! overlapping structure is found at once: linear time and memory in its elements.

use crate::{Model, StructureId};
use flexdem_geom::{
    closest_points_segment_segment, closest_points_segment_triangle,
    closest_points_triangle_triangle, Real, Vec3,
};

/// Pair tests after which the search gives up (and the structure is accepted): bounds the
/// time on structures whose boxes overlap much but whose elements do not.
const MAX_TESTS: usize = 20_000_000;

/// Relative tolerance: elements touching at rest (a chain of segments exactly as long as its
/// diameter) are not an overlap.
const TOUCHING: Real = 1e-9;

/// A box may cover at most this many cells per axis before it is tested against every box.
const MAX_CELLS_PER_AXIS: i64 = 4;

/// A collidable element of the structure: its nodes (2 or 3) and radius.
#[derive(Clone, Copy, Debug)]
struct Item {
    /// `("connection" | "PFacet", id within the structure)`.
    what: (&'static str, u32),
    nodes: [u32; 3],
    count: usize,
    radius: Real,
}

impl Item {
    fn nodes(&self) -> &[u32] {
        &self.nodes[..self.count]
    }
}

/// Two elements of one structure that overlap at the start.
#[derive(Clone, Debug)]
pub struct SelfOverlap {
    /// The first element, e.g. `connection 0 (nodes 0–1)`, ids within the structure.
    pub first: String,
    /// The second element.
    pub second: String,
    /// Distance between their skeletons (m).
    pub distance: Real,
    /// Sum of their radii (m).
    pub radii: Real,
    /// Midpoint of their closest points.
    pub at: Vec3,
}

/// The first pair of elements of structure `id` that share no node and overlap (skeleton
/// distance below the sum of their radii by more than a relative 1e-9), if any is found. Gives
/// up (None) after 2·10⁷ exact tests of pairs whose boxes overlap but whose elements do not.
/// Element and node ids in the answer count from the structure's first.
pub fn self_overlap(model: &Model, id: StructureId) -> Option<SelfOverlap> {
    let st = model.structures.get(id as usize)?;
    let pos = &model.particles.pos;
    let mut in_pfacet = vec![false; st.connections.len()];
    for f in st.pfacets.clone() {
        for &k in &model.pfacets[f as usize].connections {
            if let Some(slot) = k.checked_sub(st.connections.start) {
                if let Some(b) = in_pfacet.get_mut(slot as usize) {
                    *b = true;
                }
            }
        }
    }
    let mut items = Vec::new();
    for (slot, k) in st.connections.clone().enumerate() {
        if !in_pfacet[slot] {
            let c = &model.connections[k as usize];
            items.push(Item {
                what: ("connection", slot as u32),
                nodes: [c.nodes[0], c.nodes[1], 0],
                count: 2,
                radius: c.radius,
            });
        }
    }
    for (slot, k) in st.pfacets.clone().enumerate() {
        let f = &model.pfacets[k as usize];
        items.push(Item {
            what: ("PFacet", slot as u32),
            nodes: f.nodes,
            count: 3,
            radius: f.radius,
        });
    }
    let boxes: Vec<(Vec3, Vec3)> = items
        .iter()
        .map(|it| {
            let (lo, hi) = it.nodes().iter().fold(
                (Vec3::repeat(Real::INFINITY), Vec3::repeat(Real::NEG_INFINITY)),
                |(lo, hi), &n| (lo.inf(&pos[n as usize]), hi.sup(&pos[n as usize])),
            );
            (lo.add_scalar(-it.radius), hi.add_scalar(it.radius))
        })
        .collect();
    let mut extents: Vec<Real> = boxes.iter().map(|(lo, hi)| (hi - lo).max()).collect();
    if extents.len() < 2 || !extents.iter().all(|e| e.is_finite()) {
        return None;
    }
    let mid = extents.len() / 2;
    let (_, median, _) = extents.select_nth_unstable_by(mid, |a, b| a.total_cmp(b));
    let h = 2.0 * median.max(Real::MIN_POSITIVE);
    let origin = boxes.iter().fold(Vec3::repeat(Real::INFINITY), |m, b| m.inf(&b.0));
    let cell = |p: &Vec3| -> [i64; 3] { std::array::from_fn(|k| ((p[k] - origin[k]) / h) as i64) };
    let mut entries: Vec<([i64; 3], u32)> = Vec::new();
    let mut large = Vec::new();
    for (i, (lo, hi)) in boxes.iter().enumerate() {
        let (a, b) = (cell(lo), cell(hi));
        if (0..3).any(|k| b[k] - a[k] >= MAX_CELLS_PER_AXIS) {
            large.push(i);
            continue;
        }
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    entries.push(([x, y, z], i as u32));
                }
            }
        }
    }
    entries.sort_unstable();
    let mut tests = 0usize;
    let mut test = |i: usize, j: usize| -> Option<Option<SelfOverlap>> {
        let ((lo_i, hi_i), (lo_j, hi_j)) = (boxes[i], boxes[j]);
        if (0..3).any(|k| lo_i[k] > hi_j[k] || lo_j[k] > hi_i[k]) {
            return Some(None);
        }
        let (a, b) = (&items[i], &items[j]);
        if a.nodes().iter().any(|n| b.nodes().contains(n)) {
            return Some(None);
        }
        tests += 1;
        if tests > MAX_TESTS {
            return None;
        }
        Some(overlap(model, st.nodes.start, a, b))
    };
    let mut start = 0;
    while start < entries.len() {
        let end = start + entries[start..].iter().take_while(|e| e.0 == entries[start].0).count();
        for a in start..end {
            for b in a + 1..end {
                match test(entries[a].1 as usize, entries[b].1 as usize)? {
                    Some(found) => return Some(found),
                    None => continue,
                }
            }
        }
        start = end;
    }
    for &i in &large {
        for j in 0..items.len() {
            if j != i {
                if let Some(found) = test(i, j)? {
                    return Some(found);
                }
            }
        }
    }
    None
}

/// The overlap of two elements that share no node, if they overlap (node ids counted from
/// `first_node`, the structure's first).
fn overlap(model: &Model, first_node: u32, a: &Item, b: &Item) -> Option<SelfOverlap> {
    let pos = &model.particles.pos;
    let p = |it: &Item, k: usize| pos[it.nodes[k] as usize];
    let (first, second) = if a.count <= b.count { (a, b) } else { (b, a) };
    let (d2, x, y) = match (first.count, second.count) {
        (2, 2) => {
            let c = closest_points_segment_segment(
                &p(first, 0),
                &p(first, 1),
                &p(second, 0),
                &p(second, 1),
            );
            (c.distance_squared, c.point_a, c.point_b)
        }
        (2, _) => {
            let c = closest_points_segment_triangle(
                &p(first, 0),
                &p(first, 1),
                &p(second, 0),
                &p(second, 1),
                &p(second, 2),
            );
            (c.distance_squared, c.point_segment, c.point_triangle)
        }
        _ => {
            let c = closest_points_triangle_triangle(
                &p(first, 0),
                &p(first, 1),
                &p(first, 2),
                &p(second, 0),
                &p(second, 1),
                &p(second, 2),
            );
            (c.distance_squared, c.point_0, c.point_1)
        }
    };
    let radii = a.radius + b.radius;
    let distance = d2.sqrt();
    if distance >= radii * (1.0 - TOUCHING) {
        return None;
    }
    let describe = |it: &Item| {
        let nodes: Vec<String> =
            it.nodes().iter().map(|n| n.saturating_sub(first_node).to_string()).collect();
        format!("{} {} (nodes {})", it.what.0, it.what.1, nodes.join("–"))
    };
    Some(SelfOverlap {
        first: describe(first),
        second: describe(second),
        distance,
        radii,
        at: 0.5 * (x + y),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support::model_with_material;
    use crate::builders::{chain, helix, membrane_rectangle, straight_line};
    use crate::StructureOptions;

    #[test]
    fn a_chain_thicker_than_its_segments_overlaps_itself() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("beam", 0.01, mat);
        // segments 1 µm long, 1 cm thick: connection 0 overlaps connection 2
        let points = straight_line(Vec3::zeros(), Vec3::x(), 100_000).unwrap();
        let s = chain(&mut model, &points, &opts).unwrap();
        let o = self_overlap(&model, s).unwrap();
        assert_eq!(
            (o.first.as_str(), o.second.as_str()),
            ("connection 0 (nodes 0–1)", "connection 2 (nodes 2–3)")
        );
        assert!(o.distance < 1.1e-5 && o.radii == 0.02, "{o:?}");
        // segments exactly as long as the diameter touch at rest: no overlap
        let points = straight_line(Vec3::zeros(), Vec3::x() * 0.2, 10).unwrap();
        let s = chain(&mut model, &points, &StructureOptions::new("touching", 0.01, mat)).unwrap();
        assert!(self_overlap(&model, s).is_none());
    }

    #[test]
    fn a_helix_of_pitch_zero_overlaps_itself_and_a_proper_one_does_not() {
        let (mut model, mat) = model_with_material(1000.0);
        let flat = helix(Vec3::zeros(), 0.1, 0.0, 2.0, 12).unwrap();
        let s = chain(&mut model, &flat, &StructureOptions::new("flat", 0.01, mat)).unwrap();
        let o = self_overlap(&model, s).unwrap();
        assert!(o.distance < 1e-12, "{o:?}");
        let open = helix(Vec3::x() * 5.0, 0.1, 0.05, 2.0, 12).unwrap();
        let s = chain(&mut model, &open, &StructureOptions::new("open", 0.01, mat)).unwrap();
        assert!(self_overlap(&model, s).is_none());
    }

    #[test]
    fn a_membrane_overlaps_itself_only_with_nodes_thicker_than_its_cells() {
        let (mut model, mat) = model_with_material(1000.0);
        let (u, v) = (Vec3::x(), Vec3::y());
        let thin = StructureOptions::new("thin", 0.002, mat);
        let s =
            membrane_rectangle(&mut model, Vec3::zeros(), u, v, 1.0, 1.0, 16, 16, &thin).unwrap();
        assert!(self_overlap(&model, s).is_none());
        let thick = StructureOptions::new("thick", 0.05, mat);
        let at = Vec3::z() * 3.0;
        let s = membrane_rectangle(&mut model, at, u, v, 1.0, 1.0, 16, 16, &thick).unwrap();
        let o = self_overlap(&model, s).unwrap();
        assert!(o.first.starts_with("PFacet") && o.second.starts_with("PFacet"), "{o:?}");
    }
}

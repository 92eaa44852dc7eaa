//! Collision detection (model.md §5): the collidable elements, their boxes grown by a Verlet
//! distance, and the candidate pairs, rebuilt when any particle (node or sphere) has moved by
//! more than half the Verlet distance since the last build (YADE watches only each element's
//! first node).
//!
//! Collidable elements are the free spheres, the connections that belong to no PFacet, and
//! the PFacets (a PFacet's edges and nodes are part of it). Nodes are touched only through
//! their elements, except by walls, which touch every particle (a plane's deepest point on a
//! swept element is at a node).

use crate::broad_phase::BroadPhase;
use flexdem_elements::touching::Element;
use flexdem_elements::{Model, ParticleKind};
use flexdem_geom::{aabb_sphere, aabb_swept_segment, aabb_swept_triangle, Aabb, Real, Vec3};
use rayon::prelude::*;

/// No element for this id.
pub(crate) const NONE: u32 = u32::MAX;

/// The collidable elements and their candidate pairs.
#[derive(Clone, Debug, Default)]
pub struct Collider {
    /// Collidable elements; a pair refers to them by index.
    pub elements: Vec<Element>,
    /// Collidable index of each free sphere (by particle id), or `NONE`.
    pub(crate) sphere_element: Vec<u32>,
    /// Collidable index of each connection, or `NONE` (connections of PFacets).
    pub(crate) connection_element: Vec<u32>,
    /// Collidable index of each PFacet.
    pub(crate) pfacet_element: Vec<u32>,
    /// Candidate pairs `(i, j)`, `i < j`, indices into `elements`, sorted.
    pub pairs: Vec<(u32, u32)>,
    /// Candidate (wall, particle) pairs, sorted.
    pub wall_pairs: Vec<(u32, u32)>,
    /// Verlet distance (m).
    pub verlet: Real,
    /// Particle positions at the last build.
    reference: Vec<Vec3>,
    /// Wall points at the last build.
    wall_reference: Vec<Vec3>,
    boxes: Vec<Aabb>,
    broad: BroadPhase,
    /// Number of builds so far.
    pub builds: u64,
}

impl Collider {
    /// The collidable elements of `model`, with a Verlet distance of `verlet_factor` times
    /// the smallest radius of a particle or element.
    pub fn new(model: &Model, verlet_factor: Real) -> Self {
        let p = &model.particles;
        let mut c = Collider {
            sphere_element: vec![NONE; p.len()],
            connection_element: vec![NONE; model.connections.len()],
            pfacet_element: vec![NONE; model.pfacets.len()],
            ..Default::default()
        };
        for i in 0..p.len() {
            if p.kind[i] == ParticleKind::Sphere {
                c.sphere_element[i] = c.elements.len() as u32;
                c.elements.push(Element::Particle(i as u32));
            }
        }
        let mut in_pfacet = vec![false; model.connections.len()];
        for f in &model.pfacets {
            for &k in &f.connections {
                in_pfacet[k as usize] = true;
            }
        }
        for (k, _) in model.connections.iter().enumerate() {
            if !in_pfacet[k] {
                c.connection_element[k] = c.elements.len() as u32;
                c.elements.push(Element::Connection(k as u32));
            }
        }
        for (k, _) in model.pfacets.iter().enumerate() {
            c.pfacet_element[k] = c.elements.len() as u32;
            c.elements.push(Element::PFacet(k as u32));
        }
        let min_radius = p
            .radius
            .iter()
            .chain(model.connections.iter().map(|c| &c.radius))
            .chain(model.pfacets.iter().map(|f| &f.radius))
            .fold(Real::INFINITY, |a, &b| a.min(b));
        c.verlet = if min_radius.is_finite() { verlet_factor * min_radius } else { 0.0 };
        c
    }

    /// Whether some particle or wall has moved by more than half the Verlet distance since
    /// the last build (or there was none).
    pub fn needs_rebuild(&self, model: &Model) -> bool {
        let p = &model.particles;
        if self.reference.len() != p.len() || self.builds == 0 {
            return true;
        }
        let limit = (0.5 * self.verlet) * (0.5 * self.verlet);
        model
            .walls
            .iter()
            .zip(&self.wall_reference)
            .any(|(w, r)| (w.point - r).norm_squared() > limit)
            || (0..p.len())
                .into_par_iter()
                .any(|i| (p.pos[i] - self.reference[i]).norm_squared() > limit)
    }

    /// Mask of an element.
    fn mask(model: &Model, e: Element) -> u32 {
        match e {
            Element::Particle(i) => model.particles.mask[i as usize],
            Element::Connection(k) => model.connections[k as usize].mask,
            Element::PFacet(k) => model.pfacets[k as usize].mask,
        }
    }

    /// Nodes of an element (empty for a free sphere).
    fn nodes(model: &Model, e: Element) -> &[u32] {
        match e {
            Element::Particle(_) => &[],
            Element::Connection(k) => &model.connections[k as usize].nodes,
            Element::PFacet(k) => &model.pfacets[k as usize].nodes,
        }
    }

    /// Rebuilds the boxes and candidate pairs: boxes of the skeletons grown by the radius and
    /// by half the Verlet distance; pairs whose masks share a bit and that share no node.
    pub fn rebuild(&mut self, model: &Model) {
        let p = &model.particles;
        let margin = 0.5 * self.verlet;
        self.boxes.clear();
        self.boxes.extend(self.elements.iter().map(|&e| {
            let b = match e {
                Element::Particle(i) => aabb_sphere(&p.pos[i as usize], p.radius[i as usize]),
                Element::Connection(k) => {
                    let c = &model.connections[k as usize];
                    aabb_swept_segment(
                        &p.pos[c.nodes[0] as usize],
                        &p.pos[c.nodes[1] as usize],
                        c.radius,
                    )
                }
                Element::PFacet(k) => {
                    let f = &model.pfacets[k as usize];
                    let [a, b, d] = f.nodes.map(|n| p.pos[n as usize]);
                    aabb_swept_triangle(&a, &b, &d, f.radius)
                }
            };
            b.loosened(margin)
        }));
        let elements = &self.elements;
        let accept = |i: u32, j: u32| {
            let (a, b) = (elements[i as usize], elements[j as usize]);
            Self::mask(model, a) & Self::mask(model, b) != 0
                && !Self::nodes(model, a).iter().any(|n| Self::nodes(model, b).contains(n))
        };
        self.broad.overlapping_pairs(&self.boxes, accept, &mut self.pairs);

        self.wall_pairs.clear();
        for (w, wall) in model.walls.iter().enumerate() {
            for i in 0..p.len() {
                let gap = (p.pos[i] - wall.point).dot(&wall.normal) - p.radius[i];
                if gap <= self.verlet && (wall.mask & p.mask[i]) != 0 {
                    self.wall_pairs.push((w as u32, i as u32));
                }
            }
        }
        self.reference.clear();
        self.reference.extend_from_slice(&p.pos);
        self.wall_reference.clear();
        self.wall_reference.extend(model.walls.iter().map(|w| w.point));
        self.builds += 1;
    }
}

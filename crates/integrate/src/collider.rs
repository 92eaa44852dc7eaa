//! Collision detection (model.md §5): the collidable elements, their boxes grown by a Verlet
//! margin, and the candidate pairs, rebuilt when any particle (node or sphere) has moved by
//! more than the margin of an element it belongs to since the last build (YADE watches only
//! each element's first node).
//!
//! Each element has its own margin: half the Verlet factor times its size (the radius of its
//! bounding sphere: a sphere's radius, half a connection's length plus its radius, a PFacet's
//! circumradius about its centroid plus its radius). YADE uses one Verlet distance, a fraction
//! of the smallest radius, for the whole scene; on a membrane of 2 mm nodes and 40 mm cells hit
//! by a 0.1 m sphere that forces a rebuild nearly every step, while the element sizes give
//! margins of millimetres. Why it is safe: a pair left out had boxes apart, so its hulls were
//! more than r_a + r_b + m_a + m_b apart; until the next build no node of element a moves by more
//! than m_a (every particle's limit is the smallest margin of the elements holding it), and a
//! hull's points are convex combinations of its nodes, so the pair cannot have closed the gap.
//!
//! The boxes pair elements that a slab between their hulls keeps apart (a triangle beside the
//! next but one of a flat mesh: their boxes overlap where the triangles do not). So each
//! build tests every pair other than two free spheres with the prefilter's separating slabs
//! (`prefilter::proven_apart`), on the hulls grown by the margins, r_a + m_a and r_b + m_b,
//! and drops those it proves apart. Until the next build no node of element a moves by more
//! than m_a, so a's hull stays within m_a of its hull at the build, and a slab wider than
//! r_a + m_a + r_b + m_b at the build leaves one wider than r_a + r_b at every step to the
//! next. The pairs kept are in the same order and hold every pair that touches before the
//! next build, so the touchings, the contacts and every result are those of the whole list.
//! On the membrane of 10⁵ PFacets under spheres the test drops 76 % of the pairs (473 541 →
//! 112 448; 137 090 without the prefilter's distance of a sphere to a PFacet), which the
//! contact stage tested at every step; on the tube impact, 1 600 → 36 at each build.
//!
//! Memory: the margins and cell entries (at most 64 per element, 8 at most for a typical
//! box) are linear in the elements (the boxes are made from the nodes when the broad phase
//! asks, once per cell a box is in, and not kept); the candidate pairs are as many as the
//! pairs of overlapping boxes, linear at bounded density but not when a structure overlaps
//! itself: a chain of 10⁶ segments 1 µm long and 1 cm thick (a mutated `segments` of the
//! cantilever) has each connection's box over 20 000 others', 2·10¹⁰ pairs, and the pair
//! list asked for 16 GiB. No box test can drop those pairs without dropping real contacts;
//! such a structure cannot run anyway (its elements would push each other apart from the
//! first step), so the scene reader refuses it at once with `flexdem_elements::self_overlap`.
//!
//! Collidable elements are the free spheres, the connections that belong to no PFacet, and
//! the PFacets (a PFacet's edges and nodes are part of it). Nodes are touched only through
//! their elements, except by walls, which touch every particle (a plane's deepest point on a
//! swept element is at a node).

use crate::broad_phase::BroadPhase;
use crate::integrator::CHUNK;
use crate::parallel::{any_zipped, MIN_PARALLEL_CHEAP};
use crate::prefilter::{hull, proven_apart, write_hull, Hull};
use crate::step_work::{beyond_limit, chunk_minima, VerletWatch};
use flexdem_elements::touching::Element;
use flexdem_elements::{Model, ParticleKind};
use flexdem_geom::{aabb_sphere, aabb_swept_segment, aabb_swept_triangle, Real, Vec3};
use rayon::prelude::*;

/// Size of an element: the radius of a sphere holding it in its current configuration.
fn element_size(model: &Model, e: Element) -> Real {
    let h = hull(model, e);
    let c = h.centroid;
    let skeleton = &h.points[..h.count as usize];
    let reach = skeleton.iter().map(|x| (x - c).norm()).fold(0.0, Real::max);
    reach + h.radius
}

/// No element for this id.
pub(crate) const NONE: u32 = u32::MAX;

/// The collidable elements and their candidate pairs.
#[derive(Clone, Debug, Default)]
pub struct Collider {
    /// Collidable elements; a pair refers to them by index.
    pub elements: Vec<Element>,
    /// Collidable index of each free sphere (by particle id), or `NONE`.
    pub(crate) sphere_element: Vec<u32>,
    /// Collidable index of each connection, or `NONE` (connections of PFacets), up to the
    /// last collidable one ([`Collider::connection_element`] reads `NONE` past it: a
    /// membrane's connections, all PFacet edges, take no entry).
    connection_elements: Vec<u32>,
    /// Collidable index of each PFacet.
    pub(crate) pfacet_element: Vec<u32>,
    /// Candidate pairs `(i, j)`, `i < j`, indices into `elements`, sorted, but for the pairs
    /// of two free spheres, which are in `sphere_pairs`.
    pub pairs: Vec<(u32, u32)>,
    /// Candidate pairs of free spheres `(i, j)`, particle ids, `i < j`, sorted: those whose
    /// centres are within `r_i + r_j + m_i + m_j` (radii plus margins), the only ones that can
    /// touch before the next build (their boxes may overlap farther apart, at the corners).
    /// The engine hands the array to the neighbour list after each build (its keys), and it
    /// is empty until the next.
    pub sphere_pairs: Vec<(u32, u32)>,
    /// Candidate (wall, particle) pairs of the particles that are not free spheres, sorted.
    pub wall_pairs: Vec<(u32, u32)>,
    /// Candidate (wall, particle) pairs of the free spheres, sorted.
    pub sphere_wall_pairs: Vec<(u32, u32)>,
    /// Whether each element is in one of `pairs` (the others need no hull at a step).
    pub(crate) paired: Vec<bool>,
    /// Margin of each element (m): its boxes are grown by it (half its Verlet distance).
    pub margins: Vec<Real>,
    /// How far each particle may move before a rebuild (m): the smallest margin of the
    /// elements holding it (its own for a particle in no element).
    limits: Vec<Real>,
    /// How far a wall may move before a rebuild: the smallest particle limit.
    wall_limit: Real,
    /// How far each particle may move in one step before the run is called unstable: its
    /// radius, or the size of the smallest element holding it if larger.
    pub(crate) reach: Vec<Real>,
    /// Per chunk of the leapfrog (`integrator::CHUNK` particles), the smallest reach and the
    /// smallest limit of its particles: the leapfrog's checks read one number a chunk while
    /// no particle comes near them, where they read every particle's reach, reference and
    /// limit (40 bytes a particle, an eighth of the leapfrog's stream on the packing).
    pub(crate) chunk_reach: Vec<Real>,
    chunk_limits: Vec<Real>,
    /// Per chunk, a bound on how far any of its particles has moved since the last build
    /// (the leapfrog adds each step's largest `|v|·dt` and its round-off); ∞ when unknown
    /// (a particle moved by hand). Nothing here is saved: a new collider starts unbuilt.
    drift: Vec<Real>,
    /// Particle positions at the last build.
    reference: Vec<Vec3>,
    /// Wall points at the last build.
    wall_reference: Vec<Vec3>,
    broad: BroadPhase,
    /// Number of builds so far.
    pub builds: u64,
}

impl Collider {
    /// The collidable elements of `model`, each with a Verlet distance of `verlet_factor`
    /// times its size (see the module documentation).
    pub fn new(model: &Model, verlet_factor: Real) -> Self {
        let p = &model.particles;
        let mut c = Collider {
            sphere_element: vec![NONE; p.len()],
            connection_elements: vec![NONE; model.connections.len()],
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
                c.connection_elements[k] = c.elements.len() as u32;
                c.elements.push(Element::Connection(k as u32));
            }
        }
        let kept = c.connection_elements.iter().rposition(|&e| e != NONE).map_or(0, |k| k + 1);
        c.connection_elements.truncate(kept);
        c.connection_elements.shrink_to_fit();
        for (k, _) in model.pfacets.iter().enumerate() {
            c.pfacet_element[k] = c.elements.len() as u32;
            c.elements.push(Element::PFacet(k as u32));
        }
        let sizes: Vec<Real> = c.elements.iter().map(|&e| element_size(model, e)).collect();
        c.margins = sizes.iter().map(|&size| 0.5 * verlet_factor * size).collect();
        c.limits = vec![Real::INFINITY; p.len()];
        let mut smallest = vec![Real::INFINITY; p.len()];
        for ((&e, &m), &size) in c.elements.iter().zip(&c.margins).zip(&sizes) {
            let held: &[u32] = match e {
                Element::Particle(i) => &[i],
                _ => Self::nodes(model, e),
            };
            for &n in held {
                let n = n as usize;
                c.limits[n] = c.limits[n].min(m);
                smallest[n] = smallest[n].min(size);
            }
        }
        c.reach = p
            .radius
            .iter()
            .zip(&smallest)
            .map(|(&r, &s)| if s.is_finite() { r.max(s) } else { r })
            .collect();
        // a node in no collidable element is watched on its own radius (for walls)
        for (limit, &r) in c.limits.iter_mut().zip(&p.radius) {
            if *limit == Real::INFINITY {
                *limit = 0.5 * verlet_factor * r;
            }
        }
        c.wall_limit = c.limits.iter().copied().fold(Real::INFINITY, Real::min);
        c.chunk_reach = chunk_minima(&c.reach, CHUNK);
        c.chunk_limits = chunk_minima(&c.limits, CHUNK);
        c
    }

    /// Forgets how far the particles have moved since the last build (a particle was moved
    /// by hand): the leapfrog then checks every particle against its reference until the
    /// next build.
    pub(crate) fn forget_drift(&mut self) {
        self.drift.iter_mut().for_each(|d| *d = Real::INFINITY);
    }

    /// Sets each chunk's drift (`drift`, from the leapfrog's checks).
    pub(crate) fn set_drift(&mut self, drift: impl Iterator<Item = Real>) {
        for (d, new) in self.drift.iter_mut().zip(drift) {
            *d = new;
        }
    }

    /// Collidable index of connection `k`, or `NONE` (a PFacet's edge, or no such connection).
    #[inline]
    pub(crate) fn connection_element(&self, k: u32) -> u32 {
        self.connection_elements.get(k as usize).copied().unwrap_or(NONE)
    }

    /// Whether some particle or wall has moved by more than its limit since the last build
    /// (or there was none).
    pub fn needs_rebuild(&self, model: &Model) -> bool {
        self.needs_rebuild_after(model, None)
    }

    /// Where each particle was at the last build and how far it may move from there, for the
    /// leapfrog to watch the particles it moves (`step_work::VerletWatch`); none before a
    /// build, or when the particles are not those of the last build.
    pub(crate) fn verlet_watch(&self, particles: usize) -> Option<VerletWatch<'_>> {
        let built = self.builds > 0 && self.reference.len() == particles;
        built.then_some(VerletWatch {
            reference: &self.reference,
            limits: &self.limits,
            chunk_limits: &self.chunk_limits,
            drift: &self.drift,
        })
    }

    /// [`Collider::needs_rebuild`], with `particles_beyond` whether a particle has moved
    /// beyond its limit if that is known (the leapfrog watched the step's moves from the
    /// reference of this build, and nothing moved the particles since): then the
    /// particles are not looked at again.
    pub(crate) fn needs_rebuild_after(
        &self,
        model: &Model,
        particles_beyond: Option<bool>,
    ) -> bool {
        let p = &model.particles;
        if self.reference.len() != p.len() || self.builds == 0 {
            return true;
        }
        let wall_limit = self.wall_limit * self.wall_limit;
        let limits = &self.limits;
        debug_assert_eq!(limits.len(), p.len());
        model
            .walls
            .iter()
            .zip(&self.wall_reference)
            .any(|(w, r)| (w.point - r).norm_squared() > wall_limit)
            || particles_beyond.unwrap_or_else(|| {
                any_zipped(
                    p.pos.iter().zip(&self.reference).zip(limits),
                    p.pos.par_iter().zip(&self.reference).zip(limits),
                    |((x, x0), &limit)| beyond_limit(x, x0, limit),
                )
            })
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
    /// The structure of element `e` (`NO_STRUCTURE` for a free sphere).
    fn structure(model: &Model, e: Element) -> u32 {
        match e {
            Element::Particle(i) => model.particles.structure[i as usize],
            Element::Connection(k) => model.connections[k as usize].structure,
            Element::PFacet(k) => model.pfacets[k as usize].structure,
        }
    }

    fn nodes(model: &Model, e: Element) -> &[u32] {
        match e {
            Element::Particle(_) => &[],
            Element::Connection(k) => &model.connections[k as usize].nodes,
            Element::PFacet(k) => &model.pfacets[k as usize].nodes,
        }
    }

    /// Rebuilds the boxes and candidate pairs: boxes of the skeletons grown by the radius and
    /// by the element's margin; pairs whose masks share a bit, that share no node, that are
    /// not two parts of a structure whose self-contact is off, and whose hulls grown by their
    /// margins no slab separates (see the module documentation).
    pub fn rebuild(&mut self, model: &Model) {
        self.rebuild_with(model, &mut Vec::new());
    }

    /// [`Collider::rebuild`], with `hulls` a buffer for the elements' grown hulls (the
    /// contact stage's, which it writes anew at each step).
    pub(crate) fn rebuild_with(&mut self, model: &Model, hulls: &mut Vec<Hull>) {
        self.pair_boxes(model);
        self.mark_paired();
        self.drop_pairs_apart_until_next_build(model, hulls);
        self.mark_paired();
        let p = &model.particles;
        self.wall_pairs.clear();
        self.sphere_wall_pairs.clear();
        for (w, wall) in model.walls.iter().enumerate() {
            for i in 0..p.len() {
                let gap = (p.pos[i] - wall.point).dot(&wall.normal) - p.radius[i];
                if gap <= 2.0 * self.limits[i] && (wall.mask & p.mask[i]) != 0 {
                    if self.sphere_element[i] == NONE {
                        self.wall_pairs.push((w as u32, i as u32));
                    } else {
                        self.sphere_wall_pairs.push((w as u32, i as u32));
                    }
                }
            }
        }
        self.reference.clear();
        self.reference.extend_from_slice(&p.pos);
        self.drift.clear();
        self.drift.resize(p.len().div_ceil(CHUNK), 0.0);
        self.wall_reference.clear();
        self.wall_reference.extend(model.walls.iter().map(|w| w.point));
        self.builds += 1;
    }

    /// The pairs of overlapping boxes (grown by the margins) that the pairing rules accept:
    /// two free spheres in `sphere_pairs` (by particle id), the others in `pairs`.
    fn pair_boxes(&mut self, model: &Model) {
        let p = &model.particles;
        let (elements, margins) = (&self.elements, &self.margins);
        let accept = |i: u32, j: u32| {
            let (a, b) = (elements[i as usize], elements[j as usize]);
            if let (Element::Particle(s), Element::Particle(t)) = (a, b) {
                // two free spheres: their centres within the radii plus margins (the boxes'
                // corners pair spheres 4× as many as can touch before the next build)
                let (s, t) = (s as usize, t as usize);
                let reach = p.radius[s] + p.radius[t] + margins[i as usize] + margins[j as usize];
                return p.mask[s] & p.mask[t] != 0
                    && (p.pos[t] - p.pos[s]).norm_squared() <= reach * reach
                    && !model.self_contact_off(p.structure[s], p.structure[t]);
            }
            Self::mask(model, a) & Self::mask(model, b) != 0
                && !Self::nodes(model, a).iter().any(|n| Self::nodes(model, b).contains(n))
                && !model.self_contact_off(Self::structure(model, a), Self::structure(model, b))
        };
        let two_spheres = |i: u32, j: u32| {
            matches!(
                (elements[i as usize], elements[j as usize]),
                (Element::Particle(_), Element::Particle(_))
            )
        };
        // each box made when the broad phase asks, from the nodes (none stored: 48 bytes an
        // element; the builds are a few per cent of the step)
        let count = elements.len();
        let box_of = |i: u32| {
            let b = match elements[i as usize] {
                Element::Particle(s) => aabb_sphere(&p.pos[s as usize], p.radius[s as usize]),
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
            b.loosened(margins[i as usize])
        };
        let (sphere_pairs, pairs) = (&mut self.sphere_pairs, &mut self.pairs);
        self.broad.overlapping_pairs_split(count, box_of, accept, two_spheres, sphere_pairs, pairs);
        self.name_sphere_pairs();
    }

    /// Drops from `pairs` those whose elements' hulls, grown by their margins, are proven
    /// apart (see the module documentation: they cannot touch before the next build); the
    /// others stay in order. The hulls, of the elements `paired` marks, are written in
    /// `hulls`.
    fn drop_pairs_apart_until_next_build(&mut self, model: &Model, hulls: &mut Vec<Hull>) {
        if self.pairs.is_empty() {
            return;
        }
        let unused = Hull::new([Vec3::zeros(); 3], 1, 0.0);
        hulls.resize(self.elements.len(), unused);
        let (elements, margins, paired) = (&self.elements, &self.margins, &self.paired);
        hulls.par_iter_mut().enumerate().with_min_len(MIN_PARALLEL_CHEAP).for_each(|(i, h)| {
            // (an element in no pair keeps a stale hull: none reads it)
            if paired[i] {
                write_hull(model, elements[i], h);
                h.radius += margins[i];
            }
        });
        let hulls = &*hulls;
        let apart = |&(i, j): &(u32, u32)| proven_apart(&hulls[i as usize], &hulls[j as usize]);
        let kept = self.pairs.par_iter().with_min_len(MIN_PARALLEL_CHEAP).filter(|p| !apart(p));
        self.pairs = kept.copied().collect();
    }

    /// Names the pairs of two free spheres (`sphere_pairs`, from the broad phase as element
    /// indices) by their particle ids (the broad phase kept those whose centres are within
    /// the sum of their radii and margins). Free spheres come first among the elements, in
    /// particle order, so the list stays sorted.
    fn name_sphere_pairs(&mut self) {
        let elements = &self.elements;
        for pair in &mut self.sphere_pairs {
            let (Element::Particle(i), Element::Particle(j)) =
                (elements[pair.0 as usize], elements[pair.1 as usize])
            else {
                unreachable!("the broad phase wrote only pairs of two free spheres here");
            };
            *pair = (i, j);
        }
    }

    /// Marks the elements of `pairs` in `paired`.
    fn mark_paired(&mut self) {
        let elements = &self.elements;
        self.paired.clear();
        self.paired.resize(elements.len(), false);
        for &(a, b) in &self.pairs {
            self.paired[a as usize] = true;
            self.paired[b as usize] = true;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_contact::Material;
    use flexdem_elements::builders::{chain, membrane_rectangle, straight_line};
    use flexdem_elements::StructureOptions;

    /// A cable after a membrane: the cable's connections are elements of their own, the
    /// membrane's (PFacet edges) are not and take no entry; a membrane alone stores none.
    #[test]
    fn only_connections_outside_pfacets_are_elements() {
        let mut model = Model::new();
        let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
        let opts = StructureOptions::new("m", 0.01, mat);
        let (x, z) = (Vec3::x(), Vec3::z());
        membrane_rectangle(&mut model, Vec3::zeros(), x, z, 1.0, 1.0, 2, 2, &opts).unwrap();
        let membrane_edges = model.connections.len() as u32;
        let alone = Collider::new(&model, 0.5);
        assert!(alone.connection_elements.is_empty());
        assert_eq!(alone.connection_element(0), NONE);
        let line = straight_line(Vec3::new(0.0, 2.0, 0.0), Vec3::new(1.0, 2.0, 0.0), 3).unwrap();
        chain(&mut model, &line, &StructureOptions::new("cable", 0.01, mat)).unwrap();
        let c = Collider::new(&model, 0.5);
        for k in 0..membrane_edges {
            assert_eq!(c.connection_element(k), NONE, "membrane edge {k}");
        }
        for k in membrane_edges..membrane_edges + 3 {
            let e = c.connection_element(k);
            assert_eq!(c.elements[e as usize], Element::Connection(k));
        }
        assert_eq!(c.connection_element(membrane_edges + 3), NONE, "no such connection");
        assert_eq!(c.elements.len(), 3 + model.pfacets.len());
    }

    /// A membrane of thick nodes with a cable along it and spheres on it, touching, near or
    /// apart (positions from `seed`).
    fn membrane_under_spheres(seed: u64) -> (Model, impl FnMut() -> Real) {
        let mut state = seed | 1;
        // xorshift64*, uniform in [0, 1)
        let mut uniform = move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as Real / (1u64 << 53) as Real
        };
        let mut model = Model::new();
        let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
        let opts = StructureOptions::new("m", 0.02, mat);
        let (x, y) = (Vec3::x(), Vec3::y());
        membrane_rectangle(&mut model, Vec3::zeros(), x, y, 1.0, 1.0, 8, 8, &opts).unwrap();
        let line =
            straight_line(Vec3::new(0.05, 0.5, 0.045), Vec3::new(0.95, 0.55, 0.05), 9).unwrap();
        chain(&mut model, &line, &StructureOptions::new("cable", 0.02, mat)).unwrap();
        for _ in 0..20 {
            let (u, v, gap) = (uniform(), uniform(), 0.04 * uniform() - 0.005);
            model.add_sphere(Vec3::new(u, v, 0.07 + gap), 0.05, mat).unwrap();
        }
        (model, uniform)
    }

    /// The pairs a build drops (their hulls grown by the margins proven apart) cannot touch
    /// before the next build: with every particle then moved by up to its limit (each in
    /// a direction of its own), each pair of overlapping boxes that touches (the exact
    /// kernel) is among the pairs kept, which are the others in the same order.
    #[test]
    fn a_pair_dropped_at_a_build_cannot_touch_before_the_next() {
        let (mut dropped, mut touching) = (0, 0);
        for seed in 0..24 {
            let (mut model, mut uniform) = membrane_under_spheres(seed);
            let mut c = Collider::new(&model, 0.5);
            c.pair_boxes(&model);
            let boxes = c.pairs.clone();
            c.rebuild(&model);
            let kept = c.pairs.clone();
            let mut rest = boxes.iter();
            assert!(kept.iter().all(|k| rest.any(|b| b == k)), "kept in order, from the boxes'");
            dropped += boxes.len() - kept.len();
            for (x, &limit) in model.particles.pos.iter_mut().zip(&c.limits) {
                let d = Vec3::new(uniform(), uniform(), uniform()).add_scalar(-0.5);
                *x += d.normalize() * (limit * uniform().sqrt());
            }
            assert!(!c.needs_rebuild(&model));
            for &(i, j) in &boxes {
                let (a, b) = (c.elements[i as usize], c.elements[j as usize]);
                if crate::contacts::candidate(&model, a, b).overlap() > 0.0 {
                    touching += 1;
                    assert!(kept.binary_search(&(i, j)).is_ok(), "seed {seed}: {a:?} {b:?}");
                }
            }
        }
        assert!(dropped > 1000 && touching > 100, "{dropped} dropped, {touching} touching");
    }

    /// A column of spheres falling apart under gravity (all moving, the lowest fastest).
    fn falling_spheres() -> crate::Simulation {
        let mut model = Model::new();
        let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
        for k in 0..40 {
            model.add_sphere(Vec3::new(0.0, 0.0, 0.03 * k as Real), 0.01, mat).unwrap();
        }
        let gravity = Vec3::new(0.0, 0.0, -9.81);
        crate::Simulation::new(model, crate::Settings { gravity, ..Default::default() }).unwrap()
    }

    /// [`falling_spheres`] with the energy watch off, for tests that move or kick a sphere
    /// by hand (energy the run did not make, which the watch would stop).
    fn falling_spheres_unwatched() -> crate::Simulation {
        let mut sim = falling_spheres();
        let settings = crate::Settings { energy_tolerance: None, ..sim.settings().clone() };
        sim.set_settings(settings).unwrap();
        sim
    }

    /// The leapfrog's watch of the moves is the collider's own test: after every step it
    /// says a particle passed its limit exactly when a scan of every particle does, and the
    /// collider rebuilds when it says so.
    #[test]
    fn the_leapfrogs_watch_is_the_colliders_scan() {
        let mut sim = falling_spheres();
        let (mut passed, mut builds) = (0, sim.collider().builds);
        for _ in 0..3000 {
            sim.step().unwrap();
            let (collider, model) = (&sim.pipeline.collider, &sim.state.model);
            let scan = collider.needs_rebuild_after(model, None);
            assert_eq!(sim.pipeline.moved_beyond, Some(scan));
            passed += usize::from(scan);
            let before = collider.builds;
            sim.step().unwrap();
            assert_eq!(sim.collider().builds, before + u64::from(scan));
            builds = sim.collider().builds;
        }
        assert!(passed > 2 && builds > 3, "{passed} passes, {builds} builds");
    }

    /// A particle moved by hand, by less than its limit, is still watched against its
    /// reference: the leapfrog's bound on the chunks' moves since the build (which lets it
    /// skip their references) no longer holds, and its watch stays the collider's scan.
    #[test]
    fn a_particle_moved_by_hand_within_its_limit_stays_watched() {
        // (a move by hand can make energy: the watch is off)
        let mut sim = falling_spheres_unwatched();
        sim.run(2).unwrap();
        let builds = sim.collider().builds;
        let (i, limit) = (30, sim.pipeline.collider.limits[30]);
        let x = sim.model().particles.pos[i];
        sim.set_position(i as u32, x + Vec3::new(0.9 * limit, 0.0, 0.0)).unwrap();
        sim.step().unwrap();
        assert_eq!(sim.collider().builds, builds, "not beyond its limit yet");
        sim.set_velocity(i as u32, Vec3::new(0.02 * limit / sim.dt(), 0.0, 0.0)).unwrap();
        let mut passed = false;
        for _ in 0..20 {
            sim.step().unwrap();
            let (collider, model) = (&sim.pipeline.collider, &sim.state.model);
            let scan = collider.needs_rebuild_after(model, None);
            assert_eq!(sim.pipeline.moved_beyond, Some(scan));
            passed |= scan;
            if scan {
                break;
            }
        }
        assert!(passed, "the particle moved 0.9 of its limit by hand, then 0.02 a step");
    }

    /// A particle moved by hand is seen at the next step, whatever the leapfrog watched:
    /// the collider rebuilds and the contact it makes is found. (Found late, it puts in
    /// energy that would stop the run: the energy watch is off here.)
    #[test]
    fn a_particle_moved_by_hand_is_seen_at_the_next_step() {
        let mut sim = falling_spheres_unwatched();
        sim.run(2).unwrap();
        assert_eq!(sim.pipeline.moved_beyond, Some(false));
        let (builds, below) = (sim.collider().builds, sim.model().particles.pos[20]);
        sim.set_position(30, below + Vec3::new(0.019, 0.0, 0.0)).unwrap();
        assert_eq!(sim.pipeline.moved_beyond, None);
        sim.step().unwrap();
        assert_eq!(sim.collider().builds, builds + 1);
        assert_eq!(sim.contact_count(), 1);
    }
}

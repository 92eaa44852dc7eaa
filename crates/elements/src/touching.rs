//! One contact per touching (model.md §3): which of the candidates a body has against the
//! elements of a connected structure are real contacts, and which are the same touching
//! seen from several elements.
//!
//! # The rule
//!
//! Every element near a body reports its closest point and the [`Feature`] that point lies
//! on (a node, an edge, a face). Features are canonical: a node shared by k connections is one
//! feature, an edge shared by two PFacets is one feature.
//!
//! Candidate `j` **dominates** candidate `i` when `j`'s two elements contain both of `i`'s
//! features (so `j` saw every point `i` stands for; for a structure touching itself, in
//! either order, since the same touching is found by the pair of elements on each side and
//! by the mirror pair), `j` is at the same place (its contact point within `i`'s contact size
//! `r₁ + r₂` of `i`'s, see [`same_place`]) and either
//! - `j` is closer by more than a tolerance: `i`'s point is not where the distance to the
//!   structure is locally smallest (a sphere over a face also "touches" the neighbouring
//!   edges and nodes: those candidates are dominated by the face's), or
//! - `j` is as close within the tolerance and ranks higher: its features have the higher total
//!   dimension (a face over an edge over a node), then the smaller feature key, then the
//!   smaller index. This settles the same touching seen from several elements: k elements
//!   around a node all report the node, two PFacets report their shared edge, and a point on a
//!   region boundary may be reported as edge by one element and face by the other.
//!
//! The contacts are the candidates no other candidate dominates. On a flat mesh a sphere has
//! one contact whatever it is over; in a concave valley it has one per face it touches (the
//! faces do not contain each other's features); two folds of a structure pressed together
//! have one contact per place they touch at, even where one element reaches two of them.
//!
//! Neighbouring elements compute the same closest point with different round-off; the sites
//! snap a point within a relative 1e-9 of a node or an edge onto it (`pairs::SNAP`), so a body
//! exactly over a node or an edge is reported on the same feature by every element. What is
//! left is a band of that width around the snapping limit where two elements may report two
//! different edges of a node at once; a body has to move exactly along an edge and stop
//! within 1e-9 of a node's snapping limit to land in it.
//!
//! The engine keys contacts by their features and, when a touching changes feature (a sphere
//! sliding from one element to the next), hands the old contact's state to the new one, so
//! the force has no jump and the shear history carries over.

use crate::pairs::Candidate;
use crate::virtual_sphere::Feature;
use crate::{Connection, Model, PFacet};
use flexdem_geom::Real;

/// An element that produces candidates: the collider's unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Element {
    /// A free sphere (or a node seen as a sphere).
    Particle(u32),
    /// A connection (cylinder).
    Connection(u32),
    /// A PFacet.
    PFacet(u32),
}

/// The connectivity needed to decide which features an element contains: the nodes of each
/// connection and the nodes and connections of each PFacet (`[0]` joins nodes 0–1, `[1]`
/// 1–2, `[2]` 2–0), read from the model's own lists (no copy).
#[derive(Clone, Copy, Debug)]
pub struct Topology<'a> {
    /// The connections (their `nodes`).
    pub connections: &'a [Connection],
    /// The PFacets (their `nodes` and `connections`).
    pub pfacets: &'a [PFacet],
}

impl<'a> Topology<'a> {
    /// The topology of `model`.
    pub fn of(model: &'a Model) -> Self {
        Topology { connections: &model.connections, pfacets: &model.pfacets }
    }

    /// Whether `element` contains `feature` (its own skeleton, an end node of a connection,
    /// a node or edge of a PFacet).
    pub fn element_contains(&self, element: Element, feature: Feature) -> bool {
        match (element, feature) {
            (Element::Particle(p), Feature::Particle(q)) => p == q,
            (Element::Connection(c), Feature::Edge(e)) => c == e,
            (Element::Connection(c), Feature::Particle(n)) => {
                self.connections[c as usize].nodes.contains(&n)
            }
            (Element::PFacet(f), Feature::Face(g)) => f == g,
            (Element::PFacet(f), Feature::Edge(e)) => {
                self.pfacets[f as usize].connections.contains(&e)
            }
            (Element::PFacet(f), Feature::Particle(n)) => {
                self.pfacets[f as usize].nodes.contains(&n)
            }
            _ => false,
        }
    }

    /// Whether two features are incident: equal, or one lies on the other (a node of an
    /// edge or face, an edge of a face).
    pub fn features_incident(&self, f: Feature, g: Feature) -> bool {
        if f == g {
            return true;
        }
        let (low, high) = if f.dimension() <= g.dimension() { (f, g) } else { (g, f) };
        match high {
            Feature::Edge(c) => self.element_contains(Element::Connection(c), low),
            Feature::Face(p) => self.element_contains(Element::PFacet(p), low),
            _ => false,
        }
    }
}

/// A candidate with the two elements that produced it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementCandidate {
    /// Element on body 1.
    pub element1: Element,
    /// Element on body 2.
    pub element2: Element,
    /// The closest features and distance.
    pub candidate: Candidate,
}

/// Tolerance under which two distances are the same touching: relative to the contact's
/// size (the sum of the radii) and to the distances themselves.
fn tie_tolerance(a: &Candidate, b: &Candidate) -> Real {
    let scale = a.site1.radius + a.site2.radius + a.distance.max(b.distance);
    1e-9 * scale
}

/// Whether candidate `j` touches where `i` does: their contact points (the midpoints of the
/// virtual-sphere centres) are within `i`'s contact size `r₁ + r₂`.
///
/// A rigid body's candidates against one structure always pass (a sphere of radius `R`
/// overlapping an edge at `h` from the face point below it has `h < √(2(R + r)δ)`, and the
/// midpoints are `h/2` apart). Two deformable folds do not: an element containing the node of
/// a touching may reach deeper into the other fold a whole element away, and without this
/// test that touching would be dropped, its node sinking through the fold unresisted (the
/// Brazier winding of the validation report did so until 2026-12).
pub fn same_place(j: &Candidate, i: &Candidate) -> bool {
    let middle = |c: &Candidate| 0.5 * (c.center1 + c.center2);
    (middle(j) - middle(i)).norm() <= i.site1.radius + i.site2.radius
}

/// Rank of a candidate among ties: total feature dimension first, then the smaller feature
/// pair (in either order: a touching of a structure with itself is found from both sides).
/// Higher is preferred.
fn outranks(j: &Candidate, i: &Candidate) -> Option<bool> {
    let dim = |c: &Candidate| c.site1.feature.dimension() + c.site2.feature.dimension();
    let (dj, di) = (dim(j), dim(i));
    if dj != di {
        return Some(dj > di);
    }
    let key = |c: &Candidate| {
        let (a, b) = (c.site1.feature, c.site2.feature);
        (a.min(b), a.max(b))
    };
    let (kj, ki) = (key(j), key(i));
    if kj != ki {
        return Some(kj < ki);
    }
    None
}

/// Whether candidate `j` (index `index_j`) dominates candidate `i` (index `index_i`): see
/// the module documentation. Indices break ties between equal features.
pub fn dominates(
    j: &ElementCandidate,
    index_j: usize,
    i: &ElementCandidate,
    index_i: usize,
    topology: &Topology<'_>,
) -> bool {
    let (f1, f2) = (i.candidate.site1.feature, i.candidate.site2.feature);
    let holds = |e1, e2| {
        topology.element_contains(j.element1, e1) && topology.element_contains(j.element2, e2)
    };
    // a structure touching itself is found from both sides: (element with f1, element with
    // f2) and the mirror pair; both are the same touching
    if index_j == index_i || !(holds(f1, f2) || holds(f2, f1)) {
        return false;
    }
    let (cj, ci) = (&j.candidate, &i.candidate);
    if !same_place(cj, ci) {
        return false;
    }
    let tol = tie_tolerance(ci, cj);
    if cj.distance < ci.distance - tol {
        return true;
    }
    if cj.distance > ci.distance + tol {
        return false;
    }
    outranks(cj, ci).unwrap_or(index_j < index_i)
}

/// Applies the one-contact-per-touching rule (module docs) to the candidates of one group
/// (one body against one structure, two structures, or a structure against itself) and
/// writes into `touchings`, in increasing order, the indices of the candidates that no other
/// candidate dominates and that overlap. This is the reference form, quadratic in the group's
/// size; the engine applies the same [`dominates`] test through an index of its candidates.
pub fn resolve_touchings(
    candidates: &[ElementCandidate],
    topology: &Topology<'_>,
    touchings: &mut Vec<usize>,
) {
    touchings.clear();
    for (i, ci) in candidates.iter().enumerate() {
        if ci.candidate.overlap() > 0.0
            && !candidates.iter().enumerate().any(|(j, cj)| dominates(cj, j, ci, i, topology))
        {
            touchings.push(i);
        }
    }
}

#[cfg(test)]
mod tests;

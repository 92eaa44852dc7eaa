//! Virtual spheres (paper §3–5): every contact on a structure is a contact with a sphere of
//! the element's radius placed on the element's skeleton, whose motion is interpolated from
//! the element's nodes and whose force is shared back among them.
//!
//! A [`Site`] says where on a body a contact sits: on a particle (a free sphere, or a node of
//! a structure), on an edge (a connection, at weights `(1 − t, t)`), or on a face (a PFacet, at
//! barycentric weights `(wa, wb, wc)`). The same weights interpolate the motion (eq 16) and
//! share the force (eq 17), so the power the contact force delivers to the virtual sphere is
//! the power delivered to the nodes.

use crate::Particles;
use flexdem_contact::LinkKinematicsMode;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// The canonical feature of the model a contact sits on. Features are what contacts are keyed
/// by, so two elements reporting the same point of a structure report the same feature: a
/// node shared by several connections is one `Particle`, an edge shared by two PFacets is one
/// `Edge` (the connection), a face is its PFacet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Feature {
    /// A particle: a free sphere, or a node of a structure (the vertex feature).
    Particle(u32),
    /// A connection (cylinder), or the edge of PFacets it is shared by.
    Edge(u32),
    /// A PFacet's face.
    Face(u32),
    /// A wall.
    Wall(u32),
}

impl Feature {
    /// Dimension of the feature's skeleton: 0 for particles (and walls' contact points),
    /// 1 for edges, 2 for faces.
    pub fn dimension(&self) -> u8 {
        match self {
            Feature::Particle(_) | Feature::Wall(_) => 0,
            Feature::Edge(_) => 1,
            Feature::Face(_) => 2,
        }
    }
}

/// Where a contact sits on one body: its feature, the nodes (particles) that carry it and
/// their weights. Unused node slots have weight 0 and node 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Site {
    /// The feature the contact point lies on.
    pub feature: Feature,
    /// The particles carrying the site: 1 for a particle, 2 for an edge, 3 for a face,
    /// 0 for a wall.
    pub nodes: [u32; 3],
    /// Interpolation and distribution weights, summing to 1 over the used slots.
    pub weights: [Real; 3],
    /// Radius of the (virtual) sphere: the particle's or the element's radius.
    pub radius: Real,
}

impl Site {
    /// A site on particle `id` (a free sphere or a node) of radius `radius`.
    pub fn particle(id: u32, radius: Real) -> Self {
        Site { feature: Feature::Particle(id), nodes: [id, 0, 0], weights: [1.0, 0.0, 0.0], radius }
    }

    /// A site on connection `connection` between particles `nodes` at parameter `t` (the
    /// point `(1 − t)·x0 + t·x1`).
    pub fn edge(connection: u32, nodes: [u32; 2], t: Real, radius: Real) -> Self {
        Site {
            feature: Feature::Edge(connection),
            nodes: [nodes[0], nodes[1], 0],
            weights: [1.0 - t, t, 0.0],
            radius,
        }
    }

    /// A site on the face of PFacet `pfacet` with nodes `nodes` at barycentric weights
    /// `weights` (paper eq 15).
    pub fn face(pfacet: u32, nodes: [u32; 3], weights: [Real; 3], radius: Real) -> Self {
        Site { feature: Feature::Face(pfacet), nodes, weights, radius }
    }

    /// A site on wall `wall` (no nodes: walls are kinematic).
    pub fn wall(wall: u32) -> Self {
        Site { feature: Feature::Wall(wall), nodes: [0; 3], weights: [0.0; 3], radius: 0.0 }
    }

    /// Number of node slots in use: 1, 2, 3, or 0 for a wall.
    pub fn node_count(&self) -> usize {
        match self.feature {
            Feature::Particle(_) => 1,
            Feature::Edge(_) => 2,
            Feature::Face(_) => 3,
            Feature::Wall(_) => 0,
        }
    }
}

/// Position and velocity of a virtual sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VirtualSphere {
    /// Centre on the element's skeleton.
    pub center: Vec3,
    /// Translational velocity.
    pub velocity: Vec3,
    /// Angular velocity.
    pub angular_velocity: Vec3,
}

/// Read-only view of the particles' kinematic state, indexed by particle id.
#[derive(Clone, Copy, Debug)]
pub struct Kinematics<'a> {
    /// Positions.
    pub pos: &'a [Vec3],
    /// Velocities.
    pub vel: &'a [Vec3],
    /// Angular velocities.
    pub ang_vel: &'a [Vec3],
    /// How a virtual sphere on a connection turns with the connection's axis: `Beam`, the
    /// rigid rotation rate `s × dv / L²`; `Yade`, YADE's `s × dv` (see [`virtual_sphere`]).
    pub link_mode: LinkKinematicsMode,
}

impl<'a> Kinematics<'a> {
    /// The kinematics of `particles`, virtual spheres on connections turning with their axis
    /// at its rigid rotation rate (`Beam`).
    pub fn of(particles: &'a Particles) -> Self {
        Kinematics {
            pos: &particles.pos,
            vel: &particles.vel,
            ang_vel: &particles.ang_vel,
            link_mode: LinkKinematicsMode::Beam,
        }
    }

    /// The same kinematics with virtual spheres on connections turning as `link_mode` says.
    pub fn with_link_mode(self, link_mode: LinkKinematicsMode) -> Self {
        Kinematics { link_mode, ..self }
    }
}

/// The virtual sphere of a particle, edge or face site, from its nodes' state.
///
/// - particle: the particle itself;
/// - edge at `t`, axis `s = x1 − x0`, `L = |s|` (paper §3): `P = (1 − t)x0 + t·x1`,
///   `v = (1 − t)v0 + t·v1`, `ω = [((1 − t)ω0 + tω1)·ŝ] ŝ + s × (v1 − v0)/L²` — the axial spin
///   interpolated plus the rigid rotation rate of the axis. YADE omits the `1/L²`
///   (`Ig2_Sphere_GridConnection_ScGridCoGeom`, Grid.cpp): with `k.link_mode` `Yade` the
///   rate is YADE's `s × (v1 − v0)`, which enters the shear velocity at the contact through
///   `ω × (c − P)`; on a net of 0.1 m links its shear differs from the exact one from the
///   first step of a contact on moving links (the validation's sphere on a net);
/// - face at weights `w` (paper eq 16): `P = Σ wᵢxᵢ`, `v = Σ wᵢvᵢ`, `ω = Σ wᵢωᵢ`.
///
/// For a rigid motion of the nodes (`vᵢ = V + Ω × xᵢ`, `ωᵢ = Ω`) this returns `V + Ω × P`
/// and `Ω`. Wall sites have no nodes and return zeros (the engine handles walls).
pub fn virtual_sphere(site: &Site, k: &Kinematics<'_>) -> VirtualSphere {
    match site.feature {
        Feature::Particle(_) => {
            let i = site.nodes[0] as usize;
            VirtualSphere { center: k.pos[i], velocity: k.vel[i], angular_velocity: k.ang_vel[i] }
        }
        Feature::Edge(_) => {
            let (i0, i1) = (site.nodes[0] as usize, site.nodes[1] as usize);
            let [w0, w1, _] = site.weights;
            let center = k.pos[i0] * w0 + k.pos[i1] * w1;
            let velocity = k.vel[i0] * w0 + k.vel[i1] * w1;
            let angular_velocity = edge_angular_velocity(
                &(k.pos[i1] - k.pos[i0]),
                &(k.vel[i1] - k.vel[i0]),
                &(k.ang_vel[i0] * w0 + k.ang_vel[i1] * w1),
                k.link_mode,
            );
            VirtualSphere { center, velocity, angular_velocity }
        }
        Feature::Face(_) => {
            let mut vs = VirtualSphere {
                center: Vec3::zeros(),
                velocity: Vec3::zeros(),
                angular_velocity: Vec3::zeros(),
            };
            for slot in 0..3 {
                let (i, w) = (site.nodes[slot] as usize, site.weights[slot]);
                vs.center += k.pos[i] * w;
                vs.velocity += k.vel[i] * w;
                vs.angular_velocity += k.ang_vel[i] * w;
            }
            vs
        }
        Feature::Wall(_) => VirtualSphere {
            center: Vec3::zeros(),
            velocity: Vec3::zeros(),
            angular_velocity: Vec3::zeros(),
        },
    }
}

/// Angular velocity of a virtual sphere on a segment with axis `s` whose ends move apart at
/// `dv = v1 − v0`, given the interpolated node spin `spin`: `(spin·ŝ)ŝ + s × dv / |s|²`
/// (`Beam`), or YADE's `(spin·ŝ)ŝ + s × dv` (`Yade`). A zero-length axis keeps the
/// interpolated spin.
fn edge_angular_velocity(s: &Vec3, dv: &Vec3, spin: &Vec3, mode: LinkKinematicsMode) -> Vec3 {
    let l2 = s.norm_squared();
    if !(l2 > Real::MIN_POSITIVE) {
        return *spin;
    }
    let axial = s * (spin.dot(s) / l2);
    match mode {
        LinkKinematicsMode::Beam => axial + s.cross(dv) / l2,
        LinkKinematicsMode::Yade => axial + s.cross(dv),
    }
}

/// The geometry and kinematics of a contact between two (real or virtual) spheres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactGeometry {
    /// Unit normal from sphere 1 to sphere 2.
    pub normal: Vec3,
    /// Overlap `δ = r1 + r2 − |P2 − P1|` (positive when touching).
    pub overlap: Real,
    /// Contact point `c = P1 + (r1 − δ/2)·n`, in the middle of the overlap.
    pub point: Vec3,
    /// Velocity of the contact point on sphere 2 minus on sphere 1:
    /// `(v2 + ω2 × (c − P2)) − (v1 + ω1 × (c − P1))`.
    pub relative_velocity: Vec3,
    /// Mean spin about the normal, `n·(ω1 + ω2)/2`, which turns the tangent plane.
    pub spin_about_normal: Real,
}

/// Contact geometry of two spheres (centres `s1.center`, `s2.center`, radii `r1`, `r2`),
/// keeping the side the contact was made on (model: crossing elements).
///
/// With `d = P2 − P1` and `n₀ = previous_normal` (the normal of the contact's last update, or
/// for a new contact the one it was made with):
/// - `d·n₀ > 0` (body 2's centre on the side of `n₀`, as when the contact was made):
///   `n = d/|d|`, `δ = r1 + r2 − |d|` (eq 1's overlap);
/// - `d·n₀ ≤ 0` (the skeletons have met or passed through each other, where `d/|d|` is
///   undefined or points the wrong way): `n = n₀`, `δ = r1 + r2 − d·n₀ ≥ r1 + r2`, the
///   overlap measured along the kept normal, so that the force keeps pushing body 2 back to
///   the side it came from, and grows the further through it has gone.
///
/// Both branches give `δ = r1 + r2` where `d = 0`. YADE has no such rule: its normal is
/// `d/|d|` and flips when two elements cross. For two spheres `n₀` is right (any direction
/// is); the sites of elements need the normal of their features,
/// [`contact_geometry_crossing`] with [`crossing_normal`], for the crossed force to be
/// conservative.
pub fn contact_geometry(
    s1: &VirtualSphere,
    r1: Real,
    s2: &VirtualSphere,
    r2: Real,
    previous_normal: &Vec3,
) -> ContactGeometry {
    contact_geometry_crossing(s1, r1, s2, r2, previous_normal, || *previous_normal)
}

/// [`contact_geometry`] where the normal of crossed skeletons (`d·n₀ ≤ 0`) is `crossing()`
/// (a unit vector with `crossing()·n₀ ≥ 0`, see [`crossing_normal`]) instead of `n₀`:
/// `δ = r1 + r2 − d·n`, with `n = crossing()` evaluated only when the skeletons have crossed.
pub fn contact_geometry_crossing(
    s1: &VirtualSphere,
    r1: Real,
    s2: &VirtualSphere,
    r2: Real,
    previous_normal: &Vec3,
    crossing: impl FnOnce() -> Vec3,
) -> ContactGeometry {
    let d = s2.center - s1.center;
    let dist = d.norm();
    let scale = r1 + r2 + s1.center.abs().max() + s2.center.abs().max();
    let along = d.dot(previous_normal);
    let (normal, separation) = if dist > 1e-14 * scale && along > 0.0 {
        (d / dist, dist)
    } else {
        let n = crossing();
        (n, d.dot(&n))
    };
    let overlap = r1 + r2 - separation;
    let point = s1.center + normal * (r1 - 0.5 * overlap);
    let v1 = s1.velocity + s1.angular_velocity.cross(&(point - s1.center));
    let v2 = s2.velocity + s2.angular_velocity.cross(&(point - s2.center));
    ContactGeometry {
        normal,
        overlap,
        point,
        relative_velocity: v2 - v1,
        spin_about_normal: 0.5 * normal.dot(&(s1.angular_velocity + s2.angular_velocity)),
    }
}

/// The normal of two crossed sites (model: crossing elements): the normal of the carriers
/// of their features, oriented like the previous normal `n₀`:
/// - a face on either side (node–face, edge–face): the face's normal
///   `(x₁ − x₀) × (x₂ − x₀)/|…|`; face–face (intersecting triangles): the face normal
///   closer to `±n₀`;
/// - edge–edge: the lines' common perpendicular `a × b/|a × b|` (`a`, `b` the edges'
///   directions), or `n₀` less its components along them when the edges are parallel;
/// - particle–edge: `n₀` less its component along the edge;
/// - otherwise (particle–particle) `n₀`.
///
/// `d·n` is then the signed distance of the carriers (plane, pair of lines) whose gradient
/// with respect to the nodes is `n` shared by the sites' weights, the distribution
/// [`distribute_force`] applies: the force of a crossed contact derives from its elastic
/// energy `½kn·δ²` and neither makes nor loses energy. A kept `n₀` does not: `d·n₀` changes
/// as the closest points slide along the features, which the force does not see.
pub fn crossing_normal(site1: &Site, site2: &Site, pos: &[Vec3], previous: &Vec3) -> Vec3 {
    let node = |site: &Site, slot: usize| pos[site.nodes[slot] as usize];
    let face_normal = |site: &Site| {
        (node(site, 1) - node(site, 0)).cross(&(node(site, 2) - node(site, 0))).try_normalize(0.0)
    };
    let direction = |site: &Site| (node(site, 1) - node(site, 0)).try_normalize(0.0);
    let less_along = |n: Vec3, a: Option<Vec3>| match a {
        Some(a) => n - a * n.dot(&a),
        None => n,
    };
    let candidate = match (site1.feature, site2.feature) {
        (Feature::Face(_), Feature::Face(_)) => match (face_normal(site1), face_normal(site2)) {
            (Some(a), Some(b)) => {
                Some(if a.dot(previous).abs() >= b.dot(previous).abs() { a } else { b })
            }
            (a, b) => a.or(b),
        },
        (Feature::Face(_), _) => face_normal(site1),
        (_, Feature::Face(_)) => face_normal(site2),
        (Feature::Edge(_), Feature::Edge(_)) => match (direction(site1), direction(site2)) {
            (Some(a), Some(b)) => {
                let c = a.cross(&b);
                if c.norm() > 1e-6 {
                    Some(c)
                } else {
                    Some(less_along(*previous, Some(a)))
                }
            }
            (a, b) => Some(less_along(less_along(*previous, a), b)),
        },
        (Feature::Edge(_), Feature::Particle(_)) => Some(less_along(*previous, direction(site1))),
        (Feature::Particle(_), Feature::Edge(_)) => Some(less_along(*previous, direction(site2))),
        _ => None,
    };
    match candidate.and_then(|n| n.try_normalize(1e-12)) {
        Some(n) if n.dot(previous) < 0.0 => -n,
        Some(n) => n,
        None => *previous,
    }
}

/// YADE's "non-ratcheting" relative velocity of a contact (`ScGeom::getIncidentVel` with
/// `avoidGranularRatcheting`, which YADE's grid and PFacet functors always use):
/// `α·(v₂ − v₁) − r₂·ω₂ × n − r₁·ω₁ × n` with `α = (r₁ + r₂)/(r₁ + r₂ − δ)`, the velocities
/// of the points at the undeformed radii instead of the contact point's
/// (`(v₂ + ω₂ × (c − P₂)) − (v₁ + ω₁ × (c − P₁))`, [`ContactGeometry::relative_velocity`]).
/// The two differ by O(δ/r) of the relative velocity, which at an impact is a few 1e-4 of it
/// and moves the shear force by as much. α grows without bound as δ nears `r₁ + r₂` (elements
/// that crossed can get there, docs/model.md §1): it is capped at its value for
/// `δ = (r₁ + r₂)/2`, 2, so that the velocity stays finite and of the right size.
pub fn non_ratcheting_relative_velocity(
    s1: &VirtualSphere,
    r1: Real,
    s2: &VirtualSphere,
    r2: Real,
    normal: &Vec3,
    overlap: Real,
) -> Vec3 {
    let alpha = (r1 + r2) / (r1 + r2 - overlap.min(0.5 * (r1 + r2)));
    (s2.velocity - s1.velocity) * alpha
        - s2.angular_velocity.cross(normal) * r2
        - s1.angular_velocity.cross(normal) * r1
}

/// Force and torque a contact puts on one node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeLoad {
    /// Particle id.
    pub node: u32,
    /// Force on the node.
    pub force: Vec3,
    /// Torque on the node.
    pub torque: Vec3,
}

/// Shares a force `force` acting at `point` on the virtual sphere of `site` (centre `center`)
/// among the site's nodes (`pos` are the particles' positions), so that the node loads are
/// the transpose of the interpolation of [`virtual_sphere`]: the power of the node loads
/// equals the power of `F` at the contact point moving with the virtual sphere, and the
/// contact neither creates nor destroys energy through the distribution.
///
/// With `τ = (c − P) × F` the moment of `F` about the virtual sphere's centre:
/// - particle: the force and `τ` on the particle;
/// - face (paper eq 17): node k receives `wₖ·F` and `wₖ·τ`;
/// - edge at `t`, axis `s = x₁ − x₀`: node k receives `wₖ·F` and the axial part of the moment
///   `wₖ·(τ·ŝ)ŝ`; the perpendicular part `τ⊥` goes to the nodes as the force couple
///   `∓ τ⊥ × s / |s|²`, whose moment is `τ⊥` and whose power is `τ⊥·(s × Δv)/|s|²`, the
///   rigid rotation of the axis that the edge's interpolated spin contains. (Sharing `τ⊥` as
///   node torques, as model.md §3 words it, does not match that spin: edge contacts with
///   friction then make or lose energy.)
///
/// In every case the node forces sum to `F` and their moments about any point `O` sum to
/// `(c − O) × F`. Unused slots (and walls) get zero loads.
pub fn distribute_force(
    site: &Site,
    pos: &[Vec3],
    center: &Vec3,
    point: &Vec3,
    force: &Vec3,
) -> [NodeLoad; 3] {
    distribute_force_as(LinkKinematicsMode::Beam, site, pos, center, point, force)
}

/// [`distribute_force`] for the link kinematics `mode`. `Beam` is [`distribute_force`].
/// `Yade` shares an edge contact's whole moment as node torques `wₖ·τ`, as YADE's
/// `Law2_ScGridCoGeom_FrictPhys_CundallStrack` does: with YADE's spin of the virtual sphere
/// (`s × Δv`, [`virtual_sphere`]) this is YADE's pair, and like YADE's it does not conserve
/// energy (the moment's perpendicular part works on the nodes' spins, which the contact's
/// kinematics do not see). Sharing that part as the force couple instead, with YADE's spin,
/// made a sphere resting on four sliding contacts rock at a growing amplitude (the
/// validation's sphere on a net: its spin grew from 1e-11 to 8e-4 rad/s, YADE's stayed at
/// 1e-10). Particles and faces are shared alike in both modes.
pub fn distribute_force_as(
    mode: LinkKinematicsMode,
    site: &Site,
    pos: &[Vec3],
    center: &Vec3,
    point: &Vec3,
    force: &Vec3,
) -> [NodeLoad; 3] {
    let torque = (point - center).cross(force);
    let n = site.node_count();
    let mut loads: [NodeLoad; 3] = std::array::from_fn(|slot| {
        if slot < n {
            let w = site.weights[slot];
            NodeLoad { node: site.nodes[slot], force: force * w, torque: torque * w }
        } else {
            NodeLoad { node: site.nodes[slot], force: Vec3::zeros(), torque: Vec3::zeros() }
        }
    });
    if let (Feature::Edge(_), LinkKinematicsMode::Beam) = (site.feature, mode) {
        let s = pos[site.nodes[1] as usize] - pos[site.nodes[0] as usize];
        let l2 = s.norm_squared();
        if l2 > Real::MIN_POSITIVE {
            let axial = s * (torque.dot(&s) / l2);
            let couple = (torque - axial).cross(&s) / l2;
            for (slot, sign) in [(0, -1.0), (1, 1.0)] {
                loads[slot].torque = axial * site.weights[slot];
                loads[slot].force += couple * sign;
            }
        }
    }
    loads
}

#[cfg(test)]
mod tests;

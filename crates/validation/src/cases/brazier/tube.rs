//! The tube of the Brazier case: geometry, supports, and what is measured on it (end rotation,
//! ovalisation, strains, self-distance).

use crate::ValidationError;
use flexdem_contact::Material;
use flexdem_elements::{Dofs, Model, StructureOptions};
use flexdem_geom::{project_point_triangle, Real, Vec3};
use std::f64::consts::PI;

/// The tube and its material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TubeCase {
    /// Tube radius R (m).
    pub radius: Real,
    /// Tube length L (m), along x from the origin.
    pub length: Real,
    /// Nodes around a ring (even, so that each node has an opposite one).
    pub n_around: usize,
    /// Segments along the axis.
    pub n_along: usize,
    /// Node, connection and PFacet radius r (m): the wall thickness is 2r.
    pub node_radius: Real,
    /// Young's modulus (Pa).
    pub young: Real,
    /// Poisson ratio of the links' material (torsion of the links).
    pub poisson: Real,
    /// Density (kg/m³).
    pub density: Real,
    /// Friction angle of self-contacts (rad).
    pub friction_angle: Real,
    /// Cundall damping λ.
    pub damping: Real,
}

impl Default for TubeCase {
    /// The paper's §7 tube (R = 0.1 m, L = 0.8 m, 16 × 20 cells, r = 2 mm), E = 10 MPa,
    /// ν = 0.3, ρ = 1000 kg/m³, friction angle 0.3 rad, damping 0.3.
    fn default() -> Self {
        TubeCase {
            radius: 0.1,
            length: 0.8,
            n_around: 16,
            n_along: 20,
            node_radius: 0.002,
            young: 1.0e7,
            poisson: 0.3,
            density: 1000.0,
            friction_angle: 0.3,
            damping: 0.3,
        }
    }
}

/// Node ids of the rings of the tube that the case loads or measures.
#[derive(Clone, Debug, PartialEq)]
pub struct TubeRings {
    /// Ring at x = 0 (supported).
    pub first: Vec<u32>,
    /// Ring at x = L (loaded).
    pub last: Vec<u32>,
    /// Ring nearest L/4.
    pub quarter: Vec<u32>,
    /// Ring nearest 3L/4.
    pub three_quarters: Vec<u32>,
    /// Ring nearest L/2.
    pub middle: Vec<u32>,
}

impl TubeCase {
    /// Chord between neighbouring nodes of a ring: a = 2R·sin(π/n).
    pub fn chord(&self) -> Real {
        2.0 * self.radius * (PI / self.n_around as Real).sin()
    }

    /// Σ y_k² over the nodes of a ring about its centre: n·R²/2.
    pub fn ring_inertia_sum(&self) -> Real {
        self.n_around as Real * self.radius * self.radius / 2.0
    }

    /// Mass per unit area of the wall: the links' mass πr²ρ·(a + b + √(a² + b²)) per cell of
    /// area a·b (mass lumped from the connections, YADE).
    pub fn areal_mass(&self) -> Real {
        let (a, b) = (self.chord(), self.length / self.n_along as Real);
        PI * self.node_radius.powi(2) * self.density * (a + b + a.hypot(b)) / (a * b)
    }

    /// The model: one material, the tube along x, the ring at x = 0 blocked along x, its node
    /// 0 also along y and z and its opposite node along y (no rigid-body motion, free
    /// ovalisation). Returns the model and its rings.
    pub fn model(&self) -> Result<(Model, TubeRings), ValidationError> {
        if self.n_around < 4 || self.n_around % 2 != 0 {
            return Err(ValidationError::Case {
                case: "brazier".into(),
                message: format!("n_around = {}: expected an even number >= 4", self.n_around),
            });
        }
        let mut model = Model::new();
        let material = model.add_material(Material::new(
            self.young,
            self.poisson,
            self.density,
            self.friction_angle,
        )?)?;
        let opts = StructureOptions::new("tube", self.node_radius, material);
        let s = flexdem_elements::builders::tube(
            &mut model,
            Vec3::zeros(),
            Vec3::x(),
            self.radius,
            self.length,
            self.n_around,
            self.n_along,
            &opts,
        )?;
        let start = model.structure(s)?.nodes.start;
        let m = self.n_around as u32;
        let ring = |j: usize| (0..m).map(|i| start + i + j as u32 * m).collect::<Vec<u32>>();
        let k = self.n_along;
        let rings = TubeRings {
            first: ring(0),
            last: ring(k),
            quarter: ring((k + 2) / 4),
            three_quarters: ring((3 * k + 2) / 4),
            middle: ring(k / 2),
        };
        model.block(rings.first.iter().copied(), Dofs::X)?;
        model.block([rings.first[0]], Dofs::Y | Dofs::Z)?;
        model.block([rings.first[self.n_around / 2]], Dofs::Y)?;
        Ok((model, rings))
    }
}

/// Mean of the positions of `ring`.
pub fn centroid(pos: &[Vec3], ring: &[u32]) -> Vec3 {
    ring.iter().map(|&i| pos[i as usize]).sum::<Vec3>() / ring.len() as Real
}

/// Mean distance of the nodes of `ring` from their centroid, measured in the plane
/// perpendicular to x (the mean radius of a ring of the straight tube).
pub fn mean_radius(pos: &[Vec3], ring: &[u32]) -> Real {
    let c = centroid(pos, ring);
    ring.iter()
        .map(|&i| {
            let d = pos[i as usize] - c;
            d.y.hypot(d.z)
        })
        .sum::<Real>()
        / ring.len() as Real
}

/// Area vector of the polygon `ring` (nodes in order): ½Σ(p_k − p̄) × (p_{k+1} − p̄). Normal
/// to the ring's mean plane.
pub fn ring_normal(pos: &[Vec3], ring: &[u32]) -> Vec3 {
    let c = centroid(pos, ring);
    let n = ring.len();
    (0..n)
        .map(|k| (pos[ring[k] as usize] - c).cross(&(pos[ring[(k + 1) % n] as usize] - c)))
        .sum::<Vec3>()
        * 0.5
}

/// Angle (rad) of the projection of the ring normal on the x–y plane, measured from x about
/// z, unwrapped to be within π of `previous`: the end rotation of the tube bent about z.
pub fn ring_rotation(pos: &[Vec3], ring: &[u32], reference: Vec3, previous: Real) -> Real {
    let n = ring_normal(pos, ring);
    let angle = n.y.atan2(n.x) - reference.y.atan2(reference.x);
    let turns = ((previous - angle) / (2.0 * PI)).round();
    angle + turns * 2.0 * PI
}

/// Largest over smallest of the distances between opposite nodes (k and k + n/2) of `ring`.
pub fn ovalisation(pos: &[Vec3], ring: &[u32]) -> Real {
    let half = ring.len() / 2;
    let (lo, hi) = (0..half)
        .map(|k| (pos[ring[k] as usize] - pos[ring[k + half] as usize]).norm())
        .fold((Real::INFINITY, 0.0_f64), |(lo, hi), d: Real| (lo.min(d), hi.max(d)));
    hi / lo
}

/// Smallest distance between a node and a PFacet of `model` that is not adjacent to it: the
/// PFacet contains neither the node nor a node linked to it by a connection (brute force with
/// `project_point_triangle`). Returns `Real::INFINITY` when no pair qualifies.
pub fn min_self_distance(model: &Model) -> Real {
    let n = model.particles.len();
    let mut neighbours = vec![Vec::new(); n];
    for c in &model.connections {
        let [a, b] = c.nodes;
        neighbours[a as usize].push(b);
        neighbours[b as usize].push(a);
    }
    let pos = &model.particles.pos;
    let mut best = Real::INFINITY;
    for (node, near) in neighbours.iter().enumerate() {
        for f in &model.pfacets {
            let adjacent = f.nodes.iter().any(|&v| v as usize == node || near.contains(&v));
            if adjacent {
                continue;
            }
            let [a, b, c] = f.nodes.map(|v| pos[v as usize]);
            let projection = project_point_triangle(&pos[node], &a, &b, &c);
            best = best.min((projection.point - pos[node]).norm());
        }
    }
    best
}

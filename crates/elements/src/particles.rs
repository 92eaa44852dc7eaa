//! Every 6-DOF spherical body, free spheres and structure nodes alike, as a struct of arrays
//! indexed by particle id, so that the integrator runs one loop over plain arrays.

use crate::{Dofs, MaterialId, ParticleId, StructureId};
use flexdem_geom::{Real, Vec3};
use nalgebra::UnitQuaternion;
use serde::{Deserialize, Serialize};

/// The `structure` of a particle that belongs to no structure (a free sphere).
pub const NO_STRUCTURE: StructureId = u32::MAX;

/// What a particle is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ParticleKind {
    /// A free sphere: a body of its own, seen by the collider; mass (4/3)πr³ρ.
    Sphere,
    /// A node of a structure: never seen by the collider directly (its connections and
    /// PFacets are); mass lumped from its elements (model.md §3).
    Node,
}

/// One particle's data (an array-of-structs view of [`Particles`], used to add and read
/// particles one at a time).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Particle {
    /// Centre position.
    pub pos: Vec3,
    /// Translational velocity.
    pub vel: Vec3,
    /// Orientation.
    pub ori: UnitQuaternion<Real>,
    /// Angular velocity (world frame).
    pub ang_vel: Vec3,
    /// Radius.
    pub radius: Real,
    /// Mass.
    pub mass: Real,
    /// Isotropic scalar moment of inertia.
    pub inertia: Real,
    /// Material id.
    pub material: MaterialId,
    /// Collision group bits: two bodies interact only if their masks share a bit.
    pub mask: u32,
    /// Sphere or node.
    pub kind: ParticleKind,
    /// The structure of a node, [`NO_STRUCTURE`] for a free sphere.
    pub structure: StructureId,
    /// Blocked DOFs: they keep their current velocity component.
    pub blocked: Dofs,
}

impl Particle {
    /// A particle at rest at `pos`: zero velocities, identity orientation, no mass yet,
    /// mask 1, no structure, nothing blocked.
    pub fn at_rest(kind: ParticleKind, pos: Vec3, radius: Real, material: MaterialId) -> Self {
        Particle {
            pos,
            vel: Vec3::zeros(),
            ori: UnitQuaternion::identity(),
            ang_vel: Vec3::zeros(),
            radius,
            mass: 0.0,
            inertia: 0.0,
            material,
            mask: 1,
            kind,
            structure: NO_STRUCTURE,
            blocked: Dofs::NONE,
        }
    }
}

/// All particles as a struct of arrays; index `i` of every array is particle `i`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Particles {
    /// Centre positions.
    pub pos: Vec<Vec3>,
    /// Translational velocities.
    pub vel: Vec<Vec3>,
    /// Orientations.
    pub ori: Vec<UnitQuaternion<Real>>,
    /// Angular velocities (world frame).
    pub ang_vel: Vec<Vec3>,
    /// Radii.
    pub radius: Vec<Real>,
    /// Masses.
    pub mass: Vec<Real>,
    /// Isotropic scalar moments of inertia.
    pub inertia: Vec<Real>,
    /// Material ids.
    pub material: Vec<MaterialId>,
    /// Collision group bits.
    pub mask: Vec<u32>,
    /// Sphere or node.
    pub kind: Vec<ParticleKind>,
    /// Structure of each node, [`NO_STRUCTURE`] for free spheres.
    pub structure: Vec<StructureId>,
    /// Blocked DOFs.
    pub blocked: Vec<Dofs>,
}

impl Particles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// Whether there is no particle.
    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Gives back the memory the arrays hold beyond their length (pushing one by one leaves
    /// up to half of each array unused: 227 B per particle held for 142 used at 10⁴ particles).
    pub fn shrink_to_fit(&mut self) {
        self.pos.shrink_to_fit();
        self.vel.shrink_to_fit();
        self.ori.shrink_to_fit();
        self.ang_vel.shrink_to_fit();
        self.radius.shrink_to_fit();
        self.mass.shrink_to_fit();
        self.inertia.shrink_to_fit();
        self.material.shrink_to_fit();
        self.mask.shrink_to_fit();
        self.kind.shrink_to_fit();
        self.structure.shrink_to_fit();
        self.blocked.shrink_to_fit();
    }

    /// Appends a particle and returns its index. The caller (the [`crate::Model`]) checks that
    /// the index fits a [`ParticleId`].
    pub fn push(&mut self, p: Particle) -> usize {
        self.pos.push(p.pos);
        self.vel.push(p.vel);
        self.ori.push(p.ori);
        self.ang_vel.push(p.ang_vel);
        self.radius.push(p.radius);
        self.mass.push(p.mass);
        self.inertia.push(p.inertia);
        self.material.push(p.material);
        self.mask.push(p.mask);
        self.kind.push(p.kind);
        self.structure.push(p.structure);
        self.blocked.push(p.blocked);
        self.pos.len() - 1
    }

    /// Particle `id`'s data, or `None` if out of range.
    pub fn get(&self, id: ParticleId) -> Option<Particle> {
        let i = id as usize;
        (i < self.len()).then(|| Particle {
            pos: self.pos[i],
            vel: self.vel[i],
            ori: self.ori[i],
            ang_vel: self.ang_vel[i],
            radius: self.radius[i],
            mass: self.mass[i],
            inertia: self.inertia[i],
            material: self.material[i],
            mask: self.mask[i],
            kind: self.kind[i],
            structure: self.structure[i],
            blocked: self.blocked[i],
        })
    }

    /// Shortens every array to `len` particles (used to undo a failed build).
    pub(crate) fn truncate(&mut self, len: usize) {
        self.pos.truncate(len);
        self.vel.truncate(len);
        self.ori.truncate(len);
        self.ang_vel.truncate(len);
        self.radius.truncate(len);
        self.mass.truncate(len);
        self.inertia.truncate(len);
        self.material.truncate(len);
        self.mask.truncate(len);
        self.kind.truncate(len);
        self.structure.truncate(len);
        self.blocked.truncate(len);
    }

    /// Whether all arrays have the same length (checked by [`crate::Model::validate`], since
    /// the arrays are public).
    pub(crate) fn arrays_consistent(&self) -> bool {
        let n = self.pos.len();
        [
            self.vel.len(),
            self.ori.len(),
            self.ang_vel.len(),
            self.radius.len(),
            self.mass.len(),
            self.inertia.len(),
            self.material.len(),
            self.mask.len(),
            self.kind.len(),
            self.structure.len(),
            self.blocked.len(),
        ]
        .iter()
        .all(|&l| l == n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn push_get_truncate_round_trip() {
        let mut ps = Particles::default();
        assert!(ps.is_empty());
        let mut a = Particle::at_rest(ParticleKind::Sphere, Vec3::new(1.0, 2.0, 3.0), 0.5, 0);
        a.mass = 2.0;
        a.blocked = Dofs::X;
        let b = Particle::at_rest(ParticleKind::Node, Vec3::zeros(), 0.1, 1);
        assert_eq!(ps.push(a), 0);
        assert_eq!(ps.push(b), 1);
        assert_eq!(ps.len(), 2);
        assert_eq!(ps.get(0), Some(a));
        assert_eq!(ps.get(1), Some(b));
        assert_eq!(ps.get(2), None);
        assert!(ps.arrays_consistent());
        ps.truncate(1);
        assert_eq!(ps.len(), 1);
        assert!(ps.arrays_consistent());
        ps.mass.push(1.0);
        assert!(!ps.arrays_consistent());
    }
}

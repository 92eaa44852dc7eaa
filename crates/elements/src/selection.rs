//! Selecting nodes (by structure, box, plane, free ends) and constraining them (blocking
//! DOFs, imposing velocities). Blocked DOFs follow YADE: a blocked DOF keeps its current
//! velocity component, 0 or an imposed value.

use crate::error::ModelError;
use crate::{Dofs, Model, NodeId, ParticleId, ParticleKind, StructureId};
use flexdem_geom::{Aabb, Real, Vec3};

impl Model {
    /// The node ids of `structure`, ascending.
    pub fn structure_nodes(&self, structure: StructureId) -> Result<Vec<NodeId>, ModelError> {
        Ok(self.structure(structure)?.nodes.clone().collect())
    }

    /// The nodes (of any structure) whose centre lies in `aabb` (boundary included),
    /// ascending. Free spheres are not selected.
    pub fn nodes_in_box(&self, aabb: &Aabb) -> Vec<NodeId> {
        self.node_positions().filter(|(_, p)| aabb.contains_point(p)).map(|(i, _)| i).collect()
    }

    /// The nodes (of any structure) whose centre is within `tolerance` of the plane through
    /// `point` with normal `normal` (any length), ascending. `tolerance` is a distance ≥ 0.
    pub fn nodes_on_plane(
        &self,
        point: Vec3,
        normal: Vec3,
        tolerance: Real,
    ) -> Result<Vec<NodeId>, ModelError> {
        let length = normal.norm();
        if !(normal.iter().all(|c| c.is_finite()) && length.is_finite() && length > 0.0) {
            return Err(ModelError::InvalidVector {
                what: "plane normal",
                value: normal,
                expected: "a finite non-zero vector",
            });
        }
        if !point.iter().all(|c| c.is_finite()) {
            return Err(ModelError::InvalidVector {
                what: "plane point",
                value: point,
                expected: "finite coordinates",
            });
        }
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(ModelError::InvalidScalar {
                what: "plane tolerance",
                value: tolerance,
                expected: "a finite distance >= 0",
            });
        }
        let n = normal / length;
        Ok(self
            .node_positions()
            .filter(|(_, p)| (*p - point).dot(&n).abs() <= tolerance)
            .map(|(i, _)| i)
            .collect())
    }

    /// The free ends of `structure`: its nodes attached to exactly one of its connections,
    /// ascending. For a chain these are its first and last nodes; a closed loop, a net or
    /// a shell has none.
    pub fn structure_ends(&self, structure: StructureId) -> Result<Vec<NodeId>, ModelError> {
        let st = self.structure_in_bounds(structure)?;
        let mut degree = vec![0u32; st.nodes.len()];
        for c in st.connections.clone() {
            for n in self.connections[c as usize].nodes {
                if st.nodes.contains(&n) {
                    degree[(n - st.nodes.start) as usize] += 1;
                }
            }
        }
        Ok(st.nodes.clone().filter(|&n| degree[(n - st.nodes.start) as usize] == 1).collect())
    }

    /// Blocks `dofs` (in addition to those already blocked) on each particle of `particles`.
    /// Velocities are not changed: a blocked DOF keeps its current velocity component.
    /// Either every id is valid and all are blocked, or nothing changes.
    pub fn block(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        dofs: Dofs,
    ) -> Result<(), ModelError> {
        let ids = self.checked_ids(particles)?;
        for i in ids {
            self.particles.blocked[i] |= dofs;
        }
        Ok(())
    }

    /// Frees `dofs` on each particle of `particles` (all or nothing, as [`Model::block`]).
    pub fn unblock(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        dofs: Dofs,
    ) -> Result<(), ModelError> {
        let ids = self.checked_ids(particles)?;
        for i in ids {
            self.particles.blocked[i] = self.particles.blocked[i].difference(dofs);
        }
        Ok(())
    }

    /// Sets the velocity of each particle of `particles` to `velocity` and blocks its
    /// translational DOFs, so that the velocity persists (all or nothing).
    pub fn impose_velocity(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        velocity: Vec3,
    ) -> Result<(), ModelError> {
        check_finite("imposed velocity", velocity)?;
        let ids = self.checked_ids(particles)?;
        for i in ids {
            self.particles.vel[i] = velocity;
            self.particles.blocked[i] |= Dofs::TRANSLATION;
        }
        Ok(())
    }

    /// Sets the angular velocity of each particle of `particles` to `angular_velocity` and
    /// blocks its rotational DOFs, so that it persists (all or nothing).
    pub fn impose_angular_velocity(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        angular_velocity: Vec3,
    ) -> Result<(), ModelError> {
        check_finite("imposed angular velocity", angular_velocity)?;
        let ids = self.checked_ids(particles)?;
        for i in ids {
            self.particles.ang_vel[i] = angular_velocity;
            self.particles.blocked[i] |= Dofs::ROTATION;
        }
        Ok(())
    }

    /// Ids and positions of the nodes.
    fn node_positions(&self) -> impl Iterator<Item = (NodeId, &Vec3)> + '_ {
        let ps = &self.particles;
        (0u32..)
            .zip(ps.kind.iter().zip(&ps.pos))
            .filter(|(_, (kind, _))| **kind == ParticleKind::Node)
            .map(|(i, (_, p))| (i, p))
    }

    fn checked_ids(
        &self,
        particles: impl IntoIterator<Item = ParticleId>,
    ) -> Result<Vec<usize>, ModelError> {
        let ps = &self.particles;
        let count = ps.pos.len().min(ps.vel.len()).min(ps.ang_vel.len()).min(ps.blocked.len());
        particles
            .into_iter()
            .map(|p| {
                if (p as usize) < count {
                    Ok(p as usize)
                } else {
                    Err(ModelError::NoSuchParticle { particle: p, count })
                }
            })
            .collect()
    }
}

fn check_finite(what: &'static str, v: Vec3) -> Result<(), ModelError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(ModelError::InvalidVector { what, value: v, expected: "finite components" })
    }
}

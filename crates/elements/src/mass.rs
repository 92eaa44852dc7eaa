//! Mass and inertia lumping (model.md §3, YADE's `gridConnection`; paper §3: "the mass of the
//! cylinder element is lumped into its two nodes", "the mass of the PFacet is equally lumped
//! into the 3 nodes").

use crate::error::{Item, ModelError};
use crate::{Model, StructureId};
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// How a structure's elements give their mass to its nodes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum MassLumping {
    /// YADE's lumping: each connection of length L and radius r puts πr²Lρ/2 on each of its
    /// nodes; PFacets add nothing. A structure's mass is Σ πr²Lρ over its connections.
    #[default]
    Connections,
    /// As `Connections`, plus each PFacet of area A puts the plate mass A·2r·ρ/3 on each of
    /// its nodes (the paper's "mass equally lumped into the 3 nodes"; thickness 2r).
    Plate,
}

/// Mass and isotropic inertia given to a node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LumpedMass {
    /// Mass.
    pub mass: Real,
    /// Scalar moment of inertia.
    pub inertia: Real,
}

/// What a connection of length `length`, radius `radius` and density `density` gives to
/// each of its two nodes (model.md §3, YADE): m = πr²L·ρ/2 and J = (2/5)·m·r², the inertia of
/// a sphere of radius r and mass m (YADE's `(2/5)·V·r²·ρ` with V = πr²L/2).
pub fn connection_lumped_mass(radius: Real, length: Real, density: Real) -> LumpedMass {
    let mass = PI * radius * radius * length * density / 2.0;
    LumpedMass { mass, inertia: 0.4 * mass * radius * radius }
}

/// What a PFacet with corners `a, b, c`, radius `radius` and density `density` gives to each
/// of its three nodes with [`MassLumping::Plate`]: m = A·2r·ρ/3 with A = |(b − a) × (c − a)|/2,
/// and J = (2/5)·m·r², the same sphere-like inertia per unit mass as the connections give, so
/// that a node's rotational inertia stays proportional to its mass (a choice: the plate's own
/// rotary inertia is not what the beam links' bending stiffness is paired with in YADE).
pub fn pfacet_lumped_mass(a: Vec3, b: Vec3, c: Vec3, radius: Real, density: Real) -> LumpedMass {
    let area = 0.5 * (b - a).cross(&(c - a)).norm();
    let mass = area * 2.0 * radius * density / 3.0;
    LumpedMass { mass, inertia: 0.4 * mass * radius * radius }
}

impl Model {
    /// Adds the mass of `structure`'s connections (and, with [`MassLumping::Plate`], of its
    /// PFacets) to its nodes, with each element's own radius and material density. The
    /// connections use their rest length and the PFacets their current corner positions.
    /// Masses add up: calling it twice doubles them (the builders call it once).
    pub fn lump_structure_mass(
        &mut self,
        structure: StructureId,
        lumping: MassLumping,
    ) -> Result<(), ModelError> {
        let st = self.structure_in_bounds(structure)?.clone();
        // Check every reference before changing anything.
        for c in st.connections.clone() {
            let conn = self.connections[c as usize];
            let item = Item::Connection(c);
            self.density(item, conn.material)?;
            for n in conn.nodes {
                self.check_node(item, n)?;
            }
        }
        if lumping == MassLumping::Plate {
            for f in st.pfacets.clone() {
                let facet = self.pfacets[f as usize];
                let item = Item::PFacet(f);
                self.density(item, facet.material)?;
                for n in facet.nodes {
                    self.check_node(item, n)?;
                }
            }
        }
        for c in st.connections.clone() {
            let conn = self.connections[c as usize];
            let density = self.materials[conn.material as usize].density;
            let lumped = connection_lumped_mass(conn.radius, conn.rest_length, density);
            for n in conn.nodes {
                self.particles.mass[n as usize] += lumped.mass;
                self.particles.inertia[n as usize] += lumped.inertia;
            }
        }
        if lumping == MassLumping::Plate {
            for f in st.pfacets {
                let facet = self.pfacets[f as usize];
                let density = self.materials[facet.material as usize].density;
                let [a, b, c] = facet.nodes.map(|n| self.particles.pos[n as usize]);
                let lumped = pfacet_lumped_mass(a, b, c, facet.radius, density);
                for n in facet.nodes {
                    self.particles.mass[n as usize] += lumped.mass;
                    self.particles.inertia[n as usize] += lumped.inertia;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn connection_mass_is_half_the_cylinder_on_each_node() {
        let m = connection_lumped_mass(0.01, 0.5, 7850.0);
        let cylinder = PI * 0.01 * 0.01 * 0.5 * 7850.0;
        assert!((2.0 * m.mass - cylinder).abs() <= 1e-15 * cylinder);
        assert!((m.inertia - 0.4 * m.mass * 1e-4).abs() <= 1e-15 * m.inertia);
    }

    #[test]
    fn pfacet_plate_mass_is_a_third_of_the_plate_on_each_node() {
        let (a, b, c) = (Vec3::zeros(), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 3.0, 0.0));
        let m = pfacet_lumped_mass(a, b, c, 0.1, 1000.0);
        // area 3, thickness 0.2: plate mass 600 kg, 200 kg per node.
        assert!((m.mass - 200.0).abs() <= 1e-10);
        assert!((m.inertia - 0.4 * 200.0 * 0.01).abs() <= 1e-12);
    }
}

//! The model: materials, particles, connections, PFacets, walls and structures, with the
//! low-level ways to add them and a validation that names what is wrong.

use crate::error::{Item, ModelError, V};
use crate::{
    Connection, ConnectionId, MaterialId, NodeId, PFacet, PFacetId, Particle, ParticleId,
    ParticleKind, Particles, Structure, StructureId, Wall, WallId,
};
use flexdem_contact::Material;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A connection is degenerate when its length is at most this fraction of the size of its
/// coordinates (or of its radius, whichever is larger): round-off level.
const ZERO_LENGTH_RELATIVE: Real = 1e-12;

/// Everything that is simulated: see model.md §1.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Model {
    /// Materials, indexed by [`MaterialId`].
    pub materials: Vec<Material>,
    /// Free spheres and structure nodes.
    pub particles: Particles,
    /// Connections (cylinders), each with one beam link.
    pub connections: Vec<Connection>,
    /// PFacets.
    pub pfacets: Vec<PFacet>,
    /// Walls.
    pub walls: Vec<Wall>,
    /// Structures (named groups of contiguous id ranges).
    pub structures: Vec<Structure>,
}

/// Lengths of the model's arrays, to undo a failed build.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Snapshot {
    particles: usize,
    connections: usize,
    pfacets: usize,
    structures: usize,
}

/// `len` as a new u32 id, or an error when ids run out (u32::MAX is reserved).
fn next_id(len: usize, what: &'static str) -> Result<u32, ModelError> {
    u32::try_from(len).ok().filter(|&id| id < u32::MAX).ok_or(ModelError::TooMany { what })
}

fn is_finite(v: &Vec3) -> bool {
    v.iter().all(|c| c.is_finite())
}

impl Model {
    /// An empty model.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a material after validating it.
    pub fn add_material(&mut self, material: Material) -> Result<MaterialId, ModelError> {
        let id = next_id(self.materials.len(), "materials")?;
        material.validate().map_err(|source| ModelError::Material { material: id, source })?;
        self.materials.push(material);
        Ok(id)
    }

    /// Adds a free sphere at rest: mass m = (4/3)πr³ρ, inertia (2/5)mr² (model.md §1),
    /// mask 1, nothing blocked.
    pub fn add_sphere(
        &mut self,
        center: Vec3,
        radius: Real,
        material: MaterialId,
    ) -> Result<ParticleId, ModelError> {
        let id = next_id(self.particles.len(), "particles")?;
        let item = Item::Particle(id);
        let density = self.density(item, material)?;
        check_point(item, "position", center)?;
        check_radius(item, radius)?;
        let mut p = Particle::at_rest(ParticleKind::Sphere, center, radius, material);
        p.mass = 4.0 / 3.0 * PI * radius.powi(3) * density;
        p.inertia = 0.4 * p.mass * radius * radius;
        self.particles.push(p);
        Ok(id)
    }

    /// Adds a fixed wall through `point` with outward normal `normal` (normalized here),
    /// velocity zero and mask 1.
    pub fn add_wall(
        &mut self,
        point: Vec3,
        normal: Vec3,
        material: MaterialId,
    ) -> Result<WallId, ModelError> {
        let id = next_id(self.walls.len(), "walls")?;
        let item = Item::Wall(id);
        self.density(item, material)?;
        check_point(item, "point", point)?;
        let length = normal.norm();
        if !(is_finite(&normal) && length.is_finite() && length > 0.0) {
            return Err(ModelError::InvalidWallNormal { wall: id, normal });
        }
        self.walls.push(Wall {
            point,
            normal: normal / length,
            velocity: Vec3::zeros(),
            material,
            mask: 1,
        });
        Ok(id)
    }

    /// Opens a new, empty structure at the ends of the id arrays. Nodes, connections and
    /// PFacets are then added to it with [`Model::add_node`], [`Model::add_connection`] and
    /// [`Model::add_pfacet`] (the builders do all of this), and its mass is lumped with
    /// [`Model::lump_structure_mass`].
    pub fn add_structure(&mut self, name: &str) -> Result<StructureId, ModelError> {
        let id = next_id(self.structures.len(), "structures")?;
        let p = next_id(self.particles.len(), "particles")?;
        let c = next_id(self.connections.len(), "connections")?;
        let f = next_id(self.pfacets.len(), "PFacets")?;
        self.structures.push(Structure {
            name: name.to_owned(),
            nodes: p..p,
            connections: c..c,
            pfacets: f..f,
            self_contact: true,
        });
        Ok(id)
    }

    /// Whether the elements of structure `id` touch one another (they do by default).
    pub fn set_self_contact(&mut self, id: StructureId, on: bool) -> Result<(), ModelError> {
        self.structure(id)?;
        self.structures[id as usize].self_contact = on;
        Ok(())
    }

    /// Gives back the memory the model's arrays hold beyond their length (a built model has
    /// up to half of each unused; nothing is added to it while it runs).
    pub fn shrink_to_fit(&mut self) {
        self.particles.shrink_to_fit();
        self.connections.shrink_to_fit();
        self.pfacets.shrink_to_fit();
        self.walls.shrink_to_fit();
    }

    /// Whether two elements of structures `sa` and `sb` are parts of one structure whose
    /// self-contact is off (so they never pair).
    pub fn self_contact_off(&self, sa: StructureId, sb: StructureId) -> bool {
        sa == sb && self.structures.get(sa as usize).is_some_and(|s| !s.self_contact)
    }

    /// Adds a node at rest to `structure` (which must be the last one, with nothing added
    /// after it). Its mass is zero until the structure's mass is lumped.
    pub fn add_node(
        &mut self,
        structure: StructureId,
        pos: Vec3,
        radius: Real,
        material: MaterialId,
        mask: u32,
    ) -> Result<NodeId, ModelError> {
        let id = next_id(self.particles.len(), "particles")?;
        let item = Item::Particle(id);
        self.open_structure(structure, |s| s.nodes.end, id, "a particle was added after it")?;
        self.density(item, material)?;
        check_point(item, "position", pos)?;
        check_radius(item, radius)?;
        let mut p = Particle::at_rest(ParticleKind::Node, pos, radius, material);
        p.mask = mask;
        p.structure = structure;
        self.particles.push(p);
        self.structures[structure as usize].nodes.end = id + 1;
        Ok(id)
    }

    /// Adds a connection between two nodes to `structure` (the last one, with nothing added
    /// after it). Its rest length is the nodes' current distance. No mass is lumped here.
    pub fn add_connection(
        &mut self,
        structure: StructureId,
        nodes: [NodeId; 2],
        radius: Real,
        material: MaterialId,
        mask: u32,
    ) -> Result<ConnectionId, ModelError> {
        let id = next_id(self.connections.len(), "connections")?;
        let item = Item::Connection(id);
        self.open_structure(
            structure,
            |s| s.connections.end,
            id,
            "a connection was added after it",
        )?;
        self.density(item, material)?;
        check_radius(item, radius)?;
        for &n in &nodes {
            self.check_node(item, n)?;
        }
        let rest_length = self.connection_length(id, nodes)?;
        self.connections.push(Connection { nodes, radius, material, mask, structure, rest_length });
        self.structures[structure as usize].connections.end = id + 1;
        Ok(id)
    }

    /// Adds a PFacet to `structure` (the last one, with nothing added after it):
    /// `connections[0]` must join nodes 0–1, `[1]` 1–2, `[2]` 2–0 (either direction).
    pub fn add_pfacet(
        &mut self,
        structure: StructureId,
        nodes: [NodeId; 3],
        connections: [ConnectionId; 3],
        radius: Real,
        material: MaterialId,
        mask: u32,
    ) -> Result<PFacetId, ModelError> {
        let id = next_id(self.pfacets.len(), "PFacets")?;
        self.open_structure(structure, |s| s.pfacets.end, id, "a PFacet was added after it")?;
        let facet = PFacet { nodes, connections, radius, material, mask, structure };
        self.check_pfacet(id, &facet)?;
        self.pfacets.push(facet);
        self.structures[structure as usize].pfacets.end = id + 1;
        Ok(id)
    }

    /// The structure `id`.
    pub fn structure(&self, id: StructureId) -> Result<&Structure, ModelError> {
        self.structures
            .get(id as usize)
            .ok_or(ModelError::UnknownStructure { structure: id, count: self.structures.len() })
    }

    /// The structure `id`, checking that its ranges lie within the arrays (they are public
    /// fields), so that its elements can be indexed.
    pub(crate) fn structure_in_bounds(&self, id: StructureId) -> Result<&Structure, ModelError> {
        let st = self.structure(id)?;
        let ranges = [
            ("nodes", &st.nodes, self.particles.len()),
            ("connections", &st.connections, self.connections.len()),
            ("PFacets", &st.pfacets, self.pfacets.len()),
        ];
        for (what, r, len) in ranges {
            if r.start > r.end || r.end as usize > len {
                let item = Item::Structure(id);
                let reason = format!("its {what} range {r:?} is not within 0..{len}");
                return Err(mismatch(item, item, reason));
            }
        }
        Ok(st)
    }

    /// The first structure named `name`.
    pub fn structure_by_name(&self, name: &str) -> Option<StructureId> {
        self.structures.iter().position(|s| s.name == name).map(|i| i as StructureId)
    }

    /// Total mass of all particles.
    pub fn total_mass(&self) -> Real {
        self.particles.mass.iter().sum()
    }

    /// Checks the whole model: every id in range, radii finite and > 0, no NaN anywhere,
    /// connections of non-zero length, PFacet connections consistent with their nodes,
    /// structure ranges consistent with the elements' `structure` fields, unit wall normals,
    /// and a non-zero mass (inertia) for every particle with a free translational (rotational)
    /// DOF. Returns the first problem found.
    pub fn validate(&self) -> Result<(), ModelError> {
        for (i, m) in self.materials.iter().enumerate() {
            m.validate().map_err(|source| ModelError::Material { material: i as u32, source })?;
        }
        if !self.particles.arrays_consistent() {
            return Err(ModelError::ParticleArrays);
        }
        for i in 0..self.particles.len() {
            self.check_particle(i as ParticleId)?;
        }
        for (i, c) in self.connections.iter().enumerate() {
            let id = i as ConnectionId;
            let item = Item::Connection(id);
            self.density(item, c.material)?;
            check_radius(item, c.radius)?;
            for &n in &c.nodes {
                self.check_node(item, n)?;
            }
            self.connection_length(id, c.nodes)?;
            if !(c.rest_length.is_finite() && c.rest_length > 0.0) {
                return Err(ModelError::InvalidRestLength {
                    connection: id,
                    rest_length: c.rest_length,
                });
            }
        }
        for (i, f) in self.pfacets.iter().enumerate() {
            self.check_pfacet(i as PFacetId, f)?;
        }
        for (i, w) in self.walls.iter().enumerate() {
            let item = Item::Wall(i as WallId);
            self.density(item, w.material)?;
            check_point(item, "point", w.point)?;
            check_point(item, "velocity", w.velocity)?;
            if !(is_finite(&w.normal) && (w.normal.norm() - 1.0).abs() <= 1e-9) {
                return Err(ModelError::InvalidWallNormal { wall: i as WallId, normal: w.normal });
            }
        }
        self.check_structures()
    }

    /// Density of `material`, checking the id.
    pub(crate) fn density(&self, item: Item, material: MaterialId) -> Result<Real, ModelError> {
        self.materials
            .get(material as usize)
            .map(|m| m.density)
            .ok_or(ModelError::UnknownMaterial { item, material, count: self.materials.len() })
    }

    /// Checks that `particle` exists and is a node.
    pub(crate) fn check_node(&self, item: Item, particle: ParticleId) -> Result<(), ModelError> {
        match self.particles.kind.get(particle as usize) {
            None => {
                Err(ModelError::UnknownParticle { item, particle, count: self.particles.len() })
            }
            Some(ParticleKind::Sphere) => Err(ModelError::NotANode { item, particle }),
            Some(ParticleKind::Node) => Ok(()),
        }
    }

    /// The current distance between a connection's nodes (ids already checked), or an error
    /// when the nodes are the same or coincide.
    fn connection_length(&self, id: ConnectionId, nodes: [NodeId; 2]) -> Result<Real, ModelError> {
        let a = self.particles.pos[nodes[0] as usize];
        let b = self.particles.pos[nodes[1] as usize];
        let length = (b - a).norm();
        let scale = a.amax().max(b.amax()).max(self.particles.radius[nodes[0] as usize]);
        if nodes[0] == nodes[1] || length.is_nan() || length <= ZERO_LENGTH_RELATIVE * scale {
            return Err(ModelError::ZeroLengthConnection { connection: id, nodes, length });
        }
        Ok(length)
    }

    fn check_particle(&self, id: ParticleId) -> Result<(), ModelError> {
        let ps = &self.particles;
        let i = id as usize;
        let item = Item::Particle(id);
        self.density(item, ps.material[i])?;
        check_radius(item, ps.radius[i])?;
        check_point(item, "position", ps.pos[i])?;
        check_point(item, "velocity", ps.vel[i])?;
        check_point(item, "angular velocity", ps.ang_vel[i])?;
        let q = ps.ori[i].quaternion().coords;
        if !(q.iter().all(|c| c.is_finite()) && (q.norm() - 1.0).abs() <= 1e-6) {
            return Err(ModelError::NonFinite {
                item,
                field: "orientation (unit quaternion)",
                value: format!("{q:?}"),
            });
        }
        for (field, value, dofs) in [
            ("mass", ps.mass[i], crate::Dofs::TRANSLATION),
            ("inertia", ps.inertia[i], crate::Dofs::ROTATION),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ModelError::NegativeMass { item, field, value });
            }
            let free = dofs.difference(ps.blocked[i]);
            if value == 0.0 && !free.is_empty() {
                return Err(ModelError::MissingMass { item, field, free });
            }
        }
        let s = ps.structure[i];
        match ps.kind[i] {
            ParticleKind::Sphere if s != crate::NO_STRUCTURE => Err(mismatch(
                item,
                Item::Structure(s),
                "a free sphere must have structure NO_STRUCTURE".into(),
            )),
            ParticleKind::Node if s as usize >= self.structures.len() => {
                Err(ModelError::UnknownStructure { structure: s, count: self.structures.len() })
            }
            _ => Ok(()),
        }
    }

    fn check_pfacet(&self, id: PFacetId, f: &PFacet) -> Result<(), ModelError> {
        let item = Item::PFacet(id);
        self.density(item, f.material)?;
        check_radius(item, f.radius)?;
        for &n in &f.nodes {
            self.check_node(item, n)?;
        }
        let [a, b, c] = f.nodes;
        if a == b || b == c || c == a {
            return Err(ModelError::RepeatedPFacetNode { pfacet: id, nodes: f.nodes });
        }
        for (edge, &connection) in f.connections.iter().enumerate() {
            let Some(conn) = self.connections.get(connection as usize) else {
                return Err(ModelError::UnknownConnection {
                    item,
                    connection,
                    count: self.connections.len(),
                });
            };
            let [p, q] = f.edge_nodes(edge);
            let found = conn.nodes;
            if found != [p, q] && found != [q, p] {
                return Err(ModelError::PFacetEdgeMismatch {
                    pfacet: id,
                    edge,
                    connection,
                    expected: [p, q],
                    found,
                });
            }
        }
        Ok(())
    }

    /// Each structure's ranges lie within the arrays and its elements name it.
    fn check_structures(&self) -> Result<(), ModelError> {
        for (s, st) in self.structures.iter().enumerate() {
            let sid = s as StructureId;
            let sitem = Item::Structure(sid);
            self.structure_in_bounds(sid)?;
            let wrong = |item: Item, owner: StructureId| {
                mismatch(
                    item,
                    sitem,
                    format!("it lies in the structure's range but names structure {owner}"),
                )
            };
            for n in st.nodes.clone() {
                let owner = self.particles.structure[n as usize];
                if owner != sid || self.particles.kind[n as usize] != ParticleKind::Node {
                    return Err(wrong(Item::Particle(n), owner));
                }
            }
            for c in st.connections.clone() {
                let owner = self.connections[c as usize].structure;
                if owner != sid {
                    return Err(wrong(Item::Connection(c), owner));
                }
            }
            for f in st.pfacets.clone() {
                let owner = self.pfacets[f as usize].structure;
                if owner != sid {
                    return Err(wrong(Item::PFacet(f), owner));
                }
            }
        }
        // Conversely, every element lies in the range of the structure it names.
        let outside = |item: Item, owner: StructureId| {
            let reason = "it names the structure but lies outside its range".to_owned();
            match self.structures.get(owner as usize) {
                None => {
                    ModelError::UnknownStructure { structure: owner, count: self.structures.len() }
                }
                Some(_) => mismatch(item, Item::Structure(owner), reason),
            }
        };
        for (i, (&owner, &kind)) in
            self.particles.structure.iter().zip(&self.particles.kind).enumerate()
        {
            let st = self.structures.get(owner as usize);
            if kind == ParticleKind::Node && !st.is_some_and(|s| s.nodes.contains(&(i as u32))) {
                return Err(outside(Item::Particle(i as u32), owner));
            }
        }
        for (i, c) in self.connections.iter().enumerate() {
            let st = self.structures.get(c.structure as usize);
            if !st.is_some_and(|s| s.connections.contains(&(i as u32))) {
                return Err(outside(Item::Connection(i as u32), c.structure));
            }
        }
        for (i, f) in self.pfacets.iter().enumerate() {
            let st = self.structures.get(f.structure as usize);
            if !st.is_some_and(|s| s.pfacets.contains(&(i as u32))) {
                return Err(outside(Item::PFacet(i as u32), f.structure));
            }
        }
        Ok(())
    }

    /// Checks that `structure` is the last one and that `end(structure) == next`, i.e. the
    /// new item extends its range contiguously.
    fn open_structure(
        &self,
        structure: StructureId,
        end: impl Fn(&Structure) -> u32,
        next: u32,
        added_after: &'static str,
    ) -> Result<(), ModelError> {
        let st = self.structure(structure)?;
        if structure as usize + 1 != self.structures.len() {
            return Err(ModelError::StructureClosed {
                structure,
                reason: "a later structure exists",
            });
        }
        if end(st) != next {
            return Err(ModelError::StructureClosed { structure, reason: added_after });
        }
        Ok(())
    }

    pub(crate) fn snapshot(&self) -> Snapshot {
        Snapshot {
            particles: self.particles.len(),
            connections: self.connections.len(),
            pfacets: self.pfacets.len(),
            structures: self.structures.len(),
        }
    }

    /// Removes everything added since `snapshot` (particle masses of older nodes are not
    /// touched by builders before they succeed, so nothing else needs undoing).
    pub(crate) fn rollback(&mut self, snapshot: Snapshot) {
        self.particles.truncate(snapshot.particles);
        self.connections.truncate(snapshot.connections);
        self.pfacets.truncate(snapshot.pfacets);
        self.structures.truncate(snapshot.structures);
    }
}

fn mismatch(item: Item, structure: Item, reason: String) -> ModelError {
    ModelError::StructureMismatch { item, structure, reason }
}

fn check_radius(item: Item, radius: Real) -> Result<(), ModelError> {
    if radius.is_finite() && radius > 0.0 {
        Ok(())
    } else {
        Err(ModelError::InvalidRadius { item, radius })
    }
}

fn check_point(item: Item, field: &'static str, p: Vec3) -> Result<(), ModelError> {
    if is_finite(&p) {
        Ok(())
    } else {
        Err(ModelError::NonFinite { item, field, value: V(p).to_string() })
    }
}

#[cfg(test)]
mod tests;

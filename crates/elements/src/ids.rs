//! Ids: indices into the model's lists.

/// Id of a particle (free sphere or node): its index in [`Particles`](crate::Particles).
pub type ParticleId = u32;
/// Id of a structure node (a particle of kind [`ParticleKind::Node`](crate::ParticleKind::Node)).
pub type NodeId = u32;
/// Id of a connection: its index in [`Model::connections`](crate::Model::connections).
pub type ConnectionId = u32;
/// Id of a PFacet: its index in [`Model::pfacets`](crate::Model::pfacets).
pub type PFacetId = u32;
/// Id of a material: its index in [`Model::materials`](crate::Model::materials).
pub type MaterialId = u32;
/// Id of a wall: its index in [`Model::walls`](crate::Model::walls).
pub type WallId = u32;
/// Id of a structure: its index in [`Model::structures`](crate::Model::structures).
pub type StructureId = u32;

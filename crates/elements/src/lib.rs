//! Deformable structures for flexdem (paper §3–5): nodes, connections, PFacets, walls,
//! builders, mass lumping and the virtual-sphere kinematics that reduce every pair to a
//! sphere–sphere contact.
//!
//! The [`Model`] holds plain arrays indexed by `u32` ids, laid out for the engine's hot loops:
//! [`Particles`] (every 6-DOF sphere, free spheres and structure nodes alike, as a struct of
//! arrays), [`Connection`]s, [`PFacet`]s, [`Wall`]s, and [`Structure`]s (named groups of
//! contiguous id ranges). [`Model::adjacency`] gives node → connections, node → PFacets and
//! connection → PFacets in CSR form. The [`builders`] add whole structures (chains, helices,
//! nets, membranes, tubes, sphere shells, any triangle mesh) and lump their mass
//! (model.md §3); the selection helpers pick nodes to block or drive.

mod adjacency;
pub mod builders;
mod dofs;
mod element;
mod error;
mod ids;
mod mass;
mod model;
pub mod pairs;
mod particles;
mod selection;
pub mod self_overlap;
pub mod touching;
pub mod virtual_sphere;
mod volume;

pub use adjacency::*;
pub use builders::StructureOptions;
pub use dofs::*;
pub use element::*;
pub use error::{BuildError, Item, ModelError};
pub use ids::*;
pub use mass::*;
pub use model::*;
pub use particles::*;
pub use volume::*;

//! Builders of structures (YADE's `gridpfacet.py` helpers and what its users build by hand):
//! chains and cables from polylines, nets, PFacet membranes, tubes, closed sphere shells, and
//! any triangle mesh. Each builder validates its inputs, adds one [`crate::Structure`] (nodes,
//! connections, PFacets as contiguous id ranges), lumps its mass (model.md §3) and returns its
//! id. On error nothing is added.
//!
//! Every PFacet gets its three connections, one per unique edge (an edge shared by two
//! PFacets is one connection, hence one beam link and its mass once), numbered as in
//! `docs/architecture.md`: `connections[0]` joins nodes 0–1, `[1]` 1–2, `[2]` 2–0.

mod chain;
mod membrane;
mod mesh;
mod net;
mod shell;
pub(crate) mod skeleton;
mod tube;

pub use chain::*;
pub use membrane::*;
pub use mesh::*;
pub use net::*;
pub use shell::*;
pub use skeleton::StructureOptions;
pub use tube::*;

#[cfg(test)]
pub(crate) mod test_support;
#[cfg(test)]
mod tests;

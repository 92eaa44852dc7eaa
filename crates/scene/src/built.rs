//! What the build has made so far that later sections select by name: structures with
//! their node layout, and groups of free spheres.

use flexdem_elements::StructureId;
use std::ops::Range;

/// How a structure's nodes are laid out, for selections by side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Layout {
    /// A polyline (chain, helix): node 0 first, last node last.
    Line,
    /// A grid of `n_u × n_v` cells (net, membrane).
    Grid { n_u: usize, n_v: usize },
    /// A disc with `rings` rings (outer ring last).
    Disc { rings: usize },
    /// A tube of `along + 1` rings of `around` nodes.
    Tube { around: usize, along: usize },
    /// No sides (sphere shell, mesh).
    Unstructured,
}

/// A structure built from the scene, for selections.
#[derive(Clone, Debug)]
pub(crate) struct BuiltStructure {
    pub name: String,
    pub id: StructureId,
    pub layout: Layout,
}

/// The spheres of one `[[spheres]]` entry, for selections by `spheres = "name"`.
#[derive(Clone, Debug)]
pub(crate) struct SphereGroup {
    pub name: String,
    pub particles: Range<u32>,
}

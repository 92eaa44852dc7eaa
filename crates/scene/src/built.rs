//! What the build has made so far that later sections select by name: structures with
//! their node layout, and groups of free spheres; kept in the [`crate::Scene`] as
//! [`SceneNames`] for selections made after the build (a script's loads between stages).

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

/// The names a scene defines for its selections (`select = { structure = "net", side =
/// "corners" }`, `select = { spheres = "rocks" }`): its structures with the layout of their
/// nodes, and its groups of free spheres. [`crate::parse_loads`] selects with them after the
/// build.
#[derive(Clone, Debug)]
pub struct SceneNames {
    pub(crate) structures: Vec<BuiltStructure>,
    pub(crate) groups: Vec<SphereGroup>,
    /// False when the names are not known (a simulation resumed from a checkpoint, which
    /// does not keep them): selections by name are refused, saying so.
    pub(crate) known: bool,
}

impl SceneNames {
    /// No names yet (a build starts so).
    pub(crate) fn empty() -> SceneNames {
        SceneNames { structures: Vec::new(), groups: Vec::new(), known: true }
    }

    /// Names that are not known (a simulation resumed from a checkpoint): selections by
    /// `structure` or `spheres` are errors that say so; `ids`, `box` and `plane` work.
    pub fn unknown() -> SceneNames {
        SceneNames { known: false, ..SceneNames::empty() }
    }

    /// The structures' names, in file order.
    pub fn structures(&self) -> impl Iterator<Item = &str> {
        self.structures.iter().map(|s| s.name.as_str())
    }

    /// The sphere groups' names, in file order.
    pub fn sphere_groups(&self) -> impl Iterator<Item = &str> {
        self.groups.iter().map(|g| g.name.as_str())
    }
}

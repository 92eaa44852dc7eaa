//! The state of a scene build, which the sections' readers (`build`, `structures`,
//! `spheres`, `selection`, `output`) extend with their methods.

use crate::built::SceneNames;
use crate::error::Ctx;
use flexdem_elements::{MaterialId, Model};
use flexdem_integrate::WallControl;
use std::path::PathBuf;

/// The state of a build: the model so far and the names defined.
pub(crate) struct Builder<'a> {
    pub ctx: Ctx<'a>,
    /// Folder of the scene file: relative paths start there.
    pub dir: PathBuf,
    pub model: Model,
    pub materials: Vec<(String, MaterialId)>,
    /// The structures and sphere groups built so far, for selections.
    pub names: SceneNames,
    /// How each wall built so far moves.
    pub wall_controls: Vec<WallControl>,
    /// Servos whose area follows a section: (wall, span of the servo, whether `area` is to be
    /// filled from it), measured once every wall is built.
    pub sections: Vec<(usize, std::ops::Range<usize>, bool)>,
    /// The memory available to the simulation (bytes), if known.
    pub available: Option<u64>,
}

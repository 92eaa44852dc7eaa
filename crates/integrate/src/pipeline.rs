//! The pipeline of a simulation: what steps the [`State`] and can be dropped and rebuilt from
//! it at any time (rapier's habit): the collider, the adjacency of the features, the contact
//! buffers, the per-particle and per-wall force sums, the stage timers and the user's force
//! hook.

use crate::collider::Collider;
use crate::contacts::ContactPipeline;
use crate::homes::{particle_blocks, Homes};
use crate::integrator::StepWork;
use crate::servo::WallLoadsAtStep;
use crate::state::State;
use crate::step_work::ChunkCheck;
use crate::timers::Timers;
use flexdem_elements::{Adjacency, Particles};
use flexdem_geom::{Real, Vec3};

/// A user hook that adds forces and torques each step: `(time, particles, force, torque)`.
pub type ForceHook = Box<dyn FnMut(Real, &Particles, &mut [Vec3], &mut [Vec3]) + Send>;

/// Caches and buffers of a simulation, rebuilt from its state (nothing here is saved).
pub(crate) struct Pipeline {
    /// Collidable elements and candidate pairs.
    pub(crate) collider: Collider,
    /// Which features share nodes (for the one-contact-per-touching rule; the connections
    /// at a node only those that are elements of their own, `Model::contact_adjacency`).
    pub(crate) adjacency: Adjacency,
    /// Buffers of contact detection and update.
    pub(crate) contacts: ContactPipeline,
    /// Total force on each particle at the last step.
    pub(crate) force: Vec<Vec3>,
    /// Total torque on each particle at the last step.
    pub(crate) torque: Vec<Vec3>,
    /// Force of the imposed loads and the hook on each particle (for their work); empty
    /// until some load acts.
    pub(crate) external_force: Vec<Vec3>,
    /// Torque of the imposed loads and the hook on each particle.
    pub(crate) external_torque: Vec<Vec3>,
    /// Force and contact stiffness of the bodies on each wall at the last step, summed when
    /// asked for.
    pub(crate) walls: WallLoadsAtStep,
    /// The leapfrog's per-chunk energy sums (`leapfrog_step`'s buffer).
    pub(crate) step_work: Vec<StepWork>,
    /// Per chunk of the leapfrog, its checks' answers (their buffer).
    pub(crate) step_flags: Vec<ChunkCheck>,
    /// Whether a particle has moved beyond its limit since the collider's last build, as the
    /// leapfrog of the last step found; none when not known (before a step, or after a
    /// particle was moved by hand): the collider then looks at every particle.
    pub(crate) moved_beyond: Option<bool>,
    /// The first particle of each run of particles of one kind, then the particle count
    /// (`homes::particle_blocks`).
    pub(crate) blocks: Vec<usize>,
    /// Which thread steps which particles at this step, in every loop (`homes.rs`): the
    /// blocks cut by thread, set at the start of the step.
    pub(crate) homes: Homes,
    /// The leapfrog's homes when the pairs were stepped in parts (`Homes::set_by_parts`).
    pub(crate) part_homes: Homes,
    /// Per-stage wall-clock times.
    pub(crate) timers: Timers,
    /// The user's hook, if any.
    pub(crate) force_hook: Option<ForceHook>,
}

impl Pipeline {
    /// A fresh pipeline for `state` (no force hook, zero timers).
    pub(crate) fn new(state: &State) -> Self {
        let n = state.model.particles.len();
        Pipeline {
            collider: Collider::new(&state.model, state.settings.verlet_factor),
            adjacency: state.model.contact_adjacency(),
            contacts: ContactPipeline::new(&state.model, &state.contacts, state.settings.link_mode),
            force: vec![Vec3::zeros(); n],
            torque: vec![Vec3::zeros(); n],
            external_force: Vec::new(),
            external_torque: Vec::new(),
            walls: WallLoadsAtStep::zeros(state.model.walls.len()),
            step_work: Vec::new(),
            step_flags: Vec::new(),
            moved_beyond: None,
            blocks: particle_blocks(&state.model.particles),
            homes: Homes::default(),
            part_homes: Homes::default(),
            timers: Timers::default(),
            force_hook: None,
        }
    }

    /// Cuts the particles' blocks at the pool's thread count for this step's loops
    /// ([`Pipeline::homes`]).
    pub(crate) fn set_homes(&mut self) {
        self.homes.set_by_blocks(&self.blocks, rayon::current_num_threads());
    }

    /// Rebuilds what depends on the model and settings of `state`, keeping the force hook and
    /// the timers.
    pub(crate) fn rebuild(&mut self, state: &State) {
        let fresh = Pipeline::new(state);
        let hook = self.force_hook.take();
        let timers = self.timers;
        *self = Pipeline { force_hook: hook, timers, ..fresh };
    }
}

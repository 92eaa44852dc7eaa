//! The flexdem engine: collision detection, contact bookkeeping, parallel force assembly,
//! leapfrog integration with Cundall damping, the critical time step (model.md §4–6), walls
//! that hold a stress and the measures of a sample (stress, solid fraction; model.md §5),
//! pressure on PFacets (model.md §6).

mod broad_phase;
mod collider;
mod contact;
mod contact_forces;
mod contact_list;
mod contacts;
mod culprit;
mod dashpots;
mod energy;
mod error;
mod fresh_shares;
mod gather;
mod home_loops;
mod homes;
mod integrator;
mod integrator_lanes;
mod links;
mod measures;
mod model_edit;
mod neighbours;
mod offsets;
mod pair_book;
mod pair_chunk;
mod pair_keys;
mod pair_parts;
mod pair_passes;
mod pair_step;
mod pair_store;
mod parallel;
mod part_step;
mod pipeline;
mod prefilter;
mod pressure;
mod region;
mod servo;
mod settings;
mod simulation;
mod stages;
mod state;
mod step_work;
mod stiffness_sums;
mod time_step;
mod timers;
mod touchings;
mod turn;

pub use broad_phase::BroadPhase;
pub use collider::Collider;
pub use contact::Contact;
pub use contact_list::Contacts;
pub use energy::{Energy, EnergyAccount, EnergyWatch, PendingWork};
pub use error::SimulationError;
pub use integrator::{kinetic_energy, leapfrog_step, Leapfrog, StepWork};
pub use links::{LinkEvents, LinkLoad, LinkUpdate, Links};
pub use measures::{
    deviator_stress, love_weber_stress, mean_stress, membrane_sample_volume, normal_force,
    solid_fraction, wall_gap, wall_normal_stress,
};
pub use neighbours::{AppliedForce, ContactKey, NeighbourList, PairContact};
pub use offsets::OFFSET_RELEASE_STEPS;
pub use pipeline::ForceHook;
pub use pressure::{add_pressure_forces, pressure_node_force, Pressure};
pub use region::Region;
pub use servo::{SampleSection, StressControl, WallControl, SERVO_RELAXATION};
pub use settings::{Load, Ramp, Settings, TimeStep, DEFAULT_ENERGY_TOLERANCE};
pub use simulation::{Control, Simulation};
pub use state::{Clock, State};
pub use time_step::{critical_step_from_stiffness, p_wave_time_step, StiffnessSums};
pub use timers::{Stage, Timers};

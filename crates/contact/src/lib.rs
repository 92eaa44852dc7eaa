//! The flexdem contact law (paper §2–3): materials, stiffnesses (eq 3, 4, 8), the force and
//! moment update of one contact or beam link with plastic limits and breakage (eq 1–2, 5–7),
//! contact dashpots (model.md §7), and energy terms. Pure functions over plain contact state;
//! the engine only calls them.
//!
//! Conventions (see `docs/architecture.md`):
//! - the normal n points **from body 1 to body 2**, the overlap δ > 0 when touching;
//! - the normal force is a scalar, **compression positive**;
//! - the stored shear force is the one acting **on body 2** (body 1 gets the opposite), and the
//!   total contact force returned is the force on body 2, F2 = Fn·n + Fs;
//! - a link's relative rotation is that of node 2 relative to node 1, and its moments are
//!   reported as the moment on node 2 (node 1 gets the opposite).
//!
//! Modules: [`material`] (materials and validation), [`stiffness`] (eq 3, 4, 8), [`strength`]
//! (eq 7), [`rotation`] (exact shear transport), [`frictional`] (non-cohesive contacts),
//! [`damping`] (their dashpots), [`link`] (beam links), [`energy`].

pub mod damping;
pub mod energy;
pub mod frictional;
pub mod frictional_lanes;
pub mod link;
pub mod link_lanes;
pub mod material;
pub mod rotation;
pub mod stiffness;
pub mod strength;
mod transport_lanes;

#[cfg(test)]
mod test_support;

pub use damping::{
    contact_dashpots, damping_ratio, effective_mass, material_dashpots, restitution_of_ratio,
    Dashpots,
};
pub use energy::{
    cap_dissipation, slip_dissipation, slip_energy, spring_energy, spring_energy_squared,
    Dissipation,
};
pub use frictional::{
    update_frictional_contact, ContactForces, ContactKinematics, FrictionalContact,
    FrictionalParams,
};
pub use link::{
    link_elastic_energy, update_link, update_link_parts, LinkClass, LinkEvent, LinkForces,
    LinkKinematics, LinkKinematicsMode, LinkParams, LinkPlastic, LinkSpring, LinkState, LinkStatus,
};
pub use material::{effective_strength, ContactDamping, FailureMode, Material, MaterialError};
pub use rotation::{rotate_about_axis, rotate_between, rotation_vector, transport_tangent};
pub use stiffness::{
    beam_link_stiffness, contact_stiffness, friction_coefficient, ContactStiffness, LinkStiffness,
};
pub use strength::{contact_strength, link_strength, ContactStrength};

//! Frictional (non-cohesive) contact between two real or virtual spheres: eq 1, 2 and the
//! Coulomb limit (eq 7 with σn = σs = 0).
//!
//! Conventions: the normal n points from body 1 to body 2, the overlap δ > 0 when touching, the
//! normal force is a scalar (compression positive), and the stored shear force is the one acting
//! **on body 2** (body 1 gets the opposite). The force on body 2 is F2 = Fn·n + Fs.

use crate::energy::{slip_dissipation, spring_energy, Dissipation};
use crate::material::Material;
use crate::rotation::transport_tangent;
use crate::stiffness::{contact_stiffness, friction_coefficient};
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// Constants of a frictional contact.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrictionalParams {
    /// Normal stiffness kn (eq 3).
    pub kn: Real,
    /// Shear stiffness ks (eq 4).
    pub ks: Real,
    /// Friction coefficient tanφ, φ = min(φ1, φ2).
    pub tan_phi: Real,
}

impl FrictionalParams {
    /// kn, ks of eq 3, 4 and tan(min φ) for bodies (m1, r1) and (m2, r2).
    pub fn from_materials(m1: &Material, r1: Real, m2: &Material, r2: Real) -> Self {
        let k = contact_stiffness(m1, r1, m2, r2);
        FrictionalParams { kn: k.kn, ks: k.ks, tan_phi: friction_coefficient(m1, m2) }
    }
}

/// State carried by a frictional contact from step to step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrictionalContact {
    /// Shear force on body 2 (N), tangent to `normal`.
    pub shear_force: Vec3,
    /// Normal of the previous update (unit, from body 1 to body 2).
    pub normal: Vec3,
    /// Energy dissipated over the contact's life (only `friction` is used here).
    pub dissipated: Dissipation,
    /// Overlap offset δ₀ ≥ 0 (m): the normal force is `kn·(δ − δ₀)` (model: "contacts born
    /// deep"). 0 for a contact found when it first touched; set when a touching changes the
    /// features that own it, so that the force it carries does not jump (the engine's
    /// hand-over), and kept for the contact's life, which keeps the law conservative.
    pub overlap_offset: Real,
    /// Normal force of the last update (N): what the contact carries when it ends.
    pub normal_force: Real,
}

impl FrictionalContact {
    /// A fresh contact with no shear force and no overlap offset, at the given (unit) normal.
    pub fn new(normal: Vec3) -> Self {
        FrictionalContact {
            shear_force: Vec3::zeros(),
            normal,
            dissipated: Dissipation::default(),
            overlap_offset: 0.0,
            normal_force: 0.0,
        }
    }
}

/// Kinematics of a contact at the end of the step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactKinematics {
    /// Unit normal from body 1 to body 2.
    pub normal: Vec3,
    /// Overlap δ (> 0 when touching).
    pub overlap: Real,
    /// Velocity of the contact point on body 2 minus on body 1 (full vector; only its tangential
    /// part is used).
    pub relative_velocity: Vec3,
    /// Mean spin about the normal, n·(ω1 + ω2)/2 (rad/s): twists the stored shear force.
    pub spin_about_normal: Real,
}

/// What one update of a frictional contact returns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactForces {
    /// Normal force Fn = kn·δ (eq 1), compression positive.
    pub normal_force: Real,
    /// Shear force on body 2 (eq 2, capped by Coulomb).
    pub shear_force: Vec3,
    /// Total force on body 2: Fn·n + Fs (body 1 gets the opposite).
    pub force_on_2: Vec3,
    /// Elastic energy stored: Fn²/(2kn) + |Fs|²/(2ks).
    pub elastic_energy: Real,
    /// Energy dissipated in this update.
    pub dissipated: Dissipation,
    /// The shear force was capped by Coulomb in this update.
    pub sliding: bool,
}

/// One step of a frictional contact (eq 1, 2, 7 with σ = 0):
///
/// The overlap that makes force is `δ − δ₀` ([`FrictionalContact::overlap_offset`]); below,
/// δ stands for it.
///
/// 1. δ ≤ 0: no force; the state is reset (no shear history, normal updated).
/// 2. Rotate the stored Fs onto the new tangent plane: the minimal rotation taking the previous
///    normal to the new one, then a twist of spin·dt about n (exact Rodrigues, |Fs| preserved).
/// 3. Fs ← Fs − ks·u̇s·dt, u̇s the tangential part of the relative velocity (eq 2).
/// 4. Fn = kn·δ (eq 1); Coulomb: |Fs| ≤ Fn·tanφ, the excess dissipates
///    (|Fs_trial| − |Fs|)·|Fs|/ks.
pub fn update_frictional_contact(
    params: &FrictionalParams,
    state: &mut FrictionalContact,
    kin: &ContactKinematics,
    dt: Real,
) -> ContactForces {
    let n = kin.normal;
    debug_assert!((n.norm_squared() - 1.0).abs() < 1e-9, "normal must be unit");
    let overlap = kin.overlap - state.overlap_offset;
    if overlap.is_nan() || overlap <= 0.0 {
        state.shear_force = Vec3::zeros();
        state.normal = n;
        state.normal_force = 0.0;
        return ContactForces::default();
    }
    let rotated = transport_tangent(state.shear_force, state.normal, n, kin.spin_about_normal * dt);
    let v = kin.relative_velocity;
    let us_dot = v - n * n.dot(&v);
    let trial = rotated - us_dot * (params.ks * dt);
    let fn_ = params.kn * overlap;
    let limit = (fn_ * params.tan_phi).max(0.0);
    let trial_mag = trial.norm();
    let (fs, sliding, friction) = if trial_mag > limit {
        let fs = if trial_mag > 0.0 { trial * (limit / trial_mag) } else { Vec3::zeros() };
        (fs, true, slip_dissipation(&rotated, &trial, &fs, params.ks))
    } else {
        (trial, false, 0.0)
    };
    state.shear_force = fs;
    state.normal = n;
    state.normal_force = fn_;
    let dissipated = Dissipation { friction, ..Default::default() };
    state.dissipated += dissipated;
    ContactForces {
        normal_force: fn_,
        shear_force: fs,
        force_on_2: n * fn_ + fs,
        elastic_energy: spring_energy(fn_, params.kn) + spring_energy(fs.norm(), params.ks),
        dissipated,
        sliding,
    }
}

#[cfg(test)]
#[path = "frictional_tests.rs"]
mod tests;

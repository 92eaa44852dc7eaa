//! Frictional (non-cohesive) contact between two real or virtual spheres: eq 1, 2 and the
//! Coulomb limit (eq 7 with σn = σs = 0), with optional normal and tangential dashpots
//! (model.md §7).
//!
//! Conventions: the normal n points from body 1 to body 2, the overlap δ > 0 when touching, the
//! normal force is a scalar (compression positive), and the stored shear force is the one acting
//! **on body 2** (body 1 gets the opposite). The force on body 2 is F2 = Fn·n + Fs.

use crate::damping::contact_dashpots;
use crate::energy::{
    slip_dissipation, slip_energy, spring_energy, spring_energy_squared, Dissipation,
};
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
    /// Normal dashpot cn (N·s/m, model.md §7); 0 = none.
    pub cn: Real,
    /// Tangential dashpot ct (N·s/m, model.md §7); 0 = none.
    pub ct: Real,
}

impl FrictionalParams {
    /// kn, ks of eq 3, 4, tan(min φ) for bodies (m1, r1) and (m2, r2), and the dashpots their
    /// materials' damping gives a pair of effective mass `m_eff` (kg;
    /// [`crate::damping::contact_dashpots`]: none for materials without damping, or when
    /// `m_eff` is not finite).
    pub fn from_materials(m1: &Material, r1: Real, m2: &Material, r2: Real, m_eff: Real) -> Self {
        let k = contact_stiffness(m1, r1, m2, r2);
        let d = contact_dashpots(m1, m2, m_eff, k.kn, k.ks);
        FrictionalParams {
            kn: k.kn,
            ks: k.ks,
            tan_phi: friction_coefficient(m1, m2),
            cn: d.cn,
            ct: d.ct,
        }
    }

    /// Whether the contact has a dashpot (cn > 0 or ct > 0).
    pub fn is_damped(&self) -> bool {
        self.cn > 0.0 || self.ct > 0.0
    }
}

/// State carried by a frictional contact from step to step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrictionalContact {
    /// Force of the shear spring on body 2 (N), tangent to `normal` (without the tangential
    /// dashpot's).
    pub shear_force: Vec3,
    /// Normal of the previous update (unit, from body 1 to body 2).
    pub normal: Vec3,
    /// Energy dissipated by Coulomb slip over the contact's life (J): what the energy
    /// balance books when the contact ends. (The dashpots' dissipation is booked per
    /// update, `ContactForces::dissipated`; a frictional contact has no plastic or breakage
    /// term, so the state keeps the one total it needs: 8 bytes where a `Dissipation` is 32.)
    pub dissipated_friction: Real,
    /// Overlap offset δ₀ (m): the normal force is `kn·(δ − δ₀)` (docs/model.md §1, §2). 0 for
    /// a contact found when it first touched; set when a touching changes the features that
    /// own it, so that the force it carries does not jump (the engine's hand-over), then
    /// given back over the next steps with its energy booked; for two intersecting faces it
    /// also holds their motion along the normal (their geometric overlap stays r₁ + r₂), and
    /// is negative when they are driven deeper than that.
    pub overlap_offset: Real,
    /// Force of the normal spring at the last update (N), `kn·(δ − δ₀)` (without the
    /// dashpot's): what the spring carries when the contact ends.
    pub normal_force: Real,
}

impl FrictionalContact {
    /// A fresh contact with no shear force and no overlap offset, at the given (unit) normal.
    pub fn new(normal: Vec3) -> Self {
        FrictionalContact {
            shear_force: Vec3::zeros(),
            normal,
            dissipated_friction: 0.0,
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
    /// Velocity of the contact point on body 2 minus on body 1 (full vector: its tangential
    /// part drives the shear spring; the dashpots use all of it).
    pub relative_velocity: Vec3,
    /// Mean spin about the normal, n·(ω1 + ω2)/2 (rad/s): twists the stored shear force.
    pub spin_about_normal: Real,
}

/// What one update of a frictional contact returns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactForces {
    /// Normal force Fn = kn·δ (eq 1), with a normal dashpot `max(kn·δ − cn·vn, 0)`;
    /// compression positive.
    pub normal_force: Real,
    /// Tangential force on body 2: the shear spring (eq 2) plus the tangential dashpot,
    /// capped by Coulomb.
    pub shear_force: Vec3,
    /// Total force on body 2: Fn·n + Fs (body 1 gets the opposite).
    pub force_on_2: Vec3,
    /// The dashpots' part of `force_on_2` (N): `(Fn − kn·δ)·n − ct·u̇s`; zero without dashpots.
    pub dashpot_force: Vec3,
    /// Elastic energy stored in the springs: (kn·δ)²/(2kn) + |Fs,spring|²/(2ks).
    pub elastic_energy: Real,
    /// Energy dissipated in this update.
    pub dissipated: Dissipation,
    /// The shear force was capped by Coulomb in this update.
    pub sliding: bool,
}

/// One step of a frictional contact (eq 1, 2, 7 with σ = 0), with the dashpots of model.md §7:
///
/// The overlap that makes force is `δ − δ₀` ([`FrictionalContact::overlap_offset`]); below,
/// δ stands for it. `v` is the relative velocity (body 2 minus body 1 at the contact point),
/// `vn = n·v` (< 0 when approaching) and `u̇s = v − vn·n` its tangential part.
///
/// 1. δ ≤ 0: no force; the state is reset (no shear history, normal updated).
/// 2. Rotate the stored shear spring force Fs onto the new tangent plane: the minimal rotation
///    taking the previous normal to the new one, then a twist of spin·dt about n (exact
///    Rodrigues, |Fs| preserved).
/// 3. Fs ← Fs − ks·u̇s·dt, u̇s the tangential part of the relative velocity (eq 2).
/// 4. Fn = max(kn·δ − cn·vn, 0) (eq 1 and the normal dashpot): clamped so that the dashpot
///    never pulls the bodies together (LAMMPS's `gran/hooke` does not clamp; with cn = 0 the
///    clamp never acts). The normal dashpot applied is `Fn − kn·δ`.
/// 5. The tangential force is `Ft = Fs − ct·u̇s`; Coulomb: |Ft| ≤ Fn·tanφ. When it slides, Ft
///    is scaled onto the limit and the spring is set to `Ft + ct·u̇s`, so that spring plus
///    dashpot equal the limit (LAMMPS rescales its shear history the same way); the friction
///    dissipation is the spring's slip, `½·(Fs_rotated + Fs)·(Fs_trial − Fs)/ks`
///    ([`slip_dissipation`]; without its floor at 0 when ct > 0, [`slip_energy`]: a dashpot
///    stronger than the limit sets the spring against the slip).
///
/// The dashpots dissipate `−F_d·v·dt` in the update (`dissipated.viscous`), `F_d` their force
/// on body 2 as applied (after the clamp). `elastic_energy` is the springs' energy only.
/// With cn = ct = 0 every result is the one of the purely elastic–frictional law, bit for bit.
#[inline(always)]
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
    let vn = n.dot(&v);
    let us_dot = v - n * vn;
    let trial = rotated - us_dot * (params.ks * dt);
    let spring_n = params.kn * overlap;
    // the dashpots, each only when present: without them the law is the undamped one exactly
    let fn_ = if params.cn > 0.0 { (spring_n - params.cn * vn).max(0.0) } else { spring_n };
    let damped_t = params.ct > 0.0;
    let dashpot_t = if damped_t { us_dot * -params.ct } else { Vec3::zeros() };
    let total = if damped_t { trial + dashpot_t } else { trial };
    let limit = (fn_ * params.tan_phi).max(0.0);
    // |F| > limit from the squares: the root only when it slides
    let total2 = total.norm_squared();
    let (fs, spring, sliding, friction) = if total2 > limit * limit {
        let total_mag = total2.sqrt();
        let fs = if total_mag > 0.0 { total * (limit / total_mag) } else { Vec3::zeros() };
        if damped_t {
            let spring = fs - dashpot_t;
            (fs, spring, true, slip_energy(&rotated, &trial, &spring, params.ks))
        } else {
            (fs, fs, true, slip_dissipation(&rotated, &trial, &fs, params.ks))
        }
    } else {
        (total, trial, false, 0.0)
    };
    state.shear_force = spring;
    state.normal = n;
    state.normal_force = spring_n;
    let (dashpot_force, viscous) = if params.is_damped() {
        let f = n * (fn_ - spring_n) + dashpot_t;
        (f, -f.dot(&v) * dt)
    } else {
        (Vec3::zeros(), 0.0)
    };
    let dissipated = Dissipation { friction, viscous, ..Default::default() };
    state.dissipated_friction += friction;
    ContactForces {
        normal_force: fn_,
        shear_force: fs,
        force_on_2: n * fn_ + fs,
        dashpot_force,
        elastic_energy: spring_energy(spring_n, params.kn)
            + spring_energy_squared(spring.norm_squared(), params.ks),
        dissipated,
        sliding,
    }
}

#[cfg(test)]
#[path = "frictional_tests.rs"]
mod tests;

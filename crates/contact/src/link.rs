//! Beam links (paper §3, model.md §3): the cohesive interaction between the two nodes of a
//! connection, with stiffnesses of eq 8, the normal, shear and moment laws of eq 1, 2, 5, 6 and
//! the limits of eq 7.
//!
//! # Kinematics
//! L = |x2 − x1|, n = (x2 − x1)/L (from node 1 to node 2).
//! - Normal (eq 1): Fn = kn·(L0 + e_p − L), zero at rest length, compression positive; e_p is
//!   the plastic elongation (plastic mode only).
//! - Shear (eq 2): the stored shear force (on node 2) is rotated onto the new tangent plane
//!   (minimal rotation of the previous normal onto n, then a twist of spin·dt about n,
//!   spin = n·(ω1 + ω2)/2), then Fs ← Fs − ks·α·u̇s·dt with u̇s the tangential part of
//!   (v2 − v1) − (L/2)(ω1 + ω2) × n, the relative velocity of the link's midpoint seen from each
//!   node. [`LinkKinematicsMode::Beam`] (α = 1) makes the link an exact small-rotation
//!   Euler–Bernoulli frame element (reference §5.4); [`LinkKinematicsMode::Yade`] uses
//!   α = 2r/L, YADE's `avoidGranularRatcheting`, a softer shear term (one-element cantilever
//!   tip deflection PL³/(4EI) + PL³/(12αEI) instead of PL³/(3EI)).
//! - Moments (eq 5, 6), when `moments` is on and the link is cohesive: θ = rotation vector of
//!   q_rel = (q2·q2⁰⁻¹)·(q1·q1⁰⁻¹)⁻¹, angle in (−π, π], the total rotation of node 2 relative to
//!   node 1 since the link was made, minus the plastic rotation; twist θt = (θ·n)n, bending
//!   θb = θ − θt. Moment on node 2: Mt = −kt·θt, Mb = −kb·θb; node 1 gets the opposite.
//! - Forces: node 2 gets F2 = Fn·n + Fs, node 1 gets −F2; the shear force acts at the
//!   midpoint c, so node i also gets the torque (c − x_i) × F_i = −(L/2) n × Fs (the same on both
//!   nodes), plus its moment.
//!
//! # Limits (eq 7) and failure
//! - Plastic: tension capped at σn·A with the excess going into e_p (unloading is elastic);
//!   |Fs| capped at Fn·tanφ + σs·A; |Mt| and |Mb| capped at their limits with the excess going
//!   into the plastic rotation (stored in node 1's body frame, so it turns with the link).
//!   A plastic link never breaks.
//! - Fragile: tension above σn·A breaks the link for good ([`LinkStatus::Broken`], all forces
//!   zero from then on). A shear force above Fn·tanφ + σs·A **or a moment above its limit**
//!   makes the link lose its cohesion ([`LinkStatus::Frictional`]): from then on it is a
//!   compression-only spring around L0 with Coulomb friction (|Fs| ≤ Fn·tanφ) and no moments,
//!   which breaks as soon as it goes into tension (as YADE erases it). A moment failure is a
//!   cohesion failure like a shear failure: the nodes are still in contact, only the bond is
//!   gone. When cohesion is lost while in tension, the link is broken in the same step.
//!
//! # Energy
//! Elastic energy Fn²/(2kn) + |Fs|²/(2α·ks) + |Mt|²/(2kt) + |Mb|²/(2kb): in yade mode the shear
//! spring's effective stiffness is α·ks (the work done on the link is |Fs|·|u̇s|dt, its force
//! grows by α·ks·|u̇s|dt). Caps dissipate (|F_trial| − |F_cap|)·|F_cap|/k. Breakage and a
//! cohesion loss release what the springs that stop carrying their trial force take out of
//! the leapfrog's balance, `½·F_t·F₋/k` for one that is gone (`spring_exit`; model.md §3).

use crate::energy::{cap_dissipation, spring_energy, spring_energy_squared, Dissipation};
use crate::material::{FailureMode, Material};
use crate::rotation::{rotation_vector, transport_tangent};
use crate::stiffness::{beam_link_stiffness, LinkStiffness};
use crate::strength::{link_strength, ContactStrength};
use flexdem_geom::{Real, Vec3};
use nalgebra::UnitQuaternion;
use serde::{Deserialize, Serialize};

/// Shear kinematics of a link (model.md §3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum LinkKinematicsMode {
    /// Branch vectors of length L/2 from each node: an exact small-rotation Euler–Bernoulli
    /// frame element (default).
    #[default]
    Beam,
    /// YADE's kinematics: the tangential displacement scaled by α = 2r/L (softer in shear);
    /// a virtual sphere on a connection turning with the axis at YADE's `s × (v1 − v0)`
    /// where the rigid rate is `s × (v1 − v0)/L²`, a contact's moment shared among the
    /// connection's nodes as torques, and contacts on connections and PFacets sliding at
    /// YADE's non-ratcheting relative velocity, as YADE does
    /// (`flexdem_elements::virtual_sphere`; this pair does not conserve energy, the `Beam`
    /// one does).
    Yade,
}

/// Constants a link shares with every link of the same material, radius and kinematics
/// (88 bytes; the engine keeps one per such group, see [`LinkSpring`] for the rest).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinkClass {
    /// Radius r of the connection (m).
    pub radius: Real,
    /// Limits of eq 7 and tanφ.
    pub strength: ContactStrength,
    /// Fragile or plastic at the limits.
    pub failure: FailureMode,
    /// Twisting and bending moments on (eq 5, 6).
    pub moments: bool,
    /// Shear kinematics.
    pub mode: LinkKinematicsMode,
}

impl LinkClass {
    /// The constants of links of radius r made of material m: limits of eq 7 with R = r,
    /// failure mode and moments flag of the material.
    pub fn from_material(m: &Material, radius: Real, mode: LinkKinematicsMode) -> Self {
        LinkClass {
            radius,
            strength: link_strength(m, radius),
            failure: m.failure,
            moments: m.moments,
            mode,
        }
    }
}

/// The constants of one link that depend on its rest length (40 bytes).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinkSpring {
    /// kn, ks, kb, kt (eq 8).
    pub stiffness: LinkStiffness,
    /// Rest length L0 (m).
    pub rest_length: Real,
}

impl LinkSpring {
    /// The springs of a link of radius r and rest length L0 made of material m (eq 8).
    pub fn from_material(m: &Material, radius: Real, rest_length: Real) -> Self {
        LinkSpring { stiffness: beam_link_stiffness(m, radius, rest_length), rest_length }
    }
}

/// Every constant of one beam link: its class and its springs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinkParams {
    /// What it shares with links of the same material, radius and kinematics.
    pub class: LinkClass,
    /// Stiffnesses and rest length.
    pub spring: LinkSpring,
}

impl LinkParams {
    /// A link of radius r and rest length L0 made of material m: stiffnesses of eq 8, limits of
    /// eq 7 with R = r, failure mode and moments flag of the material.
    pub fn from_material(
        m: &Material,
        radius: Real,
        rest_length: Real,
        mode: LinkKinematicsMode,
    ) -> Self {
        LinkParams {
            class: LinkClass::from_material(m, radius, mode),
            spring: LinkSpring::from_material(m, radius, rest_length),
        }
    }
}

/// Whether a link still holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum LinkStatus {
    /// Intact cohesive beam.
    #[default]
    Cohesive,
    /// Lost its cohesion after a shear or moment failure: compression-only frictional contact.
    Frictional,
    /// Broken for good: no forces.
    Broken,
}

/// What happened to a link in one update.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum LinkEvent {
    /// Nothing.
    #[default]
    None,
    /// A fragile cohesive link exceeded its tensile limit and is now broken.
    BrokeInTension,
    /// A fragile link exceeded its shear or a moment limit and is now frictional.
    LostCohesion,
    /// A link without cohesion (lost now or before) went into tension and is now broken.
    Separated,
}

/// State of a link, carried from step to step (88 bytes): what the update reads and writes,
/// nothing else, but for the plastic part ([`LinkPlastic`]), which only the links of a plastic
/// material need. The energy a link dissipates is returned by each update
/// ([`LinkForces::dissipated`]) for the caller to sum.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinkState {
    /// Normal of the previous update (unit, node 1 → node 2).
    pub normal: Vec3,
    /// Shear force on node 2 (N), tangent to `normal`.
    pub shear_force: Vec3,
    /// q2⁰⁻¹·q1⁰, from the nodes' orientations q1⁰, q2⁰ when the link was made: the relative
    /// rotation (q2·q2⁰⁻¹)·(q1·q1⁰⁻¹)⁻¹ is q2·`rest_rotation`·q1⁻¹, two quaternion products
    /// where the two references would take three.
    pub rest_rotation: UnitQuaternion<Real>,
    /// Cohesive, frictional or broken.
    pub status: LinkStatus,
}

/// The plastic part of a link's state (32 bytes), carried from step to step: zero for the
/// links of a fragile material, which lose their cohesion at a limit instead of yielding
/// (the engine keeps it only when some material is plastic).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LinkPlastic {
    /// Plastic elongation e_p (m): the normal force is kn·(L0 + e_p − L).
    pub elongation: Real,
    /// Plastic relative rotation (rad), in node 1's body frame: the world vector is
    /// q1·`rotation`, so that it turns with the link.
    pub rotation: Vec3,
}

impl LinkState {
    /// A fresh cohesive link between nodes at x1, x2 with orientations q1, q2 (the references of
    /// the relative rotation). Coincident nodes get the normal +x.
    pub fn new(x1: Vec3, x2: Vec3, q1: UnitQuaternion<Real>, q2: UnitQuaternion<Real>) -> Self {
        LinkState {
            normal: (x2 - x1).try_normalize(0.0).unwrap_or_else(Vec3::x),
            shear_force: Vec3::zeros(),
            rest_rotation: q2.inverse() * q1,
            status: LinkStatus::Cohesive,
        }
    }
}

/// Kinematics of the two nodes at the end of the step (velocities over the step).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinkKinematics {
    /// Position of node 1.
    pub x1: Vec3,
    /// Position of node 2.
    pub x2: Vec3,
    /// Velocity of node 1.
    pub v1: Vec3,
    /// Velocity of node 2.
    pub v2: Vec3,
    /// Angular velocity of node 1.
    pub w1: Vec3,
    /// Angular velocity of node 2.
    pub w2: Vec3,
    /// Orientation of node 1.
    pub q1: UnitQuaternion<Real>,
    /// Orientation of node 2.
    pub q2: UnitQuaternion<Real>,
}

/// What one update of a link returns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LinkForces {
    /// Force on node 1 (= −`force_on_2`).
    pub force_on_1: Vec3,
    /// Force on node 2: Fn·n + Fs.
    pub force_on_2: Vec3,
    /// Torque on node 1: −(L/2) n × Fs − (Mt + Mb).
    pub torque_on_1: Vec3,
    /// Torque on node 2: −(L/2) n × Fs + (Mt + Mb).
    pub torque_on_2: Vec3,
    /// The shear force's torque about each node, −(L/2) n × Fs (the same on both).
    pub lever_torque: Vec3,
    /// Normal force Fn (compression positive).
    pub normal_force: Real,
    /// Shear force on node 2.
    pub shear_force: Vec3,
    /// Twisting moment Mt on node 2 (along n).
    pub twist_moment: Vec3,
    /// Bending moment Mb on node 2 (normal to n).
    pub bending_moment: Vec3,
    /// Elastic energy stored after the update.
    pub elastic_energy: Real,
    /// Energy dissipated in this update.
    pub dissipated: Dissipation,
    /// Breakage or cohesion loss in this update.
    pub event: LinkEvent,
}

/// Trial (elastic) quantities of one step.
struct Trial {
    n: Vec3,
    l: Real,
    fn_: Real,
    fs: Vec3,
    ks: Real,
    /// The shear force of the step before, transported onto the new tangent plane (for the
    /// springs' exit when the link breaks, [`spring_exit`]).
    fs_before: Vec3,
    /// The plastic elongation in `fn_`.
    elongation: Real,
    /// The step just done, dt₀ (s).
    dt: Real,
}

/// One step of a beam link (eq 1, 2, 5–8; see the module documentation for the kinematics,
/// limits and failure rules), with its constants in one [`LinkParams`]: [`update_link_parts`].
#[inline]
pub fn update_link(
    params: &LinkParams,
    state: &mut LinkState,
    plastic: &mut LinkPlastic,
    kin: &LinkKinematics,
    dt: Real,
) -> LinkForces {
    update_link_parts(&params.class, &params.spring, state, plastic, kin, dt)
}

/// One step of a beam link (eq 1, 2, 5–8; see the module documentation for the kinematics,
/// limits and failure rules), with its constants in two parts: the `class` it shares with
/// links of the same material and radius, and its own `spring`. Updates `state` and
/// `plastic` (written only for a plastic material: a fragile link may be given a zero one
/// that is not kept) and returns the forces and torques on both nodes. `dt` is the step
/// just done, dt₀, over which the nodes moved with `kin`'s velocities and spins: the energy
/// a break releases is measured from the poses they had then (`x − v·dt₀`,
/// `rot(−ω·dt₀)·q`), which a pose set by hand in between makes off for that step.
///
/// Inlined into the links' loop, where only the fields of the engine's `LinkLoad` are kept:
/// the rest is computed only for callers that read it.
#[inline]
pub fn update_link_parts(
    class: &LinkClass,
    spring: &LinkSpring,
    state: &mut LinkState,
    plastic: &mut LinkPlastic,
    kin: &LinkKinematics,
    dt: Real,
) -> LinkForces {
    if state.status == LinkStatus::Broken {
        return LinkForces::default();
    }
    let k = &spring.stiffness;
    let d = kin.x2 - kin.x1;
    let l = d.norm();
    // one division for n and α (a division is as slow as a square root)
    let inv_l = if l > 0.0 { 1.0 / l } else { 0.0 };
    let n = if l > 0.0 { d * inv_l } else { state.normal };
    let spin = 0.5 * n.dot(&(kin.w1 + kin.w2));
    let rotated = transport_tangent(state.shear_force, state.normal, n, spin * dt);
    let mut us = (kin.v2 - kin.v1) - (kin.w1 + kin.w2).cross(&n) * (0.5 * l);
    us -= n * n.dot(&us);
    let alpha = match class.mode {
        LinkKinematicsMode::Yade if l > 0.0 => 2.0 * class.radius * inv_l,
        _ => 1.0,
    };
    let ks = k.ks * alpha;
    state.normal = n;
    let trial = Trial {
        n,
        l,
        fn_: k.kn * (spring.rest_length + plastic.elongation - l),
        fs: rotated - us * (ks * dt),
        ks,
        fs_before: rotated,
        elongation: plastic.elongation,
        dt,
    };
    match state.status {
        LinkStatus::Cohesive => cohesive_step(class, spring, state, plastic, kin, &trial),
        _ => frictional_step(class, spring, state, kin, &trial, None),
    }
}

/// What a spring of a link takes out of the energy balance at the step where it stops
/// carrying the force its trial asks (it breaks, or is capped by the friction of a link that
/// lost its cohesion): `½·F_t·F₋/k + ½·F_a·(F_t − F₋)/k − ½·|F_a|²/k`, with `F_t` its trial
/// force at t, `F₋` its force one step before (transported), `F_a` the force it carries on
/// (0 when it is gone) and `k` its stiffness (forces and moments alike). The leapfrog's
/// balance, with the kinetic energy ½m·v(t − dt₀/2)·v(t + dt/2), is exact for a linear
/// spring present at both ends of a step; this is the jump when its force at t is `F_a`
/// instead of `F_t`: for a spring that is gone, `½k·x₋·x_t`. (The trial energy `½k·x_t²`
/// was booked before: a bias of `½k·x_t·(x_t − x₋)` towards energy lost at each break.)
#[inline]
fn spring_exit(trial: Vec3, before: Vec3, applied: Vec3, k: Real) -> Real {
    if !(k > 0.0) {
        return 0.0;
    }
    (0.5 * trial.dot(&before) + 0.5 * applied.dot(&(trial - before)) - 0.5 * applied.norm_squared())
        / k
}

/// The node-1-to-node-2 vector of the step before, from the nodes moved back along their
/// velocities: `x₋ = x − v·dt₀` (the leapfrog moved them by `v·dt₀`).
fn axis_before(t: &Trial, kin: &LinkKinematics) -> Vec3 {
    (kin.x2 - kin.v2 * t.dt) - (kin.x1 - kin.v1 * t.dt)
}

/// The normal force of the step before, `kn·(L0 + e_p − L₋)` ([`axis_before`]).
fn normal_force_before(spring: &LinkSpring, t: &Trial, kin: &LinkKinematics) -> Real {
    spring.stiffness.kn * (spring.rest_length + t.elongation - axis_before(t, kin).norm())
}

/// The twisting and bending moments (on node 2) of the step before, split about the normal
/// of the step before ([`axis_before`]), as they were applied, from the nodes turned back by
/// their spins (`q₋ = rot(−ω·dt₀)·q`, the leapfrog's turn undone).
fn moments_before(
    spring: &LinkSpring,
    s: &LinkState,
    plastic: &LinkPlastic,
    kin: &LinkKinematics,
    t: &Trial,
) -> (Vec3, Vec3) {
    let k = &spring.stiffness;
    let back = |q: &UnitQuaternion<Real>, w: &Vec3| UnitQuaternion::from_scaled_axis(-w * t.dt) * q;
    let (q1, q2) = (back(&kin.q1, &kin.w1), back(&kin.q2, &kin.w2));
    let el = rotation_vector(&(q2 * s.rest_rotation * q1.inverse())) - q1 * plastic.rotation;
    let n = axis_before(t, kin).try_normalize(0.0).unwrap_or(t.n);
    let tw = n * n.dot(&el);
    (tw * -k.kt, (el - tw) * -k.kb)
}

/// [`spring_exit`] of a link's normal and shear springs when both are gone.
fn normal_and_shear_exit(spring: &LinkSpring, kin: &LinkKinematics, t: &Trial) -> Real {
    let (x, z) = (Vec3::x(), Vec3::zeros());
    let before = normal_force_before(spring, t, kin);
    spring_exit(x * t.fn_, x * before, z, spring.stiffness.kn)
        + spring_exit(t.fs, t.fs_before, z, t.ks)
}

/// The elastic energy of a link after an update, from what an engine keeps of it: its normal
/// force `fn_`, its moment `m` on node 2 (twist and bending summed), the state's shear force
/// Fs and normal n, and its length `l` (YADE's kinematics scale the shear stiffness by 2r/l):
/// `Fn²/2kn + |Fs|²/2ks + |Mt|²/2kt + |Mb|²/2kb`, `Mt = (m·n)n`, `Mb = m − Mt` (eq 8's
/// springs). With the update's length it is the update's [`LinkForces::elastic_energy`] to
/// rounding; zero for a broken link (no force is left).
pub fn link_elastic_energy(
    class: &LinkClass,
    spring: &LinkSpring,
    state: &LinkState,
    fn_: Real,
    m: &Vec3,
    l: Real,
) -> Real {
    let k = &spring.stiffness;
    let ks = match class.mode {
        LinkKinematicsMode::Yade if l > 0.0 => k.ks * (2.0 * class.radius / l),
        _ => k.ks,
    };
    let n = &state.normal;
    let mt = n * n.dot(m);
    let mb = m - mt;
    spring_energy(fn_, k.kn)
        + spring_energy(state.shear_force.norm(), ks)
        + spring_energy(mt.norm(), k.kt)
        + spring_energy(mb.norm(), k.kb)
}

#[inline]
fn cohesive_step(
    p: &LinkClass,
    spring: &LinkSpring,
    s: &mut LinkState,
    plastic: &mut LinkPlastic,
    kin: &LinkKinematics,
    t: &Trial,
) -> LinkForces {
    let k = &spring.stiffness;
    let lim = &p.strength;
    let n = t.n;
    // Moments (eq 5, 6) from the total relative rotation q2·q2⁰⁻¹·q1⁰·q1⁻¹ minus the plastic
    // rotation.
    let (mut mt, mut mb, theta) = if p.moments {
        let theta = rotation_vector(&(kin.q2 * s.rest_rotation * kin.q1.inverse()));
        let el = if plastic.rotation == Vec3::zeros() {
            theta
        } else {
            theta - kin.q1 * plastic.rotation
        };
        let tw = n * n.dot(&el);
        (tw * -k.kt, (el - tw) * -k.kb, theta)
    } else {
        (Vec3::zeros(), Vec3::zeros(), Vec3::zeros())
    };
    // squared magnitudes: the square roots are taken only where a limit is reached
    let fs2 = t.fs.norm_squared();
    let (mt2, mb2) = (mt.norm_squared(), mb.norm_squared());
    let e_trial = spring_energy(t.fn_, k.kn)
        + spring_energy_squared(fs2, t.ks)
        + spring_energy_squared(mt2, k.kt)
        + spring_energy_squared(mb2, k.kb);
    let fragile = p.failure == FailureMode::Fragile;
    let mut diss = Dissipation::default();

    // Tension (eq 7, first line).
    let mut fn_ = t.fn_;
    if let Some(tmax) = lim.tensile_force {
        if -t.fn_ > tmax {
            if fragile {
                let moments = moments_exit(p, spring, s, plastic, kin, t, (&mt, &mb));
                s.status = LinkStatus::Broken;
                s.shear_force = Vec3::zeros();
                diss.breakage = normal_and_shear_exit(spring, kin, t) + moments;
                return LinkForces {
                    dissipated: diss,
                    event: LinkEvent::BrokeInTension,
                    ..Default::default()
                };
            }
            fn_ = -tmax;
            plastic.elongation = t.l - spring.rest_length - tmax / k.kn;
            diss.plastic += cap_dissipation(-t.fn_, tmax, k.kn);
        }
    }

    // Shear and moment limits (eq 7, lines 2–4).
    let shear_cap = lim.shear_limit(fn_).filter(|&c| exceeds(fs2, c));
    let twist_cap = lim.twist_moment.filter(|&c| p.moments && exceeds(mt2, c));
    let bend_cap = lim.bending_moment.filter(|&c| p.moments && exceeds(mb2, c));
    if fragile && (shear_cap.is_some() || twist_cap.is_some() || bend_cap.is_some()) {
        let moments = moments_exit(p, spring, s, plastic, kin, t, (&mt, &mb));
        s.status = LinkStatus::Frictional;
        return frictional_step(p, spring, s, kin, t, Some(moments));
    }
    let mut fs = t.fs;
    if let Some(c) = shear_cap {
        let mag = fs2.sqrt();
        fs = scale_to(t.fs, mag, c);
        diss.plastic += cap_dissipation(mag, c, t.ks);
    }
    if let Some(c) = twist_cap {
        let mag = mt2.sqrt();
        mt = scale_to(mt, mag, c);
        diss.plastic += cap_dissipation(mag, c, k.kt);
    }
    if let Some(c) = bend_cap {
        let mag = mb2.sqrt();
        mb = scale_to(mb, mag, c);
        diss.plastic += cap_dissipation(mag, c, k.kb);
    }
    if twist_cap.is_some() || bend_cap.is_some() {
        // New elastic rotation from the capped moments; the rest is plastic.
        let el = -(mt * inv(k.kt) + mb * inv(k.kb));
        plastic.rotation = kin.q1.inverse() * (theta - el);
    }
    s.shear_force = fs;
    let capped = fn_ != t.fn_ || shear_cap.is_some() || twist_cap.is_some() || bend_cap.is_some();
    let elastic = if capped {
        spring_energy(fn_, k.kn)
            + spring_energy(fs.norm(), t.ks)
            + spring_energy(mt.norm(), k.kt)
            + spring_energy(mb.norm(), k.kb)
    } else {
        e_trial
    };
    assemble(n, t.l, fn_, fs, mt, mb, elastic, diss, LinkEvent::None)
}

/// [`spring_exit`] of a cohesive link's moments when they are gone (its trial moments `m`,
/// twist and bending on node 2); 0 without moments.
fn moments_exit(
    p: &LinkClass,
    spring: &LinkSpring,
    s: &LinkState,
    plastic: &LinkPlastic,
    kin: &LinkKinematics,
    t: &Trial,
    m: (&Vec3, &Vec3),
) -> Real {
    if !p.moments {
        return 0.0;
    }
    let (twist, bending) = moments_before(spring, s, plastic, kin, t);
    let (k, z) = (&spring.stiffness, Vec3::zeros());
    spring_exit(*m.0, twist, z, k.kt) + spring_exit(*m.1, bending, z, k.kb)
}

/// A link without cohesion: compression-only spring with Coulomb friction, no moments; broken
/// when in tension. `losing` is given in the step in which cohesion is lost, with the exit of
/// the moments ([`moments_exit`]): the energy released then, what the springs take out of
/// the balance ([`spring_exit`]), is counted as breakage rather than friction.
#[inline]
fn frictional_step(
    p: &LinkClass,
    spring: &LinkSpring,
    s: &mut LinkState,
    kin: &LinkKinematics,
    t: &Trial,
    losing: Option<Real>,
) -> LinkForces {
    let k = &spring.stiffness;
    let mut diss = Dissipation::default();
    let fs_trial_mag = t.fs.norm();
    if t.fn_ < 0.0 {
        s.status = LinkStatus::Broken;
        s.shear_force = Vec3::zeros();
        diss.breakage = normal_and_shear_exit(spring, kin, t) + losing.unwrap_or(0.0);
        return LinkForces { dissipated: diss, event: LinkEvent::Separated, ..Default::default() };
    }
    let cap = t.fn_ * p.strength.tan_phi;
    let fs = if fs_trial_mag > cap {
        if losing.is_none() {
            diss.friction = cap_dissipation(fs_trial_mag, cap, t.ks);
        }
        scale_to(t.fs, fs_trial_mag, cap)
    } else {
        t.fs
    };
    let elastic = spring_energy(t.fn_, k.kn) + spring_energy(fs.norm(), t.ks);
    let event = if let Some(moments) = losing {
        // the normal spring carries on as it was: its exit is 0
        diss.breakage = spring_exit(t.fs, t.fs_before, fs, t.ks) + moments;
        LinkEvent::LostCohesion
    } else {
        LinkEvent::None
    };
    s.shear_force = fs;
    let z = Vec3::zeros();
    assemble(t.n, t.l, t.fn_, fs, z, z, elastic, diss, event)
}

/// Forces and torques on both nodes from the link's Fn, Fs (on node 2) and moments (on node 2).
#[inline]
fn assemble(
    n: Vec3,
    l: Real,
    fn_: Real,
    fs: Vec3,
    mt: Vec3,
    mb: Vec3,
    elastic_energy: Real,
    dissipated: Dissipation,
    event: LinkEvent,
) -> LinkForces {
    let f2 = n * fn_ + fs;
    let lever = n.cross(&fs) * (-0.5 * l);
    let m = mt + mb;
    LinkForces {
        force_on_1: -f2,
        force_on_2: f2,
        torque_on_1: lever - m,
        torque_on_2: lever + m,
        lever_torque: lever,
        normal_force: fn_,
        shear_force: fs,
        twist_moment: mt,
        bending_moment: mb,
        elastic_energy,
        dissipated,
        event,
    }
}

/// Whether a magnitude whose square is `mag2` is above `cap` (|v| > cap without the square
/// root; any magnitude is above a negative cap).
#[inline]
fn exceeds(mag2: Real, cap: Real) -> bool {
    cap < 0.0 || mag2 > cap * cap
}

/// `v` (of magnitude `mag`) scaled to magnitude `to`.
#[inline]
fn scale_to(v: Vec3, mag: Real, to: Real) -> Vec3 {
    if mag > 0.0 {
        v * (to / mag)
    } else {
        Vec3::zeros()
    }
}

#[inline]
fn inv(k: Real) -> Real {
    if k > 0.0 {
        1.0 / k
    } else {
        0.0
    }
}

#[cfg(test)]
#[path = "link_tests.rs"]
pub(crate) mod tests;

#[cfg(test)]
#[path = "link_strength_tests.rs"]
mod strength_tests;

//! Four contacts that go on, of two free spheres or of a wall and a sphere, updated at once
//! (SIMD, `wide::f64x4`): the geometry of the pair, the frictional law with its dashpots
//! ([`update_frictional_contact`](crate::update_frictional_contact)) and the two bodies'
//! loads. Every operation is the scalar path's, in its order, lane by lane (IEEE additions,
//! products, divisions and square roots give the same bits in a vector as alone; no fused
//! multiply–add), so a lane's state and loads are the scalar update's to the bit. The
//! scalar law's branches (sliding or not, dashpots or not, a zero shear force, no twist) are
//! taken lane by lane with selects that give the branch's own value; a twist beyond the
//! series is libm's for that lane, as the scalar law takes it.
//!
//! A lane off the path (apart now, centres crossed or coincident, an overlap not beyond the
//! contact's offset, a NaN) is left untouched and reported, for the caller's general step.
//! The scalar paths are the engine's (`flexdem-integrate`: `pair_step::continuing_pair` for
//! two spheres, `step_pair` with `contact::geometry_of` for a wall, then the law and
//! `apply_law`); its tests compare them bit for bit.

use crate::frictional::{FrictionalContact, FrictionalParams};
use crate::transport_lanes::{flipped, transport_tangent_lanes};
use flexdem_geom::lanes::{f64x4, V3};
use flexdem_geom::{Real, Vec3};

/// Contacts per call.
pub const LANES: usize = 4;

/// The free spheres the four contacts read: the particles' arrays (as the engine keeps
/// them) and each contact's two spheres (body 1, body 2).
#[derive(Clone, Copy)]
pub struct SpherePairLanes<'a> {
    /// Centres.
    pub pos: &'a [Vec3],
    /// Velocities.
    pub vel: &'a [Vec3],
    /// Angular velocities.
    pub ang_vel: &'a [Vec3],
    /// Radii.
    pub radius: &'a [Real],
    /// Sphere 1 and sphere 2 of each contact.
    pub pairs: [[usize; 2]; LANES],
}

/// The four contacts' update on the path, lane by lane (the lanes [`Self::taken`] says took
/// it): what the scalar law writes to the state and the loads `apply_law` makes.
#[derive(Clone, Copy, Debug)]
pub struct ContactLanesOut {
    /// Bit j set: lane j took the path.
    pub taken: u8,
    /// Bit j set: lane j's dashpots pushed (their force is not zero).
    pub pushed: u8,
    /// Bit j set: lane j's tangential force was capped by Coulomb.
    pub sliding: u8,
    normal_force_applied: f64x4,
    shear_applied: V3,
    shear: V3,
    normal: V3,
    normal_force: f64x4,
    friction: f64x4,
    force_on_2: V3,
    torques: [V3; 2],
    elastic: f64x4,
    dashpot: V3,
    moments: [V3; 2],
    viscous: f64x4,
}

impl ContactLanesOut {
    /// Writes lane `j`'s update to its contact's `state` (the scalar law's writes).
    #[inline(always)]
    pub fn write_state(&self, j: usize, state: &mut FrictionalContact) {
        state.shear_force = self.shear.lane(j);
        state.normal = self.normal.lane(j);
        state.normal_force = self.normal_force.as_array()[j];
        state.dissipated_friction += self.friction.as_array()[j];
    }

    /// Lane `j`'s normal force Fn (its dashpot's included) and tangential force Fs on body
    /// 2 (spring and dashpot, capped by Coulomb): `update_frictional_contact`'s
    /// `normal_force` and `shear_force`.
    #[inline(always)]
    pub fn applied(&self, j: usize) -> (Real, Vec3) {
        (self.normal_force_applied.as_array()[j], self.shear_applied.lane(j))
    }

    /// Lane `j`'s total force on body 2, Fn·n + Fs (N; body 1 has the opposite).
    #[inline(always)]
    pub fn force_on_2(&self, j: usize) -> Vec3 {
        self.force_on_2.lane(j)
    }

    /// Lane `j`'s torques about body 1's and body 2's centres, (x_c − c_k) × F_k (N·m).
    #[inline(always)]
    pub fn torques(&self, j: usize) -> [Vec3; 2] {
        [self.torques[0].lane(j), self.torques[1].lane(j)]
    }

    /// Lane `j`'s elastic energy of the springs after the update (J).
    #[inline(always)]
    pub fn elastic_energy(&self, j: usize) -> Real {
        self.elastic.as_array()[j]
    }

    /// Lane `j`'s dashpots: their force on body 2 (N; body 1 has the opposite), its moments
    /// about body 1's and body 2's centres (N·m), and the law's count of their dissipation
    /// in the update (J). Meaningful where [`Self::pushed`] says they pushed.
    #[inline(always)]
    pub fn dashpot(&self, j: usize) -> (Vec3, [Vec3; 2], Real) {
        let moments = [self.moments[0].lane(j), self.moments[1].lane(j)];
        (self.dashpot.lane(j), moments, self.viscous.as_array()[j])
    }
}

/// What four wall–sphere contacts read (body 1 a wall, a plane; body 2 a free sphere): the
/// particles' arrays and, per contact, its wall's point, unit normal and velocity and its
/// sphere.
#[derive(Clone, Copy)]
pub struct WallSphereLanes<'a> {
    /// Centres.
    pub pos: &'a [Vec3],
    /// Velocities.
    pub vel: &'a [Vec3],
    /// Angular velocities.
    pub ang_vel: &'a [Vec3],
    /// Radii.
    pub radius: &'a [Real],
    /// Each contact's wall: a point of its plane, its unit normal, its velocity.
    pub walls: [[Vec3; 3]; LANES],
    /// Each contact's sphere.
    pub spheres: [usize; LANES],
}

/// The kinematics of four contacts at the end of the step, lane by lane
/// (`ContactKinematics`): the unit normal n, the overlap δ, the relative velocity v of the
/// contact point (body 2 minus body 1) and the spin about n.
struct Kinematics4 {
    normal: V3,
    overlap: f64x4,
    velocity: V3,
    spin: f64x4,
}

/// What the law gave four contacts, lane by lane (`update_frictional_contact`).
struct Law4 {
    fn_: f64x4,
    fs: V3,
    spring: V3,
    spring_n: f64x4,
    friction: f64x4,
    dashpot: V3,
    viscous: f64x4,
    elastic: f64x4,
    sliding: f64x4,
    /// The lanes where the overlap beyond the offset is positive and the normal did not flip.
    ok: f64x4,
}

fn lanes(f: impl Fn(usize) -> Real) -> f64x4 {
    f64x4::new(std::array::from_fn(f))
}

/// `update_frictional_contact` of four contacts, its operations in its order lane by lane
/// (module documentation), reading their `params` and `states` (written by the caller,
/// [`ContactLanesOut::write_state`]).
#[inline(always)]
fn law_lanes(
    params: [&FrictionalParams; LANES],
    states: [&FrictionalContact; LANES],
    kin: &Kinematics4,
    dt: Real,
) -> Law4 {
    let zero = f64x4::splat(0.0);
    let half = f64x4::splat(0.5);
    let dt4 = f64x4::splat(dt);
    let (n, v) = (kin.normal, kin.velocity);
    let kn = lanes(|j| params[j].kn);
    let ks = lanes(|j| params[j].ks);
    let tan_phi = lanes(|j| params[j].tan_phi);
    let cn = lanes(|j| params[j].cn);
    let ct = lanes(|j| params[j].ct);
    let overlap = kin.overlap - lanes(|j| states[j].overlap_offset);
    let shear = V3::gather(|j| states[j].shear_force);
    let n0 = V3::gather(|j| states[j].normal);
    let rotated = transport_tangent_lanes(shear, n0, n, kin.spin * dt4);
    let vn = n.dot(v);
    let us_dot = v.minus(n.scale(vn));
    let trial = rotated.minus(us_dot.scale(ks * dt4));
    let spring_n = kn * overlap;
    let damped_n = cn.simd_gt(zero);
    let fn_ = damped_n.select((spring_n - cn * vn).max(zero), spring_n);
    let damped_t = ct.simd_gt(zero);
    let none = V3 { x: zero, y: zero, z: zero };
    let dashpot_t = V3::select(damped_t, us_dot.scale(-ct), none);
    let total = V3::select(damped_t, trial.plus(dashpot_t), trial);
    let limit = (fn_ * tan_phi).max(zero);
    let total2 = total.norm_squared();
    let sliding = total2.simd_gt(limit * limit);
    let total_mag = total2.sqrt();
    let capped = V3::select(total_mag.simd_gt(zero), total.scale(limit / total_mag), none);
    let fs = V3::select(sliding, capped, total);
    let spring = V3::select(sliding, V3::select(damped_t, capped.minus(dashpot_t), capped), trial);
    // (`slip_energy`, floored at 0 without a tangential dashpot: `slip_dissipation`)
    let has_ks = ks.simd_gt(zero);
    let slip = has_ks.select(half * rotated.plus(spring).dot(trial.minus(spring)) / ks, zero);
    let slip = damped_t.select(slip, slip.max(zero));
    let friction = sliding.select(slip, zero);
    let damped = damped_n | damped_t;
    let dashpot = V3::select(damped, n.scale(fn_ - spring_n).plus(dashpot_t), none);
    let viscous = damped.select(-dashpot.dot(v) * dt4, zero);
    // (`spring_energy`, `spring_energy_squared`: zero for a stiffness ≤ 0)
    let energy_n = kn.simd_gt(zero).select(half * spring_n * spring_n / kn, zero);
    let energy_s = has_ks.select(half * spring.norm_squared() / ks, zero);
    // a NaN fails the comparison: its lane goes the general way, whose checks name it
    let ok = overlap.simd_gt(zero) & !flipped(shear, n0, n);
    Law4 {
        fn_,
        fs,
        spring,
        spring_n,
        friction,
        dashpot,
        viscous,
        elastic: energy_n + energy_s,
        sliding,
        ok,
    }
}

/// The four contacts' output from their `law`, the contact point `point` and the two
/// bodies' centres `c1`, `c2` (`apply_law`: the force on body 2 is Fn·n + Fs, body 1's its
/// opposite, the torques and the dashpots' moments about each centre); `taken` the lanes on
/// the path.
#[inline(always)]
fn loads_lanes(law: &Law4, n: V3, point: V3, c1: V3, c2: V3, taken: f64x4) -> ContactLanesOut {
    let zero = f64x4::splat(0.0);
    let f2 = n.scale(law.fn_).plus(law.fs);
    let neg = |v: V3| V3 { x: -v.x, y: -v.y, z: -v.z };
    let (arm1, arm2) = (point.minus(c1), point.minus(c2));
    let fd = law.dashpot;
    let pushed = fd.x.simd_ne(zero) | fd.y.simd_ne(zero) | fd.z.simd_ne(zero);
    ContactLanesOut {
        taken: taken.to_bitmask() as u8,
        pushed: pushed.to_bitmask() as u8,
        sliding: law.sliding.to_bitmask() as u8,
        normal_force_applied: law.fn_,
        shear_applied: law.fs,
        shear: law.spring,
        normal: n,
        normal_force: law.spring_n,
        friction: law.friction,
        force_on_2: f2,
        torques: [arm1.cross(neg(f2)), arm2.cross(f2)],
        elastic: law.elastic,
        dashpot: fd,
        moments: [arm1.cross(neg(fd)), arm2.cross(fd)],
        viscous: law.viscous,
    }
}

/// One step of the four sphere–sphere contacts `states` (their `params`, their spheres in
/// `at`), on the path of the module documentation: for the lanes that take it
/// ([`ContactLanesOut::taken`]), what `update_frictional_contact` writes to the state
/// (for the caller to write, [`ContactLanesOut::write_state`]) and the loads.
///
/// Geometry of spheres 1, 2 (centres c₁, c₂, radii r₁, r₂): d = c₂ − c₁, n = d/|d|,
/// δ = r₁ + r₂ − |d|, contact point x_c = c₁ + n(r₁ − δ/2), relative velocity
/// v = (v₂ + ω₂ × (x_c − c₂)) − (v₁ + ω₁ × (x_c − c₁)), spin n·(ω₁ + ω₂)/2; the path needs
/// |d| > 1e-14·(r₁ + r₂ + |c₁|∞ + |c₂|∞), d·n₀ > 0 (n₀ the last normal) and δ > 0.
pub fn update_sphere_pair_lanes(
    params: [&FrictionalParams; LANES],
    states: [&FrictionalContact; LANES],
    at: &SpherePairLanes<'_>,
    dt: Real,
) -> ContactLanesOut {
    let [i1, i2] = [0, 1].map(|side| at.pairs.map(|p| p[side]));
    let zero = f64x4::splat(0.0);
    let one = f64x4::splat(1.0);
    let half = f64x4::splat(0.5);
    // geometry (`sphere_geometry`)
    let c1 = V3::gather(|j| at.pos[i1[j]]);
    let c2 = V3::gather(|j| at.pos[i2[j]]);
    let (r1, r2) = (lanes(|j| at.radius[i1[j]]), lanes(|j| at.radius[i2[j]]));
    let n0 = V3::gather(|j| states[j].normal);
    let d = c2.minus(c1);
    let dist = d.norm_squared().sqrt();
    let inf_norm = |c: V3| c.x.abs().max(c.y.abs()).max(c.z.abs());
    let scale = r1 + r2 + inf_norm(c1) + inf_norm(c2);
    let apart_ok = dist.simd_gt(f64x4::splat(1e-14) * scale) & d.dot(n0).simd_gt(zero);
    let n = d.scale(one / dist);
    let geometric = r1 + r2 - dist;
    let point = c1.plus(n.scale(r1 - half * geometric));
    let (w1, w2) = (V3::gather(|j| at.ang_vel[i1[j]]), V3::gather(|j| at.ang_vel[i2[j]]));
    let v1 = V3::gather(|j| at.vel[i1[j]]).plus(w1.cross(point.minus(c1)));
    let v2 = V3::gather(|j| at.vel[i2[j]]).plus(w2.cross(point.minus(c2)));
    let spin = half * n.dot(w1.plus(w2));
    let kin = Kinematics4 { normal: n, overlap: geometric, velocity: v2.minus(v1), spin };
    let law = law_lanes(params, states, &kin, dt);
    let taken = apart_ok & geometric.simd_gt(zero) & law.ok;
    loads_lanes(&law, n, point, c1, c2, taken)
}

/// One step of four wall–sphere contacts (body 1 the wall, body 2 the sphere; their
/// `params`, `states`, walls and spheres in `at`), as [`update_sphere_pair_lanes`] steps
/// two spheres; the wall's loads (body 1's) are made as the scalar path makes them, for the
/// caller to drop.
///
/// Geometry of a sphere (centre c, radius r) on a plane (point x_w, unit normal n, velocity
/// v_w): gap g = (c − x_w)·n, the plane's point under the centre c₁ = c − n g, δ = r − g,
/// contact point x_c = c₁ − n δ/2, relative velocity (v + ω × (x_c − c)) − v_w, spin n·ω/2
/// (`contact::geometry_of`); the path needs δ > 0.
pub fn update_wall_sphere_lanes(
    params: [&FrictionalParams; LANES],
    states: [&FrictionalContact; LANES],
    at: &WallSphereLanes<'_>,
    dt: Real,
) -> ContactLanesOut {
    let i = at.spheres;
    let zero = f64x4::splat(0.0);
    let half = f64x4::splat(0.5);
    let wall_point = V3::gather(|j| at.walls[j][0]);
    let n = V3::gather(|j| at.walls[j][1]);
    let wall_velocity = V3::gather(|j| at.walls[j][2]);
    let c = V3::gather(|j| at.pos[i[j]]);
    let gap = c.minus(wall_point).dot(n);
    let on_plane = c.minus(n.scale(gap));
    let overlap = lanes(|j| at.radius[i[j]]) - gap;
    let point = on_plane.minus(n.scale(half * overlap));
    let w = V3::gather(|j| at.ang_vel[i[j]]);
    let v = V3::gather(|j| at.vel[i[j]]).plus(w.cross(point.minus(c)));
    let spin = half * n.dot(w);
    let kin = Kinematics4 { normal: n, overlap, velocity: v.minus(wall_velocity), spin };
    let law = law_lanes(params, states, &kin, dt);
    let taken = overlap.simd_gt(zero) & law.ok;
    loads_lanes(&law, n, point, on_plane, c, taken)
}

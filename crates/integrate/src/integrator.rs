//! Leapfrog integration with Cundall's non-viscous damping (model.md §4, YADE's
//! NewtonIntegrator for spherical bodies).
//!
//! Velocities live at half steps: `v(t + dt/2) = v(t − dt₀/2) + h·a` with `h = (dt₀ + dt)/2`
//! (`dt₀` the step before, `dt` this one: with a constant step, `h = dt`; when the step changes,
//! the kick spans the time between the two half steps, which keeps the scheme second order and
//! the energy balance free of a jump at each change), then `x(t + dt) = x(t) + dt·v(t + dt/2)`; the same for the angular velocity, and the orientation
//! turns by `rot(ω·dt)`, renormalized. Per component, the acceleration (gravity included) is
//! damped as `aᵢ ← aᵢ·(1 − λ·sign(aᵢ·(vᵢ + aᵢ·dt/2)))`. A blocked DOF keeps its velocity
//! component (0, or an imposed value) and feels neither force nor gravity.

use crate::homes::{in_homes, Homes, PerChunk, Pieces, Runs};
use crate::integrator_lanes::{leapfrog_four, Chunk, Kick, LaneSums};
use crate::parallel::MAX_CHUNKS_PER_TASK;
pub use crate::step_work::StepWork;
use crate::step_work::{flags_step, Checks, ChunkCheck, DRIFT_CHECKED_BEYOND};
pub(crate) use crate::turn::{renormalized, turn_quaternion};
use flexdem_elements::{Dofs, Particles};
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// Particles per parallel chunk: fixed, so that reductions (energies) are summed in the same
/// order whatever the number of threads.
pub(crate) const CHUNK: usize = 1024;

/// `aᵢ·(1 − λ·sign(aᵢ·(vᵢ + aᵢ·dt/2)))` (Cundall's non-viscous damping of one component),
/// without a branch: the sign's direction is as good as random from one DOF to the next, and
/// a mispredicted branch costs more than the arithmetic (1 − λ·1, 1 − λ·(−1) and 1 − λ·0 are
/// exactly 1 − λ, 1 + λ and 1).
#[inline]
fn damped(a: Real, v: Real, lambda: Real, dt: Real) -> Real {
    let s = a * (v + 0.5 * a * dt);
    let sign = Real::from(u8::from(s > 0.0)) - Real::from(u8::from(s < 0.0));
    a * (1.0 - lambda * sign)
}

/// What a leapfrog step is given besides the particles and their loads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leapfrog {
    /// Gravity (m/s²).
    pub gravity: Vec3,
    /// Cundall's damping λ ∈ [0, 1).
    pub damping: Real,
    /// The step before, dt₀ (s): the kick spans `(dt₀ + dt)/2`.
    pub previous: Real,
    /// This step, dt (s).
    pub dt: Real,
}

/// Advances every particle by one leapfrog step (`step`: dt after dt₀, gravity, damping λ;
/// the kick spans `(dt₀ + dt)/2`, see the module documentation) under `force` and `torque`
/// (per particle). Returns the work of gravity and of the supports of blocked DOFs and the
/// energy taken by damping, from mid-step velocities; summed per chunk of [`CHUNK`]
/// particles into `parts` (a buffer kept by the caller, so that a step allocates nothing),
/// then in chunk order, whatever the number of threads.
pub fn leapfrog_step(
    p: &mut Particles,
    force: &[Vec3],
    torque: &[Vec3],
    step: &Leapfrog,
    parts: &mut Vec<StepWork>,
) -> StepWork {
    let checks =
        &mut Checks { reach: None, chunk_reach: &[], verlet: None, flags: &mut Vec::new() };
    leapfrog_step_lanes(p, force, torque, step, parts, true, checks, &Homes::default())
}

/// The engine's [`leapfrog_step`]: with it, each chunk's particles are checked as soon as
/// they have moved, while they are in cache ([`flags_step`]: a non-finite value, or a move
/// beyond the particle's `reach`; and with `checks.verlet`, a move beyond its limit since
/// the collider's last build); `checks.flags` keeps the chunks' answers (a buffer) and the
/// result says whether one flagged, and whether one moved beyond its limit. (A pass of its
/// own after the step read the 80 bytes of each particle again: 1.6 % of the LAMMPS twin's
/// instructions; the collider's watch, a pass at the next step over the positions, the
/// references and the limits, took 211–305 µs a step of the packing of 10⁵ spheres.)
///
/// `homes`, when they cut these particles at more than one home, share the chunks among the
/// threads as the step's other loops share their items (`homes.rs`; with the pairs in parts,
/// as those parts were: `Homes::set_by_parts`); the results are the same.
pub(crate) fn leapfrog_step_checked(
    p: &mut Particles,
    force: &[Vec3],
    torque: &[Vec3],
    step: &Leapfrog,
    parts: &mut Vec<StepWork>,
    checks: &mut Checks<'_>,
    homes: &Homes,
) -> (StepWork, ChunkCheck) {
    let work = leapfrog_step_lanes(p, force, torque, step, parts, true, checks, homes);
    let any = checks.flags.iter().fold(ChunkCheck::default(), |a, c| ChunkCheck {
        flagged: a.flagged | c.flagged,
        beyond: a.beyond | c.beyond,
        drift: 0.0,
    });
    (work, any)
}

/// [`leapfrog_step`], four free particles at a time where `four` (the same bits either way:
/// the tests compare the two), each chunk checked after its step when `checks` has reaches,
/// the chunks shared among the threads by `homes` ([`leapfrog_step_checked`]).
#[allow(clippy::too_many_arguments)]
fn leapfrog_step_lanes(
    p: &mut Particles,
    force: &[Vec3],
    torque: &[Vec3],
    step: &Leapfrog,
    parts: &mut Vec<StepWork>,
    four: bool,
    checks: &mut Checks<'_>,
    homes: &Homes,
) -> StepWork {
    let Leapfrog { gravity, damping: lambda, previous, dt } = *step;
    let gravity = &gravity;
    let kick = 0.5 * (previous + dt);
    // without damping (λ = 0) the damped acceleration is the free one and the damping's
    // terms are +0, and a zero component of gravity adds +0 to its work: both are skipped,
    // which leaves every sum as it was, bit for bit (a sum started at +0 never becomes −0)
    let undamped = lambda == 0.0;
    let dt2 = dt * dt;
    let (reach, chunk_reach, verlet) = (checks.reach, checks.chunk_reach, checks.verlet);
    let lanes = Kick { gravity: *gravity, lambda, undamped, kick, previous, dt };
    let check = |c: usize, p: &Chunk<'_>| {
        if reach.is_none() && verlet.is_none() {
            // (nothing to check: no pass over the chunk)
            return ChunkCheck::default();
        }
        // the chunk's new state, in cache: whether it is finite, its largest speed² and
        // coordinate (one pass, no particle's reach, reference or limit read)
        let state = p.pos.iter().zip(p.vel.iter()).zip(p.ang.iter());
        let (finite, v2, x_max) = state.fold((true, 0.0, 0.0), |(f, v2, xm), ((x, v), w)| {
            let sum = x.sum() + v.sum() + w.sum();
            (f & sum.is_finite(), v.norm_squared().max(v2), x.amax().max(xm))
        });
        let flagged = reach.is_some_and(|reach| {
            // every particle within the chunk's smallest reach: none flagged (the same
            // answer as each against its own, `flags_step`)
            let reach = &reach[c * CHUNK..c * CHUNK + p.pos.len()];
            let each = || {
                let moved = p.pos.iter().zip(p.vel.iter()).zip(p.ang.iter()).zip(reach);
                moved.fold(false, |any, (((x, v), w), &r)| any | flags_step(x, v, w, r, dt2))
            };
            if finite && chunk_reach.get(c).is_some_and(|&r| v2 * dt2 <= r * r) {
                debug_assert!(!each(), "chunk {c}: the smallest reach passed a flagged particle");
                return false;
            }
            each()
        });
        let (beyond, drift) = verlet.map_or((false, 0.0), |v| {
            // a bound on any particle's move in the step, round-off of `x + v·dt` included
            let moved = v2.sqrt() * dt * (1.0 + 1e-12) + x_max * 1e-15;
            let drift = v.drift.get(c).map_or(Real::INFINITY, |d| d + moved);
            let limit = v.chunk_limits.get(c).copied().unwrap_or(Real::NEG_INFINITY);
            if finite && drift <= DRIFT_CHECKED_BEYOND * limit {
                debug_assert!(!v.any_beyond(c * CHUNK, p.pos), "chunk {c}: drift {drift}");
                (false, drift)
            } else {
                (v.any_beyond(c * CHUNK, p.pos), drift)
            }
        });
        ChunkCheck { flagged, beyond, drift }
    };
    if p.len() <= CHUNK {
        // one chunk (a small scene): on this thread, without a parallel dispatch (the
        // same chunk, so the same bits)
        let Particles { pos, vel, ori, ang_vel: ang, mass, inertia, blocked, .. } = p;
        let (f, t) = (force, torque);
        let mut chunk = Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked };
        let work = step_chunk(&mut chunk, &lanes, four);
        let flagged = check(0, &chunk);
        parts.clear();
        parts.push(work);
        checks.flags.clear();
        checks.flags.push(flagged);
    } else {
        let (n, chunks) = (p.len(), p.len().div_ceil(CHUNK));
        parts.clear();
        parts.resize(chunks, StepWork::default());
        checks.flags.clear();
        checks.flags.resize(chunks, ChunkCheck::default());
        let Particles { pos, vel, ori, ang_vel: ang, mass, inertia, blocked, .. } = p;
        let (f, t) = (force, torque);
        let all = Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked };
        let step = |c: usize, chunk: &mut Chunk<'_>| {
            let work = step_chunk(chunk, &lanes, four);
            (work, check(c, chunk))
        };
        let (works, flags) = (&mut parts[..], &mut checks.flags[..]);
        if homes.shares(n) && homes.len() == n {
            // every home's chunks on one task, as the step's other loops share the particles
            let mut runs = Runs::new();
            homes.item_runs(n, CHUNK, &mut runs);
            let outputs = (
                PerChunk { outputs: works, chunk: CHUNK },
                PerChunk { outputs: flags, chunk: CHUNK },
            );
            in_homes((all, outputs), &runs, n, homes.count(), &|pieces: Pieces<Stepped<'_>>| {
                for (first, (chunk, (works, flags))) in pieces {
                    step_chunks(chunk, first / CHUNK, works.outputs, flags.outputs, &step);
                }
            });
        } else {
            step_chunks(all, 0, works, flags, &step);
        }
    }
    let mut total = StepWork::default();
    for w in parts.iter() {
        total += *w;
    }
    total
}

/// Particles of whole chunks (runs start at multiples of [`CHUNK`]) with their chunks'
/// energy terms and checks' answers.
type Stepped<'a> = (Chunk<'a>, (PerChunk<'a, StepWork>, PerChunk<'a, ChunkCheck>));

/// Steps `all` (the particles of chunks `first..`, in chunks of [`CHUNK`]), its chunks in
/// parallel in tasks of at most [`MAX_CHUNKS_PER_TASK`], each chunk's energy terms and
/// checks' answers into `works` and `flags`.
fn step_chunks<F>(
    all: Chunk<'_>,
    first: usize,
    works: &mut [StepWork],
    flags: &mut [ChunkCheck],
    step: &F,
) where
    F: Fn(usize, &mut Chunk<'_>) -> (StepWork, ChunkCheck) + Sync,
{
    let Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked } = all;
    (
        pos.par_chunks_mut(CHUNK),
        vel.par_chunks_mut(CHUNK),
        ori.par_chunks_mut(CHUNK),
        ang.par_chunks_mut(CHUNK),
        mass.par_chunks(CHUNK),
        inertia.par_chunks(CHUNK),
        blocked.par_chunks(CHUNK),
        f.par_chunks(CHUNK),
        t.par_chunks(CHUNK),
        works.par_iter_mut(),
        flags.par_iter_mut(),
    )
        .into_par_iter()
        .enumerate()
        .with_max_len(MAX_CHUNKS_PER_TASK)
        .for_each(|(c, (pos, vel, ori, ang, mass, inertia, blocked, f, t, work, flag))| {
            let mut chunk = Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked };
            (*work, *flag) = step(first + c, &mut chunk);
        });
}

/// One chunk's leapfrog step, four free particles at a time where `four`: its energy terms.
fn step_chunk(p: &mut Chunk<'_>, lanes: &Kick, four: bool) -> StepWork {
    let mut work = StepWork::default();
    // the batches' energy terms, lane by lane, added to `work` at the chunk's end
    let mut sums = LaneSums::default();
    // four particles at a time (`integrator_lanes.rs`: the same state bits, blocked DOFs or
    // not; the energy terms to round-off), in order with the others: a particle with every
    // DOF blocked (a support: the scalar way is a few additions), or one left alone, goes
    // the scalar way after the batched ones before it
    let mut batch = [0usize; 4];
    let mut count = 0;
    for i in 0..p.blocked.len() {
        if four && p.blocked[i] != Dofs::ALL {
            batch[count] = i;
            count += 1;
            if count == 4 {
                four_of(p, batch, 4, lanes, &mut sums);
                count = 0;
            }
            continue;
        }
        flush_batch(p, &batch[..count], lanes, &mut work, &mut sums);
        count = 0;
        leapfrog_one(p, i, lanes, &mut work);
    }
    flush_batch(p, &batch[..count], lanes, &mut work, &mut sums);
    sums.add_to(&mut work);
    work
}

/// The particles `batch` of chunk `p` (fewer than four, in order): two or more through the
/// lanes (the last repeated), one alone the scalar way.
fn flush_batch(
    p: &mut Chunk<'_>,
    batch: &[usize],
    k: &Kick,
    work: &mut StepWork,
    sums: &mut LaneSums,
) {
    match *batch {
        [] => {}
        [i] => leapfrog_one(p, i, k, work),
        _ => {
            let last = batch[batch.len() - 1];
            let idx = std::array::from_fn(|l| batch.get(l).copied().unwrap_or(last));
            four_of(p, idx, batch.len(), k, sums);
        }
    }
}

/// `leapfrog_four` of `idx[..count]`, without the blocked DOFs' code when none is blocked.
#[inline(always)]
fn four_of(p: &mut Chunk<'_>, idx: [usize; 4], count: usize, k: &Kick, sums: &mut LaneSums) {
    if idx.iter().all(|&i| p.blocked[i].is_empty()) {
        leapfrog_four::<false>(p, idx, count, k, sums);
    } else {
        leapfrog_four::<true>(p, idx, count, k, sums);
    }
}

/// Advances particle `i` of chunk `p` (with its blocked DOFs) by one leapfrog step, adding its
/// energy terms to `work`.
fn leapfrog_one(p: &mut Chunk<'_>, i: usize, step: &Kick, work: &mut StepWork) {
    let Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked } = p;
    let b = blocked[i];
    let Kick { gravity, lambda, undamped, kick, previous, dt } = *step;
    let gravity = &gravity;
    // one division per particle, not one per DOF
    let inv_mass = 1.0 / mass[i];
    for k in 0..3 {
        if b.contains(Dofs::translation(k)) {
            continue;
        }
        let v0 = vel[i][k];
        let a_free = f[i][k] * inv_mass + gravity[k];
        let a = if undamped { a_free } else { damped(a_free, v0, lambda, kick) };
        let v1 = v0 + a * kick;
        vel[i][k] = v1;
        work.kinetic_translation += 0.5 * mass[i] * v0 * v1;
        if gravity[k] != 0.0 {
            work.gravity += mass[i] * gravity[k] * v1 * dt;
        }
        if !undamped {
            work.damping += mass[i] * (a_free - a) * 0.5 * v0 * kick;
            work.damping_next += mass[i] * (a_free - a) * 0.5 * v1 * kick;
        }
    }
    for k in (0..3).filter(|&k| b.contains(Dofs::translation(k))) {
        let kinetic = &mut work.kinetic_translation;
        let supports = (&mut work.boundary, &mut work.boundary_next);
        add_support_terms(kinetic, supports, mass[i], f[i][k], vel[i][k], previous, dt);
    }
    pos[i] += vel[i] * dt;
    if !b.contains(Dofs::ROTATION) || ang[i] != Vec3::zeros() {
        let inv_inertia = 1.0 / inertia[i];
        for k in 0..3 {
            if b.contains(Dofs::rotation(k)) {
                continue;
            }
            let w0 = ang[i][k];
            let a_free = t[i][k] * inv_inertia;
            let a = if undamped { a_free } else { damped(a_free, w0, lambda, kick) };
            let w1 = w0 + a * kick;
            ang[i][k] = w1;
            work.kinetic_rotation += 0.5 * inertia[i] * w0 * w1;
            if !undamped {
                work.damping += inertia[i] * (a_free - a) * 0.5 * w0 * kick;
                work.damping_next += inertia[i] * (a_free - a) * 0.5 * w1 * kick;
            }
        }
        for k in (0..3).filter(|&k| b.contains(Dofs::rotation(k))) {
            let kinetic = &mut work.kinetic_rotation;
            let supports = (&mut work.boundary, &mut work.boundary_next);
            add_support_terms(kinetic, supports, inertia[i], t[i][k], ang[i][k], previous, dt);
        }
        let turn = ang[i] * dt;
        if turn != Vec3::zeros() {
            let q = turn_quaternion(turn) * ori[i];
            ori[i] = renormalized(q.into_inner());
        }
    }
}

/// The energy terms of a blocked component (velocity `v` kept, `p` the mass or the moment of
/// inertia, `f` the force or torque its support cancels): the kinetic ½p·v·v, and the
/// support's work −½f·v·dt₀ and −½f·v·dt subtracted from `supports` (the halves over the step
/// before and the step after, `StepWork::boundary` and `boundary_next`).
#[allow(clippy::too_many_arguments, reason = "one component's terms and their three sums")]
#[inline]
fn add_support_terms(
    kinetic: &mut Real,
    supports: (&mut Real, &mut Real),
    p: Real,
    f: Real,
    v: Real,
    previous: Real,
    dt: Real,
) {
    *kinetic += 0.5 * p * v * v;
    *supports.0 -= 0.5 * f * v * previous;
    *supports.1 -= 0.5 * f * v * dt;
}

/// Kinetic energy, translational and rotational, summed in a fixed order.
pub fn kinetic_energy(p: &Particles) -> (Real, Real) {
    let parts: Vec<(Real, Real)> = (
        p.vel.par_chunks(CHUNK),
        p.ang_vel.par_chunks(CHUNK),
        p.mass.par_chunks(CHUNK),
        p.inertia.par_chunks(CHUNK),
    )
        .into_par_iter()
        .map(|(v, w, m, j)| {
            let mut e = (0.0, 0.0);
            for i in 0..v.len() {
                e.0 += 0.5 * m[i] * v[i].norm_squared();
                e.1 += 0.5 * j[i] * w[i].norm_squared();
            }
            e
        })
        .collect();
    parts.iter().fold((0.0, 0.0), |a, e| (a.0 + e.0, a.1 + e.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::step_work::{chunk_minima, VerletWatch};
    use nalgebra::{Quaternion, UnitQuaternion};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        /// Particles, some with random sets of blocked DOFs (both paths in one chunk), under
        /// random forces and torques, spins up to large turns per step, with and without
        /// damping and gravity: four at a time or one by one, every position, velocity and
        /// orientation has the same bits, and the energy terms agree to round-off.
        #[test]
        fn four_at_a_time_is_one_by_one(
            n in 1usize..23,
            seed in any::<u64>(),
            damping in prop::sample::select(vec![0.0, 0.3]),
            gravity in prop::sample::select(vec![Vec3::zeros(), Vec3::new(0.0, 0.0, -9.81), Vec3::new(1.0, -2.0, 3.0)]),
            spin in prop::sample::select(vec![1.0, 1e3, 1e5]),
            blocked_every in 0usize..9,
        ) {
            let mut state = seed | 1;
            let mut r = move || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 11) as Real / (1u64 << 53) as Real * 2.0 - 1.0
            };
            let mut p = Particles::default();
            for i in 0..n {
                let mut q = Particle::at_rest(ParticleKind::Sphere, Vec3::new(r(), r(), r()), 0.1, 0);
                q.mass = 1.0 + r().abs();
                q.inertia = 0.01 + 0.01 * r().abs();
                q.vel = Vec3::new(r(), r(), r());
                q.ang_vel = Vec3::new(r(), r(), r()) * spin;
                q.ori = UnitQuaternion::from_scaled_axis(Vec3::new(r(), r(), r()) * 3.0);
                if blocked_every > 0 && i % blocked_every == 0 {
                    // any set of blocked DOFs (all, none, pinned nodes, rotations at rest)
                    q.blocked = Dofs::from_bits_truncate((64.0 * (0.5 + 0.5 * r())) as u8 & 63);
                    if q.blocked.contains(Dofs::ROTATION) && r() < 0.0 {
                        q.ang_vel = Vec3::zeros();
                    }
                }
                p.push(q);
            }
            let f: Vec<Vec3> = (0..n).map(|_| Vec3::new(r(), r(), r()) * 10.0).collect();
            let t: Vec<Vec3> = (0..n).map(|_| Vec3::new(r(), r(), r())).collect();
            let step = Leapfrog { gravity, damping, previous: 1e-4, dt: 1.1e-4 };
            let (mut a, mut b) = (p.clone(), p.clone());
            let flags = &mut Vec::new();
            let none = &mut Checks { reach: None, chunk_reach: &[], verlet: None, flags };
            let wa = leapfrog_step_lanes(&mut a, &f, &t, &step, &mut Vec::new(), true, none, &Homes::default());
            let wb = leapfrog_step_lanes(&mut b, &f, &t, &step, &mut Vec::new(), false, none, &Homes::default());
            // the energy terms, summed lane by lane, differ from the one-by-one sums by
            // round-off only: within 1e-12 of a bound on the size of every term (½m·v², m·a·v
            // over the kick, f·v and m·g·v over a step, and their rotational twins)
            let h = 0.5 * (step.previous + step.dt);
            let size: Real = (0..n).map(|i| {
                let (m, j) = (p.mass[i], p.inertia[i]);
                let (v, w) = (p.vel[i].norm() + b.vel[i].norm(), p.ang_vel[i].norm() + b.ang_vel[i].norm());
                let (a, alpha) = (f[i].norm() / m + gravity.norm(), t[i].norm() / j);
                m * v * v + j * w * w + m * a * v * h + j * alpha * w * h
            }).sum();
            let terms = |w: &StepWork| {
                [w.kinetic_translation, w.kinetic_rotation, w.gravity, w.damping, w.damping_next,
                 w.boundary, w.boundary_next]
            };
            for (x, y) in terms(&wa).into_iter().zip(terms(&wb)) {
                prop_assert!((x - y).abs() <= 1e-12 * size, "{:e} against {:e} (size {:e})", x, y, size);
            }
            let v = |x: &[Vec3]| x.iter().flat_map(|v| v.iter().map(|c| c.to_bits())).collect::<Vec<_>>();
            prop_assert_eq!(v(&a.pos), v(&b.pos));
            prop_assert_eq!(v(&a.vel), v(&b.vel));
            prop_assert_eq!(v(&a.ang_vel), v(&b.ang_vel));
            let q = |x: &[UnitQuaternion<Real>]| x.iter().flat_map(|q| q.coords.iter().map(|c| c.to_bits())).collect::<Vec<_>>();
            prop_assert_eq!(q(&a.ori), q(&b.ori));
        }
    }
    use flexdem_elements::{Particle, ParticleKind};

    /// Stepped home by home on two or three threads, with the pairs' parts of any sizes (empty
    /// ones too) or blocks of particles cut by thread, the particles get the same bits, the
    /// energy terms and the checks' answers the same values as in one run over all the chunks.
    #[test]
    fn chunks_stepped_by_their_homes_give_the_same_bits() {
        let n = 9 * CHUNK + 100;
        let mut p = Particles::default();
        for i in 0..n {
            let s = (i as Real * 0.618).fract();
            let x = Vec3::new(i as Real * 0.01, s, 0.0);
            let mut q = Particle::at_rest(ParticleKind::Sphere, x, 0.005, 0);
            q.vel = Vec3::new(0.1 * s, -0.2, 0.3 * (1.0 - s));
            q.ang_vel = Vec3::new(s, 2.0, -s);
            (q.mass, q.inertia) = (1e-3 * (1.0 + s), 1e-8);
            if i % 97 == 0 {
                q.blocked = Dofs::ALL;
            }
            p.push(q);
        }
        let f: Vec<Vec3> = (0..n).map(|i| Vec3::new((i % 7) as Real, -1.0, 0.5)).collect();
        let t: Vec<Vec3> = (0..n).map(|i| Vec3::new(0.0, (i % 5) as Real * 1e-6, 0.0)).collect();
        let step = Leapfrog {
            gravity: Vec3::new(0.0, 0.0, -9.81),
            damping: 0.2,
            previous: 1e-4,
            dt: 1.1e-4,
        };
        let reach = vec![0.005; n];
        let chunk_reach = chunk_minima(&reach, CHUNK);
        let run = |homes: &Homes| {
            let mut a = p.clone();
            let mut flags = Vec::new();
            let checks = &mut Checks {
                reach: Some(&reach),
                chunk_reach: &chunk_reach,
                verlet: None,
                flags: &mut flags,
            };
            let (work, found) =
                leapfrog_step_checked(&mut a, &f, &t, &step, &mut Vec::new(), checks, homes);
            (a, format!("{work:?} {found:?} {flags:?}"))
        };
        let (one, expected) = run(&Homes::default());
        let bits = |p: &Particles| {
            let v = p
                .pos
                .iter()
                .chain(&p.vel)
                .chain(&p.ang_vel)
                .flat_map(|v| v.map(Real::to_bits).data.0[0]);
            v.chain(p.ori.iter().flat_map(|q| q.coords.map(Real::to_bits).data.0[0]))
                .collect::<Vec<_>>()
        };
        let cases: [&[usize]; 5] = [
            &[0, n],
            &[0, 4 * CHUNK + 3, n],
            &[
                0,
                CHUNK,
                2 * CHUNK + 600,
                5 * CHUNK,
                5 * CHUNK,
                6 * CHUNK,
                8 * CHUNK + 1,
                9 * CHUNK,
                n,
            ],
            &[0, 0, 0, n, n],
            &[0, 2 * CHUNK, n - 1],
        ];
        for threads in [2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut all = Vec::new();
            for parts in cases {
                let mut homes = Homes::default();
                homes.set_by_parts(parts);
                all.push(homes);
            }
            for blocks in [&[0, n][..], &[0, 3 * CHUNK + 5, 7 * CHUNK, n], &[0, 10, 20, n]] {
                let mut homes = Homes::default();
                homes.set_by_blocks(blocks, threads);
                all.push(homes);
            }
            for homes in &all {
                let (a, got) = pool.install(|| run(homes));
                assert!(bits(&a) == bits(&one), "{threads} threads, homes {homes:?}");
                assert_eq!(got, expected, "{threads} threads, homes {homes:?}");
            }
        }
    }

    fn one_particle(mass: Real) -> Particles {
        let mut p = Particles::default();
        let mut q = Particle::at_rest(ParticleKind::Sphere, Vec3::zeros(), 0.1, 0);
        q.mass = mass;
        q.inertia = 0.4 * mass * 0.01;
        p.push(q);
        p
    }

    /// Free fall: with the leapfrog, x(t) = x0 + v0·t + g·t²/2 + g·dt·t/2 exactly (the
    /// half-step offset of the velocity), so x matches the parabola to O(dt).
    /// One step with a fresh buffer.
    fn leapfrog(
        p: &mut Particles,
        f: &[Vec3],
        t: &[Vec3],
        gravity: &Vec3,
        damping: Real,
        previous: Real,
        dt: Real,
    ) -> StepWork {
        let step = Leapfrog { gravity: *gravity, damping, previous, dt };
        leapfrog_step(p, f, t, &step, &mut Vec::new())
    }

    /// The series and nalgebra's `from_scaled_axis` agree to round-off on both sides of the
    /// switch, and a renormalized product is unit to round-off.
    #[test]
    fn turn_quaternion_is_from_scaled_axis_to_round_off() {
        let axis = Vec3::new(0.3, -0.5, 0.8).normalize();
        let mut worst: Real = 0.0;
        for k in 1..=4000 {
            let angle = k as Real * 1e-4; // to 0.4, across the switch at 0.2
            let (a, b) =
                (turn_quaternion(axis * angle), UnitQuaternion::from_scaled_axis(axis * angle));
            worst = worst.max((a.into_inner() - b.into_inner()).norm());
            let v = Vec3::new(1.0, 2.0, -0.5);
            assert!(((a * v) - (b * v)).norm() <= 1e-15 * v.norm(), "{angle}");
        }
        assert!(worst <= 3e-16, "worst difference {worst:e}");
        let mut q = UnitQuaternion::identity();
        for k in 0..100_000 {
            let turn = Vec3::new(1e-3, -2e-3 * (k as Real).sin(), 4e-3);
            q = renormalized((turn_quaternion(turn) * q).into_inner());
        }
        assert!((q.norm() - 1.0).abs() <= 4e-16, "|q| − 1 = {:e}", q.norm() - 1.0);
        // a turn below 1e-140 rad is none
        assert_eq!(turn_quaternion(Vec3::new(1e-141, -1e-141, 0.0)), UnitQuaternion::identity());
        assert_ne!(turn_quaternion(Vec3::new(1e-139, 0.0, 0.0)), UnitQuaternion::identity());
        // far from unit: exact normalization
        let far = renormalized(Quaternion::new(2.0, 0.0, 0.0, 0.0));
        assert_eq!(far.into_inner(), Quaternion::new(1.0, 0.0, 0.0, 0.0));
    }

    #[test]
    fn free_fall_follows_the_parabola() {
        let mut p = one_particle(2.0);
        let g = Vec3::new(0.0, 0.0, -9.81);
        p.vel[0] = Vec3::new(1.0, 0.0, 3.0);
        let v0 = p.vel[0];
        let dt = 1e-3;
        let n = 1000;
        let zero = vec![Vec3::zeros(); 1];
        for _ in 0..n {
            leapfrog(&mut p, &zero, &zero, &g, 0.0, dt, dt);
        }
        let t = dt * n as Real;
        // the leapfrog with v(−dt/2) = v0 gives x = v0 t + g t²/2 + g dt t/2
        let exact = v0 * t + g * (0.5 * t * t) + g * (0.5 * dt * t);
        assert!((p.pos[0] - exact).norm() < 1e-12, "{} vs {}", p.pos[0], exact);
        let parabola = v0 * t + g * (0.5 * t * t);
        assert!((p.pos[0] - parabola).norm() < 0.5 * 9.81 * dt * t + 1e-12);
    }

    #[test]
    fn blocked_dofs_keep_their_velocity_and_feel_no_gravity() {
        let mut p = one_particle(1.0);
        p.blocked[0] = Dofs::Z | Dofs::ROTATION;
        p.vel[0] = Vec3::new(0.0, 0.0, 0.5);
        let f = vec![Vec3::new(1.0, 0.0, 100.0)];
        let t = vec![Vec3::new(5.0, 5.0, 5.0)];
        leapfrog(&mut p, &f, &t, &Vec3::new(0.0, 0.0, -9.81), 0.0, 0.01, 0.01);
        assert_eq!(p.vel[0][2], 0.5);
        assert!((p.pos[0][2] - 0.005).abs() < 1e-15);
        assert!((p.vel[0][0] - 0.01).abs() < 1e-15);
        assert_eq!(p.ang_vel[0], Vec3::zeros());
    }

    #[test]
    fn cundall_damping_reduces_the_driving_acceleration() {
        let mut p = one_particle(1.0);
        let f = vec![Vec3::new(1.0, 0.0, 0.0)];
        let zero = vec![Vec3::zeros()];
        let w = leapfrog(&mut p, &f, &zero, &Vec3::zeros(), 0.2, 0.1, 0.1);
        // accelerating along the motion: a·(1 − λ)
        assert!((p.vel[0][0] - 0.08).abs() < 1e-15);
        assert!(w.damping + w.damping_next > 0.0);
    }

    #[test]
    fn rotation_turns_the_orientation() {
        let mut p = one_particle(1.0);
        p.ang_vel[0] = Vec3::new(0.0, 0.0, std::f64::consts::PI);
        let zero = vec![Vec3::zeros()];
        for _ in 0..200 {
            leapfrog(&mut p, &zero, &zero, &Vec3::zeros(), 0.0, 0.005, 0.005);
        }
        // half a turn about z
        let x = p.ori[0] * Vec3::x();
        assert!((x + Vec3::x()).norm() < 1e-12, "{x}");
    }

    /// The leapfrog's check of each chunk flags a step exactly when one particle, in any
    /// chunk, has a value not finite or moved beyond its reach (`flags_step` over all the
    /// particles after the step), and says a particle moved beyond its Verlet limit exactly
    /// when one did (the collider's test over all the particles); the step itself is
    /// [`leapfrog_step`]'s, bit for bit.
    #[test]
    fn the_checked_step_flags_one_bad_particle_in_any_chunk() {
        let n = 2 * CHUNK + 37;
        let mut p = Particles::default();
        for i in 0..n {
            let x = Vec3::new(i as Real * 0.01, 0.0, 0.0);
            let mut q = Particle::at_rest(ParticleKind::Sphere, x, 0.005, 0);
            q.vel = Vec3::new(0.1, 0.0, 0.0);
            (q.mass, q.inertia) = (1e-3, 1e-8);
            p.push(q);
        }
        let step = Leapfrog {
            gravity: Vec3::new(0.0, 0.0, -9.81),
            damping: 0.0,
            previous: 1e-4,
            dt: 1e-4,
        };
        let dt2 = step.dt * step.dt;
        let cases = [
            None,
            Some((0, 1.0)),
            Some((CHUNK + 5, Real::NAN)),
            Some((n - 1, Real::INFINITY)),
            Some((CHUNK, 1e4)),
        ];
        for (case, tiny) in cases.into_iter().map(|c| (c, None)).chain([(None, Some(CHUNK + 7))]) {
            let mut reach = vec![0.005; n];
            if let Some(i) = tiny {
                reach[i] = 1e-9;
            }
            let mut f = vec![Vec3::zeros(); n];
            if let Some((i, x)) = case {
                f[i].y = x;
            }
            let t = vec![Vec3::zeros(); n];
            let (mut a, mut b) = (p.clone(), p.clone());
            let mut flags = Vec::new();
            // one particle (another in each case) starts just short of its Verlet limit
            let reference = p.pos.clone();
            let mut limits = vec![1.0; n];
            let near = case.map_or(n / 2, |(i, _)| (i + 11) % n);
            limits[near] = 0.1 * 1e-4 * (1.0 - 1e-9);
            // per chunk, as the collider keeps them: the smallest reach and limit, and no
            // drift yet (just built)
            let (chunk_reach, chunk_limits) =
                (chunk_minima(&reach, CHUNK), chunk_minima(&limits, CHUNK));
            let drift = vec![0.0; n.div_ceil(CHUNK)];
            let verlet = Some(VerletWatch {
                reference: &reference,
                limits: &limits,
                chunk_limits: &chunk_limits,
                drift: &drift,
            });
            let checks = &mut Checks {
                reach: Some(&reach),
                chunk_reach: &chunk_reach,
                verlet,
                flags: &mut flags,
            };
            let none = Homes::default();
            let (wa, found) =
                leapfrog_step_checked(&mut a, &f, &t, &step, &mut Vec::new(), checks, &none);
            let flagged = found.flagged;
            let wb = leapfrog_step(&mut b, &f, &t, &step, &mut Vec::new());
            let same = |x: &[Vec3], y: &[Vec3]| {
                x.iter().zip(y).all(|(x, y)| x.map(Real::to_bits) == y.map(Real::to_bits))
            };
            let same_work = format!("{wa:?}") == format!("{wb:?}");
            assert!(same(&a.pos, &b.pos) && same(&a.vel, &b.vel) && same_work, "{case:?}");
            let expected =
                (0..n).any(|i| flags_step(&a.pos[i], &a.vel[i], &a.ang_vel[i], reach[i], dt2));
            // a force of 1 N on a 1 g sphere is no jump; NaN, infinity and 1e4 N are
            assert_eq!(flagged, expected, "{case:?}");
            let bad = case.is_some_and(|(_, x)| x != 1.0) || tiny.is_some();
            assert_eq!(flagged, bad, "{case:?} {tiny:?}");
            assert_eq!(flags.len(), n.div_ceil(CHUNK));
            let beyond = (0..n).any(|i| {
                let limit = limits[i];
                (a.pos[i] - reference[i]).norm_squared() > limit * limit
            });
            assert!(beyond, "{case:?}: the particle near its limit moved 0.1 m/s · 1e-4 s");
            assert_eq!(found.beyond, beyond, "{case:?}");
            // with limits of 1 m, only the particle thrown to infinity passes its own (1e4 N
            // move it by 0.1 m; a NaN compares false, as in the collider: `flags_step` has it)
            let mut c = p.clone();
            let ones = vec![1.0; n];
            let far = VerletWatch {
                reference: &reference,
                limits: &ones,
                chunk_limits: &chunk_minima(&ones, CHUNK),
                drift: &drift,
            };
            let checks =
                &mut Checks { reach: None, chunk_reach: &[], verlet: Some(far), flags: &mut flags };
            let (_, found) =
                leapfrog_step_checked(&mut c, &f, &t, &step, &mut Vec::new(), checks, &none);
            let pushed = case.is_some_and(|(_, x)| x.is_infinite());
            assert_eq!((found.flagged, found.beyond), (false, pushed), "{case:?}");
        }
    }
}

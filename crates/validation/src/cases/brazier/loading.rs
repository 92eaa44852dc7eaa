//! The two loadings of the Brazier case: the tension test (C and ν of the wall) and the end
//! moment raised slowly, held once the response turns non-linear, until buckling and winding.

use super::tube::{centroid, mean_radius, ovalisation, ring_normal, ring_rotation, TubeRings};
use super::{min_self_distance, LatticeStiffness, TubeCase};
use crate::ValidationError;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Control, Load, Ramp, Settings, Simulation, TimeStep};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// Axial strain of the tension test.
const TENSION_STRAIN: Real = 1e-3;
/// Chunks of steps per slowest period between two looks at the state.
const WINDOWS_PER_PERIOD: Real = 10.0;

/// What the tension test measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TensionResult {
    /// Total axial force (N).
    pub force: Real,
    /// Axial membrane stiffness C = (F/2πR)/ε (N/m).
    pub membrane_stiffness: Real,
    /// Poisson ratio −ε_θ/ε of the mid-length ring.
    pub poisson: Real,
    /// Steps run.
    pub steps: u64,
}

/// A simulation of `tube` with its settings (no gravity, Cundall damping, automatic dt).
fn simulation(tube: &TubeCase) -> Result<(Simulation, TubeRings), ValidationError> {
    let (model, rings) = tube.model()?;
    let settings = Settings {
        time_step: TimeStep::Auto { safety: 0.5 },
        gravity: Vec3::zeros(),
        damping: tube.damping,
        // the case measures the winding's energy balance itself and reports it as a check
        energy_tolerance: None,
        ..Settings::default()
    };
    Ok((Simulation::new(model, settings)?, rings))
}

/// Steps in a tenth of the slowest period (at least 1).
fn window_steps(tube: &TubeCase, dt: Real) -> u64 {
    (tube.slowest_period() / (WINDOWS_PER_PERIOD * dt)).ceil().max(1.0) as u64
}

/// Distance along x between the rings at L/4 and 3L/4.
fn gauge_length(pos: &[Vec3], rings: &TubeRings) -> Real {
    centroid(pos, &rings.three_quarters).x - centroid(pos, &rings.quarter).x
}

/// Tension test: an axial force F (strain about 1e-3 by the truss model) shared by the nodes
/// of the ring at x = L, ramped over one slowest period and held until the gauge strain
/// changes by less than 1e-6 (relative) over a tenth of a period. C = (F/2πR)/ε,
/// ν = −ε_θ/ε (mean radius of the mid-length ring).
pub fn tension_test(tube: &TubeCase) -> Result<TensionResult, ValidationError> {
    let (mut sim, rings) = simulation(tube)?;
    let c_truss = LatticeStiffness::of(tube).axial;
    let force = TENSION_STRAIN * c_truss * 2.0 * PI * tube.radius;
    let period = tube.slowest_period();
    sim.add_load(Load {
        particles: rings.last.clone(),
        force: Vec3::x() * force / rings.last.len() as Real,
        torque: Vec3::zeros(),
        ramp: Ramp::Linear { start: 0.0, duration: period },
    })?;
    let pos0 = sim.model().particles.pos.clone();
    let (l0, r0) = (gauge_length(&pos0, &rings), mean_radius(&pos0, &rings.middle));
    let window = window_steps(tube, sim.dt());
    let strain = |sim: &Simulation| gauge_length(&sim.model().particles.pos, &rings) / l0 - 1.0;
    let mut previous = Real::NAN;
    let max_time = 40.0 * period;
    loop {
        sim.run(window)?;
        let eps = strain(&sim);
        let settled = sim.time() > 2.0 * period && (eps - previous).abs() <= 1e-6 * eps.abs();
        if settled || sim.time() > max_time {
            if !settled {
                return Err(ValidationError::Case {
                    case: "brazier".into(),
                    message: format!(
                        "tension test not at rest after {:.3} s (strain {eps:.6e}, previous \
                         {previous:.6e})",
                        sim.time()
                    ),
                });
            }
            let eps_ring = mean_radius(&sim.model().particles.pos, &rings.middle) / r0 - 1.0;
            return Ok(TensionResult {
                force,
                membrane_stiffness: force / (2.0 * PI * tube.radius) / eps,
                poisson: -eps_ring / eps,
                steps: sim.steps(),
            });
        }
        previous = eps;
    }
}

/// The bending protocol.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Protocol {
    /// The ramp would reach eq 18's moment after this many slowest periods.
    pub ramp_periods: Real,
    /// Moment (fraction of eq 18) held to equilibrium to measure the initial stiffness.
    pub initial_fraction: Real,
    /// Non-linearity: the secant stiffness M/φ has dropped by this fraction.
    pub nonlinear_drop: Real,
    /// Moment step after the non-linearity (fraction of eq 18).
    pub moment_step: Real,
    /// A hold has converged when φ changes by less than this (relative) over a window.
    pub convergence: Real,
    /// A hold that has not converged after this many periods is buckling.
    pub max_hold_periods: Real,
    /// A hold during which φ grows by this fraction is buckling.
    pub runaway: Real,
    /// Periods at constant moment after buckling (winding, self-contact).
    pub post_periods: Real,
    /// Stop after the initial-stiffness hold (quick run).
    pub linear_only: bool,
    /// Also ramp at half the rate up to the non-linearity and compare the rotations.
    pub rate_check: bool,
}

impl Protocol {
    /// The full protocol: ramp over 20 periods, 5 % non-linearity, 2 % steps, 20 periods of
    /// winding, ramp-rate check.
    pub fn full() -> Protocol {
        Protocol {
            ramp_periods: 20.0,
            initial_fraction: 0.2,
            nonlinear_drop: 0.05,
            moment_step: 0.02,
            convergence: 1e-4,
            max_hold_periods: 10.0,
            runaway: 0.3,
            post_periods: 20.0,
            linear_only: false,
            rate_check: true,
        }
    }

    /// The quick protocol: the full one up to the initial-stiffness hold.
    pub fn quick() -> Protocol {
        Protocol { linear_only: true, rate_check: false, ..Protocol::full() }
    }
}

/// One recorded state of the bending run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// Applied moment (N·m).
    pub moment: Real,
    /// End rotation (rad).
    pub rotation: Real,
    /// Largest over smallest diameter of the mid-length ring.
    pub ovalisation: Real,
}

/// The state at the end of the winding phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FinalState {
    /// Smallest node–PFacet distance between non-neighbours at the end (m).
    pub min_distance: Real,
    /// Smallest of it over the winding, looked at every tenth of a period (m).
    pub min_distance_during: Real,
    /// Largest overlap F_n/k_n of a contact at the end (m): the penetration the linear
    /// contact law (eq 1) needs to carry its force.
    pub largest_overlap: Real,
    /// Number of contacts (all are self-contacts: there is one body).
    pub contacts: usize,
    /// End rotation (rad).
    pub rotation: Real,
    /// Largest |B(t) − B(start)| over the winding, over the energy scale (`EnergyWatch`).
    pub balance_error: Real,
}

/// What the bending run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct BendingResult {
    /// The recorded states, in time order.
    pub curve: Vec<CurvePoint>,
    /// M/φ at the initial-stiffness hold (N·m/rad).
    pub initial_stiffness: Real,
    /// Moment at which the non-linearity was detected.
    pub nonlinear_moment: Option<Real>,
    /// Largest moment held in equilibrium.
    pub last_stable_moment: Option<Real>,
    /// Moment at which the deformation kept growing (buckling).
    pub buckling_moment: Option<Real>,
    /// Position x/L of the most ovalised ring when buckling was detected.
    pub collapse_position: Option<Real>,
    /// The state at the end of the last hold in equilibrium before buckling.
    pub stable_state: Option<CurvePoint>,
    /// Largest ratio kinetic/elastic energy during the ramp (after 10 % of eq 18).
    pub ramp_energy_ratio: Real,
    /// Rotation at the non-linearity moment with the half-rate ramp, and its relative
    /// difference from the normal rate.
    pub rate_check: Option<(Real, Real)>,
    /// After winding.
    pub final_state: Option<FinalState>,
    /// VTK file of the final state (inside the output folder).
    pub vtk_file: Option<String>,
    /// Time step (s).
    pub dt: Real,
    /// Steps run (all phases).
    pub steps: u64,
}

/// Holds the moment for `periods` slowest periods (winding), then measures the self-contact
/// state: the smallest non-neighbour node–PFacet distance and the number of contacts.
fn wind(run: &mut Bending, periods: Real) -> Result<FinalState, ValidationError> {
    let end = run.sim.time() + periods * run.period;
    let mut min_during = Real::INFINITY;
    let balance0 = run.sim.energy().balance();
    let mut balance_error: Real = 0.0;
    while run.sim.time() < end {
        run.advance(0.0)?;
        min_during = min_during.min(min_self_distance(run.sim.model()));
        let change = (run.sim.energy().balance() - balance0).abs();
        balance_error = balance_error.max(change / run.sim.energy_watch().scale);
    }
    let largest_overlap =
        run.sim.contacts().iter().map(|c| c.forces.normal_force / c.params.kn).fold(0.0, Real::max);
    Ok(FinalState {
        min_distance: min_self_distance(run.sim.model()),
        min_distance_during: min_during,
        largest_overlap,
        contacts: run.sim.contacts().len(),
        rotation: run.rotation,
        balance_error,
    })
}

/// The same ramp and initial hold as [`bend`] at `rate`, up to `moment`: the end rotation
/// there (interpolated linearly in M over the last window) and the steps run.
fn rotation_at_half_rate(
    tube: &TubeCase,
    protocol: &Protocol,
    rate: Real,
    m18: Real,
    moment: Real,
) -> Result<(Real, u64), ValidationError> {
    let mut slow = Bending::new(tube)?;
    let mut ignored = 0.0;
    slow.ramp_to(rate, protocol.initial_fraction * m18, &mut ignored, m18)?;
    slow.set_moment(protocol.initial_fraction * m18);
    slow.hold(protocol.convergence, protocol.max_hold_periods, protocol.runaway)?;
    slow.ramp_to(rate, moment, &mut ignored, m18)?;
    Ok((slow.rotation * moment / slow.moment(), slow.sim.steps()))
}

/// Position x/L of the ring of `tube` with the largest ovalisation.
fn most_ovalised_ring(tube: &TubeCase, pos: &[Vec3]) -> Real {
    let m = tube.n_around as u32;
    let (j, _) = (0..=tube.n_along as u32)
        .map(|j| ovalisation(pos, &(0..m).map(|i| i + j * m).collect::<Vec<u32>>()))
        .enumerate()
        .fold((0, 0.0), |best, (j, o)| if o > best.1 { (j, o) } else { best });
    j as Real / tube.n_along as Real
}

/// The moment hook: node forces f_k = M·ẑ × (p_k − p̄)/Σ|(p_k − p̄)⊥ẑ|² on the ring `ring`,
/// from the current positions; the moment M (N·m) is read from `moment` (f64 bits).
fn end_moment_hook(ring: Vec<u32>, moment: Arc<AtomicU64>) -> flexdem_integrate::ForceHook {
    Box::new(move |_t, particles, force, _torque| {
        let m = f64::from_bits(moment.load(Ordering::Relaxed));
        let c = centroid(&particles.pos, &ring);
        let s: Real = ring
            .iter()
            .map(|&i| {
                let d = particles.pos[i as usize] - c;
                d.x * d.x + d.y * d.y
            })
            .sum();
        for &i in &ring {
            let d = particles.pos[i as usize] - c;
            force[i as usize] += Vec3::new(-d.y, d.x, 0.0) * (m / s);
        }
    })
}

/// A bending run in progress: the simulation, its moment and the measurements.
struct Bending {
    sim: Simulation,
    rings: TubeRings,
    moment: Arc<AtomicU64>,
    reference: Vec3,
    rotation: Real,
    window: u64,
    period: Real,
    curve: Vec<CurvePoint>,
}

impl Bending {
    fn new(tube: &TubeCase) -> Result<Self, ValidationError> {
        let (mut sim, rings) = simulation(tube)?;
        let moment = Arc::new(AtomicU64::new(0.0_f64.to_bits()));
        sim.set_force_hook(end_moment_hook(rings.last.clone(), moment.clone()));
        let reference = ring_normal(&sim.model().particles.pos, &rings.last);
        let window = window_steps(tube, sim.dt());
        let period = tube.slowest_period();
        Ok(Bending { sim, rings, moment, reference, rotation: 0.0, window, period, curve: vec![] })
    }

    fn moment(&self) -> Real {
        f64::from_bits(self.moment.load(Ordering::Relaxed))
    }

    fn set_moment(&self, m: Real) {
        self.moment.store(m.to_bits(), Ordering::Relaxed);
    }

    /// Runs one window with the moment growing at `rate` (0 = held), then records the state.
    fn advance(&mut self, rate: Real) -> Result<(), ValidationError> {
        let moment = self.moment.clone();
        let m0 = self.moment();
        let t0 = self.sim.time();
        self.sim.run_with(self.window, 1, |sim| {
            moment.store((m0 + rate * (sim.time() - t0)).to_bits(), Ordering::Relaxed);
            Control::Continue
        })?;
        let pos = &self.sim.model().particles.pos;
        self.rotation = ring_rotation(pos, &self.rings.last, self.reference, self.rotation);
        self.curve.push(CurvePoint {
            moment: self.moment(),
            rotation: self.rotation,
            ovalisation: ovalisation(pos, &self.rings.middle),
        });
        Ok(())
    }

    /// Holds the moment until φ changes by less than `convergence` (relative) over a window.
    /// Returns true when it converged within `max_periods`, false when it did not or when φ
    /// grew by more than `runaway` (relative).
    fn hold(
        &mut self,
        convergence: Real,
        max_periods: Real,
        runaway: Real,
    ) -> Result<bool, ValidationError> {
        let (t0, phi0) = (self.sim.time(), self.rotation.abs());
        let mut previous = self.rotation;
        loop {
            self.advance(0.0)?;
            if (self.rotation - previous).abs() <= convergence * self.rotation.abs() {
                return Ok(true);
            }
            if self.sim.time() - t0 > max_periods * self.period
                || self.rotation.abs() > (1.0 + runaway) * phi0
            {
                return Ok(false);
            }
            previous = self.rotation;
        }
    }

    /// Ramps the moment at `rate` until it reaches `target`.
    fn ramp_to(
        &mut self,
        rate: Real,
        target: Real,
        energy_ratio: &mut Real,
        m18: Real,
    ) -> Result<(), ValidationError> {
        while self.moment() < target {
            self.advance(rate)?;
            let e = self.sim.energy();
            if self.moment() > 0.1 * m18 && e.elastic_links > 0.0 {
                *energy_ratio = energy_ratio
                    .max((e.kinetic_translation + e.kinetic_rotation) / e.elastic_links);
            }
        }
        Ok(())
    }
}

/// Bends `tube` (see [`Protocol`]); `m18` is eq 18's moment, which sets the ramp rate and the
/// moment steps. Writes the final state as `brazier_final.vtp` in `out_dir` when given.
pub fn bend(
    tube: &TubeCase,
    protocol: &Protocol,
    m18: Real,
    out_dir: Option<&Path>,
) -> Result<BendingResult, ValidationError> {
    let mut run = Bending::new(tube)?;
    let rate = m18 / (protocol.ramp_periods * run.period);
    let mut energy_ratio: Real = 0.0;
    run.ramp_to(rate, protocol.initial_fraction * m18, &mut energy_ratio, m18)?;
    run.set_moment(protocol.initial_fraction * m18);
    let converged = run.hold(protocol.convergence, protocol.max_hold_periods, protocol.runaway)?;
    let initial_stiffness = if converged { run.moment() / run.rotation } else { Real::NAN };
    let mut result = BendingResult {
        curve: vec![],
        initial_stiffness,
        nonlinear_moment: None,
        last_stable_moment: converged.then(|| run.moment()),
        buckling_moment: None,
        collapse_position: None,
        stable_state: None,
        ramp_energy_ratio: energy_ratio,
        rate_check: None,
        final_state: None,
        vtk_file: None,
        dt: run.sim.dt(),
        steps: 0,
    };
    if protocol.linear_only || !converged {
        result.steps = run.sim.steps();
        result.curve = run.curve;
        return Ok(result);
    }
    // ramp until the secant stiffness drops
    while run.moment() / run.rotation > (1.0 - protocol.nonlinear_drop) * initial_stiffness {
        run.ramp_to(
            rate,
            run.moment() + rate * run.period / WINDOWS_PER_PERIOD,
            &mut energy_ratio,
            m18,
        )?;
        if run.moment() > 3.0 * m18 {
            break;
        }
    }
    result.ramp_energy_ratio = energy_ratio;
    let nonlinear = run.moment();
    let nonlinear_rotation = run.rotation;
    result.nonlinear_moment = Some(nonlinear);
    // hold, then raise in steps until a hold does not converge
    loop {
        let ok = run.hold(protocol.convergence, protocol.max_hold_periods, protocol.runaway)?;
        if !ok {
            result.buckling_moment = Some(run.moment());
            result.collapse_position =
                Some(most_ovalised_ring(tube, &run.sim.model().particles.pos));

            break;
        }
        result.last_stable_moment = Some(run.moment());
        result.stable_state = run.curve.last().copied();
        if run.moment() > 3.0 * m18 {
            break;
        }
        run.set_moment(run.moment() + protocol.moment_step * m18);
    }
    result.final_state = Some(wind(&mut run, protocol.post_periods)?);
    if let Some(dir) = out_dir {
        let file = "brazier_final.vtp".to_string();
        let path = dir.join(&file);
        let xml = flexdem_output::pfacets_polydata(&run.sim).to_xml();
        std::fs::write(&path, xml).map_err(|source| ValidationError::Io { path, source })?;
        result.vtk_file = Some(file);
    }
    result.dt = run.sim.dt();
    result.steps = run.sim.steps();
    result.curve = std::mem::take(&mut run.curve);
    if protocol.rate_check {
        let (phi, steps) = rotation_at_half_rate(tube, protocol, rate / 2.0, m18, nonlinear)?;
        result.rate_check =
            Some((phi, (phi - nonlinear_rotation).abs() / nonlinear_rotation.abs()));
        result.steps += steps;
    }
    Ok(result)
}

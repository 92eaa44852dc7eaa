//! A simulation: the model, its links, loads and settings, stepped in time.

use crate::collider::Collider;
use crate::contacts::Contacts;
use crate::integrator::{kinetic_energy, leapfrog_step, StepWork};
use crate::links::{LinkUpdate, Links};
use crate::settings::{Load, Ramp, Settings, TimeStep};
use crate::time_step::{critical_step_from_stiffness, p_wave_time_step, StiffnessSums};
use crate::timers::{Stage, Timers};
use crate::SimulationError;
use flexdem_elements::virtual_sphere::Feature;
use flexdem_elements::{Adjacency, Dofs, Model, Particles};
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// What a [`Simulation::run_with`] callback asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// End the run now.
    Stop,
}

/// A user hook that adds forces and torques each step: `(time, particles, force, torque)`.
pub type ForceHook = Box<dyn FnMut(Real, &Particles, &mut [Vec3], &mut [Vec3]) + Send>;

/// Energy terms of a simulation (model.md §6). Works and dissipations are cumulative since the
/// start; kinetic and elastic terms are the current values.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Energy {
    /// Translational kinetic energy (J).
    pub kinetic_translation: Real,
    /// Rotational kinetic energy (J).
    pub kinetic_rotation: Real,
    /// Elastic energy stored in links (J).
    pub elastic_links: Real,
    /// Elastic energy stored in contacts (J).
    pub elastic_contacts: Real,
    /// Work done by gravity (J).
    pub gravity_work: Real,
    /// Work done by imposed loads and the user's force hook: forces and torques on the free
    /// DOFs, `Σ (F·v + τ·ω)·dt` (J).
    pub load_work: Real,
    /// Work done by the boundaries: moving walls (`Σ F_wall→body·v_wall·dt` over wall
    /// contacts) and imposed velocities and spins (the support's reaction, `−Σ (F·v + τ·ω)·dt`
    /// over blocked DOFs, `F` and `τ` from links and contacts) (J).
    pub boundary_work: Real,
    /// Energy put in by contacts that started or ended between two steps (J): `½·kn·δ·δ₋`
    /// per first touch (`δ₋` the overlap one step before: negative for a contact found on
    /// time, positive for one found late, with an overlap one step of approach does not
    /// explain) and `−½·F·δ_now` per contact ended by separating (see
    /// `Contacts::settle_births`). Collisions found on time add as much as they take.
    pub contact_births: Real,
    /// Elastic energy given up by contacts that ended or were handed over while holding it
    /// (J).
    pub contact_releases: Real,
    /// Energy removed by damping (J).
    pub damping: Real,
    /// Energy dissipated by links (plastic caps, slip after decohesion, breakage) (J).
    pub links_dissipated: Real,
    /// Energy dissipated by contact friction (J).
    pub friction: Real,
}

impl Energy {
    /// Energy stored in the system: kinetic plus elastic.
    pub fn stored(&self) -> Real {
        self.kinetic_translation
            + self.kinetic_rotation
            + self.elastic_links
            + self.elastic_contacts
    }

    /// Energy put in: the works of gravity, loads and boundaries and the late contact births.
    pub fn put_in(&self) -> Real {
        self.gravity_work + self.load_work + self.boundary_work + self.contact_births
    }

    /// Energy taken out: damping, link and contact dissipation, contact releases.
    pub fn taken_out(&self) -> Real {
        self.damping + self.links_dissipated + self.friction + self.contact_releases
    }

    /// Stored energy minus the energy put in plus the energy taken out: constant in time when
    /// the balance closes.
    pub fn balance(&self) -> Real {
        self.stored() - self.put_in() + self.taken_out()
    }

    /// The energy scale a balance error is measured against: the largest of the stored
    /// energy, each work, the births and what was taken out.
    pub fn scale(&self) -> Real {
        [
            self.stored().abs(),
            self.gravity_work.abs(),
            self.load_work.abs(),
            self.boundary_work.abs(),
            self.contact_births.abs(),
            self.taken_out().abs(),
        ]
        .into_iter()
        .fold(0.0, Real::max)
    }
}

/// Works of one step (from x(t) to x(t + dt)), added to [`Energy`] at the next step so that
/// every term refers to the same instant.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PendingWork {
    /// Gravity (J).
    pub gravity: Real,
    /// Imposed loads and the force hook (J).
    pub load: Real,
    /// Moving walls and imposed velocities (J).
    pub boundary: Real,
    /// The second half of the last kick's damping (J, see `StepWork::damping_next`).
    pub damping: Real,
}

/// The energy watch (model: "a run watches its energy"): the balance at the start (after the
/// first step) and the largest energy scale seen, against which the balance error is measured
/// each step.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnergyWatch {
    /// The balance at the start of the simulation (J).
    pub initial_balance: Real,
    /// The largest of |initial balance| and [`Energy::scale`] over the run so far (J).
    pub scale: Real,
}

impl EnergyWatch {
    /// `(B(t) − B(0)) / scale`: positive when energy appeared from nowhere, negative when it
    /// went unaccounted; 0 while the scale is 0.
    pub fn relative_error(&self, e: &Energy) -> Real {
        if self.scale > 0.0 {
            (e.balance() - self.initial_balance) / self.scale
        } else {
            0.0
        }
    }
}

/// Everything a simulation needs to continue exactly where it was: the model, settings,
/// links and contacts with their history, loads, clock, time-step bookkeeping and energy
/// terms. A simulation rebuilt from it with [`Simulation::from_snapshot`] continues
/// bit-identically to the original (the user's force hook is not part of it).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Snapshot {
    /// Bodies, structures, materials.
    pub model: Model,
    /// Settings.
    pub settings: Settings,
    /// Beam links with their state.
    pub links: Links,
    /// Contacts with their state, sorted by key.
    pub contacts: Vec<crate::contacts::Contact>,
    /// Friction dissipated by contacts that have ended.
    pub ended_dissipation: Real,
    /// Imposed loads.
    pub loads: Vec<Load>,
    /// Simulated time.
    pub time: Real,
    /// Steps done.
    pub steps: u64,
    /// Time step in use.
    pub dt: Real,
    /// The step taken before (0 before the first step).
    pub previous_dt: Real,
    /// Last critical step estimate.
    pub critical_dt: Real,
    /// Step of the last full time-step estimate.
    pub dt_updated_at: u64,
    /// Per-particle stiffness sums of that estimate, with the contacts made since.
    pub stiffness: StiffnessSums,
    /// Energy terms.
    pub energy: Energy,
    /// Works of the last step not yet added to `energy`.
    pub pending_work: PendingWork,
    /// The balance at the start and the energy scale so far.
    pub watch: EnergyWatch,
    /// Contacts found late (first touches with an unexplained overlap) so far.
    pub contacts_born_deep: u64,
    /// Warnings raised so far.
    pub warnings: Vec<String>,
}

/// How the warning about energy lost beyond the energy tolerance begins.
const ENERGY_LOST_WARNING: &str = "the run lost";

/// How the warning about a fixed dt above the critical step begins.
const FIXED_DT_WARNING: &str = "the fixed time step";

/// A simulation in progress.
pub struct Simulation {
    /// Bodies, structures and materials.
    pub model: Model,
    /// Settings (gravity, damping, time step rule).
    pub settings: Settings,
    /// Beam links, one per connection.
    pub links: Links,
    /// Contacts between bodies (spheres, connections, PFacets, walls).
    pub contacts: Contacts,
    /// Collidable elements and candidate pairs.
    pub collider: Collider,
    /// Imposed forces and torques.
    pub loads: Vec<Load>,
    adjacency: Adjacency,
    dt_updated_at: u64,
    /// Per-particle stiffness at the last full estimate, plus the contacts made since.
    stiffness: StiffnessSums,
    force_hook: Option<ForceHook>,
    force: Vec<Vec3>,
    torque: Vec<Vec3>,
    external_force: Vec<Vec3>,
    external_torque: Vec<Vec3>,
    time: Real,
    steps: u64,
    dt: Real,
    previous_dt: Real,
    critical_dt: Real,
    energy: Energy,
    /// Works of the last step (from x(t) to x(t + dt)), added at the next step so that every
    /// energy term refers to the same instant.
    pending_work: PendingWork,
    watch: EnergyWatch,
    contacts_born_deep: u64,
    timers: Timers,
    warnings: Vec<String>,
}

impl Simulation {
    /// A simulation of `model` with `settings`: validates both, makes one beam link per
    /// connection at rest, and chooses the time step.
    pub fn new(model: Model, settings: Settings) -> Result<Self, SimulationError> {
        settings.validate()?;
        model.validate()?;
        check_masses(&model)?;
        let links = Links::from_model(&model, settings.link_mode);
        let mut sim = Simulation::assemble(Snapshot {
            model,
            settings,
            links,
            contacts: Vec::new(),
            ended_dissipation: 0.0,
            loads: Vec::new(),
            time: 0.0,
            steps: 0,
            dt: 0.0,
            previous_dt: 0.0,
            critical_dt: 0.0,
            dt_updated_at: 0,
            stiffness: StiffnessSums::default(),
            energy: Energy::default(),
            pending_work: PendingWork::default(),
            watch: EnergyWatch::default(),
            contacts_born_deep: 0,
            warnings: Vec::new(),
        });
        sim.update_time_step()?;
        let (kt, kr) = kinetic_energy(&sim.model.particles);
        sim.energy.kinetic_translation = kt;
        sim.energy.kinetic_rotation = kr;
        sim.watch = EnergyWatch {
            initial_balance: sim.energy.balance(),
            scale: sim.energy.balance().abs().max(sim.energy.scale()),
        };
        Ok(sim)
    }

    /// A copy of the whole state (see [`Snapshot`]).
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            model: self.model.clone(),
            settings: self.settings.clone(),
            links: self.links.clone(),
            contacts: self.contacts.list.clone(),
            ended_dissipation: self.contacts.ended_dissipation,
            loads: self.loads.clone(),
            time: self.time,
            steps: self.steps,
            dt: self.dt,
            previous_dt: self.previous_dt,
            critical_dt: self.critical_dt,
            dt_updated_at: self.dt_updated_at,
            stiffness: self.stiffness.clone(),
            energy: self.energy,
            pending_work: self.pending_work,
            watch: self.watch,
            contacts_born_deep: self.contacts_born_deep,
            warnings: self.warnings.clone(),
        }
    }

    /// The simulation a snapshot describes, checked as [`Simulation::new`] checks a new one
    /// and for consistency between its parts (a snapshot read from a file may be damaged).
    pub fn from_snapshot(s: Snapshot) -> Result<Self, SimulationError> {
        s.settings.validate()?;
        s.model.validate()?;
        check_masses(&s.model)?;
        let n = s.model.particles.len();
        let n_links = s.model.connections.len();
        let consistent = s.links.len() == n_links
            && s.links.params.len() == n_links
            && s.links.state.len() == n_links
            && s.links.check_against(&s.model)
            && s.stiffness.translational.len() == s.stiffness.rotational.len()
            && (s.stiffness.translational.is_empty() || s.stiffness.translational.len() == n)
            && s.loads.iter().all(|l| l.particles.iter().all(|&i| (i as usize) < n))
            && s.contacts.iter().all(|c| {
                [&c.site1, &c.site2]
                    .iter()
                    .all(|site| site.nodes[..site.node_count()].iter().all(|&i| (i as usize) < n))
            })
            && s.dt > 0.0
            && s.dt.is_finite()
            && s.previous_dt >= 0.0
            && s.previous_dt.is_finite()
            && s.time.is_finite();
        if !consistent {
            return Err(SimulationError::Setting {
                what: "snapshot".into(),
                value: "inconsistent parts (links, contacts or loads do not match the model)"
                    .into(),
                expected: "a snapshot written by Simulation::snapshot".into(),
            });
        }
        Ok(Simulation::assemble(s))
    }

    /// A simulation of the state `s` with fresh buffers (no checks: see `new` and
    /// `from_snapshot`).
    fn assemble(s: Snapshot) -> Self {
        let n = s.model.particles.len();
        let mut links = s.links;
        links.forces = vec![Default::default(); links.len()];
        let mut contacts = Contacts::new(&s.model);
        contacts.list = s.contacts;
        contacts.ended_dissipation = s.ended_dissipation;
        let collider = Collider::new(&s.model, s.settings.verlet_factor);
        let adjacency = s.model.adjacency();
        Simulation {
            model: s.model,
            settings: s.settings,
            links,
            contacts,
            collider,
            loads: s.loads,
            adjacency,
            dt_updated_at: s.dt_updated_at,
            stiffness: s.stiffness,
            force_hook: None,
            force: vec![Vec3::zeros(); n],
            torque: vec![Vec3::zeros(); n],
            external_force: vec![Vec3::zeros(); n],
            external_torque: vec![Vec3::zeros(); n],
            time: s.time,
            steps: s.steps,
            dt: s.dt,
            previous_dt: s.previous_dt,
            critical_dt: s.critical_dt,
            energy: s.energy,
            pending_work: s.pending_work,
            watch: s.watch,
            contacts_born_deep: s.contacts_born_deep,
            timers: Timers::default(),
            warnings: s.warnings,
        }
    }

    /// Adds an imposed load, checking its particle ids and values.
    pub fn add_load(&mut self, load: Load) -> Result<(), SimulationError> {
        let n = self.model.particles.len();
        if let Some(&bad) = load.particles.iter().find(|&&i| i as usize >= n) {
            return Err(SimulationError::Setting {
                what: "load particle".into(),
                value: bad.to_string(),
                expected: format!("a particle id below {n}"),
            });
        }
        if let Ramp::Linear { start, duration } = load.ramp {
            if !(start.is_finite() && duration.is_finite() && duration >= 0.0) {
                return Err(SimulationError::Setting {
                    what: "load ramp".into(),
                    value: format!("start {start}, duration {duration}"),
                    expected: "a finite start time and a finite, non-negative duration (s)".into(),
                });
            }
        }
        if !load.force.iter().chain(load.torque.iter()).all(|x| x.is_finite()) {
            return Err(SimulationError::Setting {
                what: "load".into(),
                value: format!("force {:?}, torque {:?}", load.force, load.torque),
                expected: "finite numbers".into(),
            });
        }
        self.loads.push(load);
        Ok(())
    }

    /// Sets a hook that adds forces and torques each step (after links and contacts).
    pub fn set_force_hook(&mut self, hook: ForceHook) {
        self.force_hook = Some(hook);
    }

    /// Simulated time (s).
    pub fn time(&self) -> Real {
        self.time
    }

    /// Steps done.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Current time step (s).
    pub fn dt(&self) -> Real {
        self.dt
    }

    /// Critical time step at the last estimate (s).
    pub fn critical_dt(&self) -> Real {
        self.critical_dt
    }

    /// Energy terms at the last step.
    pub fn energy(&self) -> &Energy {
        &self.energy
    }

    /// The balance at the start and the energy scale so far (see [`EnergyWatch`]).
    pub fn energy_watch(&self) -> &EnergyWatch {
        &self.watch
    }

    /// The energy balance error now, relative to the energy scale
    /// ([`EnergyWatch::relative_error`]).
    pub fn relative_balance_error(&self) -> Real {
        self.watch.relative_error(&self.energy)
    }

    /// First touches found with more overlap than one step of approach explains, so far.
    pub fn contacts_born_deep(&self) -> u64 {
        self.contacts_born_deep
    }

    /// Per-stage wall-clock times.
    pub fn timers(&self) -> &Timers {
        &self.timers
    }

    /// Warnings raised so far (a fixed dt above the critical one, ...).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Total force on each particle at the last step (links, contacts and loads).
    pub fn forces(&self) -> &[Vec3] {
        &self.force
    }

    /// Estimates the critical step from the links (and later the contacts) and sets `dt`.
    pub fn update_time_step(&mut self) -> Result<(), SimulationError> {
        let mut k = StiffnessSums::new(self.model.particles.len());
        let p = &self.model.particles;
        for (l, nodes) in self.links.nodes.iter().enumerate() {
            if self.links.state[l].status == flexdem_contact::LinkStatus::Broken {
                continue;
            }
            let [a, b] = nodes.map(|n| n as usize);
            let d = p.pos[b] - p.pos[a];
            let len = d.norm();
            let n = if len > 0.0 { d / len } else { Vec3::x() };
            let s = &self.links.params[l].stiffness;
            for i in [a, b] {
                k.add(i, &n, s.kn, s.ks, 0.5 * len, s.kt, s.kb);
            }
        }
        for c in &self.contacts.list {
            add_contact_stiffness(&mut k, c);
        }
        self.dt_updated_at = self.steps;
        let critical = critical_step_from_stiffness(&self.model, &k)
            .or_else(|| p_wave_time_step(&self.model))
            .unwrap_or(Real::INFINITY);
        self.stiffness = k;
        self.critical_dt = critical;
        self.dt = match self.settings.time_step {
            TimeStep::Auto { safety } => {
                if !critical.is_finite() {
                    return Err(SimulationError::NoTimeStep);
                }
                safety * critical
            }
            TimeStep::Fixed(dt) => {
                // once: the check is redone periodically and would repeat itself
                let said = self.warnings.iter().any(|w| w.starts_with(FIXED_DT_WARNING));
                if dt > critical && !said {
                    self.warnings.push(format!(
                        "{FIXED_DT_WARNING} {dt:.3e} s is above the critical step {critical:.3e} s \
                         (at step {steps}): the run may explode; use dt = auto or a step below \
                         {critical:.3e} s",
                        steps = self.steps
                    ));
                }
                dt
            }
        };
        Ok(())
    }

    /// Advances the simulation by one step: a list of named stages (model.md §4–6).
    ///
    /// The contacts and links advance their shear springs by the motion of the step just done
    /// (velocities of t − dt₀/2 over dt₀, the previous step); the leapfrog then kicks the
    /// velocities over (dt₀ + dt)/2 and moves the positions by dt (see `leapfrog_step`).
    pub fn step(&mut self) -> Result<(), SimulationError> {
        let dt = self.dt;
        let previous = if self.previous_dt > 0.0 { self.previous_dt } else { dt };
        self.collision_stage();
        let appeared = self.contact_stage(previous);
        let link_sums = self.link_stage(previous);
        let load_work = self.external_load_stage(previous);
        let work = self.integration_stage(previous, dt);
        self.previous_dt = dt;
        self.time += dt;
        self.steps += 1;
        self.check_finite()?;
        self.account_energy(&work, load_work, &link_sums, dt);
        self.watch_energy()?;
        self.time_step_stage(appeared)
    }

    /// Collision: rebuilds the candidate pairs when a particle has moved beyond its margin.
    fn collision_stage(&mut self) {
        let t0 = self.timers.start();
        if self.collider.needs_rebuild(&self.model) {
            self.collider.rebuild(&self.model);
        }
        self.timers.stop(Stage::Collision, t0);
    }

    /// Contacts: detection, births, the contact law, node loads (forces reset first).
    /// Returns whether contacts appeared.
    fn contact_stage(&mut self, dt: Real) -> bool {
        let t0 = self.timers.start();
        self.force.iter_mut().for_each(|f| *f = Vec3::zeros());
        self.torque.iter_mut().for_each(|t| *t = Vec3::zeros());
        let before = self.contacts.list.len();
        let births = self.contacts.detect(&self.model, &self.adjacency, &self.collider, dt);
        // a birth's energy is a jump at time t, where the elastic terms of this step are
        self.energy.contact_births += births.born_energy;
        self.energy.contact_releases += births.released;
        self.contacts_born_deep += births.born_deep;
        let appeared = self.contacts.list.len() > before;
        self.account_new_contacts();
        self.contacts.apply(&self.model, dt, &mut self.force, &mut self.torque);
        self.timers.stop(Stage::Contacts, t0);
        appeared
    }

    /// Links: every beam link, loads summed per node.
    fn link_stage(&mut self, dt: Real) -> LinkUpdate {
        let t0 = self.timers.start();
        let sums = self.links.update(&self.model.particles, dt);
        self.links.add_loads(&mut self.force, &mut self.torque);
        self.timers.stop(Stage::Links, t0);
        sums
    }

    /// Imposed loads and the user's hook, kept apart in `external_force` and
    /// `external_torque` for their work, and added to the totals (nothing to sum over every
    /// particle without them). Returns the half of their work over the step before (`previous`
    /// long), with the velocities of t − dt₀/2 (see `StepWork::boundary` for the halves).
    fn external_load_stage(&mut self, previous: Real) -> Real {
        if !self.is_loaded() {
            return 0.0;
        }
        self.external_force.iter_mut().for_each(|f| *f = Vec3::zeros());
        self.external_torque.iter_mut().for_each(|t| *t = Vec3::zeros());
        for load in &self.loads {
            let s = load.ramp.factor(self.time);
            for &i in &load.particles {
                self.external_force[i as usize] += load.force * s;
                self.external_torque[i as usize] += load.torque * s;
            }
        }
        if let Some(hook) = self.force_hook.as_mut() {
            hook(
                self.time,
                &self.model.particles,
                &mut self.external_force,
                &mut self.external_torque,
            );
        }
        for (f, e) in self.force.iter_mut().zip(&self.external_force) {
            *f += e;
        }
        for (t, e) in self.torque.iter_mut().zip(&self.external_torque) {
            *t += e;
        }
        self.external_power() * 0.5 * previous
    }

    /// Whether loads or a force hook act.
    fn is_loaded(&self) -> bool {
        !self.loads.is_empty() || self.force_hook.is_some()
    }

    /// Integration: the leapfrog with damping (velocities kicked over (dt₀ + dt)/2, positions
    /// moved over `dt`), then the walls move.
    fn integration_stage(&mut self, previous: Real, dt: Real) -> StepWork {
        let t0 = self.timers.start();
        let g = self.settings.gravity;
        let mut work = leapfrog_step(
            &mut self.model.particles,
            &self.force,
            &self.torque,
            &g,
            self.settings.damping,
            previous,
            dt,
        );
        let walls = self.wall_power();
        work.boundary += 0.5 * walls * previous;
        work.boundary_next += 0.5 * walls * dt;
        for wall in &mut self.model.walls {
            wall.point += wall.velocity * dt;
        }
        self.timers.stop(Stage::Integration, t0);
        work
    }

    /// Power of the moving walls at time t: `Σ F·v_wall` over wall contacts, `F` the force
    /// the wall puts on the body.
    fn wall_power(&self) -> Real {
        let walls = &self.model.walls;
        if walls.iter().all(|w| w.velocity == Vec3::zeros()) {
            return 0.0;
        }
        self.contacts
            .list
            .iter()
            .filter_map(|c| match c.site1.feature {
                Feature::Wall(w) => Some(c.forces.force_on_2.dot(&walls[w as usize].velocity)),
                _ => None,
            })
            .sum()
    }

    /// Time step: the critical step is re-estimated every `time_step_interval` steps (for a
    /// fixed dt too, to warn when contacts or large deformations have brought it below that
    /// dt) and soon after contacts appear.
    fn time_step_stage(&mut self, appeared: bool) -> Result<(), SimulationError> {
        let since = self.steps - self.dt_updated_at;
        if since >= self.settings.time_step_interval || (appeared && since >= 10) {
            self.update_time_step()?;
        }
        Ok(())
    }

    /// Adds the stiffness of the contacts made at this step to the particles they touch and,
    /// with an automatic step, lowers dt at once if one of those particles now needs it (a
    /// contact stiffer than the links must not run for even a few steps above its critical
    /// step). O(new contacts); the full estimate is redone every `time_step_interval` steps.
    fn account_new_contacts(&mut self) {
        if self.contacts.fresh.is_empty()
            || self.stiffness.translational.len() != self.model.particles.len()
        {
            return;
        }
        let TimeStep::Auto { safety } = self.settings.time_step else { return };
        let p = &self.model.particles;
        let mut lowest = Real::INFINITY;
        for &i in &self.contacts.fresh {
            let c = &self.contacts.list[i];
            add_contact_stiffness(&mut self.stiffness, c);
            for site in [&c.site1, &c.site2] {
                for slot in 0..site.node_count() {
                    let n = site.nodes[slot] as usize;
                    if p.blocked[n] == Dofs::ALL {
                        continue;
                    }
                    let (kt, kr) =
                        (self.stiffness.translational[n].max(), self.stiffness.rotational[n].max());
                    let mut ratio = Real::INFINITY;
                    if kt > 0.0 {
                        ratio = ratio.min(p.mass[n] / kt);
                    }
                    if kr > 0.0 {
                        ratio = ratio.min(p.inertia[n] / kr);
                    }
                    lowest = lowest.min((2.0 * ratio).sqrt());
                }
            }
        }
        if lowest < self.critical_dt {
            self.critical_dt = lowest;
            self.dt = self.dt.min(safety * lowest);
        }
    }

    /// Runs `n` steps.
    pub fn run(&mut self, n: u64) -> Result<(), SimulationError> {
        for _ in 0..n {
            self.step()?;
        }
        Ok(())
    }

    /// Runs up to `n` steps, calling `callback` after every `every` steps (and after the last);
    /// the callback reads the simulation and returns [`Control::Stop`] to end the run early.
    /// Returns the number of steps run.
    pub fn run_with<F>(
        &mut self,
        n: u64,
        every: u64,
        mut callback: F,
    ) -> Result<u64, SimulationError>
    where
        F: FnMut(&Simulation) -> Control,
    {
        let every = every.max(1);
        for k in 1..=n {
            self.step()?;
            if (k % every == 0 || k == n) && callback(self) == Control::Stop {
                return Ok(k);
            }
        }
        Ok(n)
    }

    /// Energy at time t (the start of the step just done): kinetic from the half-step
    /// velocities around t, elastic from the forces computed at t, works up to t (the forces
    /// at t count half over the step before t; the other half is pending, see
    /// `StepWork::boundary`). `load_work` is the loads' half over the step before.
    fn account_energy(&mut self, work: &StepWork, load_work: Real, links: &LinkUpdate, dt: Real) {
        let load_next = if self.is_loaded() { self.external_power() * 0.5 * dt } else { 0.0 };
        let e = &mut self.energy;
        e.kinetic_translation = work.kinetic_translation;
        e.kinetic_rotation = work.kinetic_rotation;
        e.elastic_links = links.elastic_energy;
        e.elastic_contacts = self.contacts.elastic_energy();
        e.friction = self.contacts.dissipated();
        e.links_dissipated = links.dissipated;
        e.gravity_work += self.pending_work.gravity;
        e.load_work += self.pending_work.load + load_work;
        e.boundary_work += self.pending_work.boundary + work.boundary;
        e.damping += self.pending_work.damping + work.damping;
        self.pending_work = PendingWork {
            gravity: work.gravity,
            load: load_next,
            boundary: work.boundary_next,
            damping: work.damping_next,
        };
        if self.steps == 1 {
            // the reference of the watch is the balance after the first step: the first kick's
            // damping and the lag of the first step's works make an O(dt²) offset at the start
            // that is large next to the energy of a run that starts from rest
            self.watch.initial_balance = e.balance();
        }
        self.watch.scale = self.watch.scale.max(e.scale());
    }

    /// Power of the imposed loads and the hook, `Σ (F·v + τ·ω)` with the current velocities,
    /// on every DOF (on a blocked one the support's reaction, counted in the boundary work,
    /// takes the rest of the node's force).
    fn external_power(&self) -> Real {
        let p = &self.model.particles;
        let forces: Real = self.external_force.iter().zip(&p.vel).map(|(f, v)| f.dot(v)).sum();
        let torques: Real =
            self.external_torque.iter().zip(&p.ang_vel).map(|(t, w)| t.dot(w)).sum();
        forces + torques
    }

    /// Stops the run when the energy balance error passes `settings.energy_tolerance`
    /// (relative to the energy scale) on the side of energy created, naming the step, the
    /// time and where the energy is. Energy lost beyond the limit (dissipation the balance
    /// does not count) raises a warning, once.
    fn watch_energy(&mut self) -> Result<(), SimulationError> {
        let Some(limit) = self.settings.energy_tolerance else { return Ok(()) };
        let error = self.watch.relative_error(&self.energy);
        if error.is_nan() || error.abs() <= limit {
            return Ok(());
        }
        let change = self.energy.balance() - self.watch.initial_balance;
        if error < 0.0 {
            if !self.warnings.iter().any(|w| w.starts_with(ENERGY_LOST_WARNING)) {
                self.warnings.push(format!(
                    "{ENERGY_LOST_WARNING} {change:+.4e} J ({error:+.3e} of the energy scale \
                     {scale:.4e} J) by step {step} (t = {time:.6e} s) that the balance does not \
                     count: {culprit}",
                    scale = self.watch.scale,
                    step = self.steps,
                    time = self.time,
                    culprit = crate::culprit::describe(self)
                ));
            }
            return Ok(());
        }
        Err(SimulationError::EnergyBalance {
            step: self.steps,
            time: self.time,
            error,
            limit,
            change,
            scale: self.watch.scale,
            culprit: crate::culprit::describe(self),
        })
    }

    /// Stops on NaN or infinity, and on a particle that moved by more than its reach in one
    /// step (the sign of an unstable run, long before NaN appears), naming the particle. The
    /// reach is the particle's radius, or for a node the size of the smallest element holding
    /// it when that is larger: a thin cable or membrane (radius of microns, elements of
    /// centimetres) legitimately moves by more than its radius per step.
    fn check_finite(&self) -> Result<(), SimulationError> {
        let p = &self.model.particles;
        let dt = self.dt;
        let reach = &self.collider.reach;
        let jump = (0..p.len())
            .into_par_iter()
            .map(|i| (p.vel[i].norm() * dt / reach[i], i))
            .filter(|(ratio, _)| *ratio > 1.0)
            .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
        let bad = (0..p.len()).into_par_iter().find_first(|&i| {
            !(p.pos[i]
                .iter()
                .chain(p.vel[i].iter())
                .chain(p.ang_vel[i].iter())
                .all(|x| x.is_finite()))
        });
        match bad {
            Some(i) => Err(SimulationError::NonFinite {
                particle: i as u32,
                step: self.steps,
                time: self.time,
                dt: self.dt,
                critical_dt: self.critical_dt,
            }),
            None => match jump {
                Some((_, i)) => Err(SimulationError::Exploding {
                    particle: i as u32,
                    displacement: p.vel[i].norm() * dt,
                    reach: self.collider.reach[i],
                    step: self.steps,
                    time: self.time,
                    dt,
                    critical_dt: self.critical_dt,
                }),
                None => Ok(()),
            },
        }
    }
}

/// Adds a contact's stiffness to the particles carrying its two sites (the full contact
/// stiffness on each: conservative), with the site's radius as the lever arm of the shear.
fn add_contact_stiffness(k: &mut StiffnessSums, c: &crate::contacts::Contact) {
    let n = c.state.normal;
    for site in [&c.site1, &c.site2] {
        for slot in 0..site.node_count() {
            let node = site.nodes[slot] as usize;
            k.add(node, &n, c.params.kn, c.params.ks, site.radius, 0.0, 0.0);
        }
    }
}

/// Every particle free in a translational DOF needs a positive mass, and free in a rotational
/// DOF a positive inertia (a node without any connection has none).
fn check_masses(model: &Model) -> Result<(), SimulationError> {
    let p = &model.particles;
    for i in 0..p.len() {
        let free_t = !p.blocked[i].contains(Dofs::TRANSLATION);
        let free_r = !p.blocked[i].contains(Dofs::ROTATION);
        if (free_t && !(p.mass[i] > 0.0 && p.mass[i].is_finite()))
            || (free_r && !(p.inertia[i] > 0.0 && p.inertia[i].is_finite()))
        {
            return Err(SimulationError::NoMass {
                particle: i as u32,
                mass: p.mass[i],
                inertia: p.inertia[i],
            });
        }
    }
    Ok(())
}

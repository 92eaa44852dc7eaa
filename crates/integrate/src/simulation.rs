//! A simulation: the model, its links, loads and settings, stepped in time.

use crate::collider::Collider;
use crate::contacts::Contacts;
use crate::integrator::{kinetic_energy, leapfrog_step, StepWork};
use crate::links::{LinkUpdate, Links};
use crate::settings::{Load, Ramp, Settings, TimeStep};
use crate::time_step::{critical_step_from_stiffness, p_wave_time_step, StiffnessSums};
use crate::timers::{Stage, Timers};
use crate::SimulationError;
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
    /// Work done by imposed loads (J).
    pub load_work: Real,
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

    /// Stored energy minus the work put in plus the energy dissipated: constant in time when
    /// the balance closes.
    pub fn balance(&self) -> Real {
        self.stored() - self.gravity_work - self.load_work
            + self.damping
            + self.links_dissipated
            + self.friction
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
    /// Last critical step estimate.
    pub critical_dt: Real,
    /// Step of the last full time-step estimate.
    pub dt_updated_at: u64,
    /// Per-particle stiffness sums of that estimate, with the contacts made since.
    pub stiffness: StiffnessSums,
    /// Energy terms.
    pub energy: Energy,
    /// Works of the last step not yet added to `energy`.
    pub pending_work: (Real, Real),
    /// Warnings raised so far.
    pub warnings: Vec<String>,
}

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
    critical_dt: Real,
    energy: Energy,
    /// Works of the last step (from x(t) to x(t + dt)), added at the next step so that every
    /// energy term refers to the same instant.
    pending_work: (Real, Real),
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
            critical_dt: 0.0,
            dt_updated_at: 0,
            stiffness: StiffnessSums::default(),
            energy: Energy::default(),
            pending_work: (0.0, 0.0),
            warnings: Vec::new(),
        });
        sim.update_time_step()?;
        let (kt, kr) = kinetic_energy(&sim.model.particles);
        sim.energy.kinetic_translation = kt;
        sim.energy.kinetic_rotation = kr;
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
            critical_dt: self.critical_dt,
            dt_updated_at: self.dt_updated_at,
            stiffness: self.stiffness.clone(),
            energy: self.energy,
            pending_work: self.pending_work,
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
            critical_dt: s.critical_dt,
            energy: s.energy,
            pending_work: s.pending_work,
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

    /// Advances the simulation by one step.
    pub fn step(&mut self) -> Result<(), SimulationError> {
        let dt = self.dt;
        self.force.iter_mut().for_each(|f| *f = Vec3::zeros());
        self.torque.iter_mut().for_each(|t| *t = Vec3::zeros());

        let t0 = self.timers.start();
        if self.collider.needs_rebuild(&self.model) {
            self.collider.rebuild(&self.model);
        }
        self.timers.stop(Stage::Collision, t0);
        let t0 = self.timers.start();
        let before = self.contacts.list.len();
        self.contacts.detect(&self.model, &self.adjacency, &self.collider);
        let appeared = self.contacts.list.len() > before;
        self.account_new_contacts();
        self.contacts.apply(&self.model, dt, &mut self.force, &mut self.torque);
        self.timers.stop(Stage::Contacts, t0);

        let t0 = self.timers.start();
        let link_sums = self.links.update(&self.model.particles, dt);
        self.links.add_loads(&mut self.force, &mut self.torque);
        self.timers.stop(Stage::Links, t0);

        // imposed loads and the user's hook (nothing to sum over every particle without them)
        let loaded = !self.loads.is_empty() || self.force_hook.is_some();
        if loaded {
            self.external_force.iter_mut().for_each(|f| *f = Vec3::zeros());
        }
        for load in &self.loads {
            let s = load.ramp.factor(self.time);
            for &i in &load.particles {
                self.external_force[i as usize] += load.force * s;
                self.torque[i as usize] += load.torque * s;
            }
        }
        if let Some(hook) = self.force_hook.as_mut() {
            self.external_torque.iter_mut().for_each(|t| *t = Vec3::zeros());
            hook(
                self.time,
                &self.model.particles,
                &mut self.external_force,
                &mut self.external_torque,
            );
            for (t, e) in self.torque.iter_mut().zip(&self.external_torque) {
                *t += e;
            }
        }
        if loaded {
            for (f, e) in self.force.iter_mut().zip(&self.external_force) {
                *f += e;
            }
        }

        let t0 = self.timers.start();
        let g = self.settings.gravity;
        let work = leapfrog_step(
            &mut self.model.particles,
            &self.force,
            &self.torque,
            &g,
            self.settings.damping,
            dt,
        );
        for wall in &mut self.model.walls {
            wall.point += wall.velocity * dt;
        }
        self.timers.stop(Stage::Integration, t0);
        self.time += dt;
        self.steps += 1;

        self.check_finite()?;
        self.account_energy(&work, &link_sums, dt);
        // the critical step is re-estimated for a fixed dt too, to warn when contacts or
        // large deformations have brought it below that dt
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
    /// velocities around t, elastic from the forces computed at t, works up to t.
    fn account_energy(&mut self, work: &StepWork, links: &LinkUpdate, dt: Real) {
        let p = &self.model.particles;
        // work of imposed forces over the step: F·v(t + dt/2)·dt, on free DOFs (nothing to
        // sum over every particle when nothing is imposed)
        let loaded = !self.loads.is_empty() || self.force_hook.is_some();
        let load_work: Real = if !loaded {
            0.0
        } else {
            self.external_force
                .iter()
                .zip(&p.vel)
                .zip(&p.blocked)
                .map(|((f, v), b)| {
                    (0..3)
                        .filter(|&k| !b.contains(Dofs::translation(k)))
                        .map(|k| f[k] * v[k])
                        .sum::<Real>()
                })
                .sum::<Real>()
                * dt
        };
        let e = &mut self.energy;
        e.kinetic_translation = work.kinetic_translation;
        e.kinetic_rotation = work.kinetic_rotation;
        e.elastic_links = links.elastic_energy;
        e.elastic_contacts = self.contacts.elastic_energy();
        e.friction = self.contacts.dissipated();
        e.links_dissipated = links.dissipated;
        e.gravity_work += self.pending_work.0;
        e.load_work += self.pending_work.1;
        self.pending_work = (work.gravity, load_work);
        e.damping += work.damping;
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

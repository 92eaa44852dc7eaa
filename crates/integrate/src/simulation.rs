//! A simulation: its saved [`State`] (model, settings, links, contacts, loads, clock, energy)
//! and the pipeline that steps it, private and rebuilt from the state (see `pipeline.rs`;
//! the stages of a step are in `stages.rs`).

use crate::collider::Collider;
use crate::contact::Contact;
use crate::energy::{
    distinct, imposed_jump, kick_jump, support_jump, Energy, EnergyWatch, ROTATIONS, TRANSLATIONS,
};
use crate::integrator::kinetic_energy;
use crate::links::Links;
use crate::model_edit::{links_carried, only_adds_bodies};
use crate::pipeline::{ForceHook, Pipeline};
use crate::pressure::{check_pressure, Pressure};
use crate::servo::WallControl;
use crate::settings::{Load, Settings};
use crate::state::{check_load, check_pressures, State};
use crate::timers::Timers;
use crate::SimulationError;
use flexdem_contact::spring_energy;
use flexdem_elements::{Dofs, Model, ParticleId};
use flexdem_geom::{Real, Vec3};
use nalgebra::UnitQuaternion;

/// What a [`Simulation::run_with`] callback asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// End the run now.
    Stop,
}

/// A simulation in progress: a [`State`] and the pipeline that steps it.
///
/// The state is read through [`Simulation::state`] and the accessors ([`Simulation::model`],
/// [`Simulation::contacts`], ...) and changed only through methods that keep the pipeline's
/// caches right: [`Simulation::edit_model`] and [`Simulation::set_settings`] re-validate and
/// rebuild what depends on what they change; the cheap setters ([`Simulation::set_velocity`],
/// [`Simulation::set_wall_velocity`], [`Simulation::set_wall_control`],
/// [`Simulation::add_load`], [`Simulation::add_pressure`], ...) change what no cache depends
/// on.
pub struct Simulation {
    pub(crate) state: State,
    pub(crate) pipeline: Pipeline,
}

impl Simulation {
    /// A simulation of `model` with `settings`: validates both, makes one beam link per
    /// connection at rest, and chooses the time step.
    pub fn new(model: Model, settings: Settings) -> Result<Self, SimulationError> {
        State::check_parts(&model, &settings)?;
        let mut sim = Simulation::assemble(State::initial(model, settings));
        sim.update_time_step()?;
        let (kt, kr) = kinetic_energy(&sim.state.model.particles);
        let e = &mut sim.state.energy;
        e.terms.kinetic_translation = kt;
        e.terms.kinetic_rotation = kr;
        let balance = e.terms.balance();
        e.watch = EnergyWatch::starting_at(balance, balance.abs().max(e.terms.scale()));
        Ok(sim)
    }

    /// The simulation a state describes (one from [`Simulation::state`], a checkpoint, ...),
    /// checked as [`Simulation::new`] checks a new one and for consistency between its parts
    /// (a state read from a file may be damaged). It continues bit-identically to the
    /// simulation the state was taken from; the force hook is not part of the state.
    pub fn from_state(state: State) -> Result<Self, SimulationError> {
        state.check()?;
        Ok(Simulation::assemble(state))
    }

    /// A simulation of `state` with a fresh pipeline (no checks: see `new` and `from_state`).
    fn assemble(mut state: State) -> Self {
        state.model.shrink_to_fit();
        state.links.loads = vec![Default::default(); state.links.len()];
        let pipeline = Pipeline::new(&state);
        Simulation { state, pipeline }
    }

    /// The whole saved state (what a checkpoint stores; clone it to keep a copy).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The state, the pipeline dropped.
    pub fn into_state(self) -> State {
        self.state
    }

    /// Bodies, structures and materials.
    pub fn model(&self) -> &Model {
        &self.state.model
    }

    /// Settings (gravity, damping, time step rule).
    pub fn settings(&self) -> &Settings {
        &self.state.settings
    }

    /// Beam links, one per connection, with their state and the forces of the last step.
    pub fn links(&self) -> &Links {
        &self.state.links
    }

    /// Current contacts with their state and the forces of the last step, sorted by key
    /// (made for the caller: those of free spheres live in a neighbour list, see
    /// [`Contacts::pairs`](crate::Contacts)). For a count, [`Simulation::contact_count`].
    pub fn contacts(&self) -> Vec<Contact> {
        let last = self.state.contacts.pairs.last_update(&self.pipeline.contacts.pairs);
        self.state.contacts.all_after(&self.state.model, Some(&last))
    }

    /// Number of current contacts.
    pub fn contact_count(&self) -> usize {
        self.state.contacts.len()
    }

    /// Imposed forces and torques.
    pub fn loads(&self) -> &[Load] {
        &self.state.loads
    }

    /// Collidable elements and candidate pairs (a cache of the pipeline).
    pub fn collider(&self) -> &Collider {
        &self.pipeline.collider
    }

    /// Adds an imposed load, checking its particle ids and values.
    pub fn add_load(&mut self, load: Load) -> Result<(), SimulationError> {
        check_load(&load, self.state.model.particles.len())?;
        self.state.loads.push(load);
        Ok(())
    }

    /// Replaces every imposed load, checking each (nothing changes on error).
    pub fn set_loads(&mut self, loads: Vec<Load>) -> Result<(), SimulationError> {
        let n = self.state.model.particles.len();
        loads.iter().try_for_each(|l| check_load(l, n))?;
        self.state.loads = loads;
        Ok(())
    }

    /// Pressures on PFacets.
    pub fn pressures(&self) -> &[Pressure] {
        &self.state.pressures
    }

    /// Adds a pressure on PFacets, checking its PFacet ids and values. Its work goes to the
    /// load work of the energy balance.
    pub fn add_pressure(&mut self, pressure: Pressure) -> Result<(), SimulationError> {
        check_pressure(&pressure, self.state.model.pfacets.len())?;
        self.state.pressures.push(pressure);
        Ok(())
    }

    /// Replaces every pressure, checking each (nothing changes on error).
    pub fn set_pressures(&mut self, pressures: Vec<Pressure>) -> Result<(), SimulationError> {
        check_pressures(&pressures, &self.state.model)?;
        self.state.pressures = pressures;
        Ok(())
    }

    /// Sets a hook that adds forces and torques each step (after links and contacts).
    pub fn set_force_hook(&mut self, hook: ForceHook) {
        self.pipeline.force_hook = Some(hook);
    }

    /// Changes the settings, validated first (nothing changes when they are refused; an error
    /// of the time step estimate comes after the change). A new Verlet factor
    /// rebuilds the collider, a new time step rule re-estimates the time step; the link
    /// kinematics cannot change (the links were made with it: build a new simulation). The
    /// energy watch switched on again in a run watches from then on
    /// ([`Settings::energy_tolerance`]).
    pub fn set_settings(&mut self, settings: Settings) -> Result<(), SimulationError> {
        settings.validate()?;
        let old = &self.state.settings;
        if settings.link_mode != old.link_mode {
            return Err(SimulationError::Setting {
                what: "link kinematics".into(),
                value: format!(
                    "{:?} (the links were made with {:?})",
                    settings.link_mode, old.link_mode
                ),
                expected: "the kinematics of the links (build a new simulation to change it)"
                    .into(),
            });
        }
        let collider = settings.verlet_factor != old.verlet_factor;
        let time_step = settings.time_step != old.time_step
            || settings.time_step_interval != old.time_step_interval;
        let watch_on = old.energy_tolerance.is_none() && settings.energy_tolerance.is_some();
        self.state.settings = settings;
        if watch_on && self.state.clock.steps > 0 {
            // (before the first step the watch starts with the run anyway)
            self.state.energy.watch.restart_at(self.state.energy.terms.balance());
        }
        if collider {
            self.pipeline.rebuild(&self.state);
        }
        if time_step {
            self.update_time_step()?;
        }
        Ok(())
    }

    /// Changes the Cundall damping λ (in [0, 1)).
    pub fn set_damping(&mut self, damping: Real) -> Result<(), SimulationError> {
        self.set_settings(Settings { damping, ..self.state.settings.clone() })
    }

    /// Changes the gravity (m/s²).
    pub fn set_gravity(&mut self, gravity: Vec3) -> Result<(), SimulationError> {
        self.set_settings(Settings { gravity, ..self.state.settings.clone() })
    }

    /// Sets the velocity of particle `i`: on its blocked DOFs a new imposed velocity, whose
    /// change of kinetic energy the support gives ([`support_jump`], boundary work); on its
    /// free ones a kick by hand, whose change `½m·(v² − v₀²)` is the user's work (load work,
    /// [`kick_jump`]; before the first step the velocities are the start state, and nothing
    /// is booked). The balance is then off by `½F·h·Δv` once (`h` the next kick's span, `F` the
    /// force of gravity, links and contacts: the works of loads and damping see the kick).
    pub fn set_velocity(&mut self, i: u32, velocity: Vec3) -> Result<(), SimulationError> {
        let i = self.particle(i, &velocity, "velocity")?;
        let started = self.state.clock.steps > 0;
        let p = &mut self.state.model.particles;
        let (m, old, blocked) = (p.mass[i], &p.vel[i], p.blocked[i]);
        let jump = support_jump(m, old, &velocity, blocked, TRANSLATIONS);
        let kick = if started { kick_jump(m, old, &velocity, blocked, TRANSLATIONS) } else { 0.0 };
        p.vel[i] = velocity;
        self.state.energy.pending.boundary += jump;
        self.state.energy.pending.load += kick;
        Ok(())
    }

    /// Sets the angular velocity of particle `i` (rad/s; see [`Simulation::set_velocity`]:
    /// on free DOFs the kick `½I·(ω² − ω₀²)` is load work).
    pub fn set_angular_velocity(&mut self, i: u32, spin: Vec3) -> Result<(), SimulationError> {
        let i = self.particle(i, &spin, "angular velocity")?;
        let started = self.state.clock.steps > 0;
        let p = &mut self.state.model.particles;
        let (inertia, old, blocked) = (p.inertia[i], &p.ang_vel[i], p.blocked[i]);
        let jump = support_jump(inertia, old, &spin, blocked, ROTATIONS);
        let kick = if started { kick_jump(inertia, old, &spin, blocked, ROTATIONS) } else { 0.0 };
        p.ang_vel[i] = spin;
        self.state.energy.pending.boundary += jump;
        self.state.energy.pending.load += kick;
        Ok(())
    }

    /// Sets the velocity of each of `particles` (all or nothing: every id is checked first),
    /// each as [`Simulation::set_velocity`] does.
    pub fn set_velocities(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        velocity: Vec3,
    ) -> Result<(), SimulationError> {
        self.set_each(distinct(particles), velocity, "velocity", Simulation::set_velocity)
    }

    /// Sets the angular velocity of each of `particles` (all or nothing), each as
    /// [`Simulation::set_angular_velocity`] does.
    pub fn set_angular_velocities(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        spin: Vec3,
    ) -> Result<(), SimulationError> {
        let set = Simulation::set_angular_velocity;
        self.set_each(distinct(particles), spin, "angular velocity", set)
    }

    /// `set(self, i, value)` for each of `ids`, once every id and the value are checked.
    fn set_each(
        &mut self,
        ids: Vec<u32>,
        value: Vec3,
        what: &str,
        set: fn(&mut Simulation, u32, Vec3) -> Result<(), SimulationError>,
    ) -> Result<(), SimulationError> {
        for &i in &ids {
            self.particle(i, &value, what)?;
        }
        ids.into_iter().try_for_each(|i| set(self, i, value))
    }

    /// Moves particle `i` to `position` by hand. The collider sees the move at the next step
    /// (it watches every particle's displacement: the leapfrog's watch of the last step no
    /// longer holds); links and contacts feel it as a deformation. A first touch the move
    /// makes is found late: its spring's energy is energy the run made, and beyond the
    /// energy tolerance it stops the run (`SimulationError::LateContacts`).
    pub fn set_position(&mut self, i: u32, position: Vec3) -> Result<(), SimulationError> {
        let i = self.particle(i, &position, "position")?;
        self.state.model.particles.pos[i] = position;
        self.pipeline.moved_beyond = None;
        self.pipeline.collider.forget_drift();
        Ok(())
    }

    /// Turns particle `i` to `orientation` by hand (links feel it as a deformation).
    pub fn set_orientation(
        &mut self,
        i: u32,
        orientation: UnitQuaternion<Real>,
    ) -> Result<(), SimulationError> {
        let i = self.particle(i, &orientation.scaled_axis(), "orientation")?;
        self.state.model.particles.ori[i] = orientation;
        Ok(())
    }

    /// Sets the velocity of wall `w` (m/s) and puts it under strain control
    /// ([`WallControl::Velocity`]): it keeps that velocity. The work of the wall over the step
    /// before counts the new velocity (its force at t is shared half over the step before),
    /// an O(dt) error once per change, as for a particle's imposed velocity.
    pub fn set_wall_velocity(&mut self, w: u32, velocity: Vec3) -> Result<(), SimulationError> {
        let w = self.wall(w)?;
        if !velocity.iter().all(|x| x.is_finite()) {
            return Err(SimulationError::Setting {
                what: "wall velocity".into(),
                value: format!("{velocity:?}"),
                expected: "finite numbers".into(),
            });
        }
        self.state.model.walls[w].velocity = velocity;
        self.state.wall_controls[w] = WallControl::Velocity;
        Ok(())
    }

    /// Sets how wall `w` moves: [`WallControl::Velocity`] (it keeps the velocity it has now)
    /// or [`WallControl::Stress`] (a servo sets its normal velocity from the next step on; see
    /// [`crate::StressControl`]), or [`WallControl::StressUntil`] (a servo, then a velocity). A control with a bad value is refused, naming it (nothing
    /// changes).
    pub fn set_wall_control(
        &mut self,
        w: u32,
        control: WallControl,
    ) -> Result<(), SimulationError> {
        let w = self.wall(w)?;
        control.validate()?;
        self.state.wall_controls[w] = control;
        Ok(())
    }

    /// How each wall moves, one control per wall.
    pub fn wall_controls(&self) -> &[WallControl] {
        &self.state.wall_controls
    }

    /// The force the bodies put on each wall at the last step (N): `−Σ F_wall→body` over its
    /// contacts; its normal part `−F·n` is ≥ 0 in compression ([`crate::normal_force`]).
    /// Zero before the first step of a simulation built or restored.
    /// Summed when first asked for after a step (the step sums them only for a servo).
    pub fn wall_forces(&self) -> &[Vec3] {
        let last = self.state.contacts.pairs.last_update(&self.pipeline.contacts.pairs);
        let walls = self.state.model.walls.len();
        &self.pipeline.walls.get_or_sum(&self.state.contacts, &last, walls).force
    }

    /// The index of wall `w` if it exists.
    fn wall(&self, w: u32) -> Result<usize, SimulationError> {
        let n = self.state.model.walls.len();
        if w as usize >= n {
            return Err(SimulationError::Setting {
                what: "wall".into(),
                value: w.to_string(),
                expected: format!("a wall id below {n}"),
            });
        }
        Ok(w as usize)
    }

    /// Blocks `dofs` on each of `particles` (all or nothing, see `Model::block`): their
    /// velocities stay as they are. No cache depends on it; the time step follows at its
    /// next estimate.
    pub fn block(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        dofs: Dofs,
    ) -> Result<(), SimulationError> {
        Ok(self.state.model.block(particles, dofs)?)
    }

    /// Frees `dofs` on each of `particles` (all or nothing): each freed DOF needs a positive
    /// mass or inertia, as in [`Simulation::new`] (nothing changes on error). The time step
    /// follows at its next estimate.
    pub fn unblock(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        dofs: Dofs,
    ) -> Result<(), SimulationError> {
        let before = self.state.model.particles.blocked.clone();
        self.state.model.unblock(particles, dofs)?;
        if let Err(e) = State::check_parts(&self.state.model, &self.state.settings) {
            self.state.model.particles.blocked = before;
            return Err(e);
        }
        Ok(())
    }

    /// Sets the velocity of each of `particles` and blocks their translations, so that it
    /// persists (all or nothing, see `Model::impose_velocity`). The support gives the change
    /// of their kinetic energy, `Σ ½m·(|v|² − |v₀|²)`: boundary work ([`support_jump`]).
    pub fn impose_velocity(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        velocity: Vec3,
    ) -> Result<(), SimulationError> {
        let ids = distinct(particles);
        let p = &self.state.model.particles;
        let jump = imposed_jump(&ids, &p.mass, &p.vel, &velocity, TRANSLATIONS);
        self.state.model.impose_velocity(ids, velocity)?;
        self.state.energy.pending.boundary += jump;
        Ok(())
    }

    /// Sets the angular velocity of each of `particles` and blocks their rotations, so that
    /// it persists (all or nothing, see `Model::impose_angular_velocity`); the support gives
    /// the change of their kinetic energy, `Σ ½I·(|ω|² − |ω₀|²)` (boundary work).
    pub fn impose_angular_velocity(
        &mut self,
        particles: impl IntoIterator<Item = ParticleId>,
        spin: Vec3,
    ) -> Result<(), SimulationError> {
        let ids = distinct(particles);
        let p = &self.state.model.particles;
        let jump = imposed_jump(&ids, &p.inertia, &p.ang_vel, &spin, ROTATIONS);
        self.state.model.impose_angular_velocity(ids, spin)?;
        self.state.energy.pending.boundary += jump;
        Ok(())
    }

    /// The index of particle `i` if it exists and `value` is finite.
    fn particle(&self, i: u32, value: &Vec3, what: &str) -> Result<usize, SimulationError> {
        let n = self.state.model.particles.len();
        if i as usize >= n {
            return Err(SimulationError::Setting {
                what: "particle".into(),
                value: i.to_string(),
                expected: format!("a particle id below {n}"),
            });
        }
        if !value.iter().all(|x| x.is_finite()) {
            return Err(SimulationError::Setting {
                what: what.into(),
                value: format!("{value:?}"),
                expected: "finite numbers".into(),
            });
        }
        Ok(i as usize)
    }

    /// Changes the model with `edit` (block DOFs, add bodies, change masks, ...), then checks
    /// it as [`Simulation::new`] does and rebuilds what depends on it: the pipeline
    /// (collider, adjacency, contact buffers), the links when the connections changed (a
    /// link whose connection is still there, the same nodes, spring and class, keeps its
    /// state, broken or not; the others are made at rest in the current configuration: the
    /// elastic energy the old ones held goes to `links_dissipated`, and what a new one's
    /// normal spring holds at once, `½·kn·(L0 − L)²`, is the user's work, `load_work`), and
    /// the time step (an automatic one raised by at most `DT_GROWTH` once the run has
    /// started). When the particles, connections, PFacets or walls changed other than by
    /// bodies added apart from the old ones (which keeps every contact, `model_edit.rs`),
    /// the contacts end (their friction stays counted as
    /// dissipated, their elastic energy goes to `contact_releases`) and are found again at the
    /// next step, late: the energy their normal springs bring back, up to what those held, is
    /// not counted against the energy watch's limit on contacts found late, but a body added
    /// into another is, and so is what a contact reborn without its overlap offset gains (it
    /// comes back with its full force `kn·δ` where it carried `kn·(δ − δ₀)`). The
    /// wall controls are kept by wall index; walls added get [`WallControl::Velocity`], the
    /// controls of walls removed from the end go. A model that fails the checks is
    /// put back as it was; an error of the time step estimate (no stiffness anywhere) comes
    /// after the change. A model whose PFacets no longer fit the pressures is put back too.
    /// Costs a copy of the model: for velocities, positions and walls use the setters (an
    /// imposed velocity changed here is not booked as the support's work, as
    /// [`Simulation::impose_velocity`] books it).
    pub fn edit_model<R>(
        &mut self,
        edit: impl FnOnce(&mut Model) -> R,
    ) -> Result<R, SimulationError> {
        let before = self.state.model.clone();
        let result = edit(&mut self.state.model);
        let checked = State::check_parts(&self.state.model, &self.state.settings)
            .and_then(|()| check_pressures(&self.state.pressures, &self.state.model));
        if let Err(e) = checked {
            self.state.model = before;
            return Err(e);
        }
        let model = &self.state.model;
        let terms = &mut self.state.energy.terms;
        if model.connections != before.connections || model.materials != before.materials {
            // the links of connections still there go on; those of connections gone give up
            // their elastic energy, as a breakage does, and those made at rest hold their
            // normal spring's at once, the user's work (`links_carried`)
            let mode = self.state.settings.link_mode;
            let carried = links_carried(&self.state.links, &before, model, mode);
            terms.links_dissipated += carried.released;
            terms.load_work += carried.made;
            terms.elastic_links += carried.made - carried.released;
            self.state.links = carried.links;
        }
        if !only_adds_bodies(&before, model) {
            // contacts ended while holding elastic energy give it up (`contact_releases`);
            // found again at the next step, late, their normal springs bring theirs back
            // (reborn with no shear), which is not energy the run made (`late_credit`)
            let contacts = &mut self.state.contacts;
            let ended = contacts.all(&before);
            let normal = ended.iter().map(|c| spring_energy(c.state.normal_force, c.params.kn));
            self.state.energy.watch.late_credit += normal.sum::<Real>();
            terms.contact_releases += terms.elastic_contacts;
            terms.elastic_contacts = 0.0;
            contacts.ended_dissipation = contacts.dissipated();
            contacts.list.clear();
            contacts.pairs.clear();
        }
        self.state.wall_controls.resize(model.walls.len(), WallControl::Velocity);
        self.pipeline.rebuild(&self.state);
        if self.state.clock.steps > 0 {
            // (the kept contacts and links would feel a step raised at once)
            self.re_estimate_time_step()?;
        } else {
            self.update_time_step()?;
        }
        Ok(result)
    }

    /// Simulated time (s).
    pub fn time(&self) -> Real {
        self.state.clock.time
    }

    /// Steps done.
    pub fn steps(&self) -> u64 {
        self.state.clock.steps
    }

    /// Current time step (s).
    pub fn dt(&self) -> Real {
        self.state.clock.dt
    }

    /// Critical time step at the last estimate (s).
    pub fn critical_dt(&self) -> Real {
        self.state.clock.critical_dt
    }

    /// Energy terms at the last step.
    pub fn energy(&self) -> &Energy {
        &self.state.energy.terms
    }

    /// The balance at the start and the energy scale so far (see [`EnergyWatch`]).
    pub fn energy_watch(&self) -> &EnergyWatch {
        &self.state.energy.watch
    }

    /// The energy balance error now, relative to the energy scale
    /// ([`EnergyWatch::relative_error`]).
    pub fn relative_balance_error(&self) -> Real {
        self.state.energy.watch.relative_error(&self.state.energy.terms)
    }

    /// First touches found with more overlap than one step of approach explains, so far.
    pub fn contacts_born_deep(&self) -> u64 {
        self.state.contacts.born_deep
    }

    /// Per-stage wall-clock times.
    pub fn timers(&self) -> &Timers {
        &self.pipeline.timers
    }

    /// Warnings raised so far (a fixed dt above the critical one, ...).
    pub fn warnings(&self) -> &[String] {
        &self.state.warnings
    }

    /// Total force on each particle at the last step (links, contacts and loads).
    pub fn forces(&self) -> &[Vec3] {
        &self.pipeline.force
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
}

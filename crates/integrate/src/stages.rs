//! The stages of a step (model.md §4–6), each its own method of [`Simulation`], and the
//! bookkeeping around them: energy terms, the energy watch, the checks of a run going
//! unstable and the time step.

use crate::culprit::describe;
use crate::energy::PendingWork;
use crate::integrator::{leapfrog_step_checked, Leapfrog, StepWork};
use crate::links::LinkUpdate;
use crate::offsets::release_offsets;
use crate::pressure::add_pressure_forces;
use crate::servo::{any_servo_at, steer_walls, WallLoads};
use crate::settings::TimeStep;
use crate::simulation::Simulation;
use crate::step_work::Checks;
use crate::stiffness_sums::{add_fresh, add_in_order, add_in_ranges, MIN_PARALLEL_SUMS};
use crate::time_step::{critical_step_from_stiffness, p_wave_time_step};
use crate::timers::Stage;
use crate::SimulationError;
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// How the warning about energy lost beyond the energy tolerance begins.
const ENERGY_LOST_WARNING: &str = "the run lost";

/// How the warning about a fixed dt above the critical step begins.
const FIXED_DT_WARNING: &str = "the fixed time step";

/// Largest factor an automatic step grows by at one re-estimate. The leapfrog's kinetic energy
/// `½m·v(t − dt₀/2)·v(t + dt/2)` has a term `O(F·v·(dt − dt₀))` (model.md §3): a step raised
/// 2.2× at once showed as a one-step spike of 1.8e-2 of the energy scale in two membranes
/// driven through each other (`tests/large_deformation.rs`).
pub(crate) const DT_GROWTH: Real = 1.1;

impl Simulation {
    /// Estimates the critical step from the links (and later the contacts) and sets `dt`.
    pub fn update_time_step(&mut self) -> Result<(), SimulationError> {
        // the last estimate's sums: their memory serves again
        let mut k = std::mem::take(&mut self.state.clock.stiffness);
        let (links, contacts) = (&self.state.links, &self.state.contacts);
        let model = &self.state.model;
        if rayon::current_num_threads() > 1 && model.particles.len() >= MIN_PARALLEL_SUMS {
            // per range of particles in parallel (the same sums)
            add_in_ranges(&mut k, links, contacts, model);
        } else {
            k.reset(model.particles.len());
            add_in_order(&mut k, links, contacts, model);
        }
        self.state.clock.dt_updated_at = self.state.clock.steps;
        let critical = critical_step_from_stiffness(&self.state.model, &k)
            .or_else(|| p_wave_time_step(&self.state.model))
            .unwrap_or(Real::INFINITY);
        self.state.clock.stiffness = k;
        self.state.clock.critical_dt = critical;
        self.state.clock.dt = match self.state.settings.time_step {
            TimeStep::Auto { safety } => {
                if !critical.is_finite() {
                    return Err(SimulationError::NoTimeStep);
                }
                safety * critical
            }
            TimeStep::Fixed(dt) => {
                // once: the check is redone periodically and would repeat itself
                if dt > critical && !self.fixed_dt_warned() {
                    self.state.warnings.push(format!(
                        "{FIXED_DT_WARNING} {dt:.3e} s is above the critical step {critical:.3e} s \
                         (at step {steps}): the run may explode; use dt = auto or a step below \
                         {critical:.3e} s",
                        steps = self.state.clock.steps
                    ));
                }
                dt
            }
        };
        Ok(())
    }

    /// Whether the warning that the fixed time step is above the critical step was given.
    fn fixed_dt_warned(&self) -> bool {
        self.state.warnings.iter().any(|w| w.starts_with(FIXED_DT_WARNING))
    }

    /// Advances the simulation by one step: a list of named stages (model.md §4–6).
    ///
    /// The contacts and links advance their shear springs by the motion of the step just done
    /// (velocities of t − dt₀/2 over dt₀, the previous step); the leapfrog then kicks the
    /// velocities over (dt₀ + dt)/2 and moves the positions by dt (see `leapfrog_step`).
    pub fn step(&mut self) -> Result<(), SimulationError> {
        let dt = self.state.clock.dt;
        let previous =
            if self.state.clock.previous_dt > 0.0 { self.state.clock.previous_dt } else { dt };
        self.pipeline.timers.begin();
        self.pipeline.set_homes();
        self.collision_stage();
        let appeared = self.contact_stage(previous);
        let link_sums = self.link_stage(previous);
        let load_work = self.external_load_stage(previous);
        let walls = self.wall_stage(dt);
        let (work, flagged) = self.integration_stage(previous, dt, walls);
        self.state.clock.previous_dt = dt;
        self.state.clock.time += dt;
        self.state.clock.steps += 1;
        let result = self.bookkeeping_stage(&work, load_work, &link_sums, dt, appeared, flagged);
        self.pipeline.timers.end();
        result
    }

    /// Bookkeeping after the step: the checks (NaN, a particle jumping: sought when the
    /// leapfrog `flagged` a particle), the energy terms, the energy watch and the time step.
    fn bookkeeping_stage(
        &mut self,
        work: &StepWork,
        load_work: Real,
        link_sums: &LinkUpdate,
        dt: Real,
        appeared: bool,
        flagged: bool,
    ) -> Result<(), SimulationError> {
        let result = self.check_finite(flagged).and_then(|()| {
            self.account_energy(work, load_work, link_sums, dt);
            self.watch_energy()?;
            self.time_step_stage(appeared)
        });
        self.pipeline.timers.lap(Stage::Bookkeeping);
        result
    }

    /// Collision: rebuilds the candidate pairs when a particle has moved beyond its margin.
    fn collision_stage(&mut self) {
        let beyond = self.pipeline.moved_beyond.take();
        if self.pipeline.collider.needs_rebuild_after(&self.state.model, beyond) {
            let collider = &mut self.pipeline.collider;
            collider.rebuild_with(&self.state.model, self.pipeline.contacts.hull_buffer());
            // the sphere pairs' array becomes the neighbour list's keys (one array, not two)
            let spheres = std::mem::take(&mut collider.sphere_pairs);
            self.state.contacts.pairs.rebuild(spheres, &collider.sphere_wall_pairs);
        }
        self.pipeline.timers.lap(Stage::Collision);
    }

    /// Contacts: detection, births, the contact law, node loads (the forces and torques made
    /// anew: `ContactPipeline::apply`). Returns whether contacts appeared.
    fn contact_stage(&mut self, dt: Real) -> bool {
        let before = self.state.contacts.len();
        let births = self.pipeline.contacts.detect(
            &mut self.state.contacts,
            &self.state.model,
            &self.pipeline.adjacency,
            &self.pipeline.collider,
            dt,
            &self.pipeline.homes,
        );
        // a birth's energy is a jump at time t, where the elastic terms of this step are
        self.state.energy.terms.contact_births += births.born_energy;
        self.state.energy.terms.contact_releases += births.released;
        self.state.contacts.born_deep += births.born_deep;
        self.state.energy.terms.contact_births += release_offsets(
            &mut self.state.contacts.list,
            &self.pipeline.contacts.fresh,
            &self.state.model,
            self.state.settings.link_mode,
            dt,
        );
        let pairs = self.pipeline.contacts.apply(
            &mut self.state.contacts,
            &self.state.model,
            dt,
            &mut self.pipeline.force,
            &mut self.pipeline.torque,
            &self.pipeline.homes,
        );
        self.state.energy.terms.contact_births += pairs.born_energy;
        self.state.energy.terms.contact_releases += pairs.released;
        self.state.contacts.born_deep += pairs.born_deep;
        let late = births.late_energy + pairs.late_energy;
        self.state.energy.watch.note_late_births(late);
        let appeared = self.state.contacts.len() > before;
        self.account_new_contacts();
        self.pipeline.timers.lap(Stage::Contacts);
        appeared
    }

    /// Links: every beam link, loads summed per node.
    fn link_stage(&mut self, dt: Real) -> LinkUpdate {
        let (p, homes) = (&self.state.model.particles, &self.pipeline.homes);
        let sums = self.state.links.update_in_homes(p, dt, homes);
        let (force, torque) = (&mut self.pipeline.force, &mut self.pipeline.torque);
        self.state.links.add_loads_in_homes(force, torque, &self.pipeline.homes);
        self.pipeline.timers.lap(Stage::Links);
        sums
    }

    /// Imposed loads, pressures on PFacets (`pressure.rs`) and the user's hook, kept apart in
    /// `external_force` and `external_torque` for their work (the load work), and added to
    /// the totals (nothing to sum over every particle without them). Returns the half of
    /// their work over the step before (`previous` long), with the velocities of t − dt₀/2
    /// (see `StepWork::boundary` for the halves).
    fn external_load_stage(&mut self, previous: Real) -> Real {
        if !self.is_loaded() {
            return 0.0;
        }
        // zeroed, and sized here: a scene without loads holds no memory for them
        let n = self.state.model.particles.len();
        for sums in [&mut self.pipeline.external_force, &mut self.pipeline.external_torque] {
            sums.clear();
            sums.resize(n, Vec3::zeros());
        }
        for load in &self.state.loads {
            let s = load.ramp.factor(self.state.clock.time);
            for &i in &load.particles {
                self.pipeline.external_force[i as usize] += load.force * s;
                self.pipeline.external_torque[i as usize] += load.torque * s;
            }
        }
        for pressure in &self.state.pressures {
            let (model, t) = (&self.state.model, self.state.clock.time);
            add_pressure_forces(pressure, model, t, &mut self.pipeline.external_force);
        }
        if let Some(hook) = self.pipeline.force_hook.as_mut() {
            hook(
                self.state.clock.time,
                &self.state.model.particles,
                &mut self.pipeline.external_force,
                &mut self.pipeline.external_torque,
            );
        }
        for (f, e) in self.pipeline.force.iter_mut().zip(&self.pipeline.external_force) {
            *f += e;
        }
        for (t, e) in self.pipeline.torque.iter_mut().zip(&self.pipeline.external_torque) {
            *t += e;
        }
        let work = self.external_power() * 0.5 * previous;
        self.pipeline.timers.lap(Stage::Loads);
        work
    }

    /// Whether loads, pressures or a force hook act.
    fn is_loaded(&self) -> bool {
        !self.state.loads.is_empty()
            || !self.state.pressures.is_empty()
            || self.pipeline.force_hook.is_some()
    }

    /// Walls: the force and the contact stiffness of the bodies on each wall at t (summed
    /// here when a servo acts, else when [`Simulation::wall_forces`] asks), then the servo of
    /// each stress-controlled wall sets its normal velocity for the step from t to t + dt
    /// (see `servo.rs`). Returns the power of the walls at t with the velocities they moved
    /// with over the step before, and with the velocities they move with over the step
    /// after: the two halves of their trapezoidal work (timed with the integration, which
    /// moves the walls).
    fn wall_stage(&mut self, dt: Real) -> WallPower {
        self.pipeline.walls.forget();
        let before = self.wall_power();
        let time = self.state.clock.time;
        let controls = &self.state.wall_controls;
        // the loads are summed for a servo, else when asked for (`Simulation::wall_forces`)
        let steered = if any_servo_at(controls, time) {
            let walls = self.state.model.walls.len();
            let last = self.state.contacts.pairs.last_update(&self.pipeline.contacts.pairs);
            let loads = self.pipeline.walls.sum_now(&self.state.contacts, &last, walls);
            steer_walls(&mut self.state.model, controls, loads, time, dt)
        } else {
            steer_walls(&mut self.state.model, controls, &WallLoads::default(), time, dt)
        };
        let after = if steered { self.wall_power() } else { before };
        self.pipeline.timers.lap(Stage::Integration);
        WallPower { before, after }
    }

    /// Integration: the leapfrog with damping (velocities kicked over (dt₀ + dt)/2, positions
    /// moved over `dt`), then the walls move with their velocities. The walls' work at t is
    /// trapezoidal, as the other works: `walls.before·dt₀/2` over the step before (with the
    /// velocities the walls moved with then) and `walls.after·dt/2` over the step after (with
    /// the velocities they move with now, which a servo may have just changed). Also says
    /// whether a particle may have gone wrong (`check_finite` then seeks it).
    fn integration_stage(
        &mut self,
        previous: Real,
        dt: Real,
        walls: WallPower,
    ) -> (StepWork, bool) {
        let g = self.state.settings.gravity;
        let step = Leapfrog { gravity: g, damping: self.state.settings.damping, previous, dt };
        let pipeline = &mut self.pipeline;
        // (the collision stage sized the reaches to the particles)
        debug_assert_eq!(pipeline.collider.reach.len(), self.state.model.particles.len());
        // the leapfrog also watches the moves for the collider (its pass at the next step)
        let verlet = pipeline.collider.verlet_watch(self.state.model.particles.len());
        let watched = verlet.is_some();
        let (reach, flags) = (Some(&pipeline.collider.reach[..]), &mut pipeline.step_flags);
        let chunk_reach = &pipeline.collider.chunk_reach[..];
        let checks = &mut Checks { reach, chunk_reach, verlet, flags };
        // the threads step the particles as they stepped their pairs, else as the other loops
        let parts = pipeline.contacts.pair_parts.homes();
        let homes = if parts.len() > 2 {
            pipeline.part_homes.set_by_parts(parts);
            &pipeline.part_homes
        } else {
            &pipeline.homes
        };
        let (mut work, found) = leapfrog_step_checked(
            &mut self.state.model.particles,
            &pipeline.force,
            &pipeline.torque,
            &step,
            &mut pipeline.step_work,
            checks,
            homes,
        );
        pipeline.moved_beyond = watched.then_some(found.beyond);
        if watched {
            pipeline.collider.set_drift(pipeline.step_flags.iter().map(|c| c.drift));
        }
        work.boundary += 0.5 * walls.before * previous;
        work.boundary_next += 0.5 * walls.after * dt;
        // the dashpots' forces at t over the two halves of the kick (model.md §7): the second
        // with the velocities just kicked and the walls' new velocities
        (work.contact_damping, work.contact_damping_next) = self
            .pipeline
            .contacts
            .dashpot_dissipation(&self.state.contacts, &self.state.model, previous, dt);
        for wall in &mut self.state.model.walls {
            wall.point += wall.velocity * dt;
        }
        self.pipeline.timers.lap(Stage::Integration);
        (work, found.flagged)
    }

    /// Power of the moving walls at time t: `Σ F·v_wall` over wall contacts, `F` the force
    /// the wall puts on the body.
    fn wall_power(&self) -> Real {
        let walls = &self.state.model.walls;
        if walls.iter().all(|w| w.velocity == Vec3::zeros()) {
            return 0.0;
        }
        let mut power = 0.0;
        let last = self.state.contacts.pairs.last_update(&self.pipeline.contacts.pairs);
        self.state.contacts.for_each_on_wall(&last, |w, force_on_2, _, _| {
            power += force_on_2.dot(&walls[w as usize].velocity);
        });
        power
    }

    /// Time step: the critical step is re-estimated every `time_step_interval` steps (for a
    /// fixed dt too, to warn when contacts or large deformations have brought it below that
    /// dt) and, with an automatic step, soon after contacts appear.
    ///
    /// With an automatic step, a re-estimate lowers dt at once but raises it by at most
    /// [`DT_GROWTH`] (model.md §3): between estimates new contacts only ever lower dt, and the
    /// next estimate, which sees the ended ones too, could raise it twofold in one step.
    ///
    /// With a fixed dt the estimate only serves the warning: the new contacts' stiffness is
    /// added as they come (`account_new_contacts`), and the full estimate is redone early only
    /// when that sum, which still counts the contacts ended since the last estimate (an upper
    /// bound of the stiffness), puts the critical step below dt: the estimate then says
    /// whether it truly is. (Redone 10 steps after contacts appeared, it cost the LAMMPS
    /// twin, whose contacts appear at every step, a tenth of an estimate per step: 4 % of
    /// its instructions.)
    fn time_step_stage(&mut self, appeared: bool) -> Result<(), SimulationError> {
        let clock = &self.state.clock;
        let since = clock.steps - clock.dt_updated_at;
        let soon = match self.state.settings.time_step {
            TimeStep::Auto { .. } => appeared,
            TimeStep::Fixed(dt) => clock.critical_dt < dt && !self.fixed_dt_warned(),
        };
        if since >= self.state.settings.time_step_interval || (soon && since >= 10) {
            self.re_estimate_time_step()?;
        }
        Ok(())
    }

    /// [`Simulation::update_time_step`] in a run: an automatic step raised by at most
    /// [`DT_GROWTH`] (the leapfrog's kinetic energy has a term `O(F·v·(dt − dt₀))`).
    pub(crate) fn re_estimate_time_step(&mut self) -> Result<(), SimulationError> {
        let before = self.state.clock.dt;
        self.update_time_step()?;
        if matches!(self.state.settings.time_step, TimeStep::Auto { .. }) {
            let clock = &mut self.state.clock;
            clock.dt = clock.dt.min(before * DT_GROWTH);
        }
        Ok(())
    }

    /// Adds the stiffness of the contacts made at this step to the particles they touch and
    /// lowers the critical step if one of those particles now needs it; with an automatic
    /// step, dt too, at once (a contact stiffer than the links must not run for even a few
    /// steps above its critical step); with a fixed one, `time_step_stage` then redoes the
    /// estimate to see whether to warn. O(new contacts); the full estimate is redone every
    /// `time_step_interval` steps.
    fn account_new_contacts(&mut self) {
        let fresh = &self.pipeline.contacts;
        if (fresh.fresh.is_empty() && fresh.pairs.fresh.is_empty())
            || self.state.clock.stiffness.translational.len() != self.state.model.particles.len()
        {
            return;
        }
        let (general, pairs) = (&fresh.fresh, &fresh.pairs.fresh);
        let k = &mut self.state.clock.stiffness;
        let shares = fresh.pairs.fresh_shares();
        let contacts = &self.state.contacts;
        let lowest = add_fresh(k, contacts, general, pairs, shares, &self.state.model);
        if lowest < self.state.clock.critical_dt {
            self.state.clock.critical_dt = lowest;
            if let TimeStep::Auto { safety } = self.state.settings.time_step {
                self.state.clock.dt = self.state.clock.dt.min(safety * lowest);
            }
        }
    }

    /// Energy at time t (the start of the step just done): kinetic from the half-step
    /// velocities around t, elastic from the forces computed at t, works up to t (the forces
    /// at t count half over the step before t; the other half is pending, see
    /// `StepWork::boundary`). `load_work` is the loads' half over the step before.
    fn account_energy(&mut self, work: &StepWork, load_work: Real, links: &LinkUpdate, dt: Real) {
        let load_next = if self.is_loaded() { self.external_power() * 0.5 * dt } else { 0.0 };
        let e = &mut self.state.energy.terms;
        e.kinetic_translation = work.kinetic_translation;
        e.kinetic_rotation = work.kinetic_rotation;
        e.elastic_links = links.elastic_energy;
        let contacts = &self.state.contacts;
        (e.elastic_contacts, e.friction) =
            contacts.energy_sums_from(&self.pipeline.contacts.energies);
        debug_assert!({
            let (elastic, friction) = contacts.energy_sums();
            elastic.to_bits() == e.elastic_contacts.to_bits()
                && friction.to_bits() == e.friction.to_bits()
        });
        e.links_dissipated += links.dissipated;
        e.gravity_work += self.state.energy.pending.gravity;
        e.load_work += self.state.energy.pending.load + load_work;
        e.boundary_work += self.state.energy.pending.boundary + work.boundary;
        e.damping += self.state.energy.pending.damping + work.damping;
        e.contact_damping += self.state.energy.pending.contact_damping + work.contact_damping;
        self.state.energy.pending = PendingWork {
            gravity: work.gravity,
            load: load_next,
            boundary: work.boundary_next,
            damping: work.damping_next,
            contact_damping: work.contact_damping_next,
        };
        let watch = &mut self.state.energy.watch;
        if self.state.clock.steps == 1 {
            // the reference of the watch is the balance after the first step: the first kick's
            // damping and the lag of the first step's works make an O(dt²) offset at the start
            // that is large next to the energy of a run that starts from rest
            watch.initial_balance = e.balance();
            watch.lowest_balance = e.balance();
            // (the overlaps of the first step are the start state, not contacts found late)
            watch.late_births = 0.0;
        }
        watch.note(e);
    }

    /// Power of the imposed loads, the pressures and the hook, `Σ (F·v + τ·ω)` with the
    /// current velocities, on every DOF (on a blocked one the support's reaction, counted in
    /// the boundary work, takes the rest of the node's force).
    fn external_power(&self) -> Real {
        let p = &self.state.model.particles;
        let forces: Real =
            self.pipeline.external_force.iter().zip(&p.vel).map(|(f, v)| f.dot(v)).sum();
        let torques: Real =
            self.pipeline.external_torque.iter().zip(&p.ang_vel).map(|(t, w)| t.dot(w)).sum();
        forces + torques
    }

    /// Stops the run when the energy balance rises by more than `settings.energy_tolerance`
    /// (relative to the energy scale) above its reference (energy created; `B(0)`, or below
    /// it once energy was lost beyond the limit: [`EnergyWatch::reference`]), naming the
    /// step, the time and where the energy is. An energy term that is NaN or infinite stops
    /// the run whether the watch is on or not (a NaN error compares false with any limit: it
    /// must not pass for a closed balance, nor be written as output). Energy lost beyond the
    /// limit since the start (dissipation the balance does not count) raises a warning, once.
    fn watch_energy(&mut self) -> Result<(), SimulationError> {
        if let Some((term, value)) = self.state.energy.terms.first_non_finite() {
            return Err(SimulationError::NonFiniteEnergy {
                term,
                value,
                step: self.state.clock.steps,
                time: self.state.clock.time,
                culprit: describe(&self.state, &self.pipeline.contacts.pairs),
            });
        }
        let Some(limit) = self.state.settings.energy_tolerance else { return Ok(()) };
        let (watch, terms) = (&self.state.energy.watch, &self.state.energy.terms);
        let (error, created) = (watch.relative_error(terms), watch.relative_created(terms, limit));
        if error >= -limit && created <= limit && watch.relative_late_births() <= limit {
            return Ok(());
        }
        // an energy scale below the round-off of the motions a step resolves is noise (spheres
        // that touch exactly hold contacts of 1e-12 N and 1e-28 J): measured against that
        // floor instead, such a run goes on
        let floor = round_off_energy(&self.state.model.particles, self.state.clock.dt);
        let scale = watch.scale.max(floor);
        let change = terms.balance() - watch.initial_balance;
        let reference = watch.reference(limit, scale);
        let risen = terms.balance() - reference;
        let (error, created) = (change / scale, risen / scale);
        let late = watch.late_births / scale;
        if error >= -limit && created <= limit && late <= limit {
            return Ok(());
        }
        if created <= limit && late > limit {
            return Err(SimulationError::LateContacts {
                step: self.state.clock.steps,
                time: self.state.clock.time,
                energy: watch.late_births,
                limit,
                scale,
                contacts: self.state.contacts.born_deep,
                culprit: describe(&self.state, &self.pipeline.contacts.pairs),
            });
        }
        if created <= limit {
            if !self.state.warnings.iter().any(|w| w.starts_with(ENERGY_LOST_WARNING)) {
                self.state.warnings.push(format!(
                    "{ENERGY_LOST_WARNING} {change:+.4e} J ({error:+.3e} of the energy scale \
                     {scale:.4e} J) by step {step} (t = {time:.6e} s) that the balance does not \
                     count: {culprit}",
                    step = self.state.clock.steps,
                    time = self.state.clock.time,
                    culprit = describe(&self.state, &self.pipeline.contacts.pairs)
                ));
            }
            return Ok(());
        }
        Err(SimulationError::EnergyBalance {
            step: self.state.clock.steps,
            time: self.state.clock.time,
            error: created,
            after_loss: reference < watch.initial_balance,
            limit,
            change: risen,
            scale,
            culprit: describe(&self.state, &self.pipeline.contacts.pairs),
        })
    }

    /// Stops on NaN or infinity, and on a particle that moved by more than its reach in one
    /// step (the sign of an unstable run, long before NaN appears), naming the particle. The
    /// reach is the particle's radius, or for a node the size of the smallest element holding
    /// it when that is larger: a thin cable or membrane (radius of microns, elements of
    /// centimetres) legitimately moves by more than its radius per step.
    fn check_finite(&self, flagged: bool) -> Result<(), SimulationError> {
        let p = &self.state.model.particles;
        let dt = self.state.clock.dt;
        let reach = &self.pipeline.collider.reach;
        // the leapfrog's cheap test (`integrator::flags_step`, no root, no division) flagged
        // a step with a non-finite value or a particle beyond its reach; only then are the
        // culprits sought
        if !flagged {
            return Ok(());
        }
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
                step: self.state.clock.steps,
                time: self.state.clock.time,
                dt: self.state.clock.dt,
                critical_dt: self.state.clock.critical_dt,
            }),
            None => match jump {
                Some((_, i)) => Err(SimulationError::Exploding {
                    particle: i as u32,
                    displacement: p.vel[i].norm() * dt,
                    reach: self.pipeline.collider.reach[i],
                    step: self.state.clock.steps,
                    time: self.state.clock.time,
                    dt,
                    critical_dt: self.state.clock.critical_dt,
                }),
                None => Ok(()),
            },
        }
    }
}

/// The power of the walls at t, `Σ F·v_wall` over wall contacts (W), with two velocities.
#[derive(Clone, Copy, Debug, PartialEq)]
struct WallPower {
    /// With the velocities the walls moved with over the step before t.
    before: Real,
    /// With the velocities they move with over the step after t.
    after: Real,
}

/// The energy below which a balance error is round-off: `ROUND_OFF_SPEED² · Σ m r²/dt²`, the
/// kinetic energy of every particle moving by `ROUND_OFF_SPEED` (1e-8) of its radius per step
/// (J). It matters only when nothing else moves: any motion a run means to show is larger.
fn round_off_energy(p: &flexdem_elements::Particles, dt: Real) -> Real {
    const ROUND_OFF_SPEED: Real = 1e-8;
    let sum: Real = p.mass.iter().zip(&p.radius).map(|(m, r)| m * r * r).sum();
    ROUND_OFF_SPEED * ROUND_OFF_SPEED * sum / (dt * dt)
}

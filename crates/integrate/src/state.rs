//! The saved state of a simulation: everything it needs to continue exactly where it was, as
//! plain data. A checkpoint stores it as it is; the pipeline that steps it (collider,
//! adjacency, contact buffers, force sums, timers, the user's force hook) is rebuilt from it
//! by [`crate::Simulation::from_state`].

use crate::contact::Contact;
use crate::contact_list::Contacts;
use crate::energy::EnergyAccount;
use crate::links::Links;
use crate::pressure::{check_pressure, Pressure};
use crate::servo::{check_controls, WallControl};
use crate::settings::{Load, Ramp, Settings};
use crate::time_step::StiffnessSums;
use crate::SimulationError;
use flexdem_elements::{Dofs, Model};
use flexdem_geom::Real;

/// The clock and the time-step bookkeeping of a simulation.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Clock {
    /// Simulated time (s).
    pub time: Real,
    /// Steps done.
    pub steps: u64,
    /// Time step in use (s).
    pub dt: Real,
    /// The step taken before (s; 0 before the first step).
    pub previous_dt: Real,
    /// Critical step at the last estimate (s).
    pub critical_dt: Real,
    /// Step of the last full time-step estimate.
    pub dt_updated_at: u64,
    /// Per-particle stiffness sums of that estimate, with the contacts made since.
    pub stiffness: StiffnessSums,
}

/// Everything a simulation needs to continue exactly where it was: the model, settings,
/// links and contacts with their history, loads, wall controls, clock, time-step
/// bookkeeping, energy terms and warnings. A simulation rebuilt from it with [`crate::Simulation::from_state`]
/// continues bit-identically to the original (the user's force hook is not part of it).
/// This is what a checkpoint stores.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Bodies, structures, materials.
    pub model: Model,
    /// Settings.
    pub settings: Settings,
    /// Beam links with their state, one per connection.
    pub links: Links,
    /// Contacts with their history, sorted by key.
    pub contacts: Contacts,
    /// Imposed loads.
    pub loads: Vec<Load>,
    /// Pressures on PFacets (follower loads).
    pub pressures: Vec<Pressure>,
    /// How each wall moves, one per wall of the model (the servo of a stress-controlled wall
    /// sets its velocity each step; the velocity itself is the wall's, in the model).
    pub wall_controls: Vec<WallControl>,
    /// Time, steps, time step.
    pub clock: Clock,
    /// Energy terms, pending works, energy watch.
    pub energy: EnergyAccount,
    /// Warnings raised so far.
    pub warnings: Vec<String>,
}

impl State {
    /// The state of a simulation of `model` with `settings` before its first step: one beam
    /// link per connection at rest, no contact, no load, every wall with the velocity it has,
    /// no time step chosen yet (`dt` 0).
    pub(crate) fn initial(model: Model, settings: Settings) -> Self {
        let links = Links::from_model(&model, settings.link_mode);
        let wall_controls = vec![WallControl::Velocity; model.walls.len()];
        State {
            model,
            settings,
            links,
            contacts: Contacts::default(),
            loads: Vec::new(),
            pressures: Vec::new(),
            wall_controls,
            clock: Clock::default(),
            energy: EnergyAccount::default(),
            warnings: Vec::new(),
        }
    }

    /// Checks the settings, the model and its masses (what [`crate::Simulation::new`] checks).
    pub(crate) fn check_parts(model: &Model, settings: &Settings) -> Result<(), SimulationError> {
        settings.validate()?;
        model.validate()?;
        check_masses(model)
    }

    /// Checks the whole state as [`crate::Simulation::new`] checks a new one, and for
    /// consistency between its parts (a state read from a file may be damaged): links,
    /// stiffness sums, loads, pressures and contacts that fit the model, one valid control
    /// per wall, a positive finite time step.
    pub(crate) fn check(&self) -> Result<(), SimulationError> {
        State::check_parts(&self.model, &self.settings)?;
        check_pressures(&self.pressures, &self.model)?;
        check_controls(&self.wall_controls, self.model.walls.len())?;
        if !self.is_consistent() {
            return Err(SimulationError::Setting {
                what: "simulation state".into(),
                value: "inconsistent parts (links, contacts or loads do not match the model, \
                        or the energy watch holds unusable numbers)"
                    .into(),
                expected: "a state written by Simulation::state".into(),
            });
        }
        Ok(())
    }

    /// Whether the parts fit the model and the clock holds usable numbers.
    fn is_consistent(&self) -> bool {
        let n = self.model.particles.len();
        let n_links = self.model.connections.len();
        let (links, k, c) = (&self.links, &self.clock.stiffness, &self.clock);
        links.len() == n_links
            && links.spring.len() == n_links
            && links.class.len() == n_links
            && links.state.len() == n_links
            && links.check_against(&self.model)
            && k.translational.len() == k.rotational.len()
            && (k.translational.is_empty() || k.translational.len() == n)
            && self.loads.iter().all(|l| l.particles.iter().all(|&i| (i as usize) < n))
            && self.contacts.list.iter().all(|c| contact_nodes_exist(c, n))
            && self.contacts.pairs.fits(n, self.model.walls.len())
            && c.dt > 0.0
            && c.dt.is_finite()
            && self.energy.watch.is_consistent()
            && c.previous_dt >= 0.0
            && c.previous_dt.is_finite()
            && c.time.is_finite()
    }
}

/// Checks each pressure against `model` (PFacet ids in range, finite values).
pub(crate) fn check_pressures(
    pressures: &[Pressure],
    model: &Model,
) -> Result<(), SimulationError> {
    pressures.iter().try_for_each(|p| check_pressure(p, model.pfacets.len()))
}

/// Whether the nodes of both sites of `c` are among the `n` particles.
fn contact_nodes_exist(c: &Contact, n: usize) -> bool {
    [&c.site1, &c.site2]
        .iter()
        .all(|site| site.nodes[..site.node_count()].iter().all(|&i| (i as usize) < n))
}

/// Checks a load against a model of `n` particles: particle ids in range, a finite ramp of
/// non-negative duration, finite force and torque.
pub(crate) fn check_load(load: &Load, n: usize) -> Result<(), SimulationError> {
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
    Ok(())
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

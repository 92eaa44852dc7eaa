//! The scene of `validation/yade/sphere_on_net/sphere_on_net.py` in flexdem: one run from a
//! start, until at rest or for a number of steps, and what its contacts hold at the end.

use crate::rest::max_speed;
use crate::ValidationError;
use flexdem_contact::{LinkKinematicsMode, Material};
use flexdem_elements::builders::{net, GridLayout, StructureOptions};
use flexdem_elements::{Dofs, Model};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use std::f64::consts::PI;

/// Net of the YADE scene: cells, spacing (m), link radius (m).
pub(super) const NET_CELLS: usize = 6;
pub(super) const NET_SPACING: Real = 0.1;
pub(super) const NET_RADIUS: Real = 0.005;
/// Sphere radius (m) and mass (kg).
pub(super) const SPHERE_RADIUS: Real = 0.1;
pub(super) const SPHERE_MASS: Real = 1.0;
/// The ensemble's starts: the sphere `k·ENSEMBLE_SHIFT` higher for `k` in `ENSEMBLE_KS`, as
/// in `sphere_on_net_ensemble.py` (`k = 0` is the reference run).
pub(super) const ENSEMBLE_SHIFT: Real = 1e-10;
pub(super) const ENSEMBLE_KS: std::ops::RangeInclusive<i32> = -7..=8;

/// One run of the scene until at rest, with its heights every 1000 steps.
pub(super) struct NetRun {
    pub(super) sim: Simulation,
    pub(super) sphere: usize,
    pub(super) centre: usize,
    pub(super) grid: GridLayout,
    /// The sphere's starting height (m).
    pub(super) z0: Real,
    pub(super) steps: u64,
    /// (time, sphere height), (time, contacts), (time, centre node height), every 1000 steps.
    pub(super) history: Vec<(Real, Real)>,
    pub(super) contact_history: Vec<(Real, Real)>,
    pub(super) centre_history: Vec<(Real, Real)>,
}

/// The scene of `sphere_on_net.py` with the sphere `shift` higher, run with step `dt` until
/// every speed stays below 1e-9 m/s at 10 outputs 1000 steps apart, or `max_steps`.
pub(super) fn run_net(dt: Real, max_steps: u64, shift: Real) -> Result<NetRun, ValidationError> {
    let phi = 30f64.to_radians();
    let mut model = Model::new();
    let net_mat = model.add_material(Material::new(1e8, 0.3, 1000.0, phi)?)?;
    let size = NET_SPACING * NET_CELLS as Real;
    let opts = StructureOptions::new("net", NET_RADIUS, net_mat);
    let s = net(
        &mut model,
        Vec3::zeros(),
        Vec3::x(),
        Vec3::y(),
        size,
        size,
        NET_CELLS,
        NET_CELLS,
        false,
        &opts,
    )?;
    let grid = GridLayout::of(&model, s, NET_CELLS, NET_CELLS)?;
    model.block(grid.corners(), Dofs::TRANSLATION)?;
    let sphere_density = SPHERE_MASS / (4.0 / 3.0 * PI * SPHERE_RADIUS.powi(3));
    let sphere_mat = model.add_material(Material::new(1e8, 0.3, sphere_density, phi)?)?;
    let half = NET_CELLS / 2;
    let centre_xy = NET_SPACING * half as Real;
    let z0 = SPHERE_RADIUS + NET_RADIUS + shift;
    let sphere =
        model.add_sphere(Vec3::new(centre_xy, centre_xy, z0), SPHERE_RADIUS, sphere_mat)? as usize;
    let centre = grid.node(half, half) as usize;
    let settings = Settings {
        time_step: TimeStep::Fixed(dt),
        gravity: Vec3::new(0.0, 0.0, -10.0),
        damping: 0.3,
        link_mode: LinkKinematicsMode::Yade,
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings)?;
    let at = |sim: &Simulation, i: usize| sim.model().particles.pos[i].z;
    let mut history = vec![(0.0, at(&sim, sphere))];
    let mut contact_history = vec![(0.0, sim.contacts().len() as Real)];
    let mut centre_history = vec![(0.0, at(&sim, centre))];
    let (mut steps, mut quiet_chunks) = (0, 0);
    while steps < max_steps && quiet_chunks < 10 {
        sim.run(1000)?;
        steps += 1000;
        history.push((sim.time(), at(&sim, sphere)));
        contact_history.push((sim.time(), sim.contacts().len() as Real));
        centre_history.push((sim.time(), at(&sim, centre)));
        quiet_chunks = if max_speed(&sim) <= 1e-9 { quiet_chunks + 1 } else { 0 };
    }
    Ok(NetRun { sim, sphere, centre, grid, z0, steps, history, contact_history, centre_history })
}

/// What the contacts carrying load hold at rest, and the run's lowest sphere height.
#[derive(Clone, Copy, Debug)]
pub(super) struct RestForces {
    /// Mean normal force (N).
    pub(super) normal: Real,
    /// Mean shear force (N).
    pub(super) shear: Real,
    /// Contacts carrying load.
    pub(super) count: usize,
    /// The sphere's lowest height at the outputs every 1000 steps (m).
    pub(super) lowest: Real,
}

pub(super) fn rest_forces(run: &NetRun) -> RestForces {
    let touching: Vec<_> =
        run.sim.contacts().into_iter().filter(|c| c.forces.normal_force > 0.0).collect();
    let n = touching.len().max(1) as Real;
    RestForces {
        normal: touching.iter().map(|c| c.forces.normal_force).sum::<Real>() / n,
        shear: touching.iter().map(|c| c.forces.shear_force.norm()).sum::<Real>() / n,
        count: touching.len(),
        lowest: run.history.iter().map(|h| h.1).fold(Real::INFINITY, Real::min),
    }
}

/// Mean, smallest and largest of `x`.
pub(super) fn spread(x: &[Real]) -> (Real, Real, Real) {
    let mean = x.iter().sum::<Real>() / x.len().max(1) as Real;
    (
        mean,
        x.iter().copied().fold(Real::INFINITY, Real::min),
        x.iter().copied().fold(Real::NEG_INFINITY, Real::max),
    )
}

//! Walls that hold a stress (model.md §5): the force the bodies put on each wall, and the
//! servo that sets the normal velocity of a stress-controlled wall from it each step (YADE's
//! `TriaxialStressController`, PFC's servo-controlled walls).
//!
//! Signs: a wall's normal `n` points to the side where the bodies live. `F` is the force the
//! bodies put on the wall, `−Σ F_wall→body` over its contacts; in compression it points
//! against `n`, so the normal force `F_n = −F·n` is ≥ 0. The servo moves the wall along `n`
//! (into the bodies) when `F_n` is below the target and away from them when it is above:
//!
//! `v·n = clamp(G·(σ_target·A − F_n), −v_max, v_max)`
//!
//! with the gain `G` (m/s per N) given, or by default `G = α/(K·dt)`: `K = Σ kn` over the
//! wall's contacts that carry a force, `dt` the step, `α` = [`SERVO_RELAXATION`]. With it the
//! wall moves in one step by `α·(F_target − F_n)/K`, the displacement that would close the
//! fraction `α` of the force error if the bodies behind the contacts did not move: a first
//! order loop `e ← (1 − α)·e`, stable for `0 < α < 2` and without overshoot for `α ≤ 1`. The
//! bodies behind the contacts yield, so the wall sees a softer spring than `K` and the loop
//! converges more slowly, never faster. A fixed gain much above `1/(K·dt)` makes the wall
//! overshoot by more than the error each step: it rattles or blows up; a small one makes the
//! wall slow to reach its target (the time constant is about `1/(G·K_sample)`, `K_sample`
//! the stiffness of the whole sample between the walls). Without any loaded contact (`K = 0`),
//! the automatic gain moves the wall at `v_max` towards its target: `v_max` is also the speed
//! of approach, choose it so that the wall moves by a small fraction of the particles' radius
//! per step.

use crate::contact_list::Contacts;
use crate::measures::{membrane_sample_volume, normal_force, wall_gap};
use crate::pair_passes::LastUpdate;
use crate::SimulationError;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// The relaxation factor `α` of the automatic gain `G = α/(K·dt)`: the fraction of the force
/// error a stress-controlled wall closes in one step (see the module documentation).
pub const SERVO_RELAXATION: Real = 0.5;

/// How a wall moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum WallControl {
    /// With the velocity it has ([`Wall::velocity`], from the scene or
    /// `Simulation::set_wall_velocity`): strain control.
    #[default]
    Velocity,
    /// With the normal velocity a servo sets each step to hold a normal stress; the
    /// tangential part of the wall's velocity is kept.
    Stress(StressControl),
    /// A servo until time `until`, then the constant velocity `then`: the platen of a
    /// triaxial test that holds the consolidation stress, then compresses the sample at a
    /// constant rate. The switch is a velocity change like any other: the wall's work books
    /// the force at the switch with the velocity it moved with on each side.
    StressUntil {
        /// The servo of the first stage.
        servo: StressControl,
        /// Time of the switch (s).
        until: Real,
        /// Velocity from `until` on (m/s).
        then: Vec3,
    },
}

impl WallControl {
    /// Checks every value, naming the bad one (see [`StressControl::validate`]; the switch
    /// time and the later velocity must be finite).
    pub fn validate(&self) -> Result<(), SimulationError> {
        match self {
            WallControl::Velocity => Ok(()),
            WallControl::Stress(s) => s.validate(),
            WallControl::StressUntil { servo, until, then } => {
                servo.validate()?;
                if !until.is_finite() {
                    return Err(SimulationError::Setting {
                        what: "servo until".into(),
                        value: until.to_string(),
                        expected: "a finite time (s)".into(),
                    });
                }
                if !then.iter().all(|v| v.is_finite()) {
                    return Err(SimulationError::Setting {
                        what: "wall velocity after the servo".into(),
                        value: format!("{then:?}"),
                        expected: "a finite velocity (m/s)".into(),
                    });
                }
                Ok(())
            }
        }
    }

    /// The servo acting at time `t`, if any.
    pub fn servo_at(&self, t: Real) -> Option<&StressControl> {
        match self {
            WallControl::Velocity => None,
            WallControl::Stress(s) => Some(s),
            WallControl::StressUntil { servo, until, .. } => (t < *until).then_some(servo),
        }
    }

    /// The servo of this control, whether or not it acts now.
    pub fn servo(&self) -> Option<&StressControl> {
        match self {
            WallControl::Velocity => None,
            WallControl::Stress(servo) | WallControl::StressUntil { servo, .. } => Some(servo),
        }
    }
}

/// A servo holding the normal stress on a wall (see the module documentation for the law).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StressControl {
    /// Target normal stress (Pa, compression positive, ≥ 0).
    pub target: Real,
    /// Area the stress is taken over (m², > 0): the target force is `target·area`.
    pub area: Real,
    /// Gain (m/s per N, > 0); `None`: the automatic gain `α/(K·dt)`.
    pub gain: Option<Real>,
    /// Largest normal speed of the wall (m/s, > 0).
    pub max_speed: Real,
    /// What the area follows as the sample deforms, measured each step (None: `area` is
    /// constant, the servo holds a force).
    pub section: Option<SampleSection>,
}

/// A sample's section that a stress-controlled wall's area follows, measured each step, so
/// that the servo holds a stress rather than a force.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum SampleSection {
    /// The mean cross-section `V/H` of a membrane sample: `V` the volume inside the PFacets
    /// of `structure` between the planes of the walls `platens`
    /// ([`crate::membrane_sample_volume`]), `H` the platens' distance (the area under a
    /// platen).
    Membrane {
        /// The membrane's structure.
        structure: u32,
        /// The two platens (walls), facing each other.
        platens: [u32; 2],
    },
    /// The rectangle whose sides are the distances between two pairs of facing walls (a
    /// platen between four lateral walls, or a lateral wall between the platens and the
    /// other two lateral walls).
    Rectangle {
        /// The first pair of walls.
        a: [u32; 2],
        /// The second pair of walls.
        b: [u32; 2],
    },
}

impl SampleSection {
    /// The section's area now (m²), or why it cannot be measured.
    pub fn area(&self, model: &flexdem_elements::Model) -> Result<Real, String> {
        match *self {
            SampleSection::Membrane { structure, platens } => {
                let height = wall_gap(model, platens[0], platens[1])?;
                Ok(membrane_sample_volume(model, structure, platens)? / height)
            }
            SampleSection::Rectangle { a, b } => {
                Ok(wall_gap(model, a[0], a[1])? * wall_gap(model, b[0], b[1])?)
            }
        }
    }
}

impl StressControl {
    /// The normal force the servo aims at, `target·area` (N).
    pub fn target_force(&self) -> Real {
        self.target * self.area
    }

    /// This servo with its area measured now in `model` when it follows a section (kept if
    /// the section cannot be measured or is not positive).
    pub fn with_current_area(&self, model: &flexdem_elements::Model) -> StressControl {
        match self.section.map(|s| s.area(model)) {
            Some(Ok(area)) if area > 0.0 && area.is_finite() => StressControl { area, ..*self },
            _ => *self,
        }
    }

    /// Checks every value, naming the bad one: a finite target ≥ 0, a finite area, gain and
    /// largest speed > 0.
    pub fn validate(&self) -> Result<(), SimulationError> {
        let bad = |what: &str, value: Real, expected: &str| {
            Err(SimulationError::Setting {
                what: what.into(),
                value: value.to_string(),
                expected: expected.into(),
            })
        };
        if !(self.target >= 0.0 && self.target.is_finite()) {
            return bad("servo target stress", self.target, "a finite stress >= 0 (Pa)");
        }
        if !(self.area > 0.0 && self.area.is_finite()) {
            return bad("servo area", self.area, "a finite area > 0 (m²)");
        }
        if let Some(g) = self.gain {
            if !(g > 0.0 && g.is_finite()) {
                return bad("servo gain", g, "a finite gain > 0 (m/s per N), or none (automatic)");
            }
        }
        if !(self.max_speed > 0.0 && self.max_speed.is_finite()) {
            return bad("servo max_speed", self.max_speed, "a finite speed > 0 (m/s)");
        }
        Ok(())
    }

    /// The wall's speed along its normal for the next step, `clamp(G·(F_target − F_n),
    /// −v_max, v_max)`, from the normal force `normal_force` (N) it receives, the stiffness
    /// `stiffness` (N/m) of its loaded contacts and the step `dt` (for the automatic gain).
    pub fn normal_speed(&self, normal_force: Real, stiffness: Real, dt: Real) -> Real {
        let error = self.target_force() - normal_force;
        let speed = match self.gain {
            Some(g) => g * error,
            None if stiffness > 0.0 && dt > 0.0 => SERVO_RELAXATION * error / (stiffness * dt),
            // no loaded contact: the automatic gain is infinite
            None if error == 0.0 => 0.0,
            None => self.max_speed.copysign(error),
        };
        speed.clamp(-self.max_speed, self.max_speed)
    }
}

/// Checks the controls against `walls` walls: one per wall, each valid.
pub(crate) fn check_controls(
    controls: &[WallControl],
    walls: usize,
) -> Result<(), SimulationError> {
    if controls.len() != walls {
        return Err(SimulationError::Setting {
            what: "wall controls".into(),
            value: format!("{} controls", controls.len()),
            expected: format!("one per wall ({walls})"),
        });
    }
    controls.iter().try_for_each(WallControl::validate)
}

/// What the bodies put on each wall at the last step.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct WallLoads {
    /// Force on each wall (N): `−Σ F_wall→body` over its contacts.
    pub(crate) force: Vec<Vec3>,
    /// Stiffness of each wall's contacts that carry a force, `Σ kn` (N/m).
    pub(crate) stiffness: Vec<Real>,
}

impl WallLoads {
    /// No force and no stiffness on each of `walls` walls.
    pub(crate) fn zeros(walls: usize) -> Self {
        WallLoads { force: vec![Vec3::zeros(); walls], stiffness: vec![0.0; walls] }
    }

    /// Sums the force and the stiffness of the contacts on each of `walls` walls (the free
    /// spheres' as their last update, `last`, applied them).
    pub(crate) fn sum(&mut self, contacts: &Contacts, last: &LastUpdate<'_>, walls: usize) {
        self.force.clear();
        self.force.resize(walls, Vec3::zeros());
        self.stiffness.clear();
        self.stiffness.resize(walls, 0.0);
        contacts.for_each_on_wall(last, |w, force_on_2, normal_force, kn| {
            let w = w as usize;
            self.force[w] -= force_on_2;
            if normal_force > 0.0 {
                self.stiffness[w] += kn;
            }
        });
    }
}

/// The walls' loads at the last step, summed when first asked for: by a servo in the step
/// ([`WallLoadsAtStep::sum_now`]) or by [`crate::Simulation::wall_forces`] after it
/// ([`WallLoadsAtStep::get_or_sum`]). The step's contacts and the last update of the free
/// spheres' pairs, which the sum reads, stay as they are until the next step's contact stage
/// (a change of the model or of the collider rebuilds the pipeline, and with it these loads,
/// zero again), so either sum is the step's. A run that reads no wall force and steers no
/// wall never sums them: over the 12 700 wall contacts of the packing of 10⁵ spheres, the
/// sum read each one's normal and stiffness from its block on one thread, 137–156 µs a step
/// (3 % of the step at 2 threads).
#[derive(Debug, Default)]
pub(crate) struct WallLoadsAtStep {
    at_step: OnceLock<WallLoads>,
    /// The buffers of the sum before, reused by `sum_now` (no allocation per step).
    spare: WallLoads,
}

impl WallLoadsAtStep {
    /// Zero on each of `walls` walls (before the first step).
    pub(crate) fn zeros(walls: usize) -> Self {
        WallLoadsAtStep {
            at_step: OnceLock::from(WallLoads::zeros(walls)),
            spare: WallLoads::default(),
        }
    }

    /// Forgets the loads of the step before (at the wall stage of a new step).
    pub(crate) fn forget(&mut self) {
        if let Some(loads) = self.at_step.take() {
            self.spare = loads;
        }
    }

    /// The loads of this step, summed now if not yet, in the buffers of the sum before.
    pub(crate) fn sum_now(
        &mut self,
        contacts: &Contacts,
        last: &LastUpdate<'_>,
        walls: usize,
    ) -> &WallLoads {
        if self.at_step.get().is_none() {
            let mut loads = std::mem::take(&mut self.spare);
            loads.sum(contacts, last, walls);
            let _ = self.at_step.set(loads);
        }
        self.at_step.get().expect("just set")
    }

    /// The loads of the last step, summed now if not yet (from the same contacts and last
    /// update as in the step).
    pub(crate) fn get_or_sum(
        &self,
        contacts: &Contacts,
        last: &LastUpdate<'_>,
        walls: usize,
    ) -> &WallLoads {
        self.at_step.get_or_init(|| {
            let mut loads = WallLoads::default();
            loads.sum(contacts, last, walls);
            loads
        })
    }
}

/// Whether a servo steers a wall at `time` (and so reads the walls' loads).
pub(crate) fn any_servo_at(controls: &[WallControl], time: Real) -> bool {
    controls.iter().any(|c| c.servo_at(time).is_some())
}

/// Sets the normal velocity of every stress-controlled wall for the next step (from `time`,
/// `dt` long) from the loads on it (the tangential part of its velocity is kept); a wall
/// whose servo has ended takes its later velocity. Returns whether a wall is steered.
pub(crate) fn steer_walls(
    model: &mut flexdem_elements::Model,
    controls: &[WallControl],
    loads: &WallLoads,
    time: Real,
    dt: Real,
) -> bool {
    let mut steered = false;
    for (w, control) in controls.iter().enumerate() {
        if let WallControl::StressUntil { until, then, .. } = control {
            if time >= *until {
                let wall = &mut model.walls[w];
                steered |= wall.velocity != *then;
                wall.velocity = *then;
                continue;
            }
        }
        // the area from where the walls are (steering changes velocities, not positions)
        let Some(servo) = control.servo_at(time).map(|s| s.with_current_area(model)) else {
            continue;
        };
        let wall = &mut model.walls[w];
        let f_n = normal_force(wall, &loads.force[w]);
        let speed = servo.normal_speed(f_n, loads.stiffness[w], dt);
        let n = wall.normal;
        wall.velocity += n * (speed - wall.velocity.dot(&n));
        steered = true;
    }
    steered
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Settings, Simulation};
    use flexdem_contact::Material;
    use flexdem_elements::Wall;

    /// Two spheres between a floor (wall 0) and a platen (wall 1, a servo pressing down),
    /// under gravity, at 2 threads (the pairs' parallel update).
    fn pressed_column() -> Simulation {
        let mut model = flexdem_elements::Model::new();
        let m = model.add_material(Material::new(1e7, 0.3, 2000.0, 0.5).unwrap()).unwrap();
        let r = 0.01;
        model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
        model.add_wall(Vec3::new(0.0, 0.0, 4.0 * r), -Vec3::z(), m).unwrap();
        model.add_sphere(Vec3::new(0.0, 0.0, r), r, m).unwrap();
        model.add_sphere(Vec3::new(1e-4 * r, 0.0, 3.0 * r), r, m).unwrap();
        let gravity = Vec3::new(0.0, 0.0, -9.81);
        let mut sim = Simulation::new(model, Settings { gravity, ..Settings::default() }).unwrap();
        let servo =
            StressControl { target: 1e4, area: 4e-4, gain: None, max_speed: 0.01, section: None };
        sim.set_wall_control(1, WallControl::Stress(servo)).unwrap();
        sim
    }

    /// The loads a servo summed in the step are those summed from the state after it, as
    /// `Simulation::wall_forces` sums them when no servo acts: the contacts and the pairs'
    /// last update stay as the wall stage saw them until the next step.
    #[test]
    fn the_walls_loads_summed_after_the_step_are_the_steps() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        pool.install(|| {
            let mut sim = pressed_column();
            let mut loaded = 0;
            for _ in 0..300 {
                sim.step().unwrap();
                let in_step = sim.pipeline.walls.at_step.get().expect("summed for the servo");
                let last = sim.state.contacts.pairs.last_update(&sim.pipeline.contacts.pairs);
                let mut after = WallLoads::default();
                after.sum(&sim.state.contacts, &last, 2);
                assert_eq!(in_step, &after);
                assert_eq!(sim.wall_forces(), &in_step.force[..]);
                loaded += usize::from(after.force[1] != Vec3::zeros());
            }
            assert!(loaded > 100, "the platen carried a force at {loaded} steps of 300");
            // a change of the model rebuilds the pipeline: zero until the next step
            sim.edit_model(|_| ()).unwrap();
            assert_eq!(sim.wall_forces(), &[Vec3::zeros(); 2]);
        });
    }

    fn servo(gain: Option<Real>) -> StressControl {
        StressControl { target: 1e5, area: 0.01, gain, max_speed: 0.1, section: None }
    }

    #[test]
    fn the_wall_moves_towards_its_target_at_most_at_its_largest_speed() {
        let s = servo(Some(1e-5));
        // 1 kN wanted, 400 N felt: into the bodies at G·600 N
        assert!((s.normal_speed(400.0, 0.0, 1e-6) - 6e-3).abs() < 1e-15);
        assert!((s.normal_speed(1600.0, 0.0, 1e-6) + 6e-3).abs() < 1e-15);
        assert_eq!(s.normal_speed(1e9, 0.0, 1e-6), -0.1);
        // automatic gain: α·error/(K·dt)
        let a = servo(None);
        let v = a.normal_speed(900.0, 1e9, 1e-6);
        assert!((v - SERVO_RELAXATION * 100.0 / (1e9 * 1e-6)).abs() < 1e-15, "{v}");
        assert!(v > 0.0 && v < a.max_speed);
        assert_eq!(a.normal_speed(0.0, 0.0, 1e-6), 0.1);
        assert_eq!(a.normal_speed(2000.0, 0.0, 1e-6), -0.1);
        let zero = StressControl { target: 0.0, ..a };
        assert_eq!(zero.normal_speed(0.0, 0.0, 1e-6), 0.0);
    }

    #[test]
    fn bad_servo_values_are_refused_by_name() {
        let ok = servo(None);
        assert!(ok.validate().is_ok());
        let cases = [
            (StressControl { target: -1.0, ..ok }, "target"),
            (StressControl { target: Real::NAN, ..ok }, "target"),
            (StressControl { area: 0.0, ..ok }, "area"),
            (StressControl { area: Real::INFINITY, ..ok }, "area"),
            (StressControl { gain: Some(0.0), ..ok }, "gain"),
            (StressControl { gain: Some(Real::NAN), ..ok }, "gain"),
            (StressControl { max_speed: -1.0, ..ok }, "max_speed"),
            (StressControl { max_speed: 0.0, ..ok }, "max_speed"),
        ];
        for (s, word) in cases {
            let e = s.validate().unwrap_err().to_string();
            assert!(e.contains(word), "{e}");
        }
        let two = [WallControl::Velocity, WallControl::Stress(ok)];
        assert!(check_controls(&two, 2).is_ok());
        assert!(check_controls(&two, 3).is_err());
    }

    #[test]
    fn steering_keeps_the_tangential_velocity() {
        let walls = [Wall {
            point: Vec3::zeros(),
            normal: Vec3::new(0.0, 0.0, -1.0),
            velocity: Vec3::new(0.2, 0.0, 5.0),
            material: 0,
            mask: 1,
        }];
        let mut model = flexdem_elements::Model::new();
        model.walls = walls.to_vec();
        let loads = WallLoads { force: vec![Vec3::new(0.0, 0.0, 400.0)], stiffness: vec![0.0] };
        let controls = [WallControl::Stress(servo(Some(1e-5)))];
        assert!(steer_walls(&mut model, &controls, &loads, 0.0, 1e-6));
        // F_n = 400 N < 1 kN: down into the bodies (along n = −z) at 6 mm/s
        assert!((model.walls[0].velocity - Vec3::new(0.2, 0.0, -6e-3)).norm() < 1e-15);
        assert!(!steer_walls(&mut model, &[WallControl::Velocity], &loads, 0.0, 1e-6));
    }

    #[test]
    fn a_servo_until_a_time_then_moves_at_its_later_velocity() {
        let walls = [Wall {
            point: Vec3::zeros(),
            normal: Vec3::z(),
            velocity: Vec3::zeros(),
            material: 0,
            mask: 1,
        }];
        let mut model = flexdem_elements::Model::new();
        model.walls = walls.to_vec();
        let then = Vec3::new(0.0, 0.0, 0.02);
        let control = WallControl::StressUntil { servo: servo(Some(1e-5)), until: 1.0, then };
        let loads = WallLoads { force: vec![Vec3::zeros()], stiffness: vec![0.0] };
        // before the switch: the servo drives the unloaded wall into the bodies
        assert!(steer_walls(&mut model, &[control], &loads, 0.5, 1e-6));
        assert!(model.walls[0].velocity.z > 0.0 && model.walls[0].velocity != then);
        assert_eq!(control.servo_at(0.5), control.servo());
        // from the switch on: the later velocity, and no servo
        assert!(steer_walls(&mut model, &[control], &loads, 1.0, 1e-6));
        assert_eq!(model.walls[0].velocity, then);
        assert!(!steer_walls(&mut model, &[control], &loads, 2.0, 1e-6));
        assert_eq!(control.servo_at(1.0), None);
        let bad = WallControl::StressUntil { servo: servo(None), until: Real::NAN, then };
        assert!(bad.validate().unwrap_err().to_string().contains("servo until"));
    }
}

//! `flexdem.Simulation`: a run of the run driver ([`flexdem_run::Run`]) seen from Python.

use crate::access::{self, ParticleColumn};
use crate::arrays::{column, dict, rows};
use crate::convert::dict_to_toml;
use crate::errors::{run_error, SceneError, SimulationError};
use crate::series::SeriesRecorder;
use crate::{loads, threads};
use flexdem_io::checkpoint::read_checkpoint;
use flexdem_run::{Run, RunError, RunLength, RunOptions, Stop};
use flexdem_scene::{load_scene, parse_scene, Scene, SceneNames};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList};
use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

/// Steps between two checks for Ctrl-C when a run has no callback.
const SIGNAL_CHECK_STEPS: u64 = 1000;

/// A simulation: a scene set up for running, with its output and checkpoints.
///
/// Build one with `Simulation.from_scene(path)`, `Simulation.from_toml(text)`,
/// `Simulation.from_dict(dict)` or `Simulation.resume(checkpoint)`; step it with `run` or
/// `step`; read its state as numpy arrays (`positions`, `contacts()`, `energy()`, ...).
#[pyclass(name = "Simulation", module = "flexdem", frozen)]
pub struct PySimulation {
    /// The run and what the module keeps beside it; locked by each call (the stepping
    /// releases the GIL, not the lock).
    inner: Mutex<Inner>,
}

/// A run with the scene's names (for the loads a script adds) and its series.
struct Inner {
    run: Run,
    /// The scene's structures and sphere groups (unknown after a resume).
    names: SceneNames,
    /// The tracked series, recorded whether or not the output is written.
    series: SeriesRecorder,
}

/// Where the output goes, from the `output` argument: None/False nothing, True the scene's
/// folder, a path that folder.
fn output_options(output: Option<&Bound<'_, PyAny>>) -> PyResult<RunOptions> {
    let mut options = RunOptions { no_output: true, ..RunOptions::default() };
    let Some(output) = output else { return Ok(options) };
    if output.is_none() {
        return Ok(options);
    }
    if let Ok(b) = output.cast::<PyBool>() {
        options.no_output = !b.is_true();
        return Ok(options);
    }
    let folder: PathBuf = output.extract().map_err(|_| {
        PyValueError::new_err("output: give None, False, True (the scene's folder) or a folder")
    })?;
    options.no_output = false;
    options.output_directory = Some(folder);
    Ok(options)
}

impl PySimulation {
    /// The run and its companions, locked.
    fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The module's simulation of `run`.
    fn wrap(run: Run, names: SceneNames, series: SeriesRecorder) -> PySimulation {
        PySimulation { inner: Mutex::new(Inner { run, names, series }) }
    }

    /// The simulation of `scene`, with the worker threads set up first.
    fn build(
        py: Python<'_>,
        scene: Scene,
        output: Option<&Bound<'_, PyAny>>,
        threads: Option<usize>,
    ) -> PyResult<PySimulation> {
        let mut options = output_options(output)?;
        threads::prepare(py, threads, scene.threads)?;
        options.threads = threads;
        let names = scene.names.clone();
        // the scene's series, kept before `no_output` takes their period from the run
        let series = SeriesRecorder::new(scene.output.series.clone(), scene.output.series_every);
        let run = py.detach(|| Run::new(scene, options)).map_err(run_error)?;
        Ok(PySimulation::wrap(run, names, series))
    }

    /// Advances `run` by up to `max_steps` on a rayon worker (the engine's parallel loops
    /// then start there instead of being handed over from this thread each time), without
    /// the GIL.
    fn advance(&self, py: Python<'_>, max_steps: u64) -> Result<Stop, RunError> {
        py.detach(|| {
            let mut guard = self.lock();
            let Inner { run, series, .. } = &mut *guard;
            rayon::join(|| run.advance(Some(max_steps), series), || ()).0
        })
    }
}

/// The scene file's folder joined to `<string>`: the name errors give, and the folder
/// relative paths start from.
fn text_source(base_dir: Option<PathBuf>) -> PathBuf {
    base_dir.unwrap_or_else(|| PathBuf::from(".")).join("<string>")
}

#[pymethods]
impl PySimulation {
    /// Reads the scene file at `path` and sets up its simulation.
    ///
    /// `output`: None or False writes nothing (the default), True the scene's `[output]`
    /// into its folder, a folder the same output there. `threads`: the worker threads
    /// (see `flexdem.set_threads`). Raises `flexdem.SceneError` (a ValueError) with the
    /// command line's message when the scene is wrong.
    #[staticmethod]
    #[pyo3(signature = (path, *, output=None, threads=None))]
    fn from_scene(
        py: Python<'_>,
        path: PathBuf,
        output: Option<&Bound<'_, PyAny>>,
        threads: Option<usize>,
    ) -> PyResult<PySimulation> {
        let scene = py.detach(|| load_scene(&path)).map_err(|e| run_error(e.into()))?;
        PySimulation::build(py, scene, output, threads)
    }

    /// Sets up the simulation of a scene given as TOML text. Relative paths in it (meshes,
    /// the output folder) start from `base_dir` (default: the current folder); errors name
    /// the text `<string>`.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None, *, output=None, threads=None))]
    fn from_toml(
        py: Python<'_>,
        text: &str,
        base_dir: Option<PathBuf>,
        output: Option<&Bound<'_, PyAny>>,
        threads: Option<usize>,
    ) -> PyResult<PySimulation> {
        let source = text_source(base_dir);
        let scene = parse_scene(text, &source).map_err(|e| run_error(e.into()))?;
        PySimulation::build(py, scene, output, threads)
    }

    /// Sets up the simulation of a scene given as a dict with the keys of a scene file
    /// (`{"simulation": {...}, "materials": {...}, "structures": [...], ...}`): it is
    /// written as TOML (`flexdem.to_toml`) and read as a file is, with the same checks;
    /// line numbers in errors are those of that text.
    #[staticmethod]
    #[pyo3(signature = (scene, base_dir=None, *, output=None, threads=None))]
    fn from_dict(
        py: Python<'_>,
        scene: &Bound<'_, PyAny>,
        base_dir: Option<PathBuf>,
        output: Option<&Bound<'_, PyAny>>,
        threads: Option<usize>,
    ) -> PyResult<PySimulation> {
        let text = dict_to_toml(scene)?;
        PySimulation::from_toml(py, &text, base_dir, output, threads)
    }

    /// Resumes the checkpoint at `path` (written by `save_checkpoint` or by `flexdem run`):
    /// the simulation continues bit-identically. `output`: False/None writes nothing, True
    /// continues the checkpointed run's output (from a checkpoint at the end of its run:
    /// once `run` goes on).
    #[staticmethod]
    #[pyo3(signature = (path, *, output=false, threads=None))]
    fn resume(
        py: Python<'_>,
        path: PathBuf,
        output: bool,
        threads: Option<usize>,
    ) -> PyResult<PySimulation> {
        if let Some(n) = threads {
            threads::set(n)?;
        }
        let options = RunOptions { no_output: !output, threads, ..RunOptions::default() };
        let (run, series) = py
            .detach(|| {
                let checkpoint =
                    read_checkpoint(&path).map_err(|e| RunError::ReadCheckpoint(Box::new(e)))?;
                let settings = &checkpoint.output;
                let series = SeriesRecorder::new(settings.series.clone(), settings.series_every);
                let folder = settings.directory.clone();
                let rows = checkpoint.output_progress.series_rows;
                let run = Run::from_checkpoint(checkpoint, &path, options)?;
                Ok((run, series, folder, rows))
            })
            .map(|(run, mut series, folder, rows): (Run, SeriesRecorder, PathBuf, u64)| {
                if output {
                    // the rows before the checkpoint, as the resumed output keeps them
                    series.continue_csv(&folder, rows);
                }
                (run, series)
            })
            .map_err(run_error)?;
        Ok(PySimulation::wrap(run, SceneNames::unknown(), series))
    }

    /// Runs `steps` steps, or `duration` seconds of simulated time, or (neither given) to
    /// the scene's run length; returns the number of steps done. `callback(sim)` is called
    /// every `every` steps and at the end; it stops the run by returning False (or by
    /// raising, which propagates). The GIL is released while the engine steps.
    #[pyo3(signature = (steps=None, duration=None, callback=None, every=100))]
    fn run(
        slf: &Bound<'_, Self>,
        steps: Option<u64>,
        duration: Option<f64>,
        callback: Option<Bound<'_, PyAny>>,
        every: u64,
    ) -> PyResult<u64> {
        let py = slf.py();
        let this = slf.get();
        if steps.is_some() && duration.is_some() {
            return Err(PyValueError::new_err("give steps or duration, not both"));
        }
        if every == 0 {
            return Err(PyValueError::new_err("every must be at least 1"));
        }
        if let Some(d) = duration {
            if !(d >= 0.0 && d.is_finite()) {
                return Err(PyValueError::new_err(format!("duration = {d}: give a time ≥ 0 s")));
            }
        }
        let (scene_target, start) = {
            let mut guard = this.lock();
            let run = &mut guard.run;
            let scene_target = run.target();
            let (steps_now, time_now) = (run.sim().steps(), run.sim().time());
            match (steps, duration) {
                (Some(n), _) => run.set_target(RunLength::Steps(steps_now.saturating_add(n))),
                (_, Some(d)) => run.set_target(RunLength::Duration(time_now + d)),
                _ => {}
            }
            (scene_target, steps_now)
        };
        let chunk = if callback.is_some() { every } else { SIGNAL_CHECK_STEPS };
        let result = (|| -> PyResult<()> {
            loop {
                let stop = this.advance(py, chunk).map_err(run_error)?;
                if let Some(f) = &callback {
                    let answer = f.call1((slf,))?;
                    if answer.cast::<PyBool>().is_ok_and(|b| !b.is_true()) {
                        return Ok(());
                    }
                } else {
                    py.check_signals()?;
                }
                if stop != Stop::StepLimit {
                    return Ok(());
                }
            }
        })();
        let mut guard = this.lock();
        let run = &mut guard.run;
        // the scene's run length again: what later checkpoints store
        run.set_target(scene_target);
        let done = run.sim().steps() - start;
        result.map(|()| done)
    }

    /// One step.
    fn step(slf: &Bound<'_, Self>) -> PyResult<()> {
        PySimulation::run(slf, Some(1), None, None, 1).map(|_| ())
    }

    /// Writes a checkpoint of the current state to `path` (the command line's format:
    /// `flexdem resume` continues it too).
    fn save_checkpoint(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| {
            let mut guard = self.lock();
            let run = &mut guard.run;
            run.set_checkpoint_path(&path);
            run.save_checkpoint()
        })
        .map_err(run_error)
    }

    /// Ends the run: writes the last output frame and row, the `.pvd` file and the plot (as
    /// the command line does at the end of a run) and returns the run's summary as a dict
    /// (what `flexdem run --summary` writes as JSON).
    fn finish<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json = py
            .detach(|| {
                let mut guard = self.lock();
                let Inner { run, series, .. } = &mut *guard;
                let summary = run.finish(series)?;
                series.finish(run.sim());
                serde_json::to_string(&summary).map_err(|e| RunError::Summary(e.to_string()))
            })
            .map_err(run_error)?;
        py.import("json")?.call_method1("loads", (json,))
    }

    /// Simulated time (s).
    #[getter]
    fn time(&self) -> f64 {
        self.lock().run.sim().time()
    }

    /// Steps done since the start of the simulation.
    #[getter]
    fn steps(&self) -> u64 {
        self.lock().run.sim().steps()
    }

    /// The current time step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.lock().run.sim().dt()
    }

    /// The critical time step at the last estimate (s).
    #[getter]
    fn critical_dt(&self) -> f64 {
        self.lock().run.sim().critical_dt()
    }

    /// Whether the scene's run length (`steps` or `duration`) is reached.
    #[getter]
    fn done(&self) -> bool {
        self.lock().run.is_done()
    }

    /// Number of particles (free spheres and structure nodes).
    #[getter]
    fn particle_count(&self) -> usize {
        access::particle_count(self.lock().run.sim())
    }

    /// Warnings raised by the engine so far.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.lock().run.sim().warnings().to_vec()
    }

    /// The scene file the simulation came from.
    #[getter]
    fn scene_file(&self) -> PathBuf {
        self.lock().run.scene_file().to_path_buf()
    }

    /// The output folder (written only when the simulation was set up with `output`).
    #[getter]
    fn output_directory(&self) -> PathBuf {
        self.lock().run.output_settings().directory.clone()
    }

    /// Particle centres, n×3 (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.vectors(py, ParticleColumn::Positions)
    }

    /// Particle velocities, n×3 (m/s).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.vectors(py, ParticleColumn::Velocities)
    }

    /// Particle angular velocities, n×3 (rad/s).
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.vectors(py, ParticleColumn::AngularVelocities)
    }

    /// Total force on each particle at the last step, n×3 (N); zero before the first step.
    #[getter]
    fn forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.vectors(py, ParticleColumn::Forces)
    }

    /// Particle radii, n (m).
    #[getter]
    fn radii<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        column(py, access::radii(self.lock().run.sim()))
    }

    /// Particle masses, n (kg).
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        column(py, access::masses(self.lock().run.sim()))
    }

    /// The structure of each particle, n; −1 for a free sphere.
    #[getter]
    fn structures<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        column(py, access::structures(self.lock().run.sim()))
    }

    /// The contacts of the last step as a dict of arrays, one row per contact: `pairs`
    /// (n×2, the feature ids of the two sites: particle, connection, PFacet or wall index),
    /// `kinds` (n×2: 0 particle, 1 edge, 2 face, 3 wall, as the VTK output's `kind1`,
    /// `kind2`), `points` (n×3), `normals` (n×3, body 1 → body 2), `normal_force` (n,
    /// compression positive), `shear_force` and `force` (n×3, on body 2).
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let t = access::contacts(self.lock().run.sim());
        dict(
            py,
            vec![
                ("pairs", rows(py, t.features, 2)?),
                ("kinds", rows(py, t.kinds, 2)?),
                ("points", rows(py, t.points, 3)?),
                ("normals", rows(py, t.normals, 3)?),
                ("normal_force", column(py, t.normal_force)),
                ("shear_force", rows(py, t.shear_force, 3)?),
                ("force", rows(py, t.force, 3)?),
            ],
        )
    }

    /// The beam links (one per connection) as a dict of arrays, one row per link: `nodes`
    /// (m×2 particle ids), `status` (m: 0 cohesive, 1 frictional, 2 broken),
    /// `normal_force` (m, compression positive), `shear_force` and `force` (m×3, on node
    /// 2); forces are zero before the first step.
    fn links<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let t = access::links(self.lock().run.sim());
        dict(
            py,
            vec![
                ("nodes", rows(py, t.nodes, 2)?),
                ("status", column(py, t.status)),
                ("normal_force", column(py, t.normal_force)),
                ("shear_force", rows(py, t.shear_force, 3)?),
                ("force", rows(py, t.force, 3)?),
            ],
        )
    }

    /// The energy terms (J) as a dict: every term of the engine's energy account
    /// (`kinetic_translation`, `elastic_links`, `gravity_work`, `friction`, ...), then
    /// `stored`, `put_in`, `taken_out`, `balance` (constant when the balance closes),
    /// `initial_balance`, `lowest_balance`, `scale`, `relative_balance_error` and
    /// `late_births` (what contacts found late put in after the first step, limited by the
    /// watch on its own).
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let terms = access::energy(self.lock().run.sim());
        let d = PyDict::new(py);
        for (k, v) in terms {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// Sets the Cundall damping coefficient (0 ≤ d < 1) for the rest of the run. Raises
    /// ValueError with the engine's message when it is refused.
    fn set_damping(&self, damping: f64) -> PyResult<()> {
        self.change(access::Change::Damping(damping))
    }

    /// Sets gravity `[gx, gy, gz]` (m/s²) for the rest of the run.
    fn set_gravity(&self, gravity: [f64; 3]) -> PyResult<()> {
        self.change(access::Change::Gravity(gravity.into()))
    }

    /// Sets the velocity `[vx, vy, vz]` (m/s) of wall `wall` (its index in the scene).
    fn set_wall_velocity(&self, wall: u32, velocity: [f64; 3]) -> PyResult<()> {
        self.change(access::Change::WallVelocity(wall, velocity.into()))
    }

    /// Makes wall `wall` a servo that holds the normal stress `stress` (Pa, compression) over
    /// `area` (m²), moving at most at `max_speed` (m/s), with the gain `gain` (m/s per N;
    /// None: automatic, 0.5/(K·dt)); `set_wall_velocity` puts it back under a constant
    /// velocity. Its work enters the energy balance as `boundary_work`.
    #[pyo3(signature = (wall, stress, area, max_speed, gain=None))]
    fn set_wall_servo(
        &self,
        wall: u32,
        stress: f64,
        area: f64,
        max_speed: f64,
        gain: Option<f64>,
    ) -> PyResult<()> {
        let servo = flexdem_integrate::StressControl {
            target: stress,
            area,
            gain,
            max_speed,
            section: None,
        };
        self.change(access::Change::WallControl(
            wall,
            flexdem_integrate::WallControl::Stress(servo),
        ))
    }

    /// Adds a pressure `pressure` (Pa) on every PFacet of the structure named `structure`: a
    /// follower force p·area·n on each, positive along the PFacets' normals (out of a tube or
    /// a shell), against them with `flip=True` (a confining pressure); `ramp=(start,
    /// duration)` grows it linearly in simulated time. Its work enters `load_work`.
    #[pyo3(signature = (structure, pressure, flip=false, ramp=None))]
    fn add_pressure(
        &self,
        structure: String,
        pressure: f64,
        flip: bool,
        ramp: Option<(f64, f64)>,
    ) -> PyResult<()> {
        let ramp = match ramp {
            Some((start, duration)) => flexdem_integrate::Ramp::Linear { start, duration },
            None => flexdem_integrate::Ramp::Constant,
        };
        let pressure = flexdem_integrate::Pressure { pfacets: Vec::new(), pressure, flip, ramp };
        self.change(access::Change::AddPressure { structure, pressure })
    }

    /// Removes every pressure.
    fn clear_pressures(&self) -> PyResult<()> {
        self.change(access::Change::ClearPressures)
    }

    /// The pressures acting, as dicts: `pfacets` (int array), `pressure` (Pa), `flip`,
    /// `ramp` (`(start, duration)` or None) and `current` (Pa, the ramp applied now).
    fn pressures<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let guard = self.lock();
        let sim = guard.run.sim();
        let list = PyList::empty(py);
        for p in sim.pressures() {
            let d = PyDict::new(py);
            let ids: Vec<i64> = p.pfacets.iter().map(|&f| i64::from(f)).collect();
            d.set_item("pfacets", crate::arrays::column(py, ids))?;
            d.set_item("pressure", p.pressure)?;
            d.set_item("flip", p.flip)?;
            match p.ramp {
                flexdem_integrate::Ramp::Linear { start, duration } => {
                    d.set_item("ramp", (start, duration))?
                }
                flexdem_integrate::Ramp::Constant => d.set_item("ramp", py.None())?,
            }
            d.set_item("current", p.pressure * p.ramp.factor(sim.time()))?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Imposes the velocity `[vx, vy, vz]` (m/s) on `particles` (their translations are
    /// driven; the supports' work enters the energy balance as `boundary_work`).
    fn impose_velocity(&self, particles: Vec<u32>, velocity: [f64; 3]) -> PyResult<()> {
        self.change(access::Change::ImposedVelocity(particles, velocity.into()))
    }

    /// Sets the velocity `[vx, vy, vz]` (m/s) of `particles` by hand: on free DOFs a kick,
    /// whose change of kinetic energy `½m·(v² − v₀²)` is the user's work (`load_work`, from
    /// the first step on: before it the velocities are the start state); on blocked ones a
    /// new imposed velocity (`boundary_work`). All or nothing.
    fn set_velocity(&self, particles: Vec<u32>, velocity: [f64; 3]) -> PyResult<()> {
        self.change(access::Change::Velocity(particles, velocity.into()))
    }

    /// Sets the angular velocity `[wx, wy, wz]` (rad/s) of `particles` by hand, as
    /// `set_velocity` does (the kick `½I·(ω² − ω₀²)` is `load_work`).
    fn set_angular_velocity(&self, particles: Vec<u32>, spin: [f64; 3]) -> PyResult<()> {
        self.change(access::Change::AngularVelocity(particles, spin.into()))
    }

    /// Adds a load for the rest of the run, given with the keys of a scene file's
    /// `[[loads]]` table: `select` (a dict: `structure` with `side`, `spheres`, `ids`,
    /// `box`, `plane`), `force` (N on each particle) or `total_force` (N, shared equally),
    /// `moment` (N·m on each), `ramp` (`{"start": s, "duration": s}`, in simulated time since
    /// the start). `box` and `plane` select by the current positions. Raises
    /// `flexdem.SceneError` (a ValueError) with the scene reader's message; nothing is
    /// added then.
    #[pyo3(signature = (**load))]
    fn add_load(&self, py: Python<'_>, load: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let load = load.cloned().unwrap_or_else(|| PyDict::new(py));
        let text = loads::to_text(PyList::new(py, [load])?.as_any())?;
        let mut guard = self.lock();
        let Inner { run, names, .. } = &mut *guard;
        let parsed = loads::parse(&text, run.sim(), names)?;
        let sim = run.sim_mut();
        for load in parsed {
            sim.add_load(load).map_err(|e| SceneError::new_err(e.to_string()))?;
        }
        Ok(())
    }

    /// Replaces every load by `loads`, a list of dicts with the keys of `add_load` (an
    /// empty list removes them all); all are checked first, nothing changes on an error.
    fn set_loads(&self, loads: &Bound<'_, PyAny>) -> PyResult<()> {
        let text = loads::to_text(loads)?;
        let mut guard = self.lock();
        let Inner { run, names, .. } = &mut *guard;
        let parsed = loads::parse(&text, run.sim(), names)?;
        run.sim_mut().set_loads(parsed).map_err(|e| SceneError::new_err(e.to_string()))
    }

    /// The loads acting, as dicts that `set_loads` takes back: `select = {"ids": array}`,
    /// `force` and `moment` on each particle (arrays of 3; a `total_force` is shared out
    /// already), `ramp` when the load is ramped.
    fn loads<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        loads::to_python(py, self.lock().run.sim().loads())
    }

    /// The tracked series (the scene's `[[output.series]]`) as a dict of numpy arrays, one
    /// per column of the command line's `series.csv`: `time_s`, `step`, then
    /// `NAME_COMPONENT_UNIT` (`impactor_position_z_m`, `e_kinetic_translation_J`, ...).
    /// Rows are recorded as the CSV's, whether or not output is written: at the start, every
    /// `series_every` steps, and at `finish`. A resumed simulation starts with the
    /// checkpoint's rows of its `series.csv` (with `output=True`), else with none.
    fn series<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.lock().series.to_dict(py)
    }

    /// Writes the series recorded so far as the command line's CSV to `path`.
    fn write_series(&self, py: Python<'_>, path: PathBuf) -> PyResult<PathBuf> {
        py.detach(|| {
            let guard = self.lock();
            let settings = guard.run.output_settings();
            let own = settings.directory.join(flexdem_output::CSV_FILE);
            if settings.series_every.is_some() && flexdem_output::same_file(&path, &own) {
                return Err(PyValueError::new_err(format!(
                    "{}: the run writes this file itself; give another path",
                    path.display()
                )));
            }
            guard.series.write_csv(&path).map_err(|e| SimulationError::new_err(e.to_string()))
        })?;
        Ok(path)
    }

    /// Writes a VTK frame of the current state into `directory` (default: the output
    /// folder), the files the command line writes at this step: `particles_N.vtp`,
    /// `connections_N.vtp`, `pfacets_N.vtp`, `contacts_N.vtp` (N the step, 6 digits).
    /// Returns their paths. The frame is not added to the run's `flexdem.pvd`.
    #[pyo3(signature = (directory=None))]
    fn write_frame(&self, py: Python<'_>, directory: Option<PathBuf>) -> PyResult<Vec<PathBuf>> {
        py.detach(|| {
            let guard = self.lock();
            let folder = directory.unwrap_or_else(|| guard.run.output_settings().directory.clone());
            flexdem_output::write_frame(&folder, guard.run.sim())
        })
        .map_err(|e| SimulationError::new_err(e.to_string()))
    }

    fn __repr__(&self) -> String {
        let guard = self.lock();
        let (run, sim) = (&guard.run, guard.run.sim());
        format!(
            "<flexdem.Simulation of {}: {} particles, step {}, t = {:.6e} s>",
            run.scene_file().display(),
            access::particle_count(sim),
            sim.steps(),
            sim.time()
        )
    }
}

impl PySimulation {
    /// Applies a change between stages; the engine's refusal as a ValueError.
    fn change(&self, change: access::Change) -> PyResult<()> {
        access::apply(self.lock().run.sim_mut(), change).map_err(PyValueError::new_err)
    }

    /// One particle column as an n×3 array.
    fn vectors<'py>(&self, py: Python<'py>, c: ParticleColumn) -> PyResult<Bound<'py, PyAny>> {
        rows(py, access::particle_vectors(self.lock().run.sim(), c), 3)
    }
}

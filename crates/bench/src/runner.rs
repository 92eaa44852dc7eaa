//! Running a scene: build, warm up, time a fixed number of steps in a rayon pool of the
//! asked size, and report the time per step, its split over the engine's stages, the memory
//! and a checksum of the final state.

use crate::heap::heap_bytes;
use crate::procfs::{cpu_time, resident_memory};
use crate::{BenchError, Case, SceneKind};
use flexdem_elements::Model;
use flexdem_geom::Real;
use flexdem_integrate::{Simulation, SimulationError, Timers};
use std::time::{Duration, Instant};

/// How many steps are timed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepChoice {
    /// Exactly this many.
    Fixed(u64),
    /// Enough for the timed run to last about `target`, estimated from the warm-up's time
    /// per step, within `[min, max]`.
    Adaptive {
        /// Wished duration of the timed run.
        target: Duration,
        /// Fewest steps.
        min: u64,
        /// Most steps.
        max: u64,
    },
}

impl StepChoice {
    /// The step count for a warm-up that took `per_step` per step (`Duration::MAX` when
    /// unknown: the fewest).
    pub fn steps(self, per_step: Duration) -> u64 {
        match self {
            StepChoice::Fixed(n) => n,
            StepChoice::Adaptive { target, min, max } => {
                let per_step = per_step.as_secs_f64().max(1e-9);
                let n = (target.as_secs_f64() / per_step).ceil();
                (n.min(u64::MAX as f64) as u64).clamp(min, max.max(min))
            }
        }
    }
}

/// One benchmark run's measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchResult {
    /// The scene (a built-in one at a size, or a file).
    pub case: Case,
    /// Particles (structure nodes and free spheres).
    pub particles: usize,
    /// Connections (one beam link each).
    pub connections: usize,
    /// PFacets.
    pub pfacets: usize,
    /// Worker threads of the pool the steps ran in.
    pub threads: usize,
    /// Untimed steps run first.
    pub warmup_steps: u64,
    /// Timed steps.
    pub steps: u64,
    /// Time step at the end (s).
    pub dt: Real,
    /// Wall time of building the simulation (model and engine).
    pub build_time: Duration,
    /// Wall time of the timed steps.
    pub wall: Duration,
    /// Wall time of each timed step, in order. The runs of one case at different thread
    /// counts take the same steps (the same state at every step), so step k of one run is
    /// step k of the other: a step slowed by the host in one run can be told from the
    /// others, and the fastest time of each step over several runs summed
    /// (`bench/scaling.sh`).
    pub step_walls: Vec<Duration>,
    /// CPU time of the process (all threads, user + system) during the timed steps (None
    /// where /proc is missing).
    pub cpu: Option<Duration>,
    /// Time spent in each stage during the timed steps.
    pub stages: Timers,
    /// Contacts at the end.
    pub contacts: usize,
    /// Resident memory added by building the simulation and warming it up: `VmRSS` after
    /// the warm-up minus `VmRSS` before the build (None where /proc is missing).
    pub memory_bytes: Option<u64>,
    /// Heap added by building the simulation and warming it up: the bytes allocated after
    /// the warm-up minus those before the build, where the binary counts them
    /// ([`crate::heap`]; None elsewhere). What the scene holds, state and kept buffers.
    pub heap_bytes: Option<u64>,
    /// A scene-specific final value, named (see [`Case::probe`]).
    pub probe: Option<(&'static str, Real)>,
    /// FNV-1a hash of the bits of every particle's position, velocity, orientation and
    /// angular velocity at the end, and of the contact count.
    pub checksum: u64,
}

impl BenchResult {
    /// Elements: the bodies the engine handles, particles (nodes and spheres) + connections
    /// + PFacets (walls not counted).
    pub fn elements(&self) -> usize {
        self.particles + self.connections + self.pfacets
    }

    /// Wall time per step (ms).
    pub fn ms_per_step(&self) -> Real {
        per_step_ms(self.wall, self.steps)
    }

    /// The median of the steps' wall times (ms; the lower middle for an even count): the
    /// typical step, whatever a few disturbed steps took. It leaves out the rarer, dearer
    /// steps too (a rebuild of the candidate pairs, a time-step estimate), so it is below
    /// [`BenchResult::ms_per_step`] even on an idle host.
    pub fn median_step_ms(&self) -> Real {
        let mut walls = self.step_walls.clone();
        walls.sort_unstable();
        walls.get(walls.len().saturating_sub(1) / 2).map_or(0.0, |&d| per_step_ms(d, 1))
    }

    /// Wall time per step and element (ns).
    pub fn ns_per_element_step(&self) -> Real {
        self.wall.as_secs_f64() * 1e9 / (self.steps as Real * self.elements().max(1) as Real)
    }

    /// Steps per second of wall time.
    pub fn steps_per_second(&self) -> Real {
        self.steps as Real / self.wall.as_secs_f64().max(1e-12)
    }

    /// CPU time over wall time of the timed steps (%): about 100 × threads when the run
    /// had its cores.
    pub fn cpu_percent(&self) -> Option<Real> {
        self.cpu.map(|c| 100.0 * c.as_secs_f64() / self.wall.as_secs_f64().max(1e-12))
    }

    /// Steps per second of CPU time (all threads): the speed a run would have had on idle
    /// cores, for one thread.
    pub fn steps_per_cpu_second(&self) -> Option<Real> {
        self.cpu.filter(|c| !c.is_zero()).map(|c| self.steps as Real / c.as_secs_f64())
    }

    /// Time per step of each stage (ms): collision, contacts, links, integration.
    pub fn stage_ms_per_step(&self) -> [Real; 4] {
        let s = &self.stages;
        [s.collision, s.contacts, s.links, s.integration].map(|d| per_step_ms(d, self.steps))
    }

    /// Share of the wall time of each stage (%): collision, contacts, links, integration,
    /// and the rest of the step (loads, checks, energy, time step).
    pub fn stage_percent(&self) -> [Real; 5] {
        let wall = self.wall.as_secs_f64().max(1e-12);
        let s = &self.stages;
        let p = [s.collision, s.contacts, s.links, s.integration]
            .map(|d| 100.0 * d.as_secs_f64() / wall);
        [p[0], p[1], p[2], p[3], (100.0 - p.iter().sum::<Real>()).max(0.0)]
    }

    /// Memory per element (bytes): the heap's ([`BenchResult::heap_bytes`]) where it is
    /// counted, else the resident memory's ([`BenchResult::memory_bytes`]).
    pub fn bytes_per_element(&self) -> Option<Real> {
        self.heap_bytes.or(self.memory_bytes).map(|b| b as Real / self.elements().max(1) as Real)
    }
}

fn per_step_ms(d: Duration, steps: u64) -> Real {
    d.as_secs_f64() * 1e3 / steps.max(1) as Real
}

/// Builds `case`, runs `warmup` steps, then the timed steps (`steps`, decided
/// from the warm-up if adaptive; the fewest without a warm-up), everything inside a rayon
/// pool of `threads` threads (`pool.install(|| sim.run(n))`).
pub fn run_case(
    case: &Case,
    threads: usize,
    warmup: u64,
    steps: StepChoice,
) -> Result<BenchResult, BenchError> {
    if threads == 0 {
        return Err(BenchError::Zero { what: "threads" });
    }
    if steps == StepChoice::Fixed(0) {
        return Err(BenchError::Zero { what: "steps" });
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| BenchError::ThreadPool { threads, message: e.to_string() })?;
    let failed =
        |source| BenchError::Simulation { scene: case.name(), size: case.size(), threads, source };
    let rss_before = resident_memory();
    let heap_before = heap_bytes();
    let start = Instant::now();
    let mut sim = pool.install(|| case.simulation(threads))?;
    let build_time = start.elapsed();
    let start = Instant::now();
    pool.install(|| sim.run(warmup)).map_err(failed)?;
    // No warm-up, no estimate: an adaptive run then takes its fewest steps.
    let warmup_per_step = if warmup == 0 {
        Duration::MAX
    } else {
        Duration::from_secs_f64(start.elapsed().as_secs_f64() / warmup as f64)
    };
    let memory_bytes = match (rss_before, resident_memory()) {
        (Some(a), Some(b)) => Some(b.current.saturating_sub(a.current)),
        _ => None,
    };
    let heap_bytes = heap_before.zip(heap_bytes()).map(|(a, b)| b.saturating_sub(a));
    let steps = steps.steps(warmup_per_step).max(1);
    let before = *sim.timers();
    let cpu_before = cpu_time();
    let mut step_walls = Vec::with_capacity(steps.min(MAX_STEP_WALLS as u64) as usize);
    let start = Instant::now();
    pool.install(|| timed_steps(&mut sim, steps, &mut step_walls)).map_err(failed)?;
    let wall = start.elapsed();
    let cpu = match (cpu_before, cpu_time()) {
        (Some(a), Some(b)) => Some(b.saturating_sub(a)),
        _ => None,
    };
    let after = *sim.timers();
    Ok(BenchResult {
        case: case.clone(),
        particles: sim.model().particles.len(),
        connections: sim.model().connections.len(),
        pfacets: sim.model().pfacets.len(),
        threads,
        warmup_steps: warmup,
        steps,
        dt: sim.dt(),
        build_time,
        wall,
        step_walls,
        cpu,
        stages: after.since(&before),
        contacts: sim.contact_count(),
        memory_bytes,
        heap_bytes,
        probe: case.probe(&sim),
        checksum: state_checksum(sim.model(), sim.contact_count()),
    })
}

/// The most steps whose wall times a run keeps ([`BenchResult::step_walls`], 16 MB); the
/// steps past them are timed in the run's whole wall time only.
pub const MAX_STEP_WALLS: usize = 1 << 20;

/// Runs `steps` steps of `sim`, pushing each one's wall time onto `walls` (the first
/// [`MAX_STEP_WALLS`]).
fn timed_steps(
    sim: &mut Simulation,
    steps: u64,
    walls: &mut Vec<Duration>,
) -> Result<(), SimulationError> {
    for _ in 0..steps {
        let start = Instant::now();
        sim.step()?;
        if walls.len() < MAX_STEP_WALLS {
            walls.push(start.elapsed());
        }
    }
    Ok(())
}

/// FNV-1a (64 bits) of the bits of every particle's position, velocity, orientation and
/// angular velocity, then of `contacts`: equal for bit-identical states.
pub fn state_checksum(model: &Model, contacts: usize) -> u64 {
    const PRIME: u64 = 0x0000_0100_0000_01B3;
    let mut h: u64 = 0xCBF2_9CE4_8422_2325;
    let mut eat = |x: u64| {
        for byte in x.to_le_bytes() {
            h = (h ^ byte as u64).wrapping_mul(PRIME);
        }
    };
    let p = &model.particles;
    for i in 0..p.len() {
        for v in [&p.pos[i], &p.vel[i], &p.ang_vel[i]] {
            v.iter().for_each(|c| eat(c.to_bits()));
        }
        p.ori[i].coords.iter().for_each(|c| eat(c.to_bits()));
    }
    eat(contacts as u64);
    h
}

/// A benchmark plan: which scenes at which sizes, with which thread counts and run lengths.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The cases, run in this order.
    pub cases: Vec<Case>,
    /// Thread counts, each run for every case (the first decides adaptive step counts).
    pub threads: Vec<usize>,
    /// Timed steps (None: the scene's fixed count, else [`Plan::adaptive`]).
    pub steps: Option<u64>,
    /// Warm-up steps (None: the case's [`Case::warmup_steps`]).
    pub warmup: Option<u64>,
    /// Run length of scenes without a fixed count when `steps` is None.
    pub adaptive: StepChoice,
}

impl Plan {
    /// Every scene at its default sizes, 1 and 2 threads, timed runs of about 1.5 s
    /// (10 to 20 000 steps).
    pub fn full(scenes: &[SceneKind]) -> Plan {
        Plan {
            cases: scenes
                .iter()
                .flat_map(|&k| k.default_sizes().into_iter().map(move |s| Case::Scene(k, s)))
                .collect(),
            threads: vec![1, 2],
            steps: None,
            warmup: None,
            adaptive: StepChoice::Adaptive {
                target: Duration::from_millis(1500),
                min: 10,
                max: 20_000,
            },
        }
    }

    /// Small sizes and a few steps: a smoke test of seconds.
    pub fn quick(scenes: &[SceneKind]) -> Plan {
        Plan {
            cases: scenes
                .iter()
                .flat_map(|&k| k.quick_sizes().into_iter().map(move |s| Case::Scene(k, s)))
                .collect(),
            threads: vec![1, 2],
            steps: Some(5),
            warmup: Some(3),
            adaptive: StepChoice::Fixed(5),
        }
    }
}

/// A run of a plan with its thread-independence verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanRow {
    /// The measurements.
    pub result: BenchResult,
    /// Whether the final state equals the first thread count's (None for that first run).
    pub same_as_first: Option<bool>,
}

/// Runs `plan`, calling `report` after each run (to print rows as they come). For each case
/// the first thread count runs first; the others run the same number of steps, and their
/// checksum is compared with the first's.
pub fn run_plan(plan: &Plan, mut report: impl FnMut(&PlanRow)) -> Result<Vec<PlanRow>, BenchError> {
    let mut rows = Vec::new();
    for case in &plan.cases {
        let warmup = plan.warmup.unwrap_or(case.warmup_steps());
        let mut choice = match (plan.steps, case.fixed_steps()) {
            (Some(n), _) | (None, Some(n)) => StepChoice::Fixed(n),
            (None, None) => plan.adaptive,
        };
        let mut first: Option<u64> = None;
        for &threads in &plan.threads {
            let result = run_case(case, threads, warmup, choice)?;
            choice = StepChoice::Fixed(result.steps);
            let same_as_first = first.map(|c| c == result.checksum);
            first.get_or_insert(result.checksum);
            let row = PlanRow { result, same_as_first };
            report(&row);
            rows.push(row);
        }
    }
    Ok(rows)
}

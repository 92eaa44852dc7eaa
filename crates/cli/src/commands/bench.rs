//! `flexdem bench`: the scene benchmarks of `flexdem-bench` (tube impact, PFacet membrane,
//! sphere packing) at several sizes and thread counts, printed as a table and written as
//! CSV.

use crate::error::{CliError, Outcome};
use clap::Args;
use flexdem_bench::report::{csv, step_times_csv, table_header, table_row};
use flexdem_bench::{run_plan, Case, Plan, SceneKind};
use flexdem_io::output::same_file;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// `flexdem bench`.
///
/// Each run builds the scene, runs its warm-up steps (tube_impact 25, so that the sphere
/// touches the tube; membrane and packing 20), then times the steps in a rayon pool of the
/// given size. Columns: ms per step, ns per element and step (elements = particles +
/// connections + PFacets), steps/s, the share of the collision, contacts, links and
/// integration stages, the contacts at the end, the resident memory per element (VmRSS
/// after the warm-up minus before the build) and whether the final state is bit-identical
/// to the first thread count's.
#[derive(Debug, Args)]
#[command(after_help = "\
Each run builds the scene, runs its warm-up steps (tube_impact 25, so that the sphere touches
the tube; membrane and packing 20), then times the steps in a rayon pool of the given size.
Columns: ms/step; ns/elem-step with elements = particles (nodes and spheres) + connections +
PFacets; steps/s; cpu%: process CPU time / wall time (about 100 per thread when the run had
its cores: lower means the machine is shared); coll%, cont%, link%, intg%, rest%: share of the
collision, contacts, links and integration stages and of the rest; contacts at the end; B/elem:
heap per element (the bytes allocated after the warm-up minus those before the build, counted
by flexdem's allocator: the scene's state and the buffers kept from step to step; the CSV
also has the resident memory's delta, which the allocator's reuse makes unreliable); vs 1st
thr: whether the final state is
bit-identical to the first thread count's (the command fails if one is DIFFERENT).
The CSV also has each stage's ms/step, dt, build time and the state checksum.")]
pub struct BenchArgs {
    /// Scenes to run: tube_impact, membrane, packing or all (comma-separated). Default: all,
    /// or none when scene files are given.
    #[arg(long, value_name = "NAME", value_delimiter = ',')]
    pub scene: Vec<String>,
    /// Scene files (TOML, as for `flexdem run`) to time as they are, after the built-in
    /// scenes; repeatable. Each runs its warm-up (default 20 steps) and the timed steps with
    /// its own settings and time step, output off.
    #[arg(long, value_name = "FILE.toml")]
    pub scene_file: Vec<PathBuf>,
    /// Sizes of the membrane (PFacets) and packing (spheres), comma-separated (default:
    /// membrane 1000,10000,100000,1000000; packing 1000,10000,100000). The tube impact has
    /// one size (640 PFacets) and ignores this.
    #[arg(long, value_name = "N,N,...", value_delimiter = ',',
          value_parser = clap::value_parser!(u64).range(1..))]
    pub sizes: Vec<u64>,
    /// Worker thread counts, comma-separated; every case runs with each, the same steps.
    #[arg(long, value_name = "T,T,...", value_delimiter = ',', default_value = "1,2",
          value_parser = clap::value_parser!(u64).range(1..=flexdem_io::scene::MAX_THREADS as u64))]
    pub threads: Vec<u64>,
    /// Timed steps of every run (default: tube_impact 725, to 0.15 s of simulated time; the
    /// others as many as take about 1.5 s, 10 to 20000, decided by the first thread count).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub steps: Option<u64>,
    /// Warm-up steps before timing (default: per scene, see above).
    #[arg(long, value_name = "N")]
    pub warmup: Option<u64>,
    /// Where the CSV goes: a file (its folder is created), or `-` for standard output (the
    /// table then goes to standard error). Default: target/flexdem/bench/latest.csv in the
    /// current folder.
    #[arg(long, value_name = "FILE", conflicts_with = "update_committed")]
    pub csv: Option<PathBuf>,
    /// Also write every timed step's wall time to this CSV (scene, size, threads, step, ms; its
    /// folder is created): the runs of a case at each thread count take the same steps, so
    /// a step the host slowed in one run can be told from the others (`bench/scaling.sh`).
    #[arg(long, value_name = "FILE.csv")]
    pub step_times: Option<PathBuf>,
    /// Write the CSV over the committed results of the source tree
    /// (bench/results/latest.csv), to update them.
    #[arg(long)]
    pub update_committed: bool,
    /// A smoke test of seconds: small sizes (200), 3 warm-up and 5 timed steps.
    #[arg(long)]
    pub quick: bool,
}

/// Default CSV file: under `target/` of the current folder.
pub const DEFAULT_CSV: &str = "target/flexdem/bench/latest.csv";

/// The committed results of the source tree this binary was built from.
pub fn committed_csv() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../bench/results/latest.csv")
}

impl BenchArgs {
    /// Where the CSV goes (`-`: standard output).
    pub fn csv_path(&self) -> PathBuf {
        match (&self.csv, self.update_committed) {
            (Some(path), _) => path.clone(),
            (None, true) => committed_csv(),
            (None, false) => PathBuf::from(DEFAULT_CSV),
        }
    }
}

/// Runs the benchmarks, printing each row when done, then writes the CSV.
pub fn bench(args: &BenchArgs) -> Result<Outcome, CliError> {
    let plan = plan(args)?;
    let csv_path = args.csv_path();
    if let Some(path) = &args.step_times {
        // (checked before the runs: minutes of timing are not lost to a path)
        if path.as_os_str() == "-" {
            return Err(CliError::Input("--step-times: a file, not `-`".into()));
        }
        if same_file(path, &csv_path) {
            let shown = path.display();
            return Err(CliError::Input(format!("--step-times: {shown} is the CSV's file")));
        }
    }
    let to_stdout = csv_path.as_os_str() == "-";
    let mut out: Box<dyn std::io::Write> =
        if to_stdout { Box::new(std::io::stderr()) } else { Box::new(std::io::stdout()) };
    let mut print = |line: &str| {
        let _ = writeln!(out, "{line}");
        let _ = out.flush();
    };
    print(&table_header());
    let rows =
        run_plan(&plan, |row| print(&table_row(row))).map_err(|e| CliError::Run(e.to_string()))?;
    let text = csv(&rows);
    if to_stdout {
        print!("{text}");
    } else {
        write_csv(&csv_path, &text)?;
        print(&format!("CSV: {}", csv_path.display()));
    }
    // (after the main CSV: a failure here loses neither it nor the table)
    if let Some(path) = &args.step_times {
        write_csv(path, &step_times_csv(&rows))?;
        print(&format!("steps' times: {}", path.display()));
    }
    if rows.iter().any(|r| r.same_as_first == Some(false)) {
        return Err(CliError::Run(
            "the final state depends on the thread count (DIFFERENT above)".into(),
        ));
    }
    Ok(Outcome::Done)
}

/// The plan of `args`: scenes, sizes, threads, steps.
fn plan(args: &BenchArgs) -> Result<Plan, CliError> {
    let mut scenes = Vec::new();
    let all = [String::from("all")];
    let names: &[String] = match (args.scene.is_empty(), args.scene_file.is_empty()) {
        (true, true) => &all,
        _ => &args.scene,
    };
    for name in names {
        let name = name.trim();
        let more = if name == "all" {
            SceneKind::ALL.to_vec()
        } else {
            vec![SceneKind::parse(name).map_err(|e| CliError::Input(format!("--scene: {e}")))?]
        };
        for k in more {
            if !scenes.contains(&k) {
                scenes.push(k);
            }
        }
    }
    let mut plan = if args.quick { Plan::quick(&scenes) } else { Plan::full(&scenes) };
    if !args.sizes.is_empty() {
        let sizes = args
            .sizes
            .iter()
            .map(|&s| {
                usize::try_from(s)
                    .map_err(|_| CliError::Input(format!("--sizes: {s} is too large")))
            })
            .collect::<Result<Vec<usize>, CliError>>()?;
        plan.cases = scenes
            .iter()
            .flat_map(|&k| {
                match k {
                    SceneKind::TubeImpact => k.default_sizes(),
                    _ => sizes.clone(),
                }
                .into_iter()
                .map(move |s| Case::Scene(k, s))
            })
            .collect();
        for case in &plan.cases {
            if let Case::Scene(k, s) = case {
                k.check_size(*s).map_err(|e| CliError::Input(format!("--sizes: {e}")))?;
            }
        }
    }
    for path in &args.scene_file {
        if !path.is_file() {
            return Err(CliError::Input(format!("--scene-file: {} is not a file", path.display())));
        }
        plan.cases.push(Case::File(path.clone()));
    }
    plan.threads = args
        .threads
        .iter()
        .map(|&t| {
            usize::try_from(t).map_err(|_| CliError::Input(format!("--threads: {t} is too large")))
        })
        .collect::<Result<Vec<usize>, CliError>>()?;
    if args.steps.is_some() {
        plan.steps = args.steps;
    }
    if args.warmup.is_some() {
        plan.warmup = args.warmup;
    }
    Ok(plan)
}

/// Writes `text` to `path`, creating its folder.
fn write_csv(path: &Path, text: &str) -> Result<(), CliError> {
    let fail = |e: std::io::Error| CliError::Run(format!("cannot write {}: {e}", path.display()));
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(fail)?;
    }
    std::fs::write(path, text).map_err(fail)
}

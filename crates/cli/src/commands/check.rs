//! `flexdem check SCENE`: reads the scene and builds its simulation without running it.

use super::common::{build_simulation, describe_run, read_scene};
use crate::cli::SceneArgs;
use crate::error::{CliError, Outcome};
use crate::report::plural;
use flexdem_integrate::TimeStep;
use flexdem_io::output::validate_series;
use flexdem_run::Counts;

/// Checks the scene of `args`: prints `ok` with the counts and the time step, or fails with
/// the scene's error (exit code 2).
pub fn check(args: &SceneArgs) -> Result<Outcome, CliError> {
    let scene = read_scene(&args.scene)?;
    let (sim, rest) = build_simulation(scene)?;
    validate_series(&rest.output.series, &sim)
        .map_err(|e| CliError::Input(format!("{}: [output]: {e}", rest.source.display())))?;
    for warning in sim.warnings() {
        eprintln!("warning: {warning}");
    }
    let c = Counts::of(&sim);
    let dt_rule = match sim.settings().time_step {
        TimeStep::Auto { safety } => {
            format!("auto, {safety} × critical {:.3e} s", sim.critical_dt())
        }
        TimeStep::Fixed(_) => format!("fixed; critical {:.3e} s", sim.critical_dt()),
    };
    println!(
        "ok: {}: {} ({}, {}), {}, {}, {}, {}; dt = {:.3e} s ({dt_rule}); run: {}",
        args.scene.display(),
        plural(c.particles, "particle"),
        plural(c.spheres, "sphere"),
        plural(c.nodes, "node"),
        plural(c.connections, "connection"),
        plural(c.pfacets, "PFacet"),
        plural(c.walls, "wall"),
        plural(c.structures, "structure"),
        sim.dt(),
        describe_run(rest.run)
    );
    Ok(Outcome::Done)
}

//! `flexdem spheres INPUT -o FILE.csv`: the free spheres of a scene or of a checkpoint, as
//! the CSV file `[[spheres]] kind = "file"` reads, in the order of space (`in_space_order`:
//! a run that reads the file keeps its order, and neighbours near in memory are faster).

use super::common::read_scene;
use crate::cli::SpheresArgs;
use crate::error::{CliError, Outcome};
use crate::report::plural;
use flexdem_elements::{ParticleKind, Particles};
use flexdem_geom::{Real, Vec3};
use flexdem_io::checkpoint::read_checkpoint;
use flexdem_io::output::same_file;
use flexdem_io::scene::sphere_file::{in_space_order, write_spheres};

/// Centres and radii of the free spheres (not the nodes of structures).
fn free_spheres(p: &Particles) -> Vec<(Vec3, Real)> {
    (0..p.len())
        .filter(|&i| p.kind[i] == ParticleKind::Sphere)
        .map(|i| (p.pos[i], p.radius[i]))
        .collect()
}

/// Writes the free spheres of `args.input` (a `.toml` scene, built; anything else is read as
/// a checkpoint) to `args.output`, in the order of space.
pub fn spheres(args: &SpheresArgs) -> Result<Outcome, CliError> {
    if same_file(&args.output, &args.input) {
        let shown = args.output.display();
        return Err(CliError::Input(format!("-o {shown}: that is the input file")));
    }
    let is_scene = args.input.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let mut spheres = if is_scene {
        free_spheres(&read_scene(&args.input)?.model.particles)
    } else {
        let checkpoint = read_checkpoint(&args.input)
            .map_err(|e| CliError::Input(format!("{}: {e}", args.input.display())))?;
        free_spheres(&checkpoint.state.model.particles)
    };
    in_space_order(&mut spheres);
    std::fs::write(&args.output, write_spheres(&spheres))
        .map_err(|e| CliError::Run(format!("cannot write {}: {e}", args.output.display())))?;
    println!("{}: {} written", args.output.display(), plural(spheres.len(), "sphere"));
    Ok(Outcome::Done)
}

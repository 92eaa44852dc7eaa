//! `flexdem info SCENE`: what a scene holds (counts, masses, materials) and how it will run
//! (time step, run length, output).

use super::common::{build_simulation, describe_run, read_scene};
use crate::cli::SceneArgs;
use crate::error::{CliError, Outcome};
use crate::report::plural;
use flexdem_contact::{ContactDamping, Material};
use flexdem_elements::ParticleKind;
use flexdem_integrate::{Simulation, TimeStep};
use flexdem_io::scene::RunLength;
use flexdem_run::Counts;
use std::path::Path;

/// Names of the materials of the scene file at `path`, in the order of the model's material
/// ids (the scene builder adds them sorted by name); `#i` for each when the file's
/// `[materials]` do not match `materials` one to one (density and Young's modulus).
fn material_names(path: &Path, materials: &[Material]) -> Vec<String> {
    let fallback = || (0..materials.len()).map(|i| format!("#{i}")).collect();
    let Ok(text) = std::fs::read_to_string(path) else { return fallback() };
    let Ok(table) = text.parse::<toml::Table>() else { return fallback() };
    let Some(toml::Value::Table(defined)) = table.get("materials") else { return fallback() };
    let mut names: Vec<(&String, &toml::Value)> = defined.iter().collect();
    names.sort_by(|a, b| a.0.cmp(b.0));
    let number = |v: &toml::Value, key: &str| match v.get(key) {
        Some(toml::Value::Float(x)) => Some(*x),
        Some(toml::Value::Integer(i)) => Some(*i as f64),
        _ => None,
    };
    let matches = names.len() == materials.len()
        && names.iter().zip(materials).all(|((_, v), m)| {
            number(v, "density") == Some(m.density) && number(v, "young") == Some(m.young)
        });
    if matches {
        names.into_iter().map(|(n, _)| n.clone()).collect()
    } else {
        fallback()
    }
}

/// The sum of `masses`, 0 (not the -0 of `f64::sum`, printed `-0.000000e0`) when empty.
fn total(masses: impl Iterator<Item = f64>) -> f64 {
    masses.fold(0.0, |a, m| a + m)
}

/// A material in one line.
fn describe_material(m: &Material) -> String {
    let strength = |s: Option<f64>| match s {
        Some(x) => format!("{x:.3e} Pa"),
        None => "unbreakable".into(),
    };
    let damping = match m.damping {
        ContactDamping::None => String::new(),
        ContactDamping::Restitution(e) => format!(", restitution {e}"),
        ContactDamping::Viscous { gamma_n, gamma_t } => {
            format!(", damping γn = {gamma_n} /s, γt = {gamma_t} /s")
        }
    };
    format!(
        "E = {:.3e} Pa, ν = {}, ρ = {} kg/m³, friction {:.1}°, tensile {}, shear {}{damping}",
        m.young,
        m.poisson,
        m.density,
        m.friction_angle.to_degrees(),
        strength(m.tensile_strength),
        strength(m.shear_strength)
    )
}

/// The number of steps of `run` at the current time step of `sim` (an estimate for a
/// duration: an automatic step shrinks as contacts stiffen).
fn steps_of(run: RunLength, sim: &Simulation) -> String {
    match run {
        RunLength::Steps(n) => format!("{n} steps"),
        RunLength::Duration(d) => {
            let auto = matches!(sim.settings().time_step, TimeStep::Auto { .. });
            format!(
                "about {} steps at the initial dt{}",
                (d / sim.dt()).ceil(),
                if auto { " (more if contacts lower the automatic step)" } else { "" }
            )
        }
    }
}

/// Prints what the scene of `args` holds and how it will run.
pub fn info(args: &SceneArgs) -> Result<Outcome, CliError> {
    let scene = read_scene(&args.scene)?;
    let (sim, rest) = build_simulation(scene)?;
    let m = &sim.model();
    let p = &m.particles;
    let c = Counts::of(&sim);
    println!("scene: {}", args.scene.display());
    println!(
        "particles: {} ({}, {}); connections: {}; PFacets: {}; walls: {}",
        c.particles,
        plural(c.spheres, "sphere"),
        plural(c.nodes, "node"),
        c.connections,
        c.pfacets,
        c.walls
    );
    println!("structures: {}", m.structures.len());
    for s in &m.structures {
        let mass = total((s.nodes.start..s.nodes.end).map(|i| p.mass[i as usize]));
        println!(
            "  {}: {} nodes, {} connections, {} PFacets, mass {:.6e} kg",
            s.name,
            s.nodes.len(),
            s.connections.len(),
            s.pfacets.len(),
            mass
        );
    }
    let sphere_mass =
        total((0..p.len()).filter(|&i| p.kind[i] == ParticleKind::Sphere).map(|i| p.mass[i]));
    println!("spheres: {}, mass {:.6e} kg", c.spheres, sphere_mass);
    println!("total mass: {:.6e} kg", m.total_mass() + 0.0);
    println!("materials: {}", m.materials.len());
    for (name, material) in material_names(&args.scene, &m.materials).iter().zip(&m.materials) {
        println!("  {name}: {}", describe_material(material));
    }
    let rule = match sim.settings().time_step {
        TimeStep::Auto { safety } => {
            format!("auto: {safety} × critical, recomputed as contacts change")
        }
        TimeStep::Fixed(dt) => format!("fixed {dt:.3e} s"),
    };
    println!("critical dt: {:.6e} s", sim.critical_dt());
    println!("dt used: {:.6e} s ({rule})", sim.dt());
    for warning in sim.warnings() {
        println!("warning: {warning}");
    }
    println!("run length: {} = {}", describe_run(rest.run), steps_of(rest.run, &sim));
    let g = sim.settings().gravity;
    println!(
        "gravity: [{}, {}, {}] m/s²; damping: {}; threads: {}",
        g.x,
        g.y,
        g.z,
        sim.settings().damping,
        match rest.threads {
            Some(n) => n.to_string(),
            None => format!("machine default ({})", rayon::current_num_threads()),
        }
    );
    let o = &rest.output;
    let every = |e: Option<u64>| e.map_or("never".to_string(), |n| format!("every {n} steps"));
    println!(
        "output: {}; VTK frames {}; series {} ({}); plot: {}",
        o.directory.display(),
        every(o.vtk_every),
        every(o.series_every),
        if o.series.is_empty() {
            "none".to_string()
        } else {
            o.series.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", ")
        },
        if o.plot { "yes" } else { "no" }
    );
    Ok(Outcome::Done)
}

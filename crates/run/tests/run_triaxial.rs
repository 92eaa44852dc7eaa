//! The `triaxial` series quantity against known answers: the strains of platens moved at a
//! known speed between fixed rigid walls, a hydrostatic state (q = 0, p equal to every
//! wall's stress), and a membrane's confining stress equal to its pressure load's ramp.

use flexdem_integrate::normal_force;
use flexdem_output::triaxial::{triaxial_state, TriaxialSpec, TRIAXIAL_COLUMNS};
use flexdem_output::Quantity;
use flexdem_run::{NoObserver, Run, RunOptions};
use flexdem_scene::parse_scene;

const MATERIALS: &str = r#"
[materials.grain]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 0
"#;

/// Six walls around a 3 × 3 × 3 lattice of spheres of radius 0.01 (spacing 0.02, touching),
/// each wall `push` (m) inside the lattice's box, the top one moving at `v_top` (m/s).
fn box_scene(push: f64, v_top: f64, steps: u64) -> String {
    let lo = push;
    let hi = 0.06 - push;
    format!(
        r#"
[simulation]
steps = {steps}
dt = 1e-5
energy_tolerance = "off"
{MATERIALS}
[[spheres]]
kind = "lattice"
material = "grain"
box = {{ min = [0, 0, 0], max = [0.06, 0.06, 0.06] }}
radius = 0.01

[[walls]]
point = [0, 0, {lo}]
normal = [0, 0, 1]
material = "grain"
[[walls]]
point = [0, 0, {hi}]
normal = [0, 0, -1]
material = "grain"
velocity = [0, 0, {v}]
[[walls]]
point = [{lo}, 0, 0]
normal = [1, 0, 0]
material = "grain"
[[walls]]
point = [{hi}, 0, 0]
normal = [-1, 0, 0]
material = "grain"
[[walls]]
point = [0, {lo}, 0]
normal = [0, 1, 0]
material = "grain"
[[walls]]
point = [0, {hi}, 0]
normal = [0, -1, 0]
material = "grain"

[output]
series_every = 1

[[output.series]]
name = "tx"
quantity = "triaxial"
walls = [0, 1]
lateral_walls = [2, 3, 4, 5]
"#,
        v = -v_top
    )
}

fn run_of(text: &str) -> Run {
    let dir = std::env::temp_dir();
    let scene = parse_scene(text, &dir.join("triaxial.toml")).unwrap_or_else(|e| panic!("{e}"));
    Run::new(scene, RunOptions { no_output: true, ..RunOptions::default() }).unwrap()
}

fn spec(run: &Run) -> TriaxialSpec {
    match &run.output_settings().series[0].quantity {
        Quantity::Triaxial(spec) => spec.clone(),
        other => panic!("not a triaxial series: {other:?}"),
    }
}

#[test]
fn platens_moved_at_a_known_speed_give_the_strains_and_the_columns_are_named() {
    // the walls just clear of the lattice: no contact, a pure kinematic check
    let mut run = run_of(&box_scene(-0.001, 0.05, 200));
    let s = spec(&run);
    assert!((s.height0 - 0.062).abs() < 1e-15 && (s.volume0 - 0.062f64.powi(3)).abs() < 1e-15);
    run.advance(None, &mut NoObserver).unwrap();
    let state = triaxial_state(run.sim(), &s).unwrap();
    let values = state.values(&s);
    let t = run.sim().time();
    let ea = 0.05 * t / 0.062;
    assert!((values[0] - ea).abs() < 1e-12, "axial strain {} vs {ea}", values[0]);
    // rigid lateral walls at rest: the volume changes as the height does
    assert!((values[1] - ea).abs() < 1e-12, "volumetric strain {} vs {ea}", values[1]);
    assert_eq!(values[2..6], [0.0; 4], "no contact, no stress");
    let summary = run.finish(&mut NoObserver).unwrap();
    let names: Vec<&str> = summary.tracked["tx"].keys().map(String::as_str).collect();
    for (column, _) in TRIAXIAL_COLUMNS {
        assert!(names.iter().any(|n| n.starts_with(&format!("tx_{column}"))), "{names:?}");
    }
}

#[test]
fn a_hydrostatic_lattice_has_no_deviator_and_the_walls_stress_as_mean_stress() {
    let mut run = run_of(&box_scene(1e-4, 0.0, 1));
    let s = spec(&run);
    run.advance(None, &mut NoObserver).unwrap();
    let sim = run.sim();
    let state = triaxial_state(sim, &s).unwrap();
    // nine spheres press each wall by the same overlap: the same force on all six
    let walls = &sim.model().walls;
    let f: Vec<f64> = (0..6).map(|w| normal_force(&walls[w], &sim.wall_forces()[w])).collect();
    assert!(f[0] > 0.0);
    for w in 1..6 {
        assert!((f[w] - f[0]).abs() <= 1e-12 * f[0], "wall {w}: {} vs {}", f[w], f[0]);
    }
    let side = 0.06 - 2e-4;
    let sigma = f[0] / (side * side);
    assert!((state.axial_stress - sigma).abs() <= 1e-12 * sigma);
    assert!((state.confining_stress - sigma).abs() <= 1e-12 * sigma);
    assert!((state.mean_stress() - sigma).abs() <= 1e-12 * sigma);
    assert!(state.deviator_stress().abs() <= 1e-12 * sigma);
}

#[test]
fn a_membrane_reads_the_confining_pressure_of_its_ramp_and_its_volume() {
    let text = format!(
        r#"
[simulation]
steps = 50
dt = 1e-5
{MATERIALS}
[[structures]]
name = "membrane"
kind = "tube"
material = "grain"
node_radius = 0.001
start = [0, 0, 0.001]
axis = [0, 0, 1]
radius = 0.05
length = 0.098
around = 24
along = 10

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "grain"
[[walls]]
point = [0, 0, 0.1]
normal = [0, 0, -1]
material = "grain"

[[pressures]]
structure = "membrane"
pressure = 5e3
flip = true
ramp = {{ start = 0, duration = 1e-3 }}

[output]
series_every = 10

[[output.series]]
name = "tx"
quantity = "triaxial"
walls = [0, 1]
of = {{ structure = "membrane" }}
"#
    );
    let mut run = run_of(&text);
    let s = spec(&run);
    // the volume of the 24-gon prism between the platens, (24/2)·R²·sin(2π/24)·H (the end
    // rings a node radius off the platens closed by ribbons to them), less the node radius
    // times the area of the PFacets (24 rectangles of side 2R·sin(π/24) by 0.098)
    let mid = 12.0 * 0.05f64.powi(2) * (2.0 * std::f64::consts::PI / 24.0).sin() * 0.1;
    let side = 2.0 * 0.05 * (std::f64::consts::PI / 24.0).sin();
    let prism = mid - 0.001 * 24.0 * side * 0.098;
    assert!((s.volume0 - prism).abs() < 1e-12 * prism, "{} vs {prism}", s.volume0);
    assert!((s.height0 - 0.1).abs() < 1e-15);
    run.advance(None, &mut NoObserver).unwrap();
    let state = triaxial_state(run.sim(), &s).unwrap();
    let t = run.sim().time();
    let expected = 5e3 * (t / 1e-3).min(1.0);
    assert!((state.confining_stress - expected).abs() < 1e-9 * 5e3, "{}", state.confining_stress);
    // pressed inward, the membrane encloses less
    assert!(state.volume < s.volume0);
}

/// A small membrane sample (about 600 spheres in a tube of PFacets between two platens)
/// consolidated isotropically to 100 kPa by the membrane's pressure and a servo platen.
const CONSOLIDATION: &str = r#"
[simulation]
duration = 0.03
damping = 0.3
energy_tolerance = 0.05

[materials.sand]
young = 1e8
poisson = 0.3
density = 26500
friction_angle_deg = 30

[materials.membrane]
young = 10e6
poisson = 0.45
density = 1000
friction_angle_deg = 0

[materials.platen]
young = 1e9
poisson = 0.3
density = 7850
friction_angle_deg = 0

[[structures]]
name = "membrane"
kind = "tube"
material = "membrane"
node_radius = 0.001
start = [0, 0, 0.001]
axis = [0, 0, 1]
radius = 0.026
length = 0.098
around = 24
along = 14

[[spheres]]
kind = "dense"
material = "sand"
cylinder = { start = [0, 0, 0], axis = [0, 0, 1], radius = 0.025, length = 0.1 }
radius_range = [1, 2]
count = 600
solid_fraction = 0.55
seed = 3

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "platen"

[[walls]]
point = [0, 0, 0.1]
normal = [0, 0, -1]
material = "platen"
servo = { stress = 1e5, area_of = { membrane = "membrane", platens = [0, 1] }, max_speed = 0.1 }

[[pressures]]
structure = "membrane"
pressure = 1e5
flip = true
ramp = { start = 0, duration = 0.01 }

[output]
series_every = 100

[[output.series]]
name = "tx"
quantity = "triaxial"
walls = [0, 1]
of = { structure = "membrane" }
"#;

#[test]
fn after_isotropic_consolidation_the_grains_stress_is_the_confining_pressure() {
    use flexdem_integrate::{love_weber_stress, mean_stress, Region};
    let mut run = run_of(CONSOLIDATION);
    let s = spec(&run);
    run.advance(None, &mut NoObserver).unwrap();
    let sim = run.sim();
    let state = triaxial_state(sim, &s).unwrap();
    assert_eq!(state.confining_stress, 1e5);
    // the grains' stress over the sample's volume (inside the membrane, between the platens)
    let region = Region::Cylinder {
        start: flexdem_geom::Vec3::new(0.0, 0.0, -0.01),
        axis: flexdem_geom::Vec3::z(),
        radius: 0.04,
        length: 0.12,
    };
    let sigma = love_weber_stress(sim.model(), &sim.contacts(), &region, Some(state.volume));
    let p = mean_stress(&sigma);
    // the platen's stress over the sample's cross-section (the servo follows it: `area_of`)
    // and the grains' mean stress, each within 3 % of the confining pressure
    let platen = state.axial_stress;
    eprintln!(
        "platen {platen} p {p} V {} V0 {} H {} H0 {}",
        state.volume, s.volume0, state.height, s.height0
    );
    assert!((platen / 1e5 - 1.0).abs() < 0.03, "platen stress {platen}");
    assert!((p / 1e5 - 1.0).abs() < 0.03, "Love–Weber mean stress {p}, σ = {sigma}");
    let e = sim.energy();
    assert!(sim.energy_watch().relative_error(e).abs() < 1e-2, "energy balance");
}

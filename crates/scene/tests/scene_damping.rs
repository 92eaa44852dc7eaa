//! The viscous contact damping keys of `[materials.<name>]` (`restitution`, `gamma_n`,
//! `gamma_t`; model.md §7): read, combined on contact, and refused with the key named.

use flexdem_contact::{damping_ratio, ContactDamping};
use flexdem_geom::Real;
use flexdem_integrate::Simulation;
use flexdem_scene::{parse_scene, SceneError};
use std::f64::consts::PI;
use std::path::Path;

/// A scene with the materials `extra` and a sphere of material `ball` resting on a wall of
/// material `floor`, already overlapping it.
fn scene_text(extra: &str) -> String {
    format!(
        r#"
[simulation]
dt = 1e-6
steps = 1

{extra}

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "floor"

[[spheres]]
kind = "single"
material = "ball"
center = [0, 0, 0.0099]
radius = 0.01
"#
    )
}

const ELASTIC: &str = "young = 1e8\npoisson = 0.3\ndensity = 2650\nfriction_angle_deg = 30\n";

fn material(name: &str, keys: &str) -> String {
    format!("[materials.{name}]\n{ELASTIC}{keys}\n")
}

fn error(text: &str) -> (SceneError, String) {
    let err = parse_scene(text, Path::new("s.toml")).unwrap_err();
    let message = err.to_string();
    (err, message)
}

#[test]
fn the_keys_are_read_into_the_material() {
    let text = scene_text(&format!(
        "{}{}",
        material("ball", "restitution = 0.5"),
        material("floor", "gamma_n = 2000\ngamma_t = 1000")
    ));
    let s = parse_scene(&text, Path::new("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let damping: Vec<ContactDamping> = s.model.materials.iter().map(|m| m.damping).collect();
    assert_eq!(
        damping,
        [
            ContactDamping::Restitution(0.5),
            ContactDamping::Viscous { gamma_n: 2000.0, gamma_t: 1000.0 }
        ]
    );
    // one rate alone: the other is 0
    let text =
        scene_text(&format!("{}{}", material("ball", "gamma_t = 10"), material("floor", "")));
    let s = parse_scene(&text, Path::new("s.toml")).unwrap();
    assert_eq!(
        s.model.materials[0].damping,
        ContactDamping::Viscous { gamma_n: 0.0, gamma_t: 10.0 }
    );
    assert_eq!(s.model.materials[1].damping, ContactDamping::None);
}

/// On contact, each dashpot is the larger of the two materials' with the pair's effective
/// mass (here the sphere's: the wall is infinitely massive): cn from the ball's restitution,
/// ct from the floor's γt.
#[test]
fn a_contact_takes_the_larger_dashpot_of_its_two_materials() {
    let text = scene_text(&format!(
        "{}{}",
        material("ball", "restitution = 0.5"),
        material("floor", "gamma_n = 1\ngamma_t = 1e5")
    ));
    let s = parse_scene(&text, Path::new("s.toml")).unwrap();
    let mut sim = Simulation::new(s.model, s.settings).unwrap();
    sim.step().unwrap();
    let contacts = sim.contacts();
    let c = &contacts[0];
    let m: Real = 4.0 / 3.0 * PI * 0.01f64.powi(3) * 2650.0;
    assert!((sim.model().particles.mass[0] / m - 1.0).abs() < 1e-12);
    let cn = 2.0 * damping_ratio(0.5) * (m * c.params.kn).sqrt();
    assert!((c.params.cn / cn - 1.0).abs() < 1e-12, "{:?}", c.params);
    assert!((c.params.ct / (m * 1e5) - 1.0).abs() < 1e-12, "{:?}", c.params);
    // without damping keys the contact has no dashpot
    let text = scene_text(&format!("{}{}", material("ball", ""), material("floor", "")));
    let s = parse_scene(&text, Path::new("s.toml")).unwrap();
    let mut sim = Simulation::new(s.model, s.settings).unwrap();
    sim.step().unwrap();
    assert!(!sim.contacts()[0].params.is_damped());
}

#[test]
fn bad_values_name_the_key_and_the_line() {
    let floor = material("floor", "");
    let cases = [
        (
            "restitution = 0",
            "materials.ball.restitution",
            "is 0: expected a coefficient of restitution with 0 < restitution <= 1",
        ),
        ("restitution = 1.5", "materials.ball.restitution", "is 1.5"),
        ("restitution = -0.5", "materials.ball.restitution", "0 < restitution <= 1"),
        ("restitution = nan", "materials.ball.restitution", "is NaN"),
        ("gamma_n = -3", "materials.ball.gamma_n", "is -3: expected a finite number >= 0 (1/s"),
        ("gamma_t = nan", "materials.ball.gamma_t", "is NaN"),
        ("gamma_t = inf", "materials.ball.gamma_t", "is inf"),
        (
            "restitution = 0.5\ngamma_t = 100",
            "materials.ball.gamma_t",
            "conflicts with `restitution`",
        ),
        ("gamma_n = 100\nrestitution = 0.5", "materials.ball.gamma_n", "not both"),
        ("damping_ratio = 0.2", "materials.ball.damping_ratio", "unknown field `damping_ratio`"),
    ];
    for (keys, key, fragment) in cases {
        let text = scene_text(&format!("{}{floor}", material("ball", keys)));
        let (err, message) = error(&text);
        let SceneError::At { key: k, line, .. } = &err else { panic!("{err:?}") };
        assert_eq!(k, key, "{message}");
        // the line of the bad key: the material table starts on line 6, its keys after 4 lines
        let bad = keys.lines().position(|l| key.ends_with(l.split(' ').next().unwrap())).unwrap();
        assert_eq!(*line, 6 + 5 + bad, "{message}");
        assert!(message.contains(&format!("`{key}`")) && message.contains(fragment), "{message}");
    }
}

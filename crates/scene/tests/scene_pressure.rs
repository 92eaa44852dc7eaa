//! `[[pressures]]` and the `volume` series: what they build, and errors that give the line
//! and the key.

use flexdem_integrate::Ramp;
use flexdem_output::Quantity;
use flexdem_scene::{parse_scene, Scene};
use std::path::Path;

/// Materials, a sphere shell (structure 0), a tube along z between two walls (structure 1,
/// walls 0 and 1), and a net (structure 2, no PFacets).
const HEAD: &str = r#"[simulation]
steps = 1

[materials.m]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[structures]]
name = "shell"
kind = "sphere_shell"
material = "m"
node_radius = 0.002
center = [0, 0, 2]
radius = 0.1
subdivisions = 1

[[structures]]
name = "membrane"
kind = "tube"
material = "m"
node_radius = 0.002
start = [0, 0, 0]
axis = [0, 0, 1]
radius = 0.1
length = 0.5
around = 12
along = 5

[[structures]]
name = "net"
kind = "net"
material = "m"
node_radius = 0.002
origin = [1, 1, 0]
size = [0.5, 0.5]
cells = [2, 2]

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "m"

[[walls]]
point = [0, 0, 0.5]
normal = [0, 0, -1]
material = "m"
"#;

/// Lines of HEAD, so that errors in the body are at HEAD_LINES + their line in the body.
fn head_lines() -> usize {
    HEAD.lines().count()
}

fn scene(body: &str) -> Scene {
    parse_scene(&format!("{HEAD}{body}"), Path::new("p.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// The error of HEAD + `body`, checked to point at line `line` of `body` (1-based) and to
/// name `key`.
fn error(body: &str, line: usize, key: &str) -> String {
    let message = match parse_scene(&format!("{HEAD}{body}"), Path::new("p.toml")) {
        Ok(_) => panic!("no error for:\n{body}"),
        Err(e) => e.to_string(),
    };
    println!("{message}");
    let at = format!("p.toml:{}:", head_lines() + line);
    assert!(message.starts_with(&at), "expected {at}…: {message}");
    assert!(message.contains(&format!("`{key}`")), "expected key `{key}`: {message}");
    message
}

#[test]
fn a_pressure_on_a_structure_loads_all_its_pfacets() {
    let s = scene(
        r#"
[[pressures]]
structure = "shell"
pressure = 1e5
flip = true
ramp = { start = 0.1, duration = 0.5 }

[[pressures]]
structure = "membrane"
pressure = -2.5e3
"#,
    );
    assert_eq!(s.pressures.len(), 2);
    let shell = &s.pressures[0];
    let range = s.model.structures[0].pfacets.clone();
    assert_eq!(shell.pfacets, range.collect::<Vec<_>>());
    assert_eq!(shell.pfacets.len(), 80);
    assert_eq!((shell.pressure, shell.flip), (1e5, true));
    assert_eq!(shell.ramp, Ramp::Linear { start: 0.1, duration: 0.5 });
    let tube = &s.pressures[1];
    assert_eq!(tube.pfacets.len(), 2 * 12 * 5);
    assert_eq!((tube.pressure, tube.flip, tube.ramp), (-2.5e3, false, Ramp::Constant));
}

#[test]
fn a_pressure_on_a_selection_loads_the_pfacets_whose_three_nodes_it_picks() {
    let s = scene(
        r#"
[[pressures]]
select = { structure = "membrane", box = { min = [-1, -1, -0.01], max = [1, 1, 0.21] } }
pressure = 1e3
"#,
    );
    // rings at z = 0, 0.1, ..., 0.5: the box holds rings 0 to 2, so the two lowest bands
    let pfacets = &s.pressures[0].pfacets;
    assert_eq!(pfacets.len(), 2 * 12 * 2);
    for &f in pfacets {
        for n in s.model.pfacets[f as usize].nodes {
            assert!(s.model.particles.pos[n as usize].z <= 0.21);
        }
    }
}

#[test]
fn bad_pressures_name_the_key_and_line() {
    let m =
        error("\n[[pressures]]\nstructure = \"shel\"\npressure = 1e5\n", 3, "pressures.structure");
    assert!(m.contains("unknown structure `shel`") && m.contains("did you mean `shell`?"), "{m}");
    let m =
        error("\n[[pressures]]\nstructure = \"shell\"\npresure = 1e5\n", 4, "pressures.presure");
    assert!(m.contains("unknown field") && m.contains("did you mean `pressure`?"), "{m}");
    let m =
        error("\n[[pressures]]\nstructure = \"net\"\npressure = 1e5\n", 3, "pressures.structure");
    assert!(m.contains("structure `net` has no PFacets"), "{m}");
    let m =
        error("\n[[pressures]]\nstructure = \"shell\"\npressure = nan\n", 4, "pressures.pressure");
    assert!(m.contains("expected a finite number (Pa)"), "{m}");
    let both =
        "\n[[pressures]]\nstructure = \"shell\"\nselect = { structure = \"net\" }\npressure = 1\n";
    assert!(error(both, 4, "pressures.select").contains("not both"));
    let none = "\n[[pressures]]\nselect = { structure = \"net\" }\npressure = 1\n";
    assert!(error(none, 3, "pressures.select").contains("holds no PFacet"));
    let ramp = "\n[[pressures]]\nstructure = \"shell\"\npressure = 1\nramp = { start = 0, duration = 0 }\n";
    assert!(error(ramp, 5, "pressures.ramp.duration").contains("expected a finite number > 0"));
    let missing = "\n[[pressures]]\npressure = 1\n";
    assert!(error(missing, 2, "pressures").contains("give `structure = \"name\"` or `select"));
}

/// Series with the head's `[output]` table.
fn series(entries: &str) -> String {
    format!("\n[output]\nseries_every = 10\n{entries}")
}

#[test]
fn the_volume_series_of_a_structure_closed_by_walls() {
    let s = scene(&series(
        r#"
[[output.series]]
name = "sample"
quantity = "volume"
of = { structure = "membrane" }
walls = [1, 0]

[[output.series]]
name = "balloon"
quantity = "volume"
of = { structure = "shell" }
"#,
    ));
    let quantities: Vec<&Quantity> = s.output.series.iter().map(|x| &x.quantity).collect();
    assert_eq!(
        quantities,
        [
            &Quantity::EnclosedVolume { structure: 1, walls: vec![1, 0] },
            &Quantity::EnclosedVolume { structure: 0, walls: vec![] }
        ]
    );
}

#[test]
fn bad_volume_series_name_the_key_and_line() {
    let entry = |of: &str, walls: &str| {
        series(&format!("\n[[output.series]]\nname = \"v\"\nquantity = \"volume\"\n{of}{walls}"))
    };
    // lines of the body: 1 blank, 2 [output], 3 series_every, 4 blank, 5 [[output.series]],
    // 6 name, 7 quantity, 8 of, 9 walls
    let m = error(&entry("of = { structure = \"membrane\" }\n", ""), 8, "output.series.of");
    assert!(
        m.contains("not closed") && m.contains("2 boundary loops") && m.contains("walls = [i, j]"),
        "{m}"
    );
    let m = error(
        &entry("of = { structure = \"membrane\" }\n", "walls = [0, 3]\n"),
        9,
        "output.series.walls",
    );
    assert!(m.contains("wall 3 does not exist: the scene has 2 [[walls]]"), "{m}");
    let m = error(
        &entry("of = { structure = \"shell\" }\n", "walls = [0]\n"),
        9,
        "output.series.walls",
    );
    assert!(m.contains("1 closing planes were given for 0 boundary loops"), "{m}");
    let m = error(
        &entry("of = { structure = \"membrane\" }\n", "walls = [0, 0]\n"),
        9,
        "output.series.walls",
    );
    assert!(m.contains("wall 0 is given twice"), "{m}");
    let m = error(
        &entry("of = { structure = \"membrane\", side = \"ends\" }\n", ""),
        8,
        "output.series.of",
    );
    assert!(m.contains("needs `of = { structure = \"name\" }`"), "{m}");
    let m =
        error(&entry("of = { structure = \"membran\" }\n", ""), 8, "output.series.of.structure");
    assert!(m.contains("did you mean `membrane`?"), "{m}");
    let m = error(&entry("of = { structure = \"net\" }\n", ""), 8, "output.series.of");
    assert!(m.contains("has no PFacets"), "{m}");
    let energy = series("\n[[output.series]]\nname = \"e\"\nquantity = \"energy\"\nwalls = [0]\n");
    assert!(error(&energy, 8, "output.series.walls")
        .contains("applies to quantity = \"volume\" or \"triaxial\" only"));
}

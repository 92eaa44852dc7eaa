//! Seeded mutation fuzzing of every input flexdem reads (cargo-fuzz needs a nightly compiler):
//! the example scenes (and one scene using the other builders and a mesh), every valid test
//! mesh through every mesh reader, and a checkpoint written by a small simulation (its payload
//! mutated, then usually its length and checksum recomputed so that the decoder and the
//! engine's checks see it). Mutations: bit flips, byte writes, insertions of random bytes
//! and of tokens (TOML syntax, non-ASCII characters, a BOM, NUL), deletions, splices from the
//! other files, duplications, truncations, swapped lines, and number mutations (huge, tiny,
//! NaN, infinite, negative, non-ASCII digits; in binary data, 8-byte NaN/huge/negative
//! values and bincode length prefixes).
//!
//! Every input must give `Ok` or an error, never a panic, an abort or a hang: each runs under
//! `catch_unwind`, and the failures are listed at the end with the seed and index that
//! replay them and the input saved under `CARGO_TARGET_TMPDIR/fuzz-failures/`. An accepted
//! scene or checkpoint is then built into a simulation and stepped twice; an accepted mesh
//! must be well formed; errors must name the file (scenes: `file:line:column`).
//!
//! The normal tests run a short seeded run (`short_seeded_fuzz`). The long run:
//!
//! ```sh
//! FLEXDEM_FUZZ_RUNS=1000000 cargo test --release -p flexdem-io --test input_fuzz -- --ignored --nocapture
//! ```
//!
//! (`FLEXDEM_FUZZ_SEED` changes the seed; `FLEXDEM_FUZZ_TARGET` = scene, mesh or checkpoint
//! runs one target only.)

mod support;

use flexdem_integrate::Simulation;
use flexdem_io::checkpoint::{
    read_checkpoint, restore_checkpoint, write_checkpoint, Checkpoint, OutputProgress,
    CHECKPOINT_HEADER_LEN,
};
use flexdem_io::scene::{load_scene, parse_scene, Scene, SceneError};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use support::meshes::{reader_for, valid_bytes, well_formed, READERS, VALID};

/// splitmix64: a small seeded generator, the same on every platform.
struct Rng(u64);

impl Rng {
    fn new(seed: u64, index: u64) -> Self {
        let mut r = Rng(seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        r.next();
        r
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// A number in `0..n` (0 for n = 0).
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
    fn chance(&mut self, one_in: usize) -> bool {
        self.below(one_in) == 0
    }
}

/// Tokens inserted into text inputs.
const TOKENS: [&str; 30] = [
    "=",
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    ",",
    "\"",
    "'",
    "\n",
    "#",
    ".",
    "-",
    "·",
    "é",
    "日本",
    "\u{FEFF}",
    "\0",
    "\r\n",
    "\t",
    "\"\"\"",
    "=\"a·b = 1",
    "[simulation]",
    "[[structures]]",
    "kind = \"helix\"",
    "true",
    "inf",
    "nan",
    "\u{1F600}",
];

/// Numbers written over a number of a text input.
const NUMBERS: [&str; 36] = [
    "0",
    "-0",
    "1",
    "-1",
    "2",
    "3",
    "1e308",
    "-1e308",
    "1e-308",
    "5e-324",
    "1e-300",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "9223372036854775807",
    "-9223372036854775808",
    "18446744073709551615",
    "4294967295",
    "4294967296",
    "2147483648",
    "1000000",
    "100000000",
    "1e9",
    "0.0000001",
    "1·5",
    "１",
    "٣",
    "½",
    "1e",
    "0x10",
    "1_000",
    ".5",
    "1e+400",
    "-1e-9",
];

/// Interesting 8-byte values written into binary data.
const WORDS: [u64; 12] = [
    0,
    u64::MAX,
    u64::MAX / 2,
    1 << 32,
    1 << 40,
    0x7FF8_0000_0000_0000, // NaN
    0x7FF0_0000_0000_0000, // +inf
    0xFFF0_0000_0000_0000, // -inf
    0xBFF0_0000_0000_0000, // -1.0
    0x7FE1_CCF3_85EB_C8A0, // 1e307
    0x0000_0000_0000_0001, // the smallest subnormal
    0x8000_0000_0000_0000, // -0.0
];

/// A number token of `text` (a run of digits with its sign, point and exponent) at random.
fn number_span(text: &[u8], rng: &mut Rng) -> Option<(usize, usize)> {
    let starts: Vec<usize> = (0..text.len())
        .filter(|&i| text[i].is_ascii_digit() && (i == 0 || !text[i - 1].is_ascii_alphanumeric()))
        .collect();
    let &start = starts.get(rng.below(starts.len()))?;
    let mut start = start;
    if start > 0 && (text[start - 1] == b'-' || text[start - 1] == b'+') {
        start -= 1;
    }
    let mut end = start + 1;
    while end < text.len()
        && (text[end].is_ascii_digit() || b".eE_".contains(&text[end]) || {
            (text[end] == b'-' || text[end] == b'+') && b"eE".contains(&text[end - 1])
        })
    {
        end += 1;
    }
    Some((start, end))
}

/// One random mutation of `bytes`; `others` are the other inputs of the same target (for
/// splices); `binary` chooses the number mutations of binary data.
fn mutate(bytes: &mut Vec<u8>, others: &[Vec<u8>], binary: bool, rng: &mut Rng) -> String {
    let len = bytes.len();
    let at = rng.below(len + 1);
    match rng.below(11) {
        0 if len > 0 => {
            let i = rng.below(len);
            let bit = rng.below(8);
            bytes[i] ^= 1 << bit;
            format!("flip bit {bit} of byte {i}")
        }
        1 if len > 0 => {
            let i = rng.below(len);
            let b = rng.next() as u8;
            bytes[i] = b;
            format!("byte {i} = {b:#04x}")
        }
        2 => {
            let n = 1 + rng.below(8);
            let inserted: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
            bytes.splice(at..at, inserted.iter().copied());
            format!("insert {inserted:02x?} at {at}")
        }
        3 => {
            let token = TOKENS[rng.below(TOKENS.len())];
            bytes.splice(at..at, token.bytes());
            format!("insert {token:?} at {at}")
        }
        4 if len > 0 => {
            let n = 1 + rng.below(32);
            let end = (at + n).min(len);
            bytes.drain(at.min(len)..end);
            format!("delete {at}..{end}")
        }
        5 if !others.is_empty() => {
            let other = &others[rng.below(others.len())];
            let from = rng.below(other.len());
            let n = 1 + rng.below(64);
            let chunk = &other[from..(from + n).min(other.len())];
            let replace = rng.below(2) == 0;
            let end = if replace { (at + chunk.len()).min(len) } else { at };
            bytes.splice(at..end, chunk.iter().copied());
            format!("splice {} bytes at {at} (replacing {})", chunk.len(), end - at)
        }
        6 if len > 0 => {
            let from = rng.below(len);
            let n = 1 + rng.below(128);
            let chunk = bytes[from..(from + n).min(len)].to_vec();
            bytes.splice(at..at, chunk.iter().copied());
            format!("duplicate {} bytes from {from} at {at}", chunk.len())
        }
        7 | 8 if binary && len >= 8 => {
            let i = rng.below(len - 7);
            if rng.chance(3) {
                // a bincode varint prefix announcing a u64 (a length or a count)
                let word = WORDS[rng.below(WORDS.len())];
                let mut prefix = vec![253u8];
                prefix.extend_from_slice(&word.to_le_bytes());
                bytes.splice(i..i + 1, prefix);
                format!("varint u64 {word:#x} at {i}")
            } else {
                let word = WORDS[rng.below(WORDS.len())];
                bytes[i..i + 8].copy_from_slice(&word.to_le_bytes());
                format!("word {word:#x} at {i}")
            }
        }
        7 | 8 => match number_span(bytes, rng) {
            Some((start, end)) => {
                let old = String::from_utf8_lossy(&bytes[start..end]).into_owned();
                let new = match rng.below(4) {
                    0 => format!("-{old}"),
                    1 => format!("{old}e{}", [300, -300, 9, -9, 18][rng.below(5)]),
                    2 => format!("{old}{}", rng.below(1000)),
                    _ => NUMBERS[rng.below(NUMBERS.len())].to_string(),
                };
                bytes.splice(start..end, new.bytes());
                format!("number {old:?} -> {new:?} at {start}")
            }
            None => "no number".into(),
        },
        9 if len > 0 => {
            bytes.truncate(at);
            format!("truncate at {at}")
        }
        _ => {
            // swap two lines
            let lines: Vec<usize> = std::iter::once(0)
                .chain((0..len).filter(|&i| bytes[i] == b'\n').map(|i| i + 1))
                .filter(|&i| i < len)
                .collect();
            if lines.len() < 2 {
                return "no lines to swap".into();
            }
            let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
            let (a, b) = (a.min(b), a.max(b));
            if a == b {
                return "same line".into();
            }
            let end = |k: usize| lines.get(k + 1).copied().unwrap_or(len);
            let (la, lb) = (bytes[lines[a]..end(a)].to_vec(), bytes[lines[b]..end(b)].to_vec());
            let mut out = bytes[..lines[a]].to_vec();
            out.extend_from_slice(&lb);
            out.extend_from_slice(&bytes[end(a)..lines[b]]);
            out.extend_from_slice(&la);
            out.extend_from_slice(&bytes[end(b)..]);
            *bytes = out;
            format!("swap lines {a} and {b}")
        }
    }
}

/// A scene that uses the builders and selections the examples do not (helix, disc, sphere
/// shell, mesh, lattice spheres, plane and id selections, ramps, imposed velocities).
const EXTRA_SCENE: &str = r#"
[simulation]
dt = 1e-5
steps = 20
gravity = [0, 0, -9.81]
damping = 0.1
link_kinematics = "yade"
verlet_factor = 0.4

[materials.steel]
young = 2e8
poisson = 0.3
density = 7850
friction_angle_deg = 25
tensile_strength = 1e7
shear_strength = 1e7
failure = "plastic"

[[structures]]
name = "spring"
kind = "helix"
material = "steel"
node_radius = 0.004
radius = 0.05
pitch = 0.03
turns = 2
segments_per_turn = 10
placement = { translate = [0, 0, 1], rotate_deg = [0, 90, 0] }

[[structures]]
name = "plate"
kind = "disc"
material = "steel"
node_radius = 0.002
center = [1, 0, 0]
radius = 0.1
rings = 3
mass = "plate"

[[structures]]
name = "ball"
kind = "sphere_shell"
material = "steel"
node_radius = 0.002
center = [2, 0, 0]
radius = 0.1
base = "octahedron"
subdivisions = 1
velocity = [0, 0, -1]

[[structures]]
name = "cube"
kind = "mesh"
material = "steel"
node_radius = 0.01
file = "../crates/mesh/tests/data/meshes/cube.obj"
placement = { translate = [3, 0, 0], scale = 0.5, axis = [0, 0, 1], angle_deg = 30 }

[[structures]]
name = "pipe"
kind = "tube"
material = "steel"
node_radius = 0.002
start = [4, 0, 0]
axis = [0, 1, 0]
radius = 0.05
length = 0.3
around = 6
along = 4

[[spheres]]
name = "grains"
kind = "lattice"
material = "steel"
box = { min = [0, 1, 0], max = [0.2, 1.2, 0.2] }
radius = 0.02
spacing = 0.05

[[walls]]
point = [0, 0, -1]
normal = [0, 0, 1]
material = "steel"
velocity = [0, 0, 0.1]

[[boundary]]
select = { structure = "plate", plane = { point = [1, 0, 0], normal = [1, 0, 0], tolerance = 0.2 } }
block = "xyzXYZ"

[[boundary]]
select = { ids = [0, 1] }
velocity = [0, 0, 0.1]

[[loads]]
select = { structure = "pipe", side = "end" }
total_force = [0, 0, -1]
ramp = { start = 0, duration = 0.001 }

[output]
series_every = 5

[[output.series]]
name = "grain0"
quantity = "velocity"
of = { ids = [170] }
"#;

/// A small simulation with links, PFacets, contacts, a wall and a load, a few steps in.
const CHECKPOINT_SCENE: &str = r#"
[simulation]
dt = 1e-5
steps = 1000
gravity = [0, 0, -9.81]

[materials.m]
young = 1e6
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[structures]]
name = "sheet"
kind = "membrane"
material = "m"
node_radius = 0.005
size = [0.2, 0.2]
cells = [2, 2]

[[structures]]
name = "cable"
kind = "chain"
material = "m"
node_radius = 0.005
start = [0, 0, 0.1]
end = [0.2, 0, 0.1]
segments = 3

[[spheres]]
name = "ball"
kind = "single"
material = "m"
center = [0.1, 0.1, 0.0215]
radius = 0.016
velocity = [0, 0, -1]

[[walls]]
point = [0, 0, -0.05]
normal = [0, 0, 1]
material = "m"

[[boundary]]
select = { box = { min = [-1, -1, -1], max = [0.001, 1, 1] } }
block = "xyz"

[[loads]]
select = { structure = "cable", side = "end" }
force = [0, 0, -0.1]
"#;

/// What an input is fed to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    Scene,
    Mesh,
    Checkpoint,
}

/// The seed inputs of each target.
struct Corpus {
    /// (name, path the scene is read as, text).
    scenes: Vec<(String, PathBuf, Vec<u8>)>,
    meshes: Vec<(String, Vec<u8>)>,
    checkpoint: Vec<u8>,
    scratch: PathBuf,
}

fn examples_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Builds the simulation of a scene as `flexdem check` does, then steps it twice (when small).
fn build_and_step(scene: Scene) {
    let elements =
        scene.model.particles.len() + scene.model.connections.len() + scene.model.pfacets.len();
    let Ok(mut sim) = Simulation::new(scene.model, scene.settings) else { return };
    for load in scene.loads {
        if sim.add_load(load).is_err() {
            return;
        }
    }
    for pressure in scene.pressures {
        if sim.add_pressure(pressure).is_err() {
            return;
        }
    }
    if elements <= 20_000 {
        let _ = sim.run(2);
    }
}

/// The examples' dense packings made small and loose (300 spheres at 0.3) in the seeds: the
/// fuzzer explores the keys and values, and a 5 000-sphere packing per accepted input would
/// take most of its time.
fn small_packings(text: &[u8]) -> Vec<u8> {
    let text = String::from_utf8_lossy(text);
    if !text.contains("kind = \"dense\"") {
        return text.into_owned().into_bytes();
    }
    text.replace("count = 5000", "count = 300")
        .replace("solid_fraction = 0.6", "solid_fraction = 0.3")
        .into_bytes()
}

fn corpus(scratch: PathBuf) -> Corpus {
    let mut scenes: Vec<(String, PathBuf, Vec<u8>)> = std::fs::read_dir(examples_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                p.clone(),
                small_packings(&std::fs::read(&p).unwrap()),
            )
        })
        .collect();
    scenes.sort();
    scenes.push((
        "extra.toml".into(),
        examples_dir().join("fuzz_extra.toml"),
        EXTRA_SCENE.as_bytes().to_vec(),
    ));
    for (name, path, text) in &scenes {
        let text = std::str::from_utf8(text).unwrap();
        if let Err(e) = parse_scene(text, path) {
            panic!("seed scene {name} does not load: {e}");
        }
    }
    let meshes = VALID.iter().map(|&n| (n.to_string(), valid_bytes(n))).collect();

    // a checkpoint of a small simulation with contacts
    let scene = parse_scene(CHECKPOINT_SCENE, &scratch.join("small.toml")).unwrap();
    let mut sim = Simulation::new(scene.model, scene.settings).unwrap();
    for load in scene.loads {
        sim.add_load(load).unwrap();
    }
    for _ in 0..2000 {
        sim.run(1).unwrap();
        if !sim.contacts().is_empty() {
            break;
        }
    }
    // a few steps into the contacts (an engine check stopping the run leaves a state to save)
    let _ = sim.run(5);
    assert!(!sim.contacts().is_empty(), "the checkpoint seed should hold contacts");
    let path = scratch.join("seed.flexdem");
    let checkpoint = Checkpoint {
        state: sim.state().clone(),
        run: scene.run,
        threads: Some(1),
        output: scene.output,
        scene: scratch.join("small.toml"),
        output_progress: OutputProgress { vtk_frames: vec![(0, 0.0), (10, 1e-4)], series_rows: 3 },
    };
    write_checkpoint(&path, &checkpoint).unwrap();
    read_checkpoint(&path).unwrap();
    let checkpoint = std::fs::read(&path).unwrap();
    Corpus { scenes, meshes, checkpoint, scratch }
}

/// The panic message of the last panic on this thread (the hook keeps it instead of
/// printing it).
static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| {
        let message = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        let place =
            info.location().map(|l| format!("{}:{}", l.file(), l.line())).unwrap_or_default();
        // the engine's frames of the stack, to see the path to the panic
        let trace = std::backtrace::Backtrace::force_capture().to_string();
        let frames: Vec<&str> = trace
            .lines()
            .filter(|l| l.contains("flexdem_") && !l.contains("input_fuzz"))
            .map(str::trim)
            .take(6)
            .collect();
        *LAST_PANIC.lock().unwrap() =
            Some(format!("{message} ({place}) via {}", frames.join(" < ")));
    }));
}

/// One problem found.
#[derive(Debug)]
struct Finding {
    target: Target,
    index: u64,
    seed_input: String,
    mutations: Vec<String>,
    what: String,
    saved: PathBuf,
}

/// Counts of one fuzz run.
#[derive(Debug, Default)]
struct Stats {
    executions: u64,
    accepted: u64,
    slowest: (Duration, String),
}

/// Runs one input of `target` (chosen and mutated from `index`); the problem, if any.
fn one(
    corpus: &Corpus,
    target: Target,
    seed: u64,
    index: u64,
    stats: &mut Stats,
) -> Option<Finding> {
    let mut rng = Rng::new(seed, index);
    let (seed_input, mut bytes, others): (String, Vec<u8>, Vec<Vec<u8>>) = match target {
        Target::Scene => {
            let k = rng.below(corpus.scenes.len());
            let others = corpus.scenes.iter().map(|s| s.2.clone()).collect();
            (corpus.scenes[k].0.clone(), corpus.scenes[k].2.clone(), others)
        }
        Target::Mesh => {
            let k = rng.below(corpus.meshes.len());
            let others = corpus.meshes.iter().map(|s| s.1.clone()).collect();
            (corpus.meshes[k].0.clone(), corpus.meshes[k].1.clone(), others)
        }
        Target::Checkpoint => ("checkpoint".into(), corpus.checkpoint.clone(), Vec::new()),
    };
    let count = 1 + rng.below(4);
    let mut mutations = Vec::new();
    match target {
        Target::Checkpoint => {
            let mut payload = bytes.split_off(CHECKPOINT_HEADER_LEN.min(bytes.len()));
            let header_only = rng.chance(16);
            let target_bytes = if header_only { &mut bytes } else { &mut payload };
            for _ in 0..count {
                mutations.push(mutate(target_bytes, &[], true, &mut rng));
            }
            let fix_header = !header_only && !rng.chance(8);
            if fix_header && bytes.len() == CHECKPOINT_HEADER_LEN {
                bytes[12..20].copy_from_slice(&(payload.len() as u64).to_le_bytes());
                bytes[20..24].copy_from_slice(&crc32fast::hash(&payload).to_le_bytes());
                mutations.push("length and checksum recomputed".into());
            }
            bytes.extend_from_slice(&payload);
        }
        _ => {
            let binary = target == Target::Mesh && seed_input.contains("binary");
            for _ in 0..count {
                mutations.push(mutate(&mut bytes, &others, binary && rng.chance(2), &mut rng));
            }
        }
    }
    let started = Instant::now();
    let mut calls = 0u64;
    let mut accepted = 0u64;
    let outcome = catch_unwind(AssertUnwindSafe(|| -> Result<(), String> {
        match target {
            Target::Scene => {
                let (_, path, _) = corpus.scenes.iter().find(|s| s.0 == seed_input).unwrap();
                let shown = path.display().to_string();
                calls += 1;
                let result = match std::str::from_utf8(&bytes) {
                    Ok(text) => parse_scene(text, path),
                    Err(_) => {
                        let file = corpus.scratch.join("not_utf8.toml");
                        std::fs::write(&file, &bytes).unwrap();
                        let r = load_scene(&file);
                        if let Err(SceneError::At { file: f, line, .. }) = &r {
                            if !f.ends_with("not_utf8.toml") || *line == 0 {
                                return Err(format!("UTF-8 error not located: {r:?}"));
                            }
                        }
                        return r.map(|_| ()).map_err(|e| e.to_string()).or_else(|m| {
                            if m.contains("not_utf8.toml:") {
                                Ok(())
                            } else {
                                Err(format!("error without its place: {m}"))
                            }
                        });
                    }
                };
                match result {
                    Ok(scene) => {
                        accepted += 1;
                        build_and_step(scene);
                    }
                    Err(e) => {
                        let m = e.to_string();
                        if !m.starts_with(&format!("{shown}:")) {
                            return Err(format!("error without its place: {m}"));
                        }
                    }
                }
                Ok(())
            }
            Target::Mesh => {
                let name = &seed_input;
                calls += 1;
                let own = reader_for(name)(&bytes, name);
                accepted += u64::from(own.is_ok());
                well_formed(own, name)?;
                let (ext, reader) = READERS[rng.below(READERS.len())];
                let other = format!("mutated.{ext}");
                calls += 1;
                well_formed(reader(&bytes, &other), &other)
            }
            Target::Checkpoint => {
                let file = corpus.scratch.join("mutated.flexdem");
                std::fs::write(&file, &bytes).unwrap();
                calls += 1;
                match restore_checkpoint(&file) {
                    Ok((mut sim, _)) => {
                        accepted += 1;
                        let _ = sim.run(2);
                    }
                    Err(e) => {
                        let m = e.to_string();
                        if !m.contains("mutated.flexdem") {
                            return Err(format!("error without the file: {m}"));
                        }
                    }
                }
                Ok(())
            }
        }
    }));
    let elapsed = started.elapsed();
    stats.executions += calls.max(1);
    stats.accepted += accepted;
    if elapsed > stats.slowest.0 {
        stats.slowest = (elapsed, format!("{target:?} #{index} ({seed_input}): {mutations:?}"));
    }
    let what = match outcome {
        Ok(Ok(())) => return None,
        Ok(Err(problem)) => problem,
        Err(_) => format!("panic: {}", LAST_PANIC.lock().unwrap().take().unwrap_or_default()),
    };
    let dir = corpus.scratch.join("fuzz-failures");
    std::fs::create_dir_all(&dir).unwrap();
    let saved = dir.join(format!("{target:?}-{seed}-{index}.bin"));
    std::fs::write(&saved, &bytes).unwrap();
    Some(Finding { target, index, seed_input, mutations, what, saved })
}

/// Runs `runs` executions from `seed` (scenes 30 %, meshes 45 %, checkpoints 25 % of the
/// inputs, or one target) and panics with the list of what failed.
fn fuzz(runs: u64, seed: u64, only: Option<Target>) {
    let scratch =
        PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("input_fuzz-{seed}-{runs}"));
    std::fs::create_dir_all(&scratch).unwrap();
    let corpus = corpus(scratch);
    quiet_panics();
    let mut stats = Stats::default();
    let mut findings: Vec<Finding> = Vec::new();
    // a watchdog: an input running for minutes is a hang; say which and abort
    let current = Arc::new(Mutex::new((Instant::now(), String::new())));
    let done = Arc::new(AtomicU64::new(0));
    {
        let (current, done) = (Arc::clone(&current), Arc::clone(&done));
        std::thread::spawn(move || loop {
            std::thread::sleep(Duration::from_secs(5));
            if done.load(Ordering::Relaxed) == 1 {
                return;
            }
            let (since, what) = current.lock().unwrap().clone();
            if since.elapsed() > Duration::from_secs(120) {
                eprintln!("HANG: {what} has run for {:?}", since.elapsed());
                std::process::abort();
            }
        });
    }
    let started = Instant::now();
    let mut index = 0u64;
    let mut reported = 0u64;
    while stats.executions < runs {
        let target = only.unwrap_or(match index % 20 {
            0..=5 => Target::Scene,
            6..=14 => Target::Mesh,
            _ => Target::Checkpoint,
        });
        *current.lock().unwrap() = (Instant::now(), format!("{target:?} #{index} seed {seed}"));
        if let Some(f) = one(&corpus, target, seed, index, &mut stats) {
            eprintln!("FOUND {:?} #{}: {}", f.target, f.index, f.what);
            findings.push(f);
        }
        index += 1;
        if stats.executions >= reported + 100_000 {
            reported = stats.executions;
            eprintln!(
                "{} executions, {} inputs, {:.0} s, {} findings",
                stats.executions,
                index,
                started.elapsed().as_secs_f64(),
                findings.len()
            );
        }
    }
    done.store(1, Ordering::Relaxed);
    drop(std::panic::take_hook());
    eprintln!(
        "fuzz: {} executions of {index} inputs (seed {seed}) in {:.1} s; {} accepted; slowest {:?}: {}; {} findings",
        stats.executions,
        started.elapsed().as_secs_f64(),
        stats.accepted,
        stats.slowest.0,
        stats.slowest.1,
        findings.len()
    );
    let list: Vec<String> = findings
        .iter()
        .map(|f| {
            format!(
                "{:?} #{} from {} with {:?}: {}\n  input: {}",
                f.target,
                f.index,
                f.seed_input,
                f.mutations,
                f.what,
                f.saved.display()
            )
        })
        .collect();
    assert!(findings.is_empty(), "{} inputs failed:\n{}", findings.len(), list.join("\n"));
}

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn env_target() -> Option<Target> {
    match std::env::var("FLEXDEM_FUZZ_TARGET").ok()?.as_str() {
        "scene" => Some(Target::Scene),
        "mesh" => Some(Target::Mesh),
        "checkpoint" => Some(Target::Checkpoint),
        other => panic!("FLEXDEM_FUZZ_TARGET={other}: expected scene, mesh or checkpoint"),
    }
}

/// A few seconds of the fuzzer, in the normal tests (a fixed seed: the same inputs each run).
#[test]
fn short_seeded_fuzz() {
    fuzz(
        env_u64("FLEXDEM_FUZZ_SHORT_RUNS", 20_000),
        env_u64("FLEXDEM_FUZZ_SEED", 13),
        env_target(),
    );
}

/// The long run: `FLEXDEM_FUZZ_RUNS` executions (default 10⁶), in release.
#[test]
#[ignore = "long: run in release with --ignored (see the module documentation)"]
fn long_seeded_fuzz() {
    fuzz(env_u64("FLEXDEM_FUZZ_RUNS", 1_000_000), env_u64("FLEXDEM_FUZZ_SEED", 2026), env_target());
}

/// The mutations change the inputs and are replayable from the index.
#[test]
fn mutations_are_seeded() {
    let text = b"[simulation]\nsteps = 10\ngravity = [0, 0, -9.81]\n".to_vec();
    let run = |index| {
        let mut rng = Rng::new(7, index);
        let mut bytes = text.clone();
        let m = mutate(&mut bytes, &[], false, &mut rng);
        (bytes, m)
    };
    assert_eq!(run(3), run(3));
    let changed = (0..50).filter(|&i| run(i).0 != text).count();
    assert!(changed > 40, "{changed}");
    assert!(Path::new(env!("CARGO_TARGET_TMPDIR")).is_absolute());
}

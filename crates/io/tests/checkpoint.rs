//! Checkpoint files: a run restarted from a checkpoint continues bit-identically, a failed
//! write leaves the previous checkpoint intact, and every kind of damaged or foreign file
//! gives its own error, never a panic.

use flexdem_contact::Material;
use flexdem_elements::builders::{chain, straight_line, StructureOptions};
use flexdem_elements::Model;
use flexdem_geom::Vec3;
use flexdem_integrate::{
    ContactKey, PairContact, Settings, Simulation, StressControl, WallControl,
};
use flexdem_io::checkpoint::{
    read_checkpoint, restore_checkpoint, write_checkpoint, Checkpoint, CheckpointError,
    OutputProgress, CHECKPOINT_HEADER_LEN, CHECKPOINT_VERSION,
};
use flexdem_io::output::{OutputSettings, Quantity, SeriesSpec};
use flexdem_io::scene::{parse_scene, RunLength};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn output_settings(dir: &Path) -> OutputSettings {
    OutputSettings {
        directory: dir.to_path_buf(),
        vtk_every: Some(10),
        series_every: Some(5),
        series: vec![SeriesSpec { name: "energy".into(), quantity: Quantity::Energy }],
        plot: false,
    }
}

fn checkpoint_of(sim: &Simulation) -> Checkpoint {
    Checkpoint {
        state: sim.state().clone(),
        run: RunLength::Duration(1.5),
        threads: Some(3),
        output: output_settings(Path::new("out/run")),
        scene: PathBuf::from("scenes/MARKERscene.toml"),
        output_progress: OutputProgress {
            vtk_frames: vec![(0, 0.0), (10, 1.25e-4), (20, 2.5e-4)],
            series_rows: 7,
        },
    }
}

/// A cable with one end blocked and a free sphere resting on a wall: links and a contact.
fn small_simulation() -> Simulation {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let heavy = model.add_material(Material::new(1e7, 0.3, 1e5, 0.5).unwrap()).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, 0.0498), 0.05, heavy).unwrap();
    let points = straight_line(Vec3::new(-1.0, 0.0, 1.0), Vec3::new(-0.4, 0.0, 1.0), 3).unwrap();
    chain(&mut model, &points, &StructureOptions::new("cable", 0.01, m)).unwrap();
    model.particles.blocked[1] = flexdem_elements::Dofs::ALL;
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    sim.run(20).unwrap();
    assert!(!sim.contacts().is_empty());
    sim
}

/// The bytes of a valid checkpoint file of [`small_simulation`].
fn valid_file() -> &'static [u8] {
    static BYTES: OnceLock<Vec<u8>> = OnceLock::new();
    BYTES.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("valid.ckp");
        write_checkpoint(&path, &checkpoint_of(&small_simulation())).unwrap();
        std::fs::read(&path).unwrap()
    })
}

/// Reads `bytes` as a checkpoint file.
fn read_bytes(bytes: &[u8]) -> Result<Checkpoint, CheckpointError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("c.ckp");
    std::fs::write(&path, bytes).unwrap();
    let result = read_checkpoint(&path);
    if let Err(e) = &result {
        assert!(e.to_string().contains(&path.display().to_string()), "file not named: {e}");
    }
    result
}

/// Rewrites the header's length and checksum for a new payload.
fn with_payload(payload: &[u8]) -> Vec<u8> {
    let mut bytes = valid_file()[..CHECKPOINT_HEADER_LEN].to_vec();
    bytes[12..20].copy_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes[20..24].copy_from_slice(&crc32fast::hash(payload).to_le_bytes());
    bytes.extend_from_slice(payload);
    bytes
}

fn encoded<T: serde::Serialize>(value: &T) -> Vec<u8> {
    bincode::serde::encode_to_vec(value, bincode::config::standard()).unwrap()
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn assert_same_state(a: &Simulation, b: &Simulation) {
    assert_eq!(a.steps(), b.steps());
    assert_eq!(a.time().to_bits(), b.time().to_bits());
    assert_eq!(a.dt().to_bits(), b.dt().to_bits());
    let (pa, pb) = (&a.model().particles, &b.model().particles);
    assert!(pa.pos == pb.pos, "positions differ");
    assert!(pa.vel == pb.vel, "velocities differ");
    assert!(pa.ori == pb.ori, "orientations differ");
    assert!(pa.ang_vel == pb.ang_vel, "angular velocities differ");
    assert_eq!(a.energy(), b.energy());
    assert_eq!(a.contacts().len(), b.contacts().len());
    // The whole state, bit for bit: contact and link history included.
    assert!(encoded(a.state()) == encoded(b.state()), "states differ");
}

/// The net_drop example with the rock released just above the net, so that it touches it
/// within a few steps.
fn net_drop() -> Simulation {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/net_drop.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text.replace("center = [0, 0, 0.5]", "center = [0.01, 0.02, 0.1025]");
    let scene = parse_scene(&text, &path).unwrap();
    let mut sim = Simulation::new(scene.model, scene.settings).unwrap();
    for load in scene.loads {
        sim.add_load(load).unwrap();
    }
    sim
}

/// Runs `n` steps; returns how many of them ended with a contact.
fn count_touching_steps(sim: &mut Simulation, n: u64) -> u64 {
    (0..n)
        .filter(|_| {
            sim.step().unwrap();
            !sim.contacts().is_empty()
        })
        .count() as u64
}

#[test]
fn a_run_restarted_from_a_checkpoint_file_continues_bit_identically() {
    let mut a = net_drop();
    // The rock bounces on the sagging net: take the checkpoint while they touch, with some
    // contact history behind it.
    a.run(1000).unwrap();
    let mut steps = 0;
    while a.contacts().is_empty() {
        assert!(steps < 5000, "the rock never touched the net");
        a.step().unwrap();
        steps += 1;
    }
    a.step().unwrap();
    assert!(!a.contacts().is_empty() && !a.links().is_empty());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("net.ckp");
    let original = checkpoint_of(&a);
    write_checkpoint(&path, &original).unwrap();
    let touching_steps = count_touching_steps(&mut a, 1500);
    assert!(touching_steps > 0, "no contact after the checkpoint: the test shows little");

    let (mut b, info) = restore_checkpoint(&path).unwrap();
    assert_eq!(info.run, original.run);
    assert_eq!(info.threads, original.threads);
    assert_eq!(info.output, original.output);
    assert_eq!(info.scene, original.scene);
    assert_eq!(info.output_progress, original.output_progress);
    assert_eq!(count_touching_steps(&mut b, 1500), touching_steps);
    assert_same_state(&a, &b);
}

/// Four spheres on a floor pressed by a servo platen (no gravity), checkpointed while the
/// platen is still finding its stress: the restored run moves the platen and the spheres
/// exactly as the uninterrupted one.
#[test]
fn a_run_with_a_servo_wall_restarted_from_a_checkpoint_continues_bit_identically() {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e8, 0.3, 2600.0, 0.5).unwrap()).unwrap();
    let r = 0.01;
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    model.add_wall(Vec3::new(0.0, 0.0, 4.2 * r), -Vec3::z(), m).unwrap();
    // 1 µm apart: spheres that touch exactly make round-off forces that the energy watch,
    // with nothing else to measure them against, takes for energy created
    for (x, z) in [(r, r), (3.2 * r, r), (r, 3.0 * r), (3.3 * r, 3.0 * r)] {
        model.add_sphere(Vec3::new(x, r, z + 1e-6 * z / r), r, m).unwrap();
    }
    let settings = Settings { damping: 0.2, ..Settings::default() };
    let mut a = Simulation::new(model, settings).unwrap();
    let servo = StressControl {
        target: 2e4,
        area: 8.0 * r * r,
        gain: None,
        max_speed: 0.05,
        section: None,
    };
    a.set_wall_control(1, WallControl::Stress(servo)).unwrap();
    while a.wall_forces()[1] == Vec3::zeros() {
        assert!(a.steps() < 10_000, "the platen never touched the spheres");
        a.step().unwrap();
    }
    a.run(50).unwrap();
    let moving = a.model().walls[1].velocity;
    assert!(moving.z != 0.0 && moving.z != -0.05, "the servo is not steering: {moving:?}");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("servo.ckp");
    write_checkpoint(&path, &checkpoint_of(&a)).unwrap();
    a.run(1500).unwrap();
    let (mut b, _) = restore_checkpoint(&path).unwrap();
    assert_eq!(b.wall_controls(), &[WallControl::Velocity, WallControl::Stress(servo)]);
    b.run(1500).unwrap();
    assert_same_state(&a, &b);
    assert_eq!(a.wall_forces(), b.wall_forces());
    assert_ne!(a.model().walls[1].velocity, moving, "the platen should have moved on");
}

/// Damped spheres (restitution 0.3) dropped on a damped floor, checkpointed while they bounce:
/// the dashpots' pending half of dissipation is in the state, and the restored run continues
/// exactly as the uninterrupted one, energy terms included.
#[test]
fn a_damped_run_restarted_from_a_checkpoint_continues_bit_identically() {
    let mut model = Model::new();
    let damped = Material::new(1e7, 0.3, 2600.0, 0.5)
        .unwrap()
        .with_damping(flexdem_contact::ContactDamping::Restitution(0.3));
    let m = model.add_material(damped).unwrap();
    let r = 0.01;
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    for (x, z) in [(0.0, 1.2 * r), (0.5 * r, 3.5 * r), (-0.4 * r, 6.0 * r)] {
        model.add_sphere(Vec3::new(x, 0.1 * x, z), r, m).unwrap();
    }
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
    let mut a = Simulation::new(model, settings).unwrap();
    // a few bounces in, while a dashpot pushes
    a.run(2000).unwrap();
    while a.state().energy.pending.contact_damping == 0.0 {
        assert!(a.steps() < 100_000, "the spheres never touched");
        a.step().unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("damped.ckp");
    write_checkpoint(&path, &checkpoint_of(&a)).unwrap();
    a.run(2000).unwrap();
    let (mut b, _) = restore_checkpoint(&path).unwrap();
    b.run(2000).unwrap();
    assert_same_state(&a, &b);
    assert!(a.energy().contact_damping > 0.0);
}

#[test]
fn a_checkpoint_round_trips_bit_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("c.ckp");
    let mut c = checkpoint_of(&small_simulation());
    // Awkward floats and long strings survive too.
    c.output_progress.vtk_frames.push((u64::MAX, -0.0));
    c.output_progress.vtk_frames.push((1, f64::MIN_POSITIVE / 3.0));
    c.scene = PathBuf::from("é/".repeat(40_000) + "scene.toml");
    c.output.series = (0..2000)
        .map(|i| SeriesSpec { name: format!("s{i}"), quantity: Quantity::Position(0) })
        .collect();
    write_checkpoint(&path, &c).unwrap();
    let first = std::fs::read(&path).unwrap();
    let back = read_checkpoint(&path).unwrap();
    assert!(encoded(&back) == encoded(&c), "the checkpoint changed on the way");
    assert_eq!(back.output_progress.vtk_frames[3].1.to_bits(), (-0.0f64).to_bits());
    write_checkpoint(&path, &back).unwrap();
    assert!(std::fs::read(&path).unwrap() == first, "writing it again gives other bytes");
    assert_eq!(files_in(dir.path()), ["c.ckp"]);
}

#[test]
fn a_failed_write_leaves_the_previous_checkpoint_untouched() {
    let sim = small_simulation();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.ckp");
    write_checkpoint(&path, &checkpoint_of(&sim)).unwrap();
    let before = std::fs::read(&path).unwrap();
    let mut newer = checkpoint_of(&sim);
    newer.output_progress.series_rows = 99;

    // The temporary file's place is taken by a folder.
    let blocker = dir.path().join(format!(".run.ckp.tmp-{}", std::process::id()));
    std::fs::create_dir(&blocker).unwrap();
    std::fs::write(blocker.join("keep"), b"x").unwrap();
    let err = write_checkpoint(&path, &newer).unwrap_err();
    assert!(matches!(err, CheckpointError::Write { .. }), "{err:?}");
    assert!(err.to_string().contains("run.ckp"), "{err}");
    assert!(std::fs::read(&path).unwrap() == before, "the previous checkpoint changed");
    assert!(blocker.join("keep").exists(), "a folder that is not ours was removed");
    std::fs::remove_dir_all(&blocker).unwrap();
    assert_eq!(files_in(dir.path()), ["run.ckp"]);

    // A checkpoint that cannot be encoded (a path that is not UTF-8) writes nothing.
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let mut bad = checkpoint_of(&sim);
        bad.scene = PathBuf::from(std::ffi::OsStr::from_bytes(b"scene-\xff.toml"));
        let err = write_checkpoint(&path, &bad).unwrap_err();
        assert!(matches!(err, CheckpointError::Encode { .. }), "{err:?}");
        assert!(std::fs::read(&path).unwrap() == before);
        assert_eq!(files_in(dir.path()), ["run.ckp"]);
    }

    // The rename fails (the target is a folder that is not empty): the temporary file, fully
    // written, is removed.
    let target = dir.path().join("taken.ckp");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("inside"), b"x").unwrap();
    let err = write_checkpoint(&target, &newer).unwrap_err();
    assert!(matches!(err, CheckpointError::Write { .. }), "{err:?}");
    assert_eq!(files_in(dir.path()), ["run.ckp", "taken.ckp"]);

    // The target's folder is gone.
    let gone = dir.path().join("gone");
    std::fs::create_dir(&gone).unwrap();
    write_checkpoint(&gone.join("run.ckp"), &newer).unwrap();
    std::fs::remove_dir_all(&gone).unwrap();
    let err = write_checkpoint(&gone.join("run.ckp"), &newer).unwrap_err();
    assert!(matches!(err, CheckpointError::Write { .. }), "{err:?}");
    assert!(!gone.exists());

    // Then a write that can succeed replaces the file.
    write_checkpoint(&path, &newer).unwrap();
    assert_eq!(read_checkpoint(&path).unwrap().output_progress.series_rows, 99);
    assert_eq!(files_in(dir.path()), ["run.ckp", "taken.ckp"]);
}

#[test]
fn truncated_files_are_reported_as_such() {
    let valid = valid_file();
    let n = valid.len();
    let lengths =
        (0..CHECKPOINT_HEADER_LEN + 64).chain((CHECKPOINT_HEADER_LEN + 64..n).step_by(97));
    for len in lengths.chain([n - 1]) {
        match read_bytes(&valid[..len]) {
            Err(CheckpointError::TooShort { len: l, .. }) if len < CHECKPOINT_HEADER_LEN => {
                assert_eq!(l, len as u64)
            }
            Err(CheckpointError::Truncated { declared, available, .. })
                if len >= CHECKPOINT_HEADER_LEN =>
            {
                assert_eq!(declared as usize, n - CHECKPOINT_HEADER_LEN);
                assert_eq!(available as usize, len - CHECKPOINT_HEADER_LEN);
            }
            other => panic!("length {len}: {other:?}"),
        }
    }
    let mut longer = valid.to_vec();
    longer.push(0);
    assert!(matches!(read_bytes(&longer), Err(CheckpointError::TrailingBytes { extra: 1, .. })));
}

#[test]
fn every_flipped_byte_is_caught() {
    let valid = valid_file();
    let n = valid.len();
    let payload_positions = (CHECKPOINT_HEADER_LEN..n).step_by(53).chain([n - 1]);
    for i in (0..CHECKPOINT_HEADER_LEN).chain(payload_positions) {
        for flip in [0x01u8, 0x80, 0xff] {
            let mut bytes = valid.to_vec();
            bytes[i] ^= flip;
            let err = read_bytes(&bytes).map(|_| ()).unwrap_err();
            let expected = match i {
                0..8 => matches!(err, CheckpointError::NotACheckpoint { .. }),
                8..12 => matches!(err, CheckpointError::Version { .. }),
                12..20 => matches!(
                    err,
                    CheckpointError::Truncated { .. } | CheckpointError::TrailingBytes { .. }
                ),
                _ => matches!(err, CheckpointError::Damaged { .. }),
            };
            assert!(expected, "byte {i} ^ {flip:#x}: {err:?}");
        }
    }
}

#[test]
fn foreign_and_odd_files_give_their_error() {
    let valid = valid_file();
    let not_ours = read_bytes(b"PK\x03\x04 this is a zip file, or something else entirely");
    assert!(matches!(not_ours, Err(CheckpointError::NotACheckpoint { .. })), "{not_ours:?}");
    assert!(matches!(read_bytes(b"FLX"), Err(CheckpointError::TooShort { len: 3, .. })));
    assert!(matches!(read_bytes(b"{}"), Err(CheckpointError::NotACheckpoint { .. })));
    let empty = read_bytes(b"");
    assert!(matches!(empty, Err(CheckpointError::TooShort { len: 0, .. })), "{empty:?}");

    // 2: the format of the engine's former `Snapshot`, before the `State` of version 3;
    // 3: the `State` before the wall controls of version 4;
    // 4: the `State` before its pressures on PFacets;
    // 5: the `State` before the free spheres' neighbour list;
    // 6: the `State` before the viscous contact damping;
    // 7: the `State` before a structure's self-contact switch;
    // 8: the `State` before the lean links (classes, springs, one rest rotation);
    // 9: the `State` before a contact state's lone friction total;
    // 10: the `State` before the links' plastic states apart and their springs shared;
    // 11: the `State` before the free spheres' lean contacts (no point kept);
    // 12: the `State` before the energy watch's lowest balance;
    // 13: the `State` before the energy watch's sum of the contacts found late
    let older = [
        (CHECKPOINT_VERSION + 1, "newer"),
        (0, "older"),
        (2, "older"),
        (4, "older"),
        (5, "older"),
        (6, "older"),
        (7, "older"),
        (8, "older"),
        (9, "older"),
        (10, "older"),
        (11, "older"),
        (12, "older"),
        (13, "older"),
    ];
    assert_eq!(CHECKPOINT_VERSION, 14);
    for (version, word) in older {
        let mut bytes = valid.to_vec();
        bytes[8..12].copy_from_slice(&version.to_le_bytes());
        let err = read_bytes(&bytes).map(|_| ()).unwrap_err();
        let CheckpointError::Version { found, expected, .. } = &err else { panic!("{err:?}") };
        assert_eq!((*found, *expected), (version, CHECKPOINT_VERSION));
        let message = err.to_string();
        assert!(message.contains(word) && message.contains(&format!("{version}")), "{message}");
    }

    // A length so large that nothing could hold it is checked against the file first.
    let mut bytes = valid.to_vec();
    bytes[12..20].copy_from_slice(&u64::MAX.to_le_bytes());
    assert!(matches!(read_bytes(&bytes), Err(CheckpointError::Truncated { .. })));

    let dir = tempfile::tempdir().unwrap();
    let err = read_checkpoint(dir.path()).map(|_| ()).unwrap_err();
    assert!(matches!(err, CheckpointError::Read { .. }), "a folder: {err:?}");
    let missing = dir.path().join("missing.ckp");
    let err = read_checkpoint(&missing).map(|_| ()).unwrap_err();
    assert!(matches!(err, CheckpointError::Read { .. }) && err.to_string().contains("missing"));
}

#[test]
fn a_payload_with_a_valid_checksum_is_still_checked() {
    let valid = valid_file();
    let payload = &valid[CHECKPOINT_HEADER_LEN..];
    let garbage: Vec<u8> =
        (0..4000u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8).collect();
    for bad in [&garbage[..], &[][..], &payload[..payload.len() / 2]] {
        let result = read_bytes(&with_payload(bad));
        assert!(matches!(result, Err(CheckpointError::Decode { .. })), "{result:?}");
    }
    let mut longer = payload.to_vec();
    longer.push(0);
    let err = read_bytes(&with_payload(&longer)).map(|_| ()).unwrap_err();
    assert!(err.to_string().contains("left over"), "{err}");

    // A string whose length is set to 2^62 bytes: refused, without trying to allocate it.
    let marker = b"MARKERscene.toml";
    let at = payload.windows(marker.len()).position(|w| w == marker).unwrap();
    let length_at = at - "scenes/".len() - 1;
    assert_eq!(payload[length_at] as usize, "scenes/MARKERscene.toml".len());
    let mut crafted = payload[..length_at].to_vec();
    crafted.push(253); // bincode varint: a u64 follows
    crafted.extend_from_slice(&(1u64 << 62).to_le_bytes());
    crafted.extend_from_slice(&payload[length_at + 1..]);
    let result = read_bytes(&with_payload(&crafted));
    assert!(matches!(result, Err(CheckpointError::Decode { .. })), "{result:?}");
}

#[test]
fn a_state_the_engine_refuses_is_reported_with_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("refused.ckp");
    let mut c = checkpoint_of(&small_simulation());
    c.state.clock.dt = -1.0;
    write_checkpoint(&path, &c).unwrap();
    let c = read_checkpoint(&path).unwrap();
    let err = c.clone().into_simulation().map(|_| ()).unwrap_err();
    assert!(matches!(err, CheckpointError::Refused { path: None, .. }), "{err:?}");
    let err = restore_checkpoint(&path).map(|_| ()).unwrap_err();
    assert!(matches!(&err, CheckpointError::Refused { path: Some(p), .. } if *p == path));
    assert!(err.to_string().contains("refused.ckp"), "{err}");
}

/// Run settings no scene gives (an edited file with its checksum recomputed): refused with
/// the file named, where an output period of 0 made a resumed run divide by zero.
#[test]
fn run_settings_no_scene_gives_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("settings.ckp");
    let good = checkpoint_of(&small_simulation());
    let mut zero_series = good.clone();
    zero_series.output.series_every = Some(0);
    let mut zero_vtk = good.clone();
    zero_vtk.output.vtk_every = Some(0);
    let mut no_threads = good.clone();
    no_threads.threads = Some(0);
    let mut too_many = good.clone();
    too_many.threads = Some(100_000);
    for (c, what) in [
        (zero_series, "series_every = 0"),
        (zero_vtk, "vtk_every = 0"),
        (no_threads, "threads = 0"),
        (too_many, "threads = 100000"),
    ] {
        write_checkpoint(&path, &c).unwrap();
        let err = restore_checkpoint(&path).map(|_| ()).unwrap_err();
        assert!(matches!(&err, CheckpointError::Refused { path: Some(p), .. } if *p == path));
        let text = err.to_string();
        assert!(text.contains("settings.ckp") && text.contains(what), "{text}");
    }
    // a series of a particle the model does not have: the writer's own check, output or not
    let mut bad_series = good.clone();
    bad_series.output.series =
        vec![SeriesSpec { name: "p".into(), quantity: Quantity::Position(1_000_000) }];
    write_checkpoint(&path, &bad_series).unwrap();
    let err = restore_checkpoint(&path).map(|_| ()).unwrap_err();
    assert!(matches!(&err, CheckpointError::Refused { path: Some(p), .. } if *p == path));
    assert!(err.to_string().contains("1000000"), "{err}");
    write_checkpoint(&path, &good).unwrap();
    assert!(restore_checkpoint(&path).is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// Random damage (flipped bytes, then possibly a cut or an extension) is always reported
    /// as an error, never a panic.
    #[test]
    fn random_damage_is_always_an_error(
        flips in prop::collection::vec((any::<prop::sample::Index>(), 1u8..=255), 1..5),
        cut in prop::option::of(any::<prop::sample::Index>()),
        extra in prop::collection::vec(any::<u8>(), 0..3),
    ) {
        let mut bytes = valid_file().to_vec();
        for (i, flip) in &flips {
            let i = i.index(bytes.len());
            bytes[i] ^= flip;
        }
        if let Some(cut) = cut {
            bytes.truncate(cut.index(bytes.len()));
        }
        bytes.extend_from_slice(&extra);
        if bytes != valid_file() {
            prop_assert!(read_bytes(&bytes).is_err());
        }
    }
}

/// The mutation fuzzer (tests/input_fuzz.rs) made checkpoints, with a recomputed checksum,
/// whose contacts held NaN weights or a normal that is not unit (a panic in the contact law
/// of a debug build) and whose time-step counter was past the last step (an overflow): they
/// are refused with the file's name.
#[test]
fn damaged_contacts_and_counters_are_refused() {
    let sim = small_simulation();
    assert!(!sim.state().contacts.pairs.is_empty());
    // the sphere on the wall is a free sphere's contact (in the neighbour list): moved to the
    // general list, as a valid state may hold it, for the damages of sites
    fn general(c: &mut Checkpoint) -> &mut flexdem_integrate::Contact {
        let all = c.state.contacts.all(&c.state.model);
        c.state.contacts.list = all;
        c.state.contacts.pairs = Default::default();
        &mut c.state.contacts.list[0]
    }
    fn pair(c: &mut Checkpoint, damage: fn(&mut PairContact)) {
        let mut touching: Vec<(ContactKey, PairContact)> = c.state.contacts.pairs.clone().into();
        damage(&mut touching[0].1);
        c.state.contacts.pairs = touching.into();
    }
    let damages: [fn(&mut Checkpoint); 17] = [
        |c| general(c).site2.weights[0] = f64::NAN,
        |c| general(c).params.cn = -1.0,
        |c| general(c).params.ct = f64::NAN,
        |c| general(c).state.overlap_offset = f64::NAN,
        |c| general(c).site2.weights = [0.7, 0.7, 0.7],
        |c| general(c).state.normal *= 2.0,
        |c| general(c).params.kn = f64::INFINITY,
        |c| pair(c, |p| p.state.overlap_offset = f64::INFINITY),
        |c| pair(c, |p| p.state.normal *= 2.0),
        |c| pair(c, |p| p.params.kn = f64::NAN),
        |c| pair(c, |p| p.params.cn = f64::INFINITY),
        |c| pair(c, |p| p.state.dissipated_friction = f64::NAN),
        |c| pair(c, |p| p.state.normal_force = f64::INFINITY),
        |c| general(c).state.dissipated_friction = f64::NEG_INFINITY,
        |c| c.state.clock.dt_updated_at = c.state.clock.steps + 5,
        |c| c.state.wall_controls.clear(),
        |c| {
            let servo = StressControl {
                target: 1e3,
                area: f64::NAN,
                gain: None,
                max_speed: 1.0,
                section: None,
            };
            c.state.wall_controls[0] = WallControl::Stress(servo);
        },
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("damaged.ckp");
    for (k, damage) in damages.iter().enumerate() {
        let mut c = checkpoint_of(&sim);
        damage(&mut c);
        write_checkpoint(&path, &c).unwrap();
        let err = restore_checkpoint(&path).map(|_| ()).unwrap_err();
        assert!(matches!(&err, CheckpointError::Refused { .. }), "damage {k}: {err:?}");
        assert!(err.to_string().contains("damaged.ckp"), "damage {k}: {err}");
    }
    write_checkpoint(&path, &checkpoint_of(&sim)).unwrap();
    restore_checkpoint(&path).unwrap();
}

//! Checkpoint files: the whole state of a run (the engine's [`State`], with contacts and
//! their shear history, links, clock, time-step bookkeeping and energy terms) together with
//! what is needed to carry on the run (run length, threads, output settings and how far the
//! output got), so that a run restarted from a checkpoint continues **bit-identically** to one
//! that was never interrupted.
//!
//! # File format (version [`CHECKPOINT_VERSION`])
//!
//! | offset | size | content |
//! |---|---|---|
//! | 0 | 8 | magic bytes [`CHECKPOINT_MAGIC`] = `FLXDMCKP` |
//! | 8 | 4 | format version, `u32` little endian |
//! | 12 | 8 | payload length in bytes, `u64` little endian |
//! | 20 | 4 | CRC-32 (IEEE, as `crc32fast` computes it) of the payload, `u32` little endian |
//! | 24 | length | payload: the [`Checkpoint`] encoded with bincode 2 through serde, standard configuration (little endian, variable-length integers) |
//!
//! Nothing follows the payload. Floating-point numbers are stored as their 8 bytes, so they
//! round-trip bit-exactly; a valid state never holds NaN.
//!
//! The version changes whenever the payload's layout changes (a field added to
//! [`State`] or to [`Checkpoint`], an enum variant moved, ...): a build reads only its own
//! version and says which version a file has.
//! Version 3 stores the engine's [`State`] (version 2 stored its predecessor, `Snapshot`,
//! with the same parts in another order): files of version 2 are refused with that message.
//! Version 4 adds the wall controls to the [`State`] (`State::wall_controls`: strain control
//! or a servo holding a stress, one per wall); version 5 the pressures on PFacets
//! (`State::pressures`) and the enclosed-volume quantity of the output series; version 6 the
//! free spheres' neighbour list (`Contacts::pairs`: their touching pairs, with their history);
//! version 7 the viscous contact damping (a material's `damping`, a contact's dashpots `cn`,
//! `ct`, their dissipation: `Dissipation::viscous`, `Energy::contact_damping` and its pending
//! half); version 8 a structure's self-contact switch (`Structure::self_contact`); version 9
//! the lean links (`Links::classes`, `class`, `springs`; a link state with one rest rotation
//! q2⁰⁻¹·q1⁰ for the two reference orientations, its plastic rotation in node 1's body
//! frame, and no per-link dissipation: the links' dissipation is summed in the energy);
//! version 10 a contact state's lifetime dissipation as its friction alone
//! (`FrictionalContact::dissipated_friction`, where it kept a whole `Dissipation`);
//! version 11 the links' plastic states apart (`Links::plastic`, a `LinkPlastic` per link
//! when some material is plastic, none otherwise; a link state without them) and their
//! springs shared (`Links::springs` once per distinct spring, `Links::spring` per link);
//! version 12 the free spheres' lean contacts (`PairContact` without the contact point of
//! its last update, made when asked from the positions); version 13 the energy watch's lowest
//! balance (`EnergyWatch::lowest_balance`); version 14 the energy contacts found late put in
//! (`EnergyWatch::late_births`).
//! Files of older versions are refused with the version error, which says so.
//!
//! # Writing
//!
//! [`write_checkpoint`] encodes the whole file in memory, writes it to a temporary file beside
//! the target (`.NAME.tmp-PID`), flushes it to disk (`sync_all`), renames it over the target
//! and flushes the folder (best effort). A crash or an error at any point leaves the previous
//! checkpoint as it was; on error the temporary file is removed.
//!
//! # Reading
//!
//! [`read_checkpoint`] checks, in this order, with an error naming the file for each: that
//! the file can be read and is at least a header long, the magic bytes (not a checkpoint), the
//! version (newer or older than this build's), the declared length against the file's size
//! (truncated, or bytes after the payload; nothing is allocated from the declared length
//! before this check), the checksum (damaged), and that the payload decodes completely. It
//! never panics, whatever the file holds. Memory taken while decoding is bounded by a multiple
//! of the payload size, so a crafted length inside the payload cannot make it allocate more
//! (payloads above 1 GiB are decoded without that bound).
//!
//! The state itself is checked by the engine when the simulation is rebuilt:
//! [`Checkpoint::into_simulation`] (or [`restore_checkpoint`], which reads and rebuilds in
//! one call and names the file in its errors).

mod atomic;
mod check;

use flexdem_integrate::{Simulation, SimulationError, State};
/// What the output had written, stored in checkpoints (defined by `flexdem-output`).
pub use flexdem_output::OutputProgress;
use flexdem_output::{check_output_settings, OutputSettings};
use flexdem_scene::{RunLength, MAX_THREADS};
use serde::{Deserialize, Serialize};
use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};

/// Magic bytes at the start of every checkpoint file.
pub const CHECKPOINT_MAGIC: [u8; 8] = *b"FLXDMCKP";

/// The format version this build writes and reads (see the module documentation).
pub const CHECKPOINT_VERSION: u32 = 14;

/// Size of the header before the payload: magic, version, length, checksum (bytes).
pub const CHECKPOINT_HEADER_LEN: usize = 24;

/// Everything a run needs to continue from where it was.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Checkpoint {
    /// The simulation's whole state (see [`Simulation::state`]).
    pub state: State,
    /// The run length of the scene: the resumed run stops where the original would have.
    pub run: RunLength,
    /// Number of worker threads of the run (None: the machine's default).
    pub threads: Option<usize>,
    /// Where and what the run writes.
    pub output: OutputSettings,
    /// The scene file the run came from (for information: it is not read again).
    pub scene: PathBuf,
    /// What the output had written when the checkpoint was taken.
    pub output_progress: OutputProgress,
}

/// The parts of a [`Checkpoint`] other than the simulation, returned by
/// [`Checkpoint::into_simulation`].
#[derive(Clone, Debug, PartialEq)]
pub struct ResumeInfo {
    /// The run length of the scene.
    pub run: RunLength,
    /// Number of worker threads (None: the machine's default).
    pub threads: Option<usize>,
    /// Where and what the run writes.
    pub output: OutputSettings,
    /// The scene file the run came from.
    pub scene: PathBuf,
    /// What the output had written.
    pub output_progress: OutputProgress,
}

impl Checkpoint {
    /// Rebuilds the simulation with [`Simulation::from_state`], which checks the state
    /// (a file may have been written by a buggy build or edited), and checks the run
    /// settings beside it (threads; the output's, with the writer's own check): the error is
    /// [`CheckpointError::Refused`] without a file name; [`restore_checkpoint`] adds it.
    pub fn into_simulation(self) -> Result<(Simulation, ResumeInfo), CheckpointError> {
        let info = ResumeInfo {
            run: self.run,
            threads: self.threads,
            output: self.output,
            scene: self.scene,
            output_progress: self.output_progress,
        };
        let refused = |source| CheckpointError::Refused { path: None, source };
        if let Some(n) = info.threads.filter(|&n| n == 0 || n > MAX_THREADS) {
            return Err(refused(SimulationError::Setting {
                what: "run settings".into(),
                value: format!("threads = {n}"),
                expected: format!("a whole number in [1, {MAX_THREADS}], as a scene gives"),
            }));
        }
        check::check_state(&self.state).map_err(|value| {
            refused(SimulationError::Setting {
                what: "simulation state".into(),
                value,
                expected: "a state written by Simulation::state".into(),
            })
        })?;
        let sim = Simulation::from_state(self.state).map_err(refused)?;
        // the output's own check (periods, plot, series against the model), which the
        // writer makes when it opens: a run without output still records the series
        check_output_settings(&info.output, &sim).map_err(|e| {
            refused(SimulationError::Setting {
                what: "output".into(),
                value: e.to_string(),
                expected: "the output settings of a scene".into(),
            })
        })?;
        Ok((sim, info))
    }
}

/// Why a checkpoint could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// The file could not be opened or read (missing, a folder, no permission, ...).
    #[error("cannot read the checkpoint {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: io::Error,
    },
    /// The file could not be written; the previous checkpoint, if any, is unchanged.
    #[error(
        "cannot write the checkpoint {}: {source} (the previous checkpoint there, if any, is \
         unchanged)",
        path.display()
    )]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: io::Error,
    },
    /// The checkpoint could not be encoded (e.g. a path that is not valid UTF-8).
    #[error("cannot encode the checkpoint for {}: {message}", path.display())]
    Encode {
        /// The file it was meant for.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// The file is shorter than a checkpoint header (an empty file included).
    #[error(
        "{} is not a flexdem checkpoint or is truncated: it is {len} bytes long, shorter than \
         the {CHECKPOINT_HEADER_LEN}-byte header",
        path.display()
    )]
    TooShort {
        /// The file.
        path: PathBuf,
        /// Its length (bytes).
        len: u64,
    },
    /// The file does not start with [`CHECKPOINT_MAGIC`].
    #[error("{} is not a flexdem checkpoint (it does not start with `FLXDMCKP`)", path.display())]
    NotACheckpoint {
        /// The file.
        path: PathBuf,
    },
    /// The file has another format version than this build's.
    #[error(
        "checkpoint {} has format version {found}, {}; this build of flexdem reads version \
         {expected} only",
        path.display(),
        if found > expected { "written by a newer flexdem" } else { "written by an older flexdem" }
    )]
    Version {
        /// The file.
        path: PathBuf,
        /// The version in the file.
        found: u32,
        /// The version this build reads ([`CHECKPOINT_VERSION`]).
        expected: u32,
    },
    /// The file ends before the payload its header announces.
    #[error(
        "checkpoint {} is truncated: its header announces {declared} bytes of data but only \
         {available} follow",
        path.display()
    )]
    Truncated {
        /// The file.
        path: PathBuf,
        /// The payload length in the header (bytes).
        declared: u64,
        /// The bytes after the header (bytes).
        available: u64,
    },
    /// The file goes on after the payload its header announces.
    #[error(
        "checkpoint {} is damaged: {extra} unexpected bytes follow the {declared} bytes of data \
         its header announces",
        path.display()
    )]
    TrailingBytes {
        /// The file.
        path: PathBuf,
        /// The payload length in the header (bytes).
        declared: u64,
        /// The bytes beyond it.
        extra: u64,
    },
    /// The payload's checksum does not match the header's.
    #[error(
        "checkpoint {} is damaged: checksum mismatch (header {stored:08x}, data {computed:08x})",
        path.display()
    )]
    Damaged {
        /// The file.
        path: PathBuf,
        /// The checksum in the header.
        stored: u32,
        /// The checksum of the payload read.
        computed: u32,
    },
    /// The payload passed the checksum but does not decode to a checkpoint.
    #[error(
        "checkpoint {} cannot be decoded ({message}): it was written by an incompatible build \
         of flexdem, or damaged",
        path.display()
    )]
    Decode {
        /// The file.
        path: PathBuf,
        /// What the decoder reported.
        message: String,
    },
    /// The file is too large to be loaded into memory.
    #[error("checkpoint {} is too large to load: {len} bytes of data", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The payload length (bytes).
        len: u64,
    },
    /// The engine refuses the state in the checkpoint (see [`Simulation::from_state`]).
    #[error(
        "{}the simulation state is refused by the engine: {source}",
        path.as_ref().map(|p| format!("checkpoint {}: ", p.display())).unwrap_or_default()
    )]
    Refused {
        /// The file (None when the checkpoint was not read by [`restore_checkpoint`]).
        path: Option<PathBuf>,
        /// The engine's error.
        source: SimulationError,
    },
}

/// Writes `checkpoint` to `path` atomically: the file at `path` holds either its previous
/// content or the new checkpoint in full, whatever fails and whenever the process dies (see
/// the module documentation for the format and the procedure).
pub fn write_checkpoint(path: &Path, checkpoint: &Checkpoint) -> Result<(), CheckpointError> {
    let payload = bincode::serde::encode_to_vec(checkpoint, bincode::config::standard())
        .map_err(|e| CheckpointError::Encode { path: path.to_owned(), message: e.to_string() })?;
    let header = encode_header(&payload);
    atomic::write_atomically(path, &[&header, &payload])
        .map_err(|source| CheckpointError::Write { path: path.to_owned(), source })
}

/// The header of a file holding `payload` in the current format.
fn encode_header(payload: &[u8]) -> [u8; CHECKPOINT_HEADER_LEN] {
    let mut header = [0u8; CHECKPOINT_HEADER_LEN];
    header[0..8].copy_from_slice(&CHECKPOINT_MAGIC);
    header[8..12].copy_from_slice(&CHECKPOINT_VERSION.to_le_bytes());
    header[12..20].copy_from_slice(&(payload.len() as u64).to_le_bytes());
    header[20..24].copy_from_slice(&crc32fast::hash(payload).to_le_bytes());
    header
}

/// Reads and checks the checkpoint at `path` (see the module documentation for the checks).
/// The state is checked by the engine later, in [`Checkpoint::into_simulation`].
pub fn read_checkpoint(path: &Path) -> Result<Checkpoint, CheckpointError> {
    let read_err = |source| CheckpointError::Read { path: path.to_owned(), source };
    let mut file = File::open(path).map_err(read_err)?;
    let file_len = file.metadata().map_err(read_err)?.len();
    let mut header = [0u8; CHECKPOINT_HEADER_LEN];
    let got = read_up_to(&mut file, &mut header).map_err(read_err)?;
    if got < CHECKPOINT_HEADER_LEN {
        let known = got.min(CHECKPOINT_MAGIC.len());
        if header[..known] != CHECKPOINT_MAGIC[..known] {
            return Err(CheckpointError::NotACheckpoint { path: path.to_owned() });
        }
        return Err(CheckpointError::TooShort { path: path.to_owned(), len: got as u64 });
    }
    let (declared, stored) = check_header(path, &header)?;
    let available = file_len.saturating_sub(CHECKPOINT_HEADER_LEN as u64);
    if declared > available {
        return Err(CheckpointError::Truncated { path: path.to_owned(), declared, available });
    }
    let too_large = || CheckpointError::TooLarge { path: path.to_owned(), len: declared };
    let len = usize::try_from(declared).map_err(|_| too_large())?;
    let mut payload = Vec::new();
    payload.try_reserve_exact(len).map_err(|_| too_large())?;
    // Read one byte more than declared to see whether the file goes on (it may have grown since
    // its size was taken).
    let limit = declared.saturating_add(1);
    (&mut file).take(limit).read_to_end(&mut payload).map_err(read_err)?;
    if (payload.len() as u64) < declared {
        let available = payload.len() as u64;
        return Err(CheckpointError::Truncated { path: path.to_owned(), declared, available });
    }
    if payload.len() > len || available > declared {
        let extra = available.saturating_sub(declared).max(1);
        return Err(CheckpointError::TrailingBytes { path: path.to_owned(), declared, extra });
    }
    let computed = crc32fast::hash(&payload);
    if computed != stored {
        return Err(CheckpointError::Damaged { path: path.to_owned(), stored, computed });
    }
    decode_payload(&payload)
        .map_err(|message| CheckpointError::Decode { path: path.to_owned(), message })
}

/// Reads the checkpoint at `path` and rebuilds its simulation: [`read_checkpoint`] then
/// [`Checkpoint::into_simulation`], with the file named in every error.
pub fn restore_checkpoint(path: &Path) -> Result<(Simulation, ResumeInfo), CheckpointError> {
    read_checkpoint(path)?.into_simulation().map_err(|e| match e {
        CheckpointError::Refused { source, .. } => {
            CheckpointError::Refused { path: Some(path.to_owned()), source }
        }
        other => other,
    })
}

/// Checks the magic bytes and the version of a header; returns the declared payload length
/// and the stored checksum.
fn check_header(
    path: &Path,
    header: &[u8; CHECKPOINT_HEADER_LEN],
) -> Result<(u64, u32), CheckpointError> {
    let field = |range: std::ops::Range<usize>| {
        let mut bytes = [0u8; 8];
        bytes[..range.len()].copy_from_slice(&header[range]);
        u64::from_le_bytes(bytes)
    };
    if header[..8] != CHECKPOINT_MAGIC {
        return Err(CheckpointError::NotACheckpoint { path: path.to_owned() });
    }
    let found = field(8..12) as u32;
    if found != CHECKPOINT_VERSION {
        return Err(CheckpointError::Version {
            path: path.to_owned(),
            found,
            expected: CHECKPOINT_VERSION,
        });
    }
    Ok((field(12..20), field(20..24) as u32))
}

/// Reads into `buf` until it is full or the file ends; returns the bytes read.
fn read_up_to(file: &mut File, buf: &mut [u8]) -> io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match file.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(n) => got += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

/// Bytes the decoder may claim per payload byte: bincode claims the in-memory size of each
/// integer (up to 16 bytes for a `u128` stored in one) and the length of each string.
const CLAIMS_PER_BYTE: usize = 16;

/// Decodes a whole payload (every byte must be used). The decoder's limit, the smallest of a
/// few sizes above [`CLAIMS_PER_BYTE`] × the payload size, bounds what a crafted length
/// inside the payload (a string's) can make it allocate.
fn decode_payload(payload: &[u8]) -> Result<Checkpoint, String> {
    let need = payload.len().saturating_mul(CLAIMS_PER_BYTE).saturating_add(1 << 16);
    let (checkpoint, used) = if need <= 1 << 26 {
        decode_limited::<{ 1 << 26 }>(payload)
    } else if need <= 1 << 30 {
        decode_limited::<{ 1 << 30 }>(payload)
    } else {
        decode_large(payload, need)
    }?;
    if used != payload.len() {
        return Err(format!("{} bytes left over after the data", payload.len() - used));
    }
    Ok(checkpoint)
}

/// Decodes with a limit of `LIMIT` bytes claimed by the decoder.
fn decode_limited<const LIMIT: usize>(payload: &[u8]) -> Result<(Checkpoint, usize), String> {
    let config = bincode::config::standard().with_limit::<LIMIT>();
    bincode::serde::decode_from_slice(payload, config).map_err(|e| e.to_string())
}

/// Decodes a payload of more than 64 MiB: with a limit of 16 GiB up to 1 GiB of payload (on
/// 64-bit platforms), without a limit above.
#[cold]
fn decode_large(payload: &[u8], need: usize) -> Result<(Checkpoint, usize), String> {
    #[cfg(target_pointer_width = "64")]
    if need <= 1 << 34 {
        return decode_limited::<{ 1 << 34 }>(payload);
    }
    let _ = need;
    bincode::serde::decode_from_slice(payload, bincode::config::standard())
        .map_err(|e| e.to_string())
}

//! Checkpoints of a run directory (`checkpoint.bin`): the state after some steps and how much of
//! the outputs had been written then, so that `flocking run --resume DIR` cuts the outputs back to
//! that point and continues bit-identically.
//!
//! The file is little-endian: the magic `FLOCKCK5`, then as u64 the dimension, the number of
//! agents, the steps, the bits of H(0), the records written, the bytes of `metrics.csv` and of the
//! trajectory, the bytes of the scenario's text and the number of vehicle state values; then the
//! positions and the velocities as f64 (`dim` per agent), the vehicles' states as f64 (none for
//! point masses), the resolved scenario as RON text (so that a resume can refuse a
//! `scenario.ron` edited since), the state of the run's conditions as RON text (empty for an
//! ideal run), and last an
//! FNV-1a hash of everything before it. `FLOCKCK5` is the same layout from a flocking that drew
//! each link's packet loss and jitter from a Philox block of its own (before a receiver's links
//! shared its blocks), `FLOCKCK4` the same from one whose normal draws came from Box–Muller
//! (before the ziggurat), `FLOCKCK3` the same from one whose random draws came from ChaCha8
//! (before issue 31's Philox4x32-10), and `FLOCKCK2` the same without the vehicle count and
//! states: all are still read, their [`Checkpoint::draws`] marking whose draws they continue, and
//! a run whose draws could not continue bit for bit from them (one that draws per link, one that
//! draws normals, one that draws at
//! random) is not resumed. It is written to `checkpoint.tmp`, flushed to the disk, and
//! renamed over `checkpoint.bin` (the directory flushed too), so a run killed while writing one
//! leaves the previous checkpoint intact.
//!
//! The hash is the `fnv` crate's [`FnvHasher`]. The layout is written and read here with
//! `to_le_bytes`/`from_le_bytes`, not by a serialization crate: it is fixed by the checkpoints
//! of five versions that must still resume or be refused with the reason (`FLOCKCK2` to
//! `FLOCKCK6`), and its vectors carry no length of their own (the header's counts size them),
//! which `bincode` and its kin would add; and the state is streamed through the hash into the
//! file, never copied (issue 49).

use std::fs;
use std::hash::Hasher as _;
use std::io::{self, Write};
use std::path::Path;

use fnv::FnvHasher;

use crate::run::Start;
use crate::storage::fs::at;
pub use crate::storage::fs::sync_dir;

/// The checkpoint's file name in the run directory.
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// The temporary file a checkpoint is written to before its rename.
pub const CHECKPOINT_TMP: &str = "checkpoint.tmp";

const MAGIC: &[u8; 8] = b"FLOCKCK6";

/// The magic of the format whose link draws took a block per link, same layout.
const MAGIC_BLOCK_PER_LINK: &[u8; 8] = b"FLOCKCK5";

/// The magic of the format whose normal draws came from Box–Muller, same layout.
const MAGIC_BOX_MULLER: &[u8; 8] = b"FLOCKCK4";

/// The magic of the format whose random draws came from ChaCha8, same layout.
const MAGIC_CHACHA8: &[u8; 8] = b"FLOCKCK3";

/// The magic of the format before vehicles (draws from ChaCha8), read as one without vehicle
/// states.
const MAGIC_WITHOUT_VEHICLES: &[u8; 8] = b"FLOCKCK2";

/// A run's state and the lengths of its outputs at that state.
#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    /// The dimension.
    pub dim: usize,
    /// The state.
    pub start: Start,
    /// The records written.
    pub records: u64,
    /// The bytes of `metrics.csv`.
    pub metrics_bytes: u64,
    /// The bytes of `trajectory.csv`, or the records of `trajectory.npy`.
    pub trajectory_bytes: u64,
    /// The resolved scenario of the run, as RON.
    pub scenario: String,
    /// The random draws of the flocking that wrote it.
    pub draws: DrawsOf,
}

/// The random draws of the flocking that wrote a checkpoint, oldest first: a run continues bit
/// for bit only from a checkpoint whose draws are this version's for every kind it draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum DrawsOf {
    /// ChaCha8 (`FLOCKCK2`, `FLOCKCK3`).
    ChaCha8,
    /// Philox4x32-10 with normals by Box–Muller (`FLOCKCK4`).
    BoxMuller,
    /// Philox4x32-10, normals by the ziggurat, a block per link's loss or jitter draw
    /// (`FLOCKCK5`).
    BlockPerLink,
    /// This version's: a receiver's links share its blocks (`FLOCKCK6`).
    Current,
}

impl Checkpoint {
    /// Writes the checkpoint into `dir` atomically (temporary file, then rename).
    ///
    /// # Errors
    /// On any I/O error.
    pub fn write(&self, dir: &Path) -> io::Result<()> {
        let counts = Counts {
            dim: self.dim,
            records: self.records,
            metrics_bytes: self.metrics_bytes,
            trajectory_bytes: self.trajectory_bytes,
        };
        write_checkpoint(dir, &counts, &self.start, &self.scenario)
    }

    /// Reads the checkpoint of `dir`, if it has one.
    ///
    /// # Errors
    /// A file that is not a whole checkpoint (wrong magic, length or hash), or any I/O error.
    pub fn read(dir: &Path) -> io::Result<Option<Self>> {
        let path = dir.join(CHECKPOINT_FILE);
        let bytes = match fs::read(&path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(at(format_args!("read {}", path.display()))(e)),
        };
        Self::parse(&bytes, &path).map(Some)
    }

    /// The checkpoint of the bytes `bytes` of the file `path` (named by the errors), every field
    /// checked as user input (the fuzz target `checkpoint` feeds it any bytes: fuzz/README.md).
    ///
    /// # Errors
    /// Bytes that are not a whole checkpoint (wrong magic, length or hash), or a field out of its
    /// range, naming it.
    pub fn parse(bytes: &[u8], path: &Path) -> io::Result<Self> {
        let corrupt = |why: &str| {
            io::Error::new(
                io::ErrorKind::InvalidData,
                format!("{} is not a flock checkpoint: {why}", path.display()),
            )
        };
        let (body, hash) = bytes
            .split_last_chunk::<8>()
            .ok_or_else(|| corrupt("too short"))?;
        let words = if [MAGIC, MAGIC_BLOCK_PER_LINK, MAGIC_BOX_MULLER, MAGIC_CHACHA8]
            .iter()
            .any(|magic| body.starts_with(*magic))
        {
            9
        } else if body.starts_with(MAGIC_WITHOUT_VEHICLES) {
            8
        } else {
            return Err(corrupt("wrong magic"));
        };
        if fnv1a(body) != u64::from_le_bytes(*hash) {
            return Err(corrupt("its hash does not match"));
        }
        let word = |k: usize| {
            body.get(MAGIC.len() + 8 * k..MAGIC.len() + 8 * (k + 1))
                .map(|w| u64::from_le_bytes(w.try_into().unwrap_or_default()))
        };
        let header: Option<Vec<u64>> = (0..words).map(word).collect();
        let Some(
            [
                dim,
                agents,
                steps,
                energy,
                records,
                metrics_bytes,
                trajectory_bytes,
                scenario_bytes,
                vehicle @ ..,
            ],
        ) = header.as_deref()
        else {
            return Err(corrupt("too short"));
        };
        // every field read back is checked as user input (issue 27: a forged file with a valid
        // hash and `agents = 2⁶³` overflowed here)
        if !(*dim == 2 || *dim == 3) {
            return Err(corrupt(&format!("its dimension is {dim}, not 2 or 3")));
        }
        if *agents == 0 || *agents > crate::MAX_AGENTS as u64 {
            return Err(corrupt(&format!(
                "it holds {agents} agents, not 1 to {}",
                crate::MAX_AGENTS
            )));
        }
        // at most 3 × 10⁸ coordinates: no overflow
        let size = usize::try_from(dim * agents).map_err(|_| corrupt("too large"))?;
        let vehicle = match vehicle.first() {
            // at most 32 values per agent: no overflow
            Some(&k) if k <= 32 * agents => k as usize,
            Some(k) => return Err(corrupt(&format!("it holds {k} vehicle state values"))),
            None => 0,
        };
        let state_end = MAGIC.len() + 8 * (words + 2 * size + vehicle);
        if body.len() < state_end {
            return Err(corrupt("its length does not match its size"));
        }
        let state: Option<Vec<u64>> = (words..words + 2 * size + vehicle).map(word).collect();
        let state = state.ok_or_else(|| corrupt("its length does not match its size"))?;
        let texts = &body[state_end..];
        let (scenario, conditions) = usize::try_from(*scenario_bytes)
            .ok()
            .and_then(|n| texts.split_at_checked(n))
            .ok_or_else(|| corrupt("its scenario's length does not match"))?;
        let text = |bytes: &[u8], what: &str| {
            std::str::from_utf8(bytes)
                .map(str::to_owned)
                .map_err(|_| corrupt(&format!("its {what} is not text")))
        };
        let floats = |w: &[u64]| w.iter().map(|&b| f64::from_bits(b)).collect();
        Ok(Self {
            dim: usize::try_from(*dim).map_err(|_| corrupt("bad dimension"))?,
            start: Start {
                steps: *steps,
                initial_energy: f64::from_bits(*energy),
                positions: floats(&state[..size]),
                velocities: floats(&state[size..2 * size]),
                conditions: text(conditions, "state of the conditions")?,
                vehicle: floats(&state[2 * size..]),
            },
            records: *records,
            metrics_bytes: *metrics_bytes,
            trajectory_bytes: *trajectory_bytes,
            scenario: text(scenario, "scenario")?,
            draws: if body.starts_with(MAGIC) {
                DrawsOf::Current
            } else if body.starts_with(MAGIC_BLOCK_PER_LINK) {
                DrawsOf::BlockPerLink
            } else if body.starts_with(MAGIC_BOX_MULLER) {
                DrawsOf::BoxMuller
            } else {
                DrawsOf::ChaCha8
            },
        })
    }
}

/// What a checkpoint counts of the outputs besides the state: the dimension, the records and
/// the bytes of `metrics.csv` and of the trajectory written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Counts {
    pub dim: usize,
    pub records: u64,
    pub metrics_bytes: u64,
    pub trajectory_bytes: u64,
}

/// Writes the checkpoint of `start` (with `counts` and the resolved `scenario`) into `dir`
/// atomically, streamed through its hash: the state is never copied (issue 49: a delay line of
/// 320 MB peaked at 1.8 GB while its checkpoint was copied whole twice).
pub(crate) fn write_checkpoint(
    dir: &Path,
    counts: &Counts,
    start: &Start,
    scenario: &str,
) -> io::Result<()> {
    let temporary = dir.join(CHECKPOINT_TMP);
    let write = || {
        let mut out = Hashing {
            inner: io::BufWriter::new(fs::File::create(&temporary)?),
            hash: FnvHasher::default(),
        };
        out.write_all(MAGIC)?;
        for word in [
            counts.dim as u64,
            (start.positions.len() / counts.dim.max(1)) as u64,
            start.steps,
            start.initial_energy.to_bits(),
            counts.records,
            counts.metrics_bytes,
            counts.trajectory_bytes,
            scenario.len() as u64,
            start.vehicle.len() as u64,
        ] {
            out.write_all(&word.to_le_bytes())?;
        }
        for x in start
            .positions
            .iter()
            .chain(&start.velocities)
            .chain(&start.vehicle)
        {
            out.write_all(&x.to_le_bytes())?;
        }
        out.write_all(scenario.as_bytes())?;
        out.write_all(start.conditions.as_bytes())?;
        let hash = out.hash.finish();
        let mut file = out.inner;
        file.write_all(&hash.to_le_bytes())?;
        file.into_inner()
            .map_err(io::IntoInnerError::into_error)?
            .sync_all()
    };
    write().map_err(at(format_args!("write {}", temporary.display())))?;
    let path = dir.join(CHECKPOINT_FILE);
    fs::rename(&temporary, &path).map_err(at(format_args!(
        "rename {} to {}",
        temporary.display(),
        path.display()
    )))?;
    sync_dir(dir).map_err(at(format_args!("flush {}", dir.display())))
}

/// A writer that hashes what goes through it (64-bit FNV-1a, [`FnvHasher`]).
struct Hashing<W> {
    inner: W,
    hash: FnvHasher,
}

impl<W: Write> Hashing<W> {
    fn write_all(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.hash.write(bytes);
        self.inner.write_all(bytes)
    }
}

/// The 64-bit FNV-1a hash of `bytes`.
fn fnv1a(bytes: &[u8]) -> u64 {
    let mut hash = FnvHasher::default();
    hash.write(bytes);
    hash.finish()
}

//! A growing NumPy `.npy` file (format version 1.0) of records of a fixed structured dtype, which
//! `numpy.load` reads without custom code (`np.load("trajectory.npy")["q"]`, memory-mapped with
//! `mmap_mode="r"`).
//!
//! The header has a fixed length, so appending a record is one write of the record at the end of
//! the file followed by one rewrite of the header's row count: a process killed between the two
//! leaves a file whose header counts only complete records (numpy reads exactly that many).
//!
//! Written here, not by a kept library: `npyz` and `ndarray-npy` write a header once (its shape
//! known at the start, or patched at the end of a finished write), so a killed run would leave a
//! header that counts no record or records cut short, and neither reopens a file to append to
//! after a resume; both parse headers with `py_literal` (pest, num-bigint), a compile cost for
//! every build (issue 51). This file is one fixed structured dtype ([`trajectory_dtype`]), and
//! [`read_trajectory_npy`](super::read_trajectory_npy) reads exactly what it writes.

use std::fs::{File, OpenOptions};
use std::io::{self, Seek, SeekFrom, Write};
use std::path::Path;

/// The magic string and version 1.0 of the format.
const MAGIC: &[u8] = b"\x93NUMPY\x01\x00";

/// A `.npy` file of `rows` records of a structured dtype, open for appending.
#[derive(Debug)]
pub struct NpyFile {
    file: File,
    descr: String,
    header_len: u64,
    row_bytes: u64,
    rows: u64,
}

impl NpyFile {
    /// Creates `path` with no rows. `descr` is the dtype as numpy writes it (e.g.
    /// `[('t', '<f8'), ('q', '<f8', (100, 2))]`) and `row_bytes` its item size.
    ///
    /// # Errors
    /// On any I/O error.
    pub fn create(path: &Path, descr: String, row_bytes: u64) -> io::Result<Self> {
        let mut this = Self::at(File::create(path)?, descr, row_bytes, 0);
        this.cut_back()?;
        Ok(this)
    }

    /// Opens the file written by [`NpyFile::create`] at `path`, unchanged, when it holds at least
    /// `rows` records (those a checkpoint counted); [`NpyFile::cut_back`] then cuts it to them.
    ///
    /// # Errors
    /// When the file is shorter than `rows` records ([`io::ErrorKind::UnexpectedEof`]), or on any
    /// I/O error.
    pub fn open_holding(path: &Path, descr: String, row_bytes: u64, rows: u64) -> io::Result<Self> {
        let file = OpenOptions::new().read(true).write(true).open(path)?;
        let this = Self::at(file, descr, row_bytes, rows);
        if this.file.metadata()?.len() < this.len() && rows > 0 {
            return Err(io::Error::new(
                io::ErrorKind::UnexpectedEof,
                format!(
                    "{} holds fewer than the {rows} records its checkpoint counts",
                    path.display()
                ),
            ));
        }
        Ok(this)
    }

    /// The file of `rows` records of `descr` in `file` (not yet cut to them).
    fn at(file: File, descr: String, row_bytes: u64, rows: u64) -> Self {
        let mut this = Self {
            file,
            header_len: 0,
            descr,
            row_bytes,
            rows,
        };
        this.header_len = this.header(u64::MAX).len() as u64;
        this
    }

    /// The length of the file with its records.
    const fn len(&self) -> u64 {
        self.header_len + self.rows * self.row_bytes
    }

    /// Cuts the file to its records and writes its header.
    ///
    /// # Errors
    /// On any I/O error.
    pub fn cut_back(&mut self) -> io::Result<()> {
        self.file.set_len(self.len())?;
        self.write_header()
    }

    /// The number of records.
    #[must_use]
    pub const fn rows(&self) -> u64 {
        self.rows
    }

    /// Flushes the file's data to the disk.
    ///
    /// # Errors
    /// On any I/O error.
    pub fn sync_data(&self) -> io::Result<()> {
        self.file.sync_data()
    }

    /// Appends one record, `row_bytes` long.
    ///
    /// # Errors
    /// When `row` is not one record long, or on any I/O error.
    pub fn append(&mut self, row: &[u8]) -> io::Result<()> {
        if row.len() as u64 != self.row_bytes {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "a record of {} bytes where the dtype has {}",
                    row.len(),
                    self.row_bytes
                ),
            ));
        }
        self.file.seek(SeekFrom::Start(
            self.header_len + self.rows * self.row_bytes,
        ))?;
        self.file.write_all(row)?;
        self.rows += 1;
        self.write_header()
    }

    fn write_header(&mut self) -> io::Result<()> {
        let header = self.header(self.rows);
        self.file.seek(SeekFrom::Start(0))?;
        self.file.write_all(&header)
    }

    /// The header for `rows` records, padded with spaces to the length the largest count needs,
    /// a multiple of 64 bytes as the format asks.
    fn header(&self, rows: u64) -> Vec<u8> {
        let dict = format!(
            "{{'descr': {}, 'fortran_order': False, 'shape': ({rows},), }}",
            self.descr
        );
        let widest = format!(
            "{{'descr': {}, 'fortran_order': False, 'shape': ({},), }}",
            self.descr,
            u64::MAX
        );
        let unpadded = MAGIC.len() + 2 + widest.len() + 1;
        let total = unpadded.div_ceil(64) * 64;
        let dict_len = total - MAGIC.len() - 2;
        let mut header = MAGIC.to_vec();
        let len = u16::try_from(dict_len).unwrap_or(u16::MAX);
        header.extend_from_slice(&len.to_le_bytes());
        header.extend_from_slice(dict.as_bytes());
        header.resize(total - 1, b' ');
        header.push(b'\n');
        header
    }
}

/// The dtype of a trajectory record: `t` and the `n × dim` positions `q` and velocities `p`,
/// with `vehicle` > 0 state values per agent the `n × vehicle` vehicle states `s`, and with
/// `failed` the `n` bytes `failed` (1: the agent has failed, 0: it works).
#[must_use]
pub fn trajectory_dtype(agents: usize, dim: usize, vehicle: usize, failed: bool) -> (String, u64) {
    let mut descr =
        format!("[('t', '<f8'), ('q', '<f8', ({agents}, {dim})), ('p', '<f8', ({agents}, {dim}))");
    if vehicle > 0 {
        descr.push_str(&format!(", ('s', '<f8', ({agents}, {vehicle}))"));
    }
    if failed {
        descr.push_str(&format!(", ('failed', '|u1', ({agents},))"));
    }
    descr.push(']');
    let flags = if failed { agents } else { 0 };
    (
        descr,
        (8 * (1 + agents * (2 * dim + vehicle)) + flags) as u64,
    )
}

//! [`CONTROLS_FILE`]: where a run's inputs came from when not from the scenario's protocol
//! (Python's `controls=f`), so that a resume supplies the same.

use std::fs::File;
use std::io;
use std::path::Path;

use super::directory::RunDirectory;
use super::errors::ResumeError;
use crate::storage::fs::{at, sync_dir, write_durably};

/// The file of a run directory that records where the run's inputs came from when not from the
/// scenario's protocol (Python's `controls=f`).
pub const CONTROLS_FILE: &str = "controls.txt";

/// The start of [`CONTROLS_FILE`]'s line.
const CONTROLS_PREFIX: &str = "inputs from ";

/// The source of the controls recorded in `partial` ([`CONTROLS_FILE`]), if any.
pub(super) fn read_controls(partial: &Path) -> Result<Option<String>, ResumeError> {
    use std::io::Read as _;
    let path = partial.join(CONTROLS_FILE);
    let file = match File::open(&path) {
        Ok(file) => file,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(at(format_args!("read {}", path.display()))(e).into()),
    };
    let mut text = String::new();
    file.take(4096)
        .read_to_string(&mut text)
        .map_err(at(format_args!("read {}", path.display())))?;
    let line = text.trim_end();
    Ok(Some(
        line.strip_prefix(CONTROLS_PREFIX)
            .unwrap_or(line)
            .to_owned(),
    ))
}

impl RunDirectory {
    /// Records in [`CONTROLS_FILE`] that the run's inputs come from `source` (e.g. "Python
    /// controls `f`"), not from the scenario's protocol: a resume must supply them
    /// ([`RunDirectory::resume_with_controls`]). The file stays in the finished `DIR`.
    ///
    /// # Errors
    /// Any I/O error, with its path.
    pub fn record_controls(&mut self, source: &str) -> io::Result<()> {
        let line = source.replace('\n', " ");
        write_durably(
            &self.partial.join(CONTROLS_FILE),
            format!("{CONTROLS_PREFIX}{line}\n").as_bytes(),
        )?;
        sync_dir(&self.partial).map_err(at(format_args!("flush {}", self.partial.display())))?;
        self.controls = Some(line);
        Ok(())
    }

    /// Where the run's inputs come from, when not from the scenario's protocol
    /// ([`RunDirectory::record_controls`]).
    #[must_use]
    pub fn controls(&self) -> Option<&str> {
        self.controls.as_deref()
    }
}

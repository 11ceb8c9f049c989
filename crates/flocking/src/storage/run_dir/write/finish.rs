//! The end of a run directory: finished and moved into place ([`RunDirectory::finish`]), kept
//! incomplete with its note, or abandoned.

use std::fs;
use std::io;
use std::path::PathBuf;

use super::columns::{agent_header, write_state};
use super::directory::{Finished, RunDirectory};
use super::note::{FAILED, INCOMPLETE_FILE, INCOMPLETE_TMP, force_line, write_incomplete};
use crate::storage::fs::{at, parent_of, rename_no_replace, sync_dir, write_durably};
use crate::storage::owned::{self, DirError, Kind};
use crate::storage::run_dir::checkpoint::{CHECKPOINT_FILE, CHECKPOINT_TMP};
use crate::storage::run_dir::verdict::{VERDICT_FILE, judge_metrics_file, verdict_text};
use crate::verdict::Verdict;

/// The files of a running or interrupted run that a complete run does not keep, the note last:
/// removed by the final rename's tidy-up and by a resume that finds the rename done.
pub(super) const RUN_LEFTOVERS: [&str; 5] = [
    CHECKPOINT_FILE,
    CHECKPOINT_TMP,
    INCOMPLETE_TMP,
    owned::MANIFEST_TMP,
    INCOMPLETE_FILE,
];

impl RunDirectory {
    /// Writes `final.csv` and [`VERDICT_FILE`] and moves the directory into place: renames
    /// `DIR.partial` to `DIR`, then removes its checkpoint and `INCOMPLETE` note. A `DIR` is
    /// replaced only if it was empty when the run started and still is, or if `force` was set
    /// and it is flocking's ([`owned::remove`]); a `DIR` that appeared during the run is never
    /// renamed over (the rename itself refuses an existing `DIR`: it is made with `RENAME_NOREPLACE`).
    ///
    /// # Errors
    /// Any I/O error, naming the operation and the path; `DIR.partial` is then kept with its
    /// records, its checkpoint and its note, resumable (the message says how).
    pub fn finish(mut self) -> io::Result<Finished> {
        let verdict = self.complete().map_err(|e| {
            io::Error::new(
                e.kind(),
                format!(
                    "{e}\nthe run is kept in {}; once that is fixed, finish it with `flocking run --resume {}`",
                    self.partial.display(),
                    self.target.display()
                ),
            )
        })?;
        Ok(Finished {
            path: self.target.clone(),
            verdict,
        })
    }

    fn complete(&mut self) -> io::Result<Option<Verdict>> {
        let header = agent_header(self.dim, self.vehicle_columns, self.marks_failed);
        let mut last = format!("{}\n", header[1..].join(",")).into_bytes();
        let coordinates = self.row_width();
        for (i, state) in self.last_state.chunks_exact(coordinates).enumerate() {
            write_state(&mut last, i, state);
        }
        write_durably(&self.partial.join("final.csv"), &last)?;
        self.sync_outputs()?;
        let verdict = judge_metrics_file(
            &self.partial.join("metrics.csv"),
            self.agents,
            self.verdict_kind,
            &self.criteria,
        )?;
        let text = verdict_text(verdict.as_ref(), self.verdict_kind, &self.criteria);
        write_durably(&self.partial.join(VERDICT_FILE), text.as_bytes())?;
        // every file of the run, by size and content, once none will change (issue 27)
        owned::record_manifest(&self.partial)?;
        self.clear_target()?;
        // a `DIR` that appears between the check and the rename is not renamed over
        rename_no_replace(&self.partial, &self.target).map_err(|e| {
            if e.kind() == io::ErrorKind::AlreadyExists {
                io::Error::new(
                    e.kind(),
                    format!(
                        "cannot rename {} to {}: {} appeared during the run; move it away",
                        self.partial.display(),
                        self.target.display(),
                        self.target.display()
                    ),
                )
            } else {
                at(format_args!(
                    "rename {} to {}",
                    self.partial.display(),
                    self.target.display()
                ))(e)
            }
        })?;
        self.lock.moved_to(&self.target);
        let parent = parent_of(&self.target);
        sync_dir(parent).map_err(at(format_args!("flush {}", parent.display())))?;
        // with the temporary files a failed write (a full disk) may have left
        owned::remove_own_files(&self.target, Kind::Run, &RUN_LEFTOVERS)
            .map_err(io::Error::other)?;
        Ok(verdict)
    }

    /// Makes way for the rename to `DIR`: removes a `DIR` that was empty when the run started
    /// and still is, or with `force` one that flocking wrote; refuses any other, even an empty
    /// one that appeared during the run.
    fn clear_target(&self) -> io::Result<()> {
        let target = &self.target;
        if fs::symlink_metadata(target).is_err() {
            return Ok(());
        }
        // `remove_dir` removes only an empty directory, atomically.
        if self.empty_target && fs::remove_dir(target).is_ok() {
            return Ok(());
        }
        let refused = |why: String| {
            io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!(
                    "cannot rename {} to {}: {why}",
                    self.partial.display(),
                    target.display()
                ),
            )
        };
        if !self.force {
            return Err(refused(format!(
                "{} appeared during the run; move it away",
                target.display()
            )));
        }
        owned::remove(target, Kind::Run).map_err(|e| match e {
            DirError::Io(e) => e,
            e => refused(e.to_string()),
        })
    }

    /// Abandons the run: removes the partial directory (flocking's, [`owned::remove`]).
    pub fn abandon(self) {
        let _ = owned::remove(&self.partial, Kind::Run);
    }

    /// Keeps the partial directory, its records and its last checkpoint, and says in its
    /// `INCOMPLETE` file why the run stopped; `resumable` tells whether `flocking run --resume` may
    /// continue it. Returns the partial directory.
    ///
    /// # Errors
    /// When the note cannot be written.
    pub fn keep_incomplete(self, why: &str, resumable: bool) -> io::Result<PathBuf> {
        let note = if resumable {
            format!(
                "incomplete: {why}\nEvery record in this directory is complete up to the last one written.\nResume: flocking run --resume {}\n{}",
                self.target.display(),
                force_line(self.force)
            )
        } else {
            format!(
                "{FAILED}: {why}\nEvery record in this directory is complete up to the last one written; the run cannot be resumed.\n"
            )
        };
        write_incomplete(&self.partial, &note)?;
        Ok(self.partial)
    }
}

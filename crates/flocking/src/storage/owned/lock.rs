//! The lock of a directory being written ([`DirLock`]): one writer at a time.

use std::fs::{self, File, OpenOptions};
use std::io::{Read as _, Seek as _, Write as _};
use std::os::unix::fs::MetadataExt as _;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use super::error::DirError;
use super::names::LOCK_FILE;
use crate::storage::fs::at;

/// An exclusive lock on a directory being written, held until dropped (or until the process
/// dies: the operating system then releases it). Dropping it removes its [`LOCK_FILE`], if that
/// path still names the very file it locked.
#[derive(Debug)]
pub struct DirLock {
    file: File,
    path: PathBuf,
}

impl DirLock {
    /// Locks the existing directory `dir` and writes this process's id and start time into its
    /// [`LOCK_FILE`].
    ///
    /// # Errors
    /// [`DirError::Busy`] when another process holds the lock; any I/O error, with its path.
    pub fn acquire(dir: &Path) -> Result<Self, DirError> {
        let path = dir.join(LOCK_FILE);
        loop {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(at(format_args!("open {}", path.display())))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(fs::TryLockError::WouldBlock) => {
                    let mut holder = String::new();
                    let _ = file.read_to_string(&mut holder);
                    let holder = holder.trim();
                    return Err(DirError::Busy {
                        dir: dir.to_owned(),
                        holder: if holder.is_empty() {
                            "another process".into()
                        } else {
                            holder.to_owned()
                        },
                    });
                }
                Err(fs::TryLockError::Error(e)) => {
                    return Err(at(format_args!("lock {}", path.display()))(e).into());
                }
            }
            // The holder before us may have removed the file between our open and our lock: the
            // lock is ours only if the path still names the file we locked.
            let same = |m: fs::Metadata| {
                file.metadata()
                    .is_ok_and(|ours| ours.ino() == m.ino() && ours.dev() == m.dev())
            };
            if !fs::metadata(&path).is_ok_and(same) {
                continue;
            }
            let holder = format!("process {}, started {}\n", std::process::id(), utc_now());
            let write = |file: &mut File| {
                file.set_len(0)?;
                file.rewind()?;
                file.write_all(holder.as_bytes())
            };
            write(&mut file).map_err(at(format_args!("write {}", path.display())))?;
            return Ok(Self { file, path });
        }
    }

    /// Follows the directory after it was renamed to `dir`.
    pub fn moved_to(&mut self, dir: &Path) {
        self.path = dir.join(LOCK_FILE);
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        // Removed while still locked, so that no other writer can lock this file afterwards
        // believing it holds the directory; only if the path still names the file this lock
        // holds (same device and inode), so that nothing else put there is ever removed.
        let ours = |m: fs::Metadata| {
            self.file
                .metadata()
                .is_ok_and(|held| m.is_file() && (held.dev(), held.ino()) == (m.dev(), m.ino()))
        };
        if fs::symlink_metadata(&self.path).is_ok_and(ours) {
            let _ = fs::remove_file(&self.path);
        }
        let _ = self.file.unlock();
    }
}

/// The current time in UTC, `YYYY-MM-DD HH:MM:SS UTC`.
fn utc_now() -> String {
    let seconds = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, time) = (seconds / 86_400, seconds % 86_400);
    // Howard Hinnant's days-to-civil algorithm.
    let z = days.cast_signed() + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC",
        time / 3600,
        time / 60 % 60,
        time % 60
    )
}

#[cfg(test)]
mod tests {
    use super::{DirLock, LOCK_FILE};

    /// A lock removes its own lock file when dropped, and leaves a file that has replaced it.
    #[test]
    fn a_dropped_lock_removes_only_its_own_file() {
        let dir = std::env::temp_dir().join(format!("flocking-dirlock-{}", std::process::id()));
        std::fs::create_dir(&dir).expect("a new directory");
        let lock_file = dir.join(LOCK_FILE);
        drop(DirLock::acquire(&dir).expect("locked"));
        assert!(!lock_file.exists(), "its own lock file removed");

        let lock = DirLock::acquire(&dir).expect("locked");
        let moved = dir.join("moved");
        std::fs::rename(&lock_file, &moved).expect("moved away");
        std::fs::write(&lock_file, "another's\n").expect("a file in its place");
        drop(lock);
        assert_eq!(std::fs::read(&lock_file).expect("kept"), b"another's\n");

        // only the two files this test made, each checked to hold what was written into it
        let holder = format!("process {}, started ", std::process::id());
        let moved_text = std::fs::read_to_string(&moved).expect("the moved lock file");
        assert!(moved_text.starts_with(&holder), "{moved_text}");
        for file in [&lock_file, &moved] {
            std::fs::remove_file(file).expect("clean");
        }
        std::fs::remove_dir(&dir).expect("clean");
    }
}

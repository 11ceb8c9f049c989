//! flocking's own temporary files (`NAME.tmp`): written new, never through a link, never over a
//! file flocking did not leave.

use std::fs::{self, OpenOptions};
use std::io::{self, Write as _};
use std::path::Path;

use super::error::link_refused;
use super::special::is_mount_point;
use crate::storage::fs::at;

/// Writes `bytes` into `tmp`, one of flocking's own `.tmp` names, flushed, never through a link
/// (`O_NOFOLLOW`) and never over a file it finds there (`O_EXCL`) unless `leftover_is_ours`: the
/// caller has checked flocking's marker and knows a `tmp` there can only be a write of
/// flocking's cut short (the manifest's own temporary file, or a `NAME.tmp` whose write the
/// manifest records), which is then removed first, and only a regular file that is no mount
/// point. When the write fails, the file this call created is removed, and only while `tmp`
/// still names it.
///
/// # Errors
/// A link or a file flocking did not leave in `tmp`'s place, or any I/O error, with its path.
pub(crate) fn write_tmp(tmp: &Path, bytes: &[u8], leftover_is_ours: bool) -> io::Result<()> {
    use std::os::unix::fs::{MetadataExt as _, OpenOptionsExt as _};
    let create = || {
        OpenOptions::new()
            .write(true)
            .create_new(true)
            .custom_flags(rustix::fs::OFlags::NOFOLLOW.bits().cast_signed())
            .open(tmp)
    };
    let found = || fs::symlink_metadata(tmp);
    let opened = match create() {
        Err(e)
            if e.kind() == io::ErrorKind::AlreadyExists
                && leftover_is_ours
                && found().is_ok_and(|m| m.is_file())
                && !is_mount_point(tmp) =>
        {
            fs::remove_file(tmp).map_err(at(format_args!("remove {}", tmp.display())))?;
            create()
        }
        opened => opened,
    };
    let mut file = opened.map_err(|e| {
        if e.kind() == io::ErrorKind::AlreadyExists {
            io::Error::new(
                e.kind(),
                format!(
                    "{} exists and flocking did not leave it there: flocking never writes over it; move it away",
                    tmp.display()
                ),
            )
        } else if e.raw_os_error() == Some(rustix::io::Errno::LOOP.raw_os_error()) {
            link_refused(tmp)
        } else {
            at(format_args!("write {}", tmp.display()))(e)
        }
    })?;
    file.write_all(bytes)
        .and_then(|()| file.sync_all())
        .map_err(|e| {
            // only the file created above, while `tmp` still names it
            let created = file.metadata().map(|m| (m.dev(), m.ino()));
            if found().is_ok_and(|m| created.is_ok_and(|c| c == (m.dev(), m.ino()))) {
                let _ = fs::remove_file(tmp);
            }
            at(format_args!("write {}", tmp.display()))(e)
        })
}

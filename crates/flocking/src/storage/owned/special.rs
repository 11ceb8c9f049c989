//! The directories flocking never removes: the filesystem root, the working directory and its
//! ancestors, and mount points.

use std::fs;
use std::os::unix::fs::MetadataExt as _;
use std::path::Path;

use super::error::DirError;
use crate::storage::fs::at;

/// Refuses the filesystem root, the working directory and its ancestors, and mount points.
pub(super) fn check_special(dir: &Path) -> Result<(), DirError> {
    let special = |what| {
        Err(DirError::Special {
            dir: dir.to_owned(),
            what,
        })
    };
    let real = fs::canonicalize(dir).map_err(at(format_args!("resolve {}", dir.display())))?;
    let Some(parent) = real.parent() else {
        return special("the filesystem root");
    };
    let cwd = std::env::current_dir().map_err(at("read the working directory"))?;
    if fs::canonicalize(&cwd).is_ok_and(|cwd| cwd.starts_with(&real)) {
        return special("the working directory or one of its parents");
    }
    let device = |path: &Path| {
        fs::metadata(path)
            .map(|m| m.dev())
            .map_err(at(format_args!("read {}", path.display())))
    };
    if device(&real)? != device(parent)? || is_mount_point(&real) {
        return special("a mount point");
    }
    Ok(())
}

/// Whether `/proc/self/mountinfo` lists `dir` (a canonical path) as a mount point (a bind mount
/// shares its parent's device).
pub(super) fn is_mount_point(dir: &Path) -> bool {
    let Ok(table) = fs::read_to_string("/proc/self/mountinfo") else {
        return false;
    };
    table
        .lines()
        .filter_map(|line| line.split(' ').nth(4))
        .any(|point| Path::new(&unescape_mount_point(point)) == dir)
}

/// A mount point as `/proc/self/mountinfo` writes it, with `\ooo` octal escapes undone.
fn unescape_mount_point(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let octal = bytes.get(i + 1..i + 4).and_then(|digits| {
            std::str::from_utf8(digits)
                .ok()
                .and_then(|d| u8::from_str_radix(d, 8).ok())
        });
        match (bytes[i], octal) {
            (b'\\', Some(byte)) => {
                out.push(byte);
                i += 4;
            }
            (byte, _) => {
                out.push(byte);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::unescape_mount_point;

    #[test]
    fn mount_points_are_unescaped() {
        assert_eq!(unescape_mount_point(r"/mnt/a\040b"), "/mnt/a b");
        assert_eq!(unescape_mount_point("/plain"), "/plain");
    }
}

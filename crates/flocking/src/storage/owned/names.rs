//! The names of flocking's own files in every directory it writes: its marker, its lock and its
//! manifest.

/// The marker file of every directory flocking writes.
pub const MARKER_FILE: &str = ".flocking";

/// The lock file of a directory being written: it holds the writer's process id and start time
/// while it writes, and is removed when the writer is done.
pub const LOCK_FILE: &str = ".flocking.lock";

/// The manifest file of a directory flocking wrote.
pub const MANIFEST_FILE: &str = ".flocking.manifest";

/// The manifest being written, renamed over [`MANIFEST_FILE`] once whole.
pub const MANIFEST_TMP: &str = ".flocking.manifest.tmp";

//! What wrote a directory ([`Kind`]), and the names a directory of each kind is made of.

use super::names::{LOCK_FILE, MANIFEST_FILE, MANIFEST_TMP, MARKER_FILE};

/// What wrote a directory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A run directory (`flocking run`, `DIR` and `DIR.partial`).
    Run,
    /// A sweep's output directory (`flocking sweep`, `sweep merge`, Python's `sweep`).
    Sweep,
    /// The gallery of `flocking figures`.
    Figures,
}

impl Kind {
    /// The marker's text.
    pub(super) fn marker(self) -> String {
        format!("written by flocking {}\n", self.command())
    }

    /// What a directory of this kind is, for messages.
    pub(super) const fn what(self) -> &'static str {
        match self {
            Self::Run => "a run directory",
            Self::Sweep => "a sweep's output directory",
            Self::Figures => "a gallery of flocking figures",
        }
    }

    pub(super) fn command(self) -> &'static str {
        match self {
            Self::Run => "run",
            Self::Sweep => "sweep",
            Self::Figures => "figures",
        }
    }

    /// The files a directory of this kind may hold at its top level when [`remove`] removes it
    /// (each a regular file, never a link), besides the subdirectories of [`Kind::subdirectories`].
    pub(super) fn entries(self) -> &'static [&'static str] {
        match self {
            Self::Run => RUN_FILES,
            // Sweeps and galleries are written into, never removed.
            Self::Sweep | Self::Figures => &[],
        }
    }

    /// Whether `name` is one of the names a directory of this kind is made of, which
    /// [`write_file`] never replaces: its files and subdirectories.
    pub(super) fn is_reserved(self, name: &str) -> bool {
        let files: &[&str] = match self {
            Self::Run => RUN_FILES,
            Self::Sweep => &[
                MARKER_FILE,
                LOCK_FILE,
                "sweep.ron",
                "sweep.tmp",
                "runs.csv",
                "runs.tmp",
                "times.csv",
                "times.tmp",
                "rows",
                "runs",
                MANIFEST_FILE,
                MANIFEST_TMP,
            ],
            Self::Figures => &[
                MARKER_FILE,
                LOCK_FILE,
                MANIFEST_FILE,
                MANIFEST_TMP,
                "index.html",
                "functions",
            ],
        };
        files.contains(&name) || self.subdirectories().iter().any(|&(dir, _)| dir == name)
    }

    /// The subdirectories a directory of this kind may hold when [`remove`] removes it, each
    /// with the files it may hold (regular files, never links, no deeper directories).
    pub(super) fn subdirectories(self) -> &'static [(&'static str, &'static [&'static str])] {
        match self {
            Self::Run => &[(FIGURES_DIR, RUN_FIGURES)],
            Self::Sweep | Self::Figures => &[],
        }
    }
}

/// Every file flocking writes at the top of a run directory.
const RUN_FILES: &[&str] = &[
    MARKER_FILE,
    LOCK_FILE,
    "metrics.csv",
    "trajectory.csv",
    "trajectory.npy",
    "final.csv",
    "scenario.ron",
    "flocking.txt",
    "checkpoint.bin",
    "checkpoint.tmp",
    "INCOMPLETE",
    "INCOMPLETE.tmp",
    "controls.txt",
    MANIFEST_FILE,
    MANIFEST_TMP,
];

/// The subdirectory of a run directory that `flocking plot` draws into.
pub const FIGURES_DIR: &str = "figures";

/// Every file `flocking plot` writes into a run's [`FIGURES_DIR`]: a run directory holding any
/// other is never removed (issue 27: ownership at every depth).
pub const RUN_FIGURES: &[&str] = &[
    "snapshots.svg",
    "snapshots.png",
    "snapshots_top.svg",
    "snapshots_top.png",
    "views.svg",
    "views.png",
    "metrics.svg",
    "metrics.png",
    "reynolds.svg",
    "reynolds.png",
    "animation.gif",
    "player.html",
];

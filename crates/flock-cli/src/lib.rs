//! The `flocking` command line: what is about the terminal — the progress bar of a run
//! ([`Progress`]), the printed summary ([`Report`]), `flocking figures` ([`figures()`]) and
//! `flocking bench` ([`mod@bench`]), `flocking sweep` ([`sweep`]), the resource estimate and bounds ([`resources`]). Scenarios, runs and run directories are the `flocking`
//! library's; figures are `flock-viz`'s.

#[macro_use]
pub mod console;
pub mod bench;
pub mod figures;
pub mod progress;
pub mod resources;
pub mod summary;
pub mod sweep;

pub use figures::{FiguresError, figures};
pub use progress::Progress;
pub use summary::Report;

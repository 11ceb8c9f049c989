//! Integration tests of `flock-cli`, one binary (see STYLE.md): the `flocking` binary's commands,
//! errors and crash safety (kills, Ctrl-C, resume), the printed summary, `flocking bench`, `flocking plot`, `flocking figures`
//! the HTML player in a browser, and the warnings before a run.

mod bench;
mod browser;
mod common;
mod errors;
mod figures_cmd;
mod hostile;
mod issue27;
mod issue49;
mod merging;
mod names;
mod pipes;
mod plot;
mod round_trip;
mod summary;
mod sweep;
mod trust;
mod warnings;

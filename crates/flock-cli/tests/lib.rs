//! Integration tests of `flock-cli`, one binary (see STYLE.md): the `flock` binary's commands,
//! errors and crash safety (kills, Ctrl-C, resume), `flock bench`, `flock plot`, `flock figures`
//! and the HTML player in a browser.

mod bench;
mod browser;
mod common;
mod errors;
mod figures_cmd;
mod plot;
mod sweep;
mod trust;

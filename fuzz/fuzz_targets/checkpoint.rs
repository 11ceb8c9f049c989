//! Checkpoint bytes → [`Checkpoint::parse`]: `Ok` or `Err`, whatever the bytes — never a panic,
//! an abort or an allocation that cannot be met (issue 27: a forged checkpoint with a valid hash,
//! `dim = 1, agents = 2⁶³`, panicked). An accepted checkpoint holds `dim` (2 or 3) coordinates
//! per agent in its positions and velocities.
#![no_main]

use std::path::Path;

use flocking::run_dir::Checkpoint;
use libfuzzer_sys::fuzz_target;

fn check_input(data: &[u8]) {
    let Ok(checkpoint) = Checkpoint::parse(data, Path::new("fuzz/checkpoint.bin")) else {
        return;
    };
    assert!(checkpoint.dim == 2 || checkpoint.dim == 3, "dim {}", checkpoint.dim);
    let start = &checkpoint.start;
    assert_eq!(start.positions.len(), start.velocities.len());
    assert_eq!(start.positions.len() % checkpoint.dim, 0);
}

fuzz_target!(|data: &[u8]| check_input(data));

//! Checkpoint bytes → [`Checkpoint::parse`]: `Ok` or `Err`, whatever the bytes — never a panic,
//! an abort or an allocation that cannot be met (issue 27: a forged checkpoint with a valid hash,
//! `dim = 1, agents = 2⁶³`, panicked); each input is tried as it is and with a valid hash
//! appended, so that mutations get past the hash to every field's check. An accepted checkpoint
//! holds `dim` (2 or 3) coordinates per agent in its positions and velocities.
#![no_main]

use std::path::Path;

use flocking::run_dir::Checkpoint;
use libfuzzer_sys::fuzz_target;

/// The 64-bit FNV-1a hash a checkpoint ends with (as `checkpoint.rs` computes it).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn check_input(data: &[u8]) {
    check_parsed(data);
    // the bytes forged with a valid hash, so that mutations reach the checks of every field
    let mut forged = data.to_vec();
    forged.extend_from_slice(&fnv1a(data).to_le_bytes());
    check_parsed(&forged);
}

fn check_parsed(data: &[u8]) {
    let Ok(checkpoint) = Checkpoint::parse(data, Path::new("fuzz/checkpoint.bin")) else {
        return;
    };
    assert!(checkpoint.dim == 2 || checkpoint.dim == 3, "dim {}", checkpoint.dim);
    let start = &checkpoint.start;
    assert_eq!(start.positions.len(), start.velocities.len());
    assert_eq!(start.positions.len() % checkpoint.dim, 0);
}

fuzz_target!(|data: &[u8]| check_input(data));

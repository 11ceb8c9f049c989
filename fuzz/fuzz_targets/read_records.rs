//! A run directory's `metrics.csv`, read back → [`read_records`] (what `--resume` and the
//! verdict of `flocking.txt` read): `Ok` or `Err`, whatever the bytes and the number of agents —
//! never a panic or an abort. The first byte is the number of agents (0 to 255), the rest the
//! file.
#![no_main]

use flocking::run_dir::read_records;
use libfuzzer_sys::fuzz_target;

fn check_input(data: &[u8]) {
    let Some((&agents, text)) = data.split_first() else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("flock-fuzz-records-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    let path = dir.join("metrics.csv");
    std::fs::write(&path, text).expect("the file written");
    let _ = read_records(&path, usize::from(agents));
}

fuzz_target!(|data: &[u8]| check_input(data));

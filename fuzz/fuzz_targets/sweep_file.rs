//! Sweep text → [`Sweep::parse`]: `Ok` or `Err`, whatever the bytes — never a panic, an abort, an
//! allocation that cannot be met, a stack overflow or a hang (docs/fuzzing.md).
//!
//! Base scenarios named by `Path("…")` are read relative to `fixtures/`, so that the fuzzer reaches
//! the checks of axes and runs with real scenarios. An accepted sweep also round-trips: the
//! self-contained `to_ron` (what `sweep.ron` of an output directory holds) parses back equal, with
//! the same runs and run ids.
#![no_main]

use std::path::Path;

use flocking::sweep::Sweep;
use libfuzzer_sys::fuzz_target;

/// Sweeps with more runs are skipped once their count is known (`Sweep::parse` checks every
/// run's scenario, about 0.1–1 ms each: 10⁶ runs are minutes, a cost linear in what the file
/// asks and bounded by `MAX_RUNS`, which the CLI's Ctrl-C interrupts). Counts above `MAX_RUNS`
/// are still parsed, and refused.
const MAX_CHECKED_RUNS: usize = 64;

fn check_input(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let fixtures = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../fixtures"));
    // The run count of the file as written, before `parse` checks every run.
    if let Ok(raw) = flocking::input::ron_options()
        .from_str::<Sweep>(flocking::input::without_bom(text))
        && let Ok(runs) = raw.run_count()
        && runs > MAX_CHECKED_RUNS
    {
        return;
    }
    let Ok(sweep) = Sweep::parse(text, "fuzz", fixtures) else {
        return;
    };
    let runs = sweep.runs();
    assert_eq!(Ok(runs.len()), sweep.run_count(), "runs() and run_count()");
    let ron = sweep.to_ron().expect("a parsed sweep serializes");
    let back = Sweep::parse(&ron, "round-trip", fixtures)
        .unwrap_or_else(|e| panic!("to_ron output does not parse back: {e}\n{ron}"));
    assert_eq!(back, sweep, "to_ron changed the sweep\n{ron}");
    let back_runs = back.runs();
    for (run, again) in runs.iter().zip(&back_runs) {
        assert_eq!(run.id(&sweep.axes), again.id(&back.axes), "a run id changed");
    }
}

fuzz_target!(|data: &[u8]| check_input(data));

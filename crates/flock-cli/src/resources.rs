//! What a command may ask of the machine: thread counts within reason, finite ε, and the
//! resource estimate printed and checked before a run or sweep writes anything.

use std::path::Path;

use flocking::estimate::{Estimate, Resources, check_threads};

/// `--threads` / `--jobs`: from 1 to [`flocking::estimate::THREADS_PER_CORE`] × the available
/// cores.
///
/// # Errors
/// Not a whole number in that range, with the range.
pub fn parse_threads(text: &str) -> Result<usize, String> {
    // a number that does not parse gets the range too: the check of 0 says it
    let threads = text.parse::<usize>().unwrap_or(0);
    check_threads(threads).map_err(|e| format!("{text:?}: {e}"))
}

/// `--epsilon1` / `--epsilon2`: a finite number > 0.
///
/// # Errors
/// NaN, an infinity, zero, a negative number or not a number.
pub fn parse_epsilon(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(e) if e.is_finite() && e > 0.0 => Ok(e),
        _ => Err(format!(
            "{text:?}: give a finite tolerance > 0 (the papers' examples use 0.01)"
        )),
    }
}

/// Prints `estimate` (one line on stdout, its warnings on stderr) and, unless `unchecked`,
/// refuses it when it does not fit in this machine's memory or the free space where `out` goes.
/// The fixes named are those of `flocking sweep` when `sweep`, else of `flocking run`.
///
/// # Errors
/// What does not fit, with the figures and the flag that overrides.
pub fn announce(
    estimate: &Estimate,
    out: Option<&Path>,
    flags: (bool, bool),
) -> Result<(), String> {
    outln!("{estimate}");
    check(estimate, out, flags)
}

/// [`announce`] without the estimate's line: its warnings on stderr and, unless `unchecked`, the
/// refusal of what does not fit (for `flocking validate`, whose stdout is the scenario alone).
///
/// # Errors
/// As [`announce`].
pub fn check(
    estimate: &Estimate,
    out: Option<&Path>,
    (unchecked, sweep): (bool, bool),
) -> Result<(), String> {
    let warnings = if sweep {
        estimate.sweep_warnings()
    } else {
        estimate.warnings()
    };
    for warning in warnings {
        errln!("{warning}");
    }
    if unchecked {
        return Ok(());
    }
    let resources = match out {
        Some(out) => Resources::of_machine(out),
        None => Resources {
            disk_bytes: None,
            ..Resources::of_machine(Path::new("."))
        },
    };
    if sweep {
        estimate.check_sweep(&resources)
    } else {
        estimate.check(&resources)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thread_counts_and_tolerances_are_bounded() {
        assert_eq!(parse_threads("1"), Ok(1));
        for bad in ["0", "100000", "-1", "two"] {
            assert!(
                parse_threads(bad).unwrap_err().contains("from 1 to"),
                "{bad}"
            );
        }
        assert_eq!(parse_epsilon("0.01"), Ok(0.01));
        for bad in ["NaN", "inf", "0", "-1"] {
            assert!(parse_epsilon(bad).is_err(), "{bad}");
        }
    }
}

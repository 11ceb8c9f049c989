//! `flocking.txt`: the model's verdict judged on a finished run's `metrics.csv` over a window of
//! its records (by default the last quarter) — TAC 2006 Definition 5 (an α-flock, a strict one)
//! or a classic model's own states ([`Verdict`]); the records of a `metrics.csv` read back
//! ([`read_records`]).

use std::io;
use std::path::Path;

use flock_metrics::{FlockMetrics, FlockingCriteria};

use crate::verdict::{Verdict, VerdictKind, criteria_text};

use super::read::{TIME, read_metrics};

/// The verdict's file in a finished run directory.
pub const VERDICT_FILE: &str = "flocking.txt";

/// The verdict of kind `kind` judged on the `metrics.csv` at `path` of a run of `agents` agents;
/// `None` when the window holds no record.
///
/// # Errors
/// As [`read_records`].
pub fn judge_metrics_file(
    path: &Path,
    agents: usize,
    kind: VerdictKind,
    criteria: &FlockingCriteria,
) -> io::Result<Option<Verdict>> {
    Ok(Verdict::judge(kind, &read_records(path, agents)?, criteria))
}

/// The records of the `metrics.csv` at `path` of a run of `agents` agents, as a run's
/// [`RunSummary::history`](crate::RunSummary::history) holds them: every row, also those before a
/// `--resume` (the number of components is read back from C = (n − #components)/(n − 1)).
///
/// # Errors
/// A file that cannot be read or lacks a metric column.
pub fn read_records(path: &Path, agents: usize) -> io::Result<Vec<(f64, FlockMetrics)>> {
    let columns = read_metrics(path).map_err(io::Error::other)?;
    let column = |name: &str| {
        columns
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, values)| values.as_slice())
            .ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!("{} has no {name:?} column", path.display()),
                )
            })
    };
    let (t, collisions) = (column(TIME)?, column("collisions")?);
    let reals =
        (FlockMetrics::REAL_COLUMNS.into_iter().map(column)).collect::<io::Result<Vec<_>>>()?;
    // files written before the extra columns existed leave them NaN
    let extras: Vec<Option<&[f64]>> = FlockMetrics::EXTRA_COLUMNS
        .into_iter()
        .map(|name| column(name).ok())
        .collect();
    let n = agents as f64;
    Ok((0..t.len())
        .map(|k| {
            let values: [f64; 6] = std::array::from_fn(|j| reals[j][k]);
            // an empty flock's C is NaN (undefined): no component
            let components = if values[0].is_nan() {
                0
            } else if agents <= 1 {
                1
            } else {
                (n - values[0] * (n - 1.0)).round() as usize
            };
            let metrics = FlockMetrics::from_reals(values, components, collisions[k] as usize)
                .with_extras(std::array::from_fn(|j| {
                    extras[j].map_or(f64::NAN, |column| column[k])
                }));
            (t[k], metrics)
        })
        .collect())
}

/// The text of `flocking.txt`: the verdict (of kind `kind`) and the criteria it was judged by.
#[must_use]
pub fn verdict_text(
    verdict: Option<&Verdict>,
    kind: VerdictKind,
    criteria: &FlockingCriteria,
) -> String {
    let line = verdict.map_or_else(|| "no record in the window".to_owned(), ToString::to_string);
    format!("{line}\n{}\n", criteria_text(kind, criteria))
}

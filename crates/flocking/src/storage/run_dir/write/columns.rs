//! The columns of the files a run writes: `metrics.csv`'s header and records, a trajectory row
//! and `final.csv`.

use std::fs;
use std::io::{self, Write as _};
use std::path::Path;

use crate::scenario::Scenario;
use crate::simulation::State;
use crate::storage::fs::at;
use crate::storage::run_dir::read::{FAILED_COLUMN, trajectory_header_with};

/// The header of `metrics.csv`: t, [`FlockMetrics::REAL_COLUMNS`](flock_metrics::FlockMetrics::REAL_COLUMNS),
/// the collisions, the energy, then (appended later, so that the former columns keep their
/// places) [`FlockMetrics::EXTRA_COLUMNS`](flock_metrics::FlockMetrics::EXTRA_COLUMNS) and the
/// number of components; the protocol's diagnostics follow.
pub const METRICS_HEADER: &str = "t,connectivity,giant_component,cohesion_radius,deviation_energy,velocity_mismatch,min_distance,collisions,energy,polarisation,milling,nearest_neighbour_mean,nearest_neighbour_min,group_speed,components";

/// The columns of `metrics.csv` that count agents or pairs (`docs/outputs.md`), besides every
/// vehicle limit `at_…_limit` ([`is_count_column`]).
pub const COUNT_COLUMNS: [&str; 9] = [
    "collisions",
    "components",
    "inside_obstacles",
    "stress_towards",
    "stress_away",
    "stress_neutral",
    "at_acceleration_limit",
    "at_speed_limit",
    "failed",
];

/// Whether the `metrics.csv` column `name` counts agents or pairs (whole numbers, printed as
/// such): [`COUNT_COLUMNS`] and every `at_…_limit`.
///
/// # Example
/// ```
/// use flocking::run_dir::is_count_column;
///
/// assert!(is_count_column("collisions") && is_count_column("at_bank_limit"));
/// assert!(!is_count_column("connectivity") && !is_count_column("links_lost"));
/// ```
#[must_use]
pub fn is_count_column(name: &str) -> bool {
    COUNT_COLUMNS.contains(&name) || name.starts_with("at_") && name.ends_with("_limit")
}

/// Whether the trajectory and `final.csv` of `scenario` mark each agent `failed`: its conditions
/// have `faults` (issue 28; the column's sum at a record is `metrics.csv`'s `failed`).
pub(super) fn marks_failed(scenario: &Scenario) -> bool {
    scenario.conditions.faults.is_some()
}

/// The columns of a trajectory row: [`trajectory_header_with`], then [`FAILED_COLUMN`] when
/// `failed`.
pub(super) fn agent_header(dim: usize, vehicle: &[&str], failed: bool) -> Vec<String> {
    let mut header = trajectory_header_with(dim, vehicle);
    if failed {
        header.push(FAILED_COLUMN.to_owned());
    }
    header
}

/// The header line of the `trajectory.csv` of `scenario`.
pub(super) fn trajectory_csv_header(scenario: &Scenario) -> String {
    let vehicle = scenario.vehicle.state_columns(scenario.dim);
    format!(
        "{}\n",
        agent_header(scenario.dim, vehicle, marks_failed(scenario)).join(",")
    )
}

/// The header line of `metrics.csv` with the diagnostic columns `columns`.
pub(super) fn metrics_header(columns: &[String]) -> String {
    let mut header = String::from(METRICS_HEADER);
    for column in columns {
        header.push(',');
        header.push_str(column);
    }
    header.push('\n');
    header
}

/// The diagnostic columns of the header of the `metrics.csv` at `path`: the names after those of
/// [`METRICS_HEADER`].
pub(super) fn diagnostic_columns(path: &Path) -> io::Result<Vec<String>> {
    let text = fs::read_to_string(path).map_err(at(format_args!("read {}", path.display())))?;
    let header = text.lines().next().unwrap_or_default();
    let Some(rest) = header.strip_prefix(METRICS_HEADER) else {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "{} does not start with the header {METRICS_HEADER}",
                path.display()
            ),
        ));
    };
    Ok(rest
        .split(',')
        .filter(|name| !name.is_empty())
        .map(str::to_owned)
        .collect())
}

/// Whether agent `i` of `state` has failed (never, when its run marks no failures).
pub(super) fn failed(state: &State<'_>, i: usize) -> bool {
    state.failed.as_ref().is_some_and(|failed| failed[i])
}

/// Appends `id,x,y[,z],vx,vy[,vz]` of agent `i` (shortest round-trip decimal forms).
pub(super) fn write_state(out: &mut Vec<u8>, i: usize, state: &[f64]) {
    // Writing to a Vec cannot fail.
    let _ = write!(out, "{i}");
    for x in state {
        let _ = write!(out, ",{x}");
    }
    out.push(b'\n');
}

#[cfg(test)]
mod tests {
    use flock_metrics::FlockMetrics;

    use super::METRICS_HEADER;
    use crate::storage::run_dir::TIME;

    /// The header names what a record writes, in its order: t, [`FlockMetrics::reals`], the
    /// collisions, the energy, [`FlockMetrics::extras`] and the components.
    #[test]
    fn the_metrics_header_names_the_recorded_values() {
        let names: Vec<&str> = std::iter::once(TIME)
            .chain(FlockMetrics::REAL_COLUMNS)
            .chain(["collisions", "energy"])
            .chain(FlockMetrics::EXTRA_COLUMNS)
            .chain(["components"])
            .collect();
        assert_eq!(METRICS_HEADER, names.join(","));
    }
}

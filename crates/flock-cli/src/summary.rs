//! The one-screen summary `flocking run` prints.

use std::fmt;

use flocking::metrics::{Closest, FlockMetrics};
use flocking::{RunSummary, VerdictKind};

/// The diagnostic columns that count agents (`docs/outputs.md`), besides the vehicles' limits
/// (`at_…_limit`): printed as whole numbers.
pub const COUNT_COLUMNS: [&str; 7] = [
    "inside_obstacles",
    "stress_towards",
    "stress_away",
    "stress_neutral",
    "at_acceleration_limit",
    "at_speed_limit",
    "failed",
];

/// A diagnostic's value as the summary prints it: a count as an integer (`failed 1`), any other
/// value in scientific notation (`defect_factor 1.234560e-3`).
#[must_use]
pub fn diagnostic(name: &str, value: f64) -> String {
    let counts =
        COUNT_COLUMNS.contains(&name) || name.starts_with("at_") && name.ends_with("_limit");
    if counts && value.fract() == 0.0 && value.abs() < 1e15 {
        format!("{value:.0}")
    } else {
        format!("{value:.6e}")
    }
}

/// A run summary with its scenario's name and its records, ready to print.
#[derive(Debug)]
pub struct Report<'a> {
    /// The scenario's name.
    pub name: &'a str,
    /// The run.
    pub summary: &'a RunSummary,
    /// Every record of the run (its whole `metrics.csv`, also after `--resume`).
    pub records: &'a [(f64, FlockMetrics)],
    /// The time from which the run has settled (`--settle` × the duration).
    pub settled_from: f64,
}

impl fmt::Display for Report<'_> {
    /// What matters for the run's model: for Definition 5's models the lattice (Ẽ, K̃, the
    /// lattice's edges, the topology, H) and the collisions; for the classic models the order
    /// parameters (polarisation, milling), the groups and, for Cucker–Smale, the velocity
    /// mismatch ([`VerdictKind`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.summary;
        let m = &s.metrics;
        let kind = s.verdict_kind;
        let rate = (s.agents as f64 * s.steps as f64) / s.elapsed.as_secs_f64().max(1e-9);
        writeln!(
            f,
            "flocking run: {} ({}D, n = {}, {} steps to t = {})",
            self.name, s.dim, s.agents, s.steps, s.t
        )?;
        if m.is_empty_flock() {
            writeln!(
                f,
                "  metrics               undefined: no agent is left (every agent was removed by faults)"
            )?;
        } else {
            writeln!(
                f,
                "  connectivity C        {:.4}   ({} component(s))",
                m.connectivity, m.components
            )?;
            writeln!(f, "  giant component C*    {:.4}", m.giant_component)?;
            writeln!(f, "  cohesion radius R     {:.4}", m.cohesion_radius)?;
            if kind.has_lattice() {
                writeln!(f, "  deviation energy Ẽ    {:.3e}", m.deviation_energy)?;
            }
            if kind.has_lattice() || kind == VerdictKind::CuckerSmale {
                writeln!(
                    f,
                    "  velocity mismatch K̃   {:.3e}   (within components {:.3e})",
                    m.velocity_mismatch, s.component_velocity_mismatch
                )?;
            }
            writeln!(
                f,
                "  group speed ‖p_c‖     {:.4}   (root-mean-square speed {:.4})",
                m.group_speed,
                m.rms_speed()
            )?;
            writeln!(
                f,
                "  polarisation          {:.4}   (milling {:.4}, mean nearest neighbour {:.4})",
                m.polarisation, m.milling, m.nearest_neighbour_mean
            )?;
        }
        let from = self.settled_from;
        let [whole, settled] = [f64::NEG_INFINITY, from].map(|t| Closest::over(self.records, t));
        let [whole_distance, settled_distance] = [whole, settled]
            .map(|c| c.map_or_else(|| "–".to_owned(), |c| format!("{:.4}", c.min_distance)));
        writeln!(
            f,
            "  least distance        {whole_distance} over the run, {settled_distance} after settling (t ≥ {from})"
        )?;
        if kind.counts_collisions() {
            let [whole_pairs, settled_pairs] = [whole, settled]
                .map(|c| c.map_or_else(|| "–".to_owned(), |c| c.collisions.to_string()));
            writeln!(
                f,
                "  most colliding pairs  {whole_pairs} over the run, {settled_pairs} after settling"
            )?;
        }
        if s.merged.agents > 0 {
            writeln!(
                f,
                "  merged agents         {}   (closer than 10⁻³ d: the α-force cannot separate them)",
                s.merged
            )?;
        }
        for &(name, value) in &s.diagnostics {
            writeln!(f, "  {name:<21} {}", diagnostic(name, value))?;
        }
        if kind.has_lattice() {
            writeln!(f, "  lattice               {}", s.lattice)?;
            // of this run's records (after its start, when resumed)
            writeln!(
                f,
                "  topology invariant from t = {:.2}{}",
                s.topology_invariant_from,
                if s.topology_invariant_from < s.t {
                    ""
                } else {
                    " (still changing at the final record)"
                }
            )?;
            writeln!(
                f,
                "  energy H              {:.6e} -> {:.6e}",
                s.initial_energy, s.final_energy
            )?;
        }
        write!(
            f,
            "  wall time             {:.3} s ({rate:.3e} agent-steps/s)",
            s.elapsed.as_secs_f64()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_print_as_integers_and_measures_in_scientific_notation() {
        assert_eq!(diagnostic("failed", 1.0), "1");
        assert_eq!(diagnostic("inside_obstacles", 0.0), "0");
        assert_eq!(diagnostic("at_speed_limit", 12.0), "12");
        assert_eq!(diagnostic("at_acceleration_limit", 3.0), "3");
        assert_eq!(diagnostic("at_bank_limit", 30.0), "30");
        assert_eq!(diagnostic("links_lost", 1.0), "1.000000e0");
        assert_eq!(diagnostic("information_age", 0.05), "5.000000e-2");
    }
}

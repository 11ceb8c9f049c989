//! The one-screen summary `flocking run` prints.

use std::fmt;

use flocking::metrics::{Closest, FlockMetrics};
use flocking::run_dir::is_count_column;
use flocking::{RunSummary, VerdictKind};

/// The units of the diagnostic columns that have one (`docs/outputs.md`); the others are ratios
/// or counts.
const UNITS: [(&str, &str); 11] = [
    ("obstacle_clearance", "m"),
    ("defect_factor", "m²"),
    ("structural_energy", "m²/s²"),
    ("translational_energy", "m²/s²"),
    ("gamma_position_error", "m"),
    ("gamma_velocity_error", "m/s"),
    ("velocity_disagreement", "m²/s²"),
    ("min_linked_distance", "m"),
    ("wall_violation", "m"),
    ("information_age", "s"),
    ("acceleration_tracking_error", "m/s²"),
];

/// The width of the label column: the longest label, `acceleration_tracking_error` (the verdict's
/// and the outputs' lines use it too).
pub const LABEL_WIDTH: usize = 27;

/// A diagnostic's value as the summary prints it: a count as an integer (`failed 1`), any other
/// value as [`measure`] with its unit (`gamma_position_error 0.03050 m`).
#[must_use]
pub fn diagnostic(name: &str, value: f64) -> String {
    if is_count_column(name) && value.fract() == 0.0 && value.abs() < 1e15 {
        format!("{value:.0}")
    } else {
        let unit = UNITS
            .iter()
            .find(|(n, _)| *n == name)
            .map_or("", |(_, u)| u);
        with_unit(value, unit)
    }
}

/// A measure as every line of the summary prints it: 4 significant digits (`40.13`, `1.000`,
/// `0.03050`), in exponent form below 10⁻³ and from 10⁵ on (`2.811e-4`, `5.788e5`); `0` for
/// zero; `inf`, `NaN` as Rust prints them.
#[must_use]
pub fn measure(x: f64) -> String {
    let a = x.abs();
    if !x.is_finite() || a == 0.0 {
        return format!("{x}");
    }
    if !(1e-3..1e5).contains(&a) {
        return format!("{x:.3e}");
    }
    let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
    let text = format!("{x:.decimals$}");
    // 9.9996 rounds to 10.000: five digits, one too many
    if text
        .trim_start_matches('-')
        .replace('.', "")
        .trim_start_matches('0')
        .len()
        > 4
        && decimals > 0
    {
        format!("{x:.prec$}", prec = decimals - 1)
    } else {
        text
    }
}

/// [`measure`] followed by its unit, if any.
fn with_unit(x: f64, unit: &str) -> String {
    if unit.is_empty() {
        measure(x)
    } else {
        format!("{} {unit}", measure(x))
    }
}

/// `label` padded to [`LABEL_WIDTH`] columns as a terminal shows it (a combining mark, the tilde
/// of K̃ and Ẽ written as one, takes none).
#[must_use]
pub fn padded(label: &str) -> String {
    let width = label
        .chars()
        .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
        .count();
    format!("{label}{}", " ".repeat(LABEL_WIDTH.saturating_sub(width)))
}

/// One line of the summary: the label, padded, and the text.
fn row(f: &mut fmt::Formatter<'_>, label: &str, text: impl fmt::Display) -> fmt::Result {
    writeln!(f, "  {} {text}", padded(label))
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
            "flocking run: {} ({}D, n = {}, {} steps to t = {} s)",
            self.name, s.dim, s.agents, s.steps, s.t
        )?;
        if m.is_empty_flock() {
            row(
                f,
                "metrics",
                "undefined: no agent is left (every agent was removed by faults)",
            )?;
        } else {
            let groups = if m.components == 1 {
                "1 component".to_owned()
            } else {
                format!("{} components", m.components)
            };
            row(
                f,
                "connectivity C",
                format_args!("{}   ({groups})", measure(m.connectivity)),
            )?;
            row(f, "giant component C*", measure(m.giant_component))?;
            row(f, "cohesion radius R", with_unit(m.cohesion_radius, "m"))?;
            if kind.has_lattice() {
                row(f, "deviation energy Ẽ", measure(m.deviation_energy))?;
            }
            if kind.has_lattice() || kind == VerdictKind::CuckerSmale {
                row(
                    f,
                    "velocity mismatch K̃",
                    format_args!(
                        "{}   (within components {})",
                        with_unit(m.velocity_mismatch, "m²/s²"),
                        with_unit(s.component_velocity_mismatch, "m²/s²")
                    ),
                )?;
            }
            row(
                f,
                "group speed ‖p_c‖",
                format_args!(
                    "{}   (root-mean-square speed {})",
                    with_unit(m.group_speed, "m/s"),
                    with_unit(m.rms_speed(), "m/s")
                ),
            )?;
            row(
                f,
                "polarisation",
                format_args!(
                    "{}   (milling {}, mean nearest neighbour {})",
                    measure(m.polarisation),
                    measure(m.milling),
                    with_unit(m.nearest_neighbour_mean, "m")
                ),
            )?;
        }
        let from = self.settled_from;
        let [whole, settled] = [f64::NEG_INFINITY, from].map(|t| Closest::over(self.records, t));
        let [whole_distance, settled_distance] = [whole, settled]
            .map(|c| c.map_or_else(|| "–".to_owned(), |c| with_unit(c.min_distance, "m")));
        row(
            f,
            "least distance",
            format_args!(
                "{whole_distance} over the run, {settled_distance} after settling (t ≥ {from} s)"
            ),
        )?;
        if kind.counts_collisions() {
            let [whole_pairs, settled_pairs] = [whole, settled]
                .map(|c| c.map_or_else(|| "–".to_owned(), |c| c.collisions.to_string()));
            row(
                f,
                "most colliding pairs",
                format_args!("{whole_pairs} over the run, {settled_pairs} after settling"),
            )?;
        }
        if s.merged.agents > 0 {
            row(
                f,
                "merged agents",
                format_args!(
                    "{}   (closer than 10⁻³ d: the α-force cannot separate them)",
                    s.merged
                ),
            )?;
        }
        for &(name, value) in &s.diagnostics {
            row(f, name, diagnostic(name, value))?;
        }
        if kind.has_lattice() {
            row(f, "lattice", s.lattice)?;
            // of this run's records (after its start, when resumed)
            row(
                f,
                "topology invariant",
                format_args!(
                    "from t = {:.2} s{}",
                    s.topology_invariant_from,
                    if s.topology_invariant_from < s.t {
                        ""
                    } else {
                        " (still changing at the final record)"
                    }
                ),
            )?;
            row(
                f,
                "energy H",
                format_args!(
                    "{} → {}",
                    measure(s.initial_energy),
                    with_unit(s.final_energy, "m²/s²")
                ),
            )?;
        }
        write!(
            f,
            "  {} {} s ({} agent-steps/s)",
            padded("wall time"),
            measure(s.elapsed.as_secs_f64()),
            measure(rate)
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
        assert_eq!(diagnostic("links_lost", 1.0), "1.000");
        assert_eq!(diagnostic("information_age", 0.05), "0.05000 s");
        assert_eq!(
            diagnostic("gamma_position_error", 3.049_546e-2),
            "0.03050 m"
        );
    }

    #[test]
    fn measures_have_four_significant_digits() {
        assert_eq!(measure(1.0), "1.000");
        assert_eq!(measure(40.133_12), "40.13");
        assert_eq!(measure(2.811_449e-4), "2.811e-4");
        assert_eq!(measure(5_788.101), "5788");
        assert_eq!(measure(578_810.1), "5.788e5");
        assert_eq!(measure(0.000_2), "2.000e-4");
        assert_eq!(measure(-0.125), "-0.1250");
        assert_eq!(measure(9.999_6), "10.00");
        assert_eq!(measure(0.0), "0");
        assert_eq!(measure(f64::INFINITY), "inf");
    }

    #[test]
    fn labels_pad_to_one_column_whatever_their_marks() {
        // K̃ is K and a combining tilde: two chars, one column
        assert_eq!(
            padded("velocity mismatch K̃").chars().count(),
            LABEL_WIDTH + 1
        );
        assert_eq!(padded("giant component C*").len(), LABEL_WIDTH);
    }
}

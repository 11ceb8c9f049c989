//! [`WholeRun`]: what a run did over all its records, not only at its final time — the closest
//! approach, the collisions, the least share of the largest flock — and [`whole_run_rows`], the
//! table the gallery page gives per figure with the model's verdict and, for the models of an
//! α-lattice, the final lattice and the time from which the net's topology no longer changes.

use flocking::RunSummary;
use flocking::metrics::FlockMetrics;

use crate::data::metric_series::Metrics;
use crate::gallery::papers::{Measure, seconds};

/// The time after which a colliding pair counts against the protocol rather than the random
/// start (s).
pub const AFTER_START: f64 = 2.0;

/// Extremes of a run's records, each with the time of the record that reached it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WholeRun {
    /// The least distance between two agents and its time.
    pub least_distance: (f64, f64),
    /// The most pairs closer than the collision distance at one record, and the first time.
    pub most_collisions: (usize, f64),
    /// The records after [`AFTER_START`] with at least one colliding pair.
    pub colliding_records_after_start: usize,
    /// The records after [`AFTER_START`].
    pub records_after_start: usize,
    /// The least C* (share of the largest component) and its first time.
    pub least_giant_component: (f64, f64),
}

impl WholeRun {
    /// The extremes of `history`, (t, metrics) per record (`None` when it is empty); ties go to
    /// the first record.
    ///
    /// # Example
    /// ```
    /// use flock_viz::WholeRun;
    /// use flocking::metrics::FlockMetrics;
    ///
    /// let at = |min_distance, collisions, giant_component| FlockMetrics {
    ///     connectivity: 1.0,
    ///     giant_component,
    ///     components: 1,
    ///     cohesion_radius: 10.0,
    ///     deviation_energy: 0.0,
    ///     velocity_mismatch: 0.0,
    ///     min_distance,
    ///     collisions,
    ///     polarisation: 1.0,
    ///     milling: 0.0,
    ///     nearest_neighbour_mean: min_distance,
    ///     nearest_neighbour_min: min_distance,
    ///     group_speed: 1.0,
    /// };
    /// let run = WholeRun::of(&[(0.0, at(0.5, 2, 0.8)), (3.0, at(6.0, 1, 1.0))]).unwrap();
    /// assert_eq!(run.least_distance, (0.5, 0.0));
    /// assert_eq!(run.colliding_records_after_start, 1);
    /// ```
    #[must_use]
    pub fn of(history: &[(f64, FlockMetrics)]) -> Option<Self> {
        let (&(t0, first), rest) = history.split_first()?;
        let mut run = Self {
            least_distance: (first.min_distance, t0),
            most_collisions: (first.collisions, t0),
            colliding_records_after_start: 0,
            records_after_start: 0,
            least_giant_component: (first.giant_component, t0),
        };
        for &(t, m) in history {
            if t > AFTER_START {
                run.records_after_start += 1;
                run.colliding_records_after_start += usize::from(m.collisions > 0);
            }
        }
        for &(t, m) in rest {
            if m.min_distance < run.least_distance.0 {
                run.least_distance = (m.min_distance, t);
            }
            if m.collisions > run.most_collisions.0 {
                run.most_collisions = (m.collisions, t);
            }
            if m.giant_component < run.least_giant_component.0 {
                run.least_giant_component = (m.giant_component, t);
            }
        }
        Some(run)
    }
}

/// The rows (name, value) of a run's whole-run table: [`WholeRun`] of its history, `verdict` (the
/// first line of its `flocking.txt`), the final lattice, the topology's invariance time and, with
/// obstacles, the agents inside them. The colliding pairs, the lattice and the topology only for
/// the models they mean something for ([`VerdictKind`](flocking::VerdictKind)).
#[must_use]
pub fn whole_run_rows(
    summary: &RunSummary,
    metrics: &Metrics,
    verdict: &str,
) -> Vec<(String, String)> {
    let kind = summary.verdict_kind;
    let mut rows = Vec::new();
    if let Some(run) = WholeRun::of(&summary.history) {
        let (distance, t) = run.least_distance;
        rows.push((
            "least distance".to_owned(),
            format!("{distance:.3} at t = {} s", seconds(t)),
        ));
        let (pairs, t) = run.most_collisions;
        if kind.counts_collisions() {
            rows.push((
            "most colliding pairs".to_owned(),
            format!(
                "{pairs}, first at t = {} s; {} of the {} records after t = {AFTER_START} s have a \
                 colliding pair",
                seconds(t),
                run.colliding_records_after_start,
                run.records_after_start
            ),
            ));
        }
        let (giant, t) = run.least_giant_component;
        rows.push((
            "least C*".to_owned(),
            format!("{giant:.3} at t = {} s", seconds(t)),
        ));
    }
    rows.push(("verdict".to_owned(), verdict.to_owned()));
    if kind.has_lattice() {
        lattice_rows(summary, metrics, &mut rows);
    }
    if metrics.column("inside_obstacles").is_some() {
        rows.push((
            "obstacles".to_owned(),
            Measure::NeverInside.of(summary, metrics),
        ));
    }
    rows
}

/// The rows of the final lattice and of the topology's invariance time.
fn lattice_rows(summary: &RunSummary, metrics: &Metrics, rows: &mut Vec<(String, String)>) {
    let lattice = &summary.lattice;
    rows.push((
        format!("lattice at t = {} s", seconds(summary.t)),
        format!(
            "{} of {} edges within ±10 % of d; {}; {}",
            lattice.near_edges,
            lattice.edges,
            match (lattice.equilateral_triangles, lattice.triangles) {
                (Some(equilateral), Some(all)) => {
                    format!("{equilateral} of {all} triangles equilateral")
                }
                _ => format!("triangles not counted ({})", lattice.too_dense()),
            },
            match lattice.crossings {
                Some(c) => format!("{c} crossing edges"),
                None if lattice.crossings_too_dense() => {
                    format!("crossing edges not counted ({})", lattice.too_dense())
                }
                None => "crossing edges not counted (3D)".to_owned(),
            }
        ),
    ));
    rows.push((
        "topology".to_owned(),
        Measure::TopologyInvariant.of(summary, metrics),
    ));
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use flocking::metrics::{FlockMetrics, LatticeSummary};
    use flocking::{MergedAgents, RunSummary, VerdictKind};

    use super::{WholeRun, whole_run_rows};
    use crate::data::metric_series::Metrics;

    fn at(min_distance: f64, collisions: usize, giant_component: f64) -> FlockMetrics {
        FlockMetrics {
            connectivity: 1.0,
            giant_component,
            components: 1,
            cohesion_radius: 10.0,
            deviation_energy: 0.0,
            velocity_mismatch: 0.0,
            min_distance,
            collisions,
            polarisation: 1.0,
            milling: 0.0,
            nearest_neighbour_mean: min_distance,
            nearest_neighbour_min: min_distance,
            group_speed: 1.0,
        }
    }

    /// Four records: a random start, a split at t = 3 with a collision, a collision at t = 4 and
    /// a settled flock at t = 5.
    fn history() -> Vec<(f64, FlockMetrics)> {
        vec![
            (0.0, at(0.4, 2, 0.5)),
            (3.0, at(0.3, 3, 0.4)),
            (4.0, at(1.0, 3, 1.0)),
            (5.0, at(6.5, 0, 1.0)),
        ]
    }

    fn summary(topology_invariant_from: f64) -> RunSummary {
        RunSummary {
            agents: 4,
            dim: 2,
            steps: 500,
            t: 5.0,
            metrics: at(6.5, 0, 1.0),
            component_velocity_mismatch: 0.0,
            initial_energy: 1.0,
            final_energy: 0.5,
            diagnostics: Vec::new(),
            lattice: LatticeSummary {
                agents: 4,
                edges: 5,
                near_edges: 4,
                triangles: Some(2),
                equilateral_triangles: Some(1),
                edge_bound: Some(6),
                crossings: Some(0),
            },
            history: history(),
            first_merge: None,
            merged: MergedAgents::default(),
            topology_invariant_from,
            elapsed: Duration::ZERO,
            verdict_kind: VerdictKind::Definition5,
        }
    }

    #[test]
    fn the_extremes_carry_the_time_of_their_first_record() {
        let run = WholeRun::of(&history()).expect("records");
        assert_eq!(run.least_distance, (0.3, 3.0));
        // 3 pairs at t = 3 and t = 4: the first
        assert_eq!(run.most_collisions, (3, 3.0));
        // t = 3 and 4 of the three records after t = 2
        assert_eq!(run.colliding_records_after_start, 2);
        assert_eq!(run.records_after_start, 3);
        assert_eq!(run.least_giant_component, (0.4, 3.0));
        assert_eq!(WholeRun::of(&[]), None);
    }

    #[test]
    fn the_rows_give_the_whole_run_the_verdict_the_lattice_and_the_topology() {
        let metrics = Metrics::default();
        let rows = whole_run_rows(&summary(4.0), &metrics, "α-flocking: yes");
        let values: Vec<&str> = rows.iter().map(|(_, v)| v.as_str()).collect();
        assert_eq!(
            values,
            [
                "0.300 at t = 3 s",
                "3, first at t = 3 s; 2 of the 3 records after t = 2 s have a colliding pair",
                "0.400 at t = 3 s",
                "α-flocking: yes",
                "4 of 5 edges within ±10 % of d; 1 of 2 triangles equilateral; 0 crossing edges",
                "edge set unchanged from t = 4 s to the end (t = 5 s)",
            ]
        );
        assert_eq!(rows[4].0, "lattice at t = 5 s");
        // the last record changed the edge set
        let rows = whole_run_rows(&summary(5.0), &metrics, "");
        assert_eq!(
            rows[5].1,
            "edge set still changing at t = 5 s: the last record changed it"
        );
        // a net too dense to count, and one in 3D
        let mut dense = summary(4.0);
        dense.lattice.triangles = None;
        dense.lattice.equilateral_triangles = None;
        dense.lattice.crossings = None;
        assert_eq!(
            whole_run_rows(&dense, &metrics, "")[4].1,
            "4 of 5 edges within ±10 % of d; triangles not counted (mean degree 2.5: too dense to \
             count); crossing edges not counted (mean degree 2.5: too dense to count)"
        );
        dense.lattice.edge_bound = None;
        assert!(
            whole_run_rows(&dense, &metrics, "")[4]
                .1
                .ends_with("not counted (3D)")
        );
    }

    /// Issue 50: a classic model's table leaves out what means nothing for it (collisions at
    /// d/4, the lattice, the topology of the net).
    #[test]
    fn a_classic_model_has_no_lattice_or_collision_rows() {
        let metrics = Metrics::default();
        let mut couzin = summary(4.0);
        couzin.verdict_kind = VerdictKind::Couzin;
        let rows = whole_run_rows(&couzin, &metrics, "Couzin et al. 2002 state: torus");
        let names: Vec<&str> = rows.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["least distance", "least C*", "verdict"]);
    }

    #[test]
    fn runs_with_obstacles_add_their_row() {
        let metrics = Metrics::from_columns(vec![
            ("t".into(), vec![0.0, 5.0]),
            ("inside_obstacles".into(), vec![1.0, 0.0]),
            ("obstacle_clearance".into(), vec![-0.5, 2.0]),
        ])
        .expect("columns");
        let rows = whole_run_rows(&summary(4.0), &metrics, "");
        assert_eq!(
            rows.last().expect("rows").1,
            "at most 1 agents inside an obstacle at any record; least clearance -0.50"
        );
    }
}

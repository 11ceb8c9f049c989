//! Scenario text → parse → validate → round trip through `to_ron` → a few steps of the run.
//!
//! The oracle (docs/fuzzing.md):
//! - nothing panics, aborts, runs out of memory or hangs, whatever the bytes;
//! - a scenario that [`Scenario::parse`] accepts still validates once resolved, and
//!   `parse(to_ron(s)) == s` for the parsed and the resolved scenario (both round-trip through RON);
//! - a small accepted scenario (at most [`MAX_AGENTS`] agents, [`MAX_OBSTACLES`] obstacles),
//!   cut to at most [`MAX_STEPS`] steps, either fails with an `Err`, or every value it records and
//!   summarises is finite: positions, velocities, energies, metrics and the protocol's
//!   diagnostics, every record naming the same diagnostic columns. The only exceptions are the ones the metrics document: `min_distance` and
//!   `min_linked_distance` are +∞ for a single agent (no pair, no link). NaN is never accepted.
#![no_main]

use flocking::metrics::FlockMetrics;
use flocking::{Algorithm, Cloud, Record, Recorder, RunSummary, Scenario, TannerGraph};
use libfuzzer_sys::fuzz_target;

/// Larger flocks are cut to this many agents (or not run, when the scenario lists every agent).
const MAX_AGENTS: usize = 64;
/// Scenarios with more obstacles are parsed and validated but not run.
const MAX_OBSTACLES: usize = 16;
/// The run is cut to at most this many steps of the scenario's own step.
const MAX_STEPS: u64 = 6;

/// Asserts that `value`, `field` of the record at time `t`, is finite (or +∞ where `infinite_ok`).
#[track_caller]
fn check(field: &str, t: f64, value: f64, infinite_ok: bool) {
    assert!(
        value.is_finite() || (infinite_ok && value == f64::INFINITY),
        "{field} = {value} at t = {t}: a non-finite value recorded as valid"
    );
}

/// Checks every recorded instant; panics on the first value the oracle refuses.
struct FiniteRecorder {
    /// The number of agents (+∞ distances are documented for fewer than two).
    agents: usize,
    /// The names of the diagnostic columns, in order, as the first record names them.
    columns: Option<Vec<&'static str>>,
    /// The number of records seen.
    records: u64,
}

impl FiniteRecorder {
    fn check_extra(&self, name: &str, t: f64, value: f64) {
        // `min_linked_distance` is ∞ without edges, i.e. for a single agent on a connected graph.
        let infinite_ok = name == "min_linked_distance" && self.agents < 2;
        check(name, t, value, infinite_ok);
    }

    fn check_metrics(&self, t: f64, metrics: &FlockMetrics) {
        let single = self.agents < 2;
        check("connectivity", t, metrics.connectivity, false);
        check("giant_component", t, metrics.giant_component, false);
        check("cohesion_radius", t, metrics.cohesion_radius, false);
        check("deviation_energy", t, metrics.deviation_energy, false);
        check("velocity_mismatch", t, metrics.velocity_mismatch, false);
        check("min_distance", t, metrics.min_distance, single);
    }

    fn check_summary(&self, summary: &RunSummary) {
        let t = summary.t;
        check("summary.t", t, t, false);
        self.check_metrics(t, &summary.metrics);
        check(
            "summary.component_velocity_mismatch",
            t,
            summary.component_velocity_mismatch,
            false,
        );
        check("summary.initial_energy", t, summary.initial_energy, false);
        check("summary.final_energy", t, summary.final_energy, false);
        self.check_diagnostics(t, &summary.diagnostics);
    }

    /// Every diagnostic finite, under the names of the first record.
    fn check_diagnostics(&self, t: f64, diagnostics: &[(&'static str, f64)]) {
        let names: Vec<&'static str> = diagnostics.iter().map(|&(name, _)| name).collect();
        assert_eq!(
            self.columns.as_ref(),
            Some(&names),
            "at t = {t}: the diagnostic columns changed"
        );
        for &(name, value) in diagnostics {
            self.check_extra(name, t, value);
        }
    }
}

impl Recorder for FiniteRecorder {
    type Error = std::convert::Infallible;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let t = record.t;
        check("t", t, t, false);
        self.check_metrics(t, &record.metrics);
        check("energy", t, record.energy, false);
        let state = &record.state;
        for (k, x) in state.positions.iter().enumerate() {
            assert!(x.is_finite(), "position of agent {} = {x} at t = {t}", k / state.dim);
        }
        for (k, x) in state.velocities.iter().enumerate() {
            assert!(x.is_finite(), "velocity of agent {} = {x} at t = {t}", k / state.dim);
        }
        self.columns
            .get_or_insert_with(|| record.diagnostics.iter().map(|&(name, _)| name).collect());
        self.check_diagnostics(t, record.diagnostics);
        self.records += 1;
        Ok(())
    }
}

/// The scenario cut to a few steps and at most [`MAX_AGENTS`] agents, or `None` when it is too big
/// to run here (an explicit list of agents, or many obstacles).
fn small(scenario: &Scenario) -> Option<Scenario> {
    if scenario.obstacles.len() > MAX_OBSTACLES {
        return None;
    }
    let mut small = scenario.clone();
    if small.agents > MAX_AGENTS {
        let explicit = |cloud: &Cloud| matches!(cloud, Cloud::Explicit(_));
        let edges = matches!(
            small.algorithm,
            Algorithm::Tanner {
                graph: TannerGraph::Edges(_)
            }
        );
        if explicit(&small.initial.positions) || explicit(&small.initial.velocities) || edges {
            return None;
        }
        small.agents = MAX_AGENTS;
    }
    if small.steps() > MAX_STEPS {
        // At most the original duration, so still valid: step ≤ duration and both finite.
        small.duration = small.step * MAX_STEPS as f64;
    }
    Some(small)
}

/// The oracle on one input.
fn check_input(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(parsed) = Scenario::parse(text, "fuzz") else {
        return;
    };
    // `parse` validated; with its defaults written out the scenario is still valid…
    let scenario = parsed.clone().resolved();
    if let Err(e) = scenario.validate() {
        panic!("the resolved scenario no longer validates: {e}\n{scenario:#?}");
    }
    // …and both it and the scenario as parsed (defaults unset) round-trip through RON.
    for scenario in [&parsed, &scenario] {
        let ron = scenario.to_ron().expect("a valid scenario serializes");
        match Scenario::parse(&ron, "round-trip") {
            Ok(back) => assert_eq!(&back, scenario, "to_ron changed the scenario\n{ron}"),
            Err(e) => panic!("to_ron output does not parse back: {e}\n{ron}"),
        }
    }
    let Some(small) = small(&scenario) else {
        return;
    };
    let mut recorder = FiniteRecorder {
        agents: small.agents,
        columns: None,
        records: 0,
    };
    if let Ok(summary) = flocking::run(&small, &mut recorder) {
        assert!(
            recorder.records >= 2,
            "a run records t = 0 and its last step"
        );
        assert_eq!(summary.steps, small.steps(), "steps taken");
        recorder.check_summary(&summary);
    }
}

fuzz_target!(
    init: {
        // One thread: libFuzzer runs one input at a time, and the machine is shared.
        let _ = rayon::ThreadPoolBuilder::new().num_threads(1).build_global();
    },
    |data: &[u8]| check_input(data)
);

//! Short runs of every fixture: insta snapshots of their rounded summaries, and determinism —
//! the same run twice, and the same run on rayon pools of 1 and 3 threads, are bit-identical.

use std::fmt::Write as _;
use std::time::Duration;

use flocking::metrics::FlockMetrics;
use flocking::{Record, Recorder, RunSummary, Scenario};

use crate::common::{fixture_paths, sig6, stem};

/// The steps of the short runs (2 s of the papers' fixtures, at h = 0.01).
const SHORT: u64 = 200;

/// Every fixture, shortened to [`SHORT`] steps.
fn short_fixtures() -> Vec<(String, Scenario)> {
    fixture_paths()
        .iter()
        .map(|path| {
            let mut scenario =
                Scenario::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            scenario.duration = SHORT as f64 * scenario.step;
            assert_eq!(scenario.validate(), Ok(()), "{}", path.display());
            (stem(path), scenario)
        })
        .collect()
}

/// The summary without its wall time, every number rounded to 6 significant digits.
fn rounded(name: &str, s: &RunSummary) -> String {
    let m = &s.metrics;
    let mut text = String::new();
    let mut line =
        |key: &str, value: String| writeln!(text, "{key}: {value}").expect("write to a String");
    line("scenario", name.to_owned());
    line("agents", s.agents.to_string());
    line("dim", s.dim.to_string());
    line("steps", s.steps.to_string());
    line("t", sig6(s.t));
    line("connectivity", sig6(m.connectivity));
    line("giant_component", sig6(m.giant_component));
    line("components", m.components.to_string());
    line("cohesion_radius", sig6(m.cohesion_radius));
    line("deviation_energy", sig6(m.deviation_energy));
    line("velocity_mismatch", sig6(m.velocity_mismatch));
    line(
        "component_velocity_mismatch",
        sig6(s.component_velocity_mismatch),
    );
    line("min_distance", sig6(m.min_distance));
    line("collisions", m.collisions.to_string());
    line("initial_energy", sig6(s.initial_energy));
    line("final_energy", sig6(s.final_energy));
    for (column, value) in FlockMetrics::EXTRA_COLUMNS.into_iter().zip(m.extras()) {
        line(column, sig6(value));
    }
    for (column, value) in &s.diagnostics {
        line(column, sig6(*value));
    }
    text
}

/// Every number of a summary as its bits, except the wall time.
fn bits(s: &RunSummary) -> Vec<u64> {
    let m = &s.metrics;
    let floats = [s.t].into_iter().chain(m.reals()).chain(m.extras()).chain([
        s.component_velocity_mismatch,
        s.initial_energy,
        s.final_energy,
    ]);
    let counts = [
        s.agents as u64,
        s.dim as u64,
        s.steps,
        m.components as u64,
        m.collisions as u64,
    ];
    floats.map(f64::to_bits).chain(counts).collect()
}

fn short_run(scenario: &Scenario) -> RunSummary {
    flocking::run(scenario, &mut ()).expect("the scenario runs")
}

#[test]
fn short_runs_match_their_snapshots() {
    for (name, scenario) in short_fixtures() {
        let summary = short_run(&scenario);
        assert_eq!(summary.steps, SHORT, "{name}");
        insta::assert_snapshot!(format!("short_{name}"), rounded(&name, &summary));
    }
}

#[test]
fn the_same_run_twice_is_bit_identical() {
    for (name, scenario) in short_fixtures() {
        let mut first = short_run(&scenario);
        let mut second = short_run(&scenario);
        assert_eq!(bits(&first), bits(&second), "{name}");
        first.elapsed = Duration::ZERO;
        second.elapsed = Duration::ZERO;
        assert_eq!(first, second, "{name}");
    }
}

/// Keeps the state of the last record, padded to three components, and counts the records.
#[derive(Debug, Default)]
struct LastState {
    records: usize,
    times: Vec<f64>,
    energies: Vec<f64>,
    positions: Vec<[f64; 3]>,
    velocities: Vec<[f64; 3]>,
}

fn padded(v: &[f64]) -> [f64; 3] {
    let mut out = [0.0; 3];
    out[..v.len()].copy_from_slice(v);
    out
}

impl Recorder for LastState {
    type Error = std::convert::Infallible;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        self.records += 1;
        self.times.push(record.t);
        self.energies.push(record.energy);
        let state = &record.state;
        self.positions = state
            .positions
            .chunks_exact(state.dim)
            .map(padded)
            .collect();
        self.velocities = state
            .velocities
            .chunks_exact(state.dim)
            .map(padded)
            .collect();
        Ok(())
    }
}

impl LastState {
    /// Every recorded number as its bits.
    fn bits(&self) -> Vec<u64> {
        let states = self.positions.iter().chain(&self.velocities).flatten();
        self.times
            .iter()
            .chain(&self.energies)
            .chain(states)
            .map(|x| x.to_bits())
            .collect()
    }
}

fn run_on_pool(scenario: &Scenario, threads: usize) -> (RunSummary, LastState) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a rayon pool");
    pool.install(|| {
        let mut state = LastState::default();
        let summary = flocking::run(scenario, &mut state).expect("the scenario runs");
        (summary, state)
    })
}

#[test]
fn one_and_three_threads_give_bit_identical_states() {
    for (name, mut scenario) in short_fixtures() {
        scenario.duration = 5.0;
        let (summary1, state1) = run_on_pool(&scenario, 1);
        let (summary3, state3) = run_on_pool(&scenario, 3);
        assert_eq!(state1.positions.len(), scenario.agents, "{name}");
        assert_eq!(state1.velocities.len(), scenario.agents, "{name}");
        assert_eq!(
            state1.bits(),
            state3.bits(),
            "{name}: final states differ between 1 and 3 threads"
        );
        assert_eq!(
            bits(&summary1),
            bits(&summary3),
            "{name}: summaries differ between 1 and 3 threads"
        );
        if scenario.dim == 2 {
            let mut third_axis = state1
                .positions
                .iter()
                .chain(&state1.velocities)
                .map(|v| v[2]);
            assert!(third_axis.all(|z| z == 0.0), "{name}: a 2D state has no z");
        }
    }
}

#[test]
fn records_start_at_zero_every_record_every_steps_and_at_the_end() {
    for (name, mut scenario) in short_fixtures() {
        // 200 steps; every 30 steps gives 30, 60, …, 180, then the last step 200.
        scenario.record_every = 30;
        let mut state = LastState::default();
        let summary = flocking::run(&scenario, &mut state).expect("the scenario runs");
        assert_eq!(state.records, 1 + 6 + 1, "{name}: {:?}", state.times);
        assert_eq!(state.times[0], 0.0, "{name}");
        approx::assert_relative_eq!(state.times[1], 30.0 * scenario.step, max_relative = 1e-12);
        assert_eq!(*state.times.last().expect("records"), summary.t, "{name}");
        assert_eq!(
            state.energies[0].to_bits(),
            summary.initial_energy.to_bits(),
            "{name}"
        );
        assert_eq!(
            state.energies.last().expect("records").to_bits(),
            summary.final_energy.to_bits(),
            "{name}"
        );
        assert!(
            state.times.windows(2).all(|w| w[0] < w[1]),
            "{name}: {:?}",
            state.times
        );
    }
}

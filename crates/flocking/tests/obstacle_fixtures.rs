//! TAC 2006 Fig. 14–17 (issue 22): the split/rejoin around a convex wedge and the squeeze between
//! two balls, asserted at every record of the fixtures' runs against the numbers their headers
//! measure.

use flocking::{Record, Recorder};

use crate::common::fixture;

/// Per record: t, C*, the pairs closer than d/4, the least pair distance and whether an agent is
/// inside an obstacle; per agent, the y at which it crossed the line x = `line` first (`None`
/// until it does).
struct Pass {
    line: f64,
    records: Vec<(f64, f64, usize, f64, bool)>,
    previous: Vec<f64>,
    crossings: Vec<Option<(f64, f64)>>,
}

impl Pass {
    /// The run of the fixture `name`, watched crossing x = `line`.
    fn of(name: &str, line: f64) -> Self {
        let scenario = fixture(name);
        let mut pass = Self {
            line,
            records: Vec::new(),
            previous: Vec::new(),
            crossings: vec![None; scenario.agents],
        };
        flocking::run(&scenario, &mut pass).expect("the scenario runs");
        pass
    }

    /// The records with t in `times`.
    fn during(
        &self,
        times: core::ops::RangeInclusive<f64>,
    ) -> impl Iterator<Item = &(f64, f64, usize, f64, bool)> {
        self.records.iter().filter(move |r| times.contains(&r.0))
    }
}

impl Recorder for Pass {
    type Error = std::convert::Infallible;
    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let inside = record
            .diagnostics
            .iter()
            .find(|&&(name, _)| name == "inside_obstacles")
            .expect("Algorithm 3 records inside_obstacles")
            .1;
        self.records.push((
            record.t,
            record.metrics.giant_component,
            record.metrics.collisions,
            record.metrics.min_distance,
            inside > 0.0,
        ));
        let positions = &record.state.positions;
        if !self.previous.is_empty() {
            for (i, (q, p)) in positions
                .chunks_exact(2)
                .zip(self.previous.chunks_exact(2))
                .enumerate()
            {
                if self.crossings[i].is_none() && p[0] < self.line && q[0] >= self.line {
                    let f = (self.line - p[0]) / (q[0] - p[0]);
                    self.crossings[i] = Some((record.t, p[1] + f * (q[1] - p[1])));
                }
            }
        }
        self.previous.clear();
        self.previous.extend_from_slice(positions);
        Ok(())
    }
}

/// The balls of Fig. 16 are centred on x = 140, their surfaces 14 m either side of y = 0.
const SQUEEZE_LINE: f64 = 140.0;
const SQUEEZE_HALF_GAP: f64 = 14.0;

/// TAC 2006 Fig. 16–17, in SPEC.md's gain ordering c₁^α < c₁^γ < c₁^β: every agent passes
/// between the two balls (its y within the gap when it crosses their centre line), the flock holds
/// together while it squeezes through (C* = 1 at every record of the pass, measured; asserted
/// ≥ 0.98), no agent enters a ball, no pair comes closer than d/4 once the start has settled
/// (t ≥ 1 s; the last such pair parts at 0.4 s) and none closer than 5.1 from 2 s on (measured
/// least 5.26 = 0.75 d at 35.6 s).
#[test]
fn tac2006_fig16_every_agent_squeezes_between_the_balls() {
    let pass = Pass::of("tac2006_fig16_squeeze_n150", SQUEEZE_LINE);
    let mut times = Vec::new();
    for (i, crossing) in pass.crossings.iter().enumerate() {
        let (t, y) = crossing.unwrap_or_else(|| panic!("agent {i} never crosses x = 140"));
        assert!(
            y.abs() < SQUEEZE_HALF_GAP,
            "agent {i} crosses x = 140 at y = {y}, t = {t}: outside the gap"
        );
        times.push(t);
    }
    let first = times.iter().copied().fold(f64::INFINITY, f64::min);
    let last = times.iter().copied().fold(0.0, f64::max);
    for &(t, c_star, ..) in pass.during(first..=last) {
        assert!(c_star >= 0.98, "C* = {c_star} at t = {t} during the pass");
    }
    for &(t, _, collisions, least, inside) in &pass.records {
        assert!(!inside, "an agent inside a ball at t = {t}");
        if t >= 1.0 {
            assert_eq!(collisions, 0, "pairs closer than d/4 at t = {t} ({least})");
        }
        if t >= 2.0 {
            assert!(least >= 5.1, "a pair within {least} at t = {t}");
        }
    }
}

/// TAC 2006 Fig. 14–15, in SPEC.md's gain ordering c₁^α = 3 < c₁^γ = 3.5 < c₁^β = 30: the
/// flock splits on the wedge's tip into two halves (C* = 0.51 at t = 50.8 s, measured), rejoins
/// behind it (C* = 1 from 77.6 s) and ends as one net; no agent enters the wedge and no pair comes
/// closer than d/4 after t = 0.4 s (least distance 3.42 from then, 5.62 from 2 s on: no pair
/// pressed together at the tip, where the action function with b = 5 merges pairs).
#[test]
fn tac2006_fig14_splits_on_the_wedge_and_rejoins() {
    // No line to cross: x = ∞.
    let pass = Pass::of("tac2006_fig14_split_rejoin_n150", f64::INFINITY);
    let least_c_star = pass
        .during(40.0..=90.0)
        .map(|r| r.1)
        .fold(f64::INFINITY, f64::min);
    assert!(least_c_star <= 0.55, "no split: least C* {least_c_star}");
    let split = pass
        .during(40.0..=90.0)
        .find(|r| r.1 < 1.0)
        .expect("a split")
        .0;
    assert!((49.0..=53.0).contains(&split), "split at t = {split}");
    let last_apart = pass
        .during(split..=f64::INFINITY)
        .filter(|r| r.1 < 1.0)
        .map(|r| r.0)
        .fold(split, f64::max);
    assert!(
        (76.0..=79.0).contains(&last_apart),
        "apart until t = {last_apart}"
    );
    for &(t, c_star, ..) in pass.during(79.0..=f64::INFINITY) {
        assert_eq!(c_star, 1.0, "not rejoined at t = {t}");
    }
    for &(t, _, collisions, least, inside) in &pass.records {
        assert!(!inside, "an agent inside the wedge at t = {t}");
        if t >= 0.4 {
            assert_eq!(collisions, 0, "pairs closer than d/4 at t = {t}");
            assert!(least >= 3.3, "a pair within {least} at t = {t}");
        }
        if t >= 2.0 {
            assert!(least >= 5.5, "a pair within {least} at t = {t}");
        }
    }
}

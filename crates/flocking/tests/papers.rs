//! Full runs of the TAC 2006 fixtures (no output), checked against what the paper shows:
//! Algorithm 2 (Figs. 10, 11, 13) flocks into one collision-free quasi α-lattice moving at one
//! velocity; Algorithm 1 from a sparse cloud (Fig. 12) fragments into rigidly moving flocks while its
//! energy H decreases.

use flocking::{Algorithm, Record, Recorder, RunSummary, Scenario};

use crate::common::fixture;

fn run_fixture(name: &str) -> (Scenario, RunSummary) {
    let scenario = fixture(name);
    let summary = flocking::run(&scenario, &mut ()).expect("the scenario runs");
    assert_eq!(summary.steps, scenario.steps(), "{name}: every step taken");
    approx::assert_relative_eq!(summary.t, scenario.duration, max_relative = 1e-9);
    (scenario, summary)
}

/// Theorem 2 of TAC 2006 as the fixtures reproduce it: connected, a quasi α-lattice (small
/// deviation energy), velocity matching, and no two agents much closer than d.
fn assert_flocks(name: &str) -> Scenario {
    let (scenario, s) = run_fixture(name);
    let m = &s.metrics;
    let d = scenario.alpha.d;
    let report = format!("{name}: {s:#?}");
    assert_eq!(m.connectivity, 1.0, "{report}");
    assert_eq!(m.components, 1, "{report}");
    assert_eq!(m.giant_component, 1.0, "{report}");
    assert!(m.deviation_energy <= 0.01, "{report}");
    assert!(m.velocity_mismatch <= 1e-3, "{report}");
    assert!(m.min_distance >= 0.85 * d, "{report}");
    assert_eq!(m.collisions, 0, "{report}");
    assert!(s.component_velocity_mismatch <= 1e-3, "{report}");
    scenario
}

#[test]
fn tac2006_fig10_algorithm2_n150_flocks() {
    assert_eq!(assert_flocks("tac2006_fig10_alg2_n150").agents, 150);
}

#[test]
fn tac2006_fig11_algorithm2_n100_flocks() {
    assert_eq!(assert_flocks("tac2006_fig11_alg2_n100").agents, 100);
}

#[test]
fn tac2006_fig13_algorithm2_3d_n50_flocks() {
    assert_eq!(assert_flocks("tac2006_fig13_alg2_3d_n50").dim, 3);
}

#[test]
fn tac2006_fig12_algorithm1_n40_fragments_into_rigid_flocks() {
    let (_, s) = run_fixture("tac2006_fig12_alg1_n40");
    let m = &s.metrics;
    let report = format!("{s:#?}");
    assert!(m.giant_component < 1.0, "{report}");
    assert!(m.components >= 2, "{report}");
    assert!(m.connectivity < 1.0, "{report}");
    // Each component is a rigid lattice moving at its own velocity …
    assert!(s.component_velocity_mismatch <= 1e-3, "{report}");
    // … but the flocks move apart: no common velocity.
    assert!(m.velocity_mismatch > 0.1, "{report}");
    assert_eq!(m.collisions, 0, "{report}");
}

#[test]
fn tac2006_fig12_algorithm1_energy_decreases() {
    let (_, s) = run_fixture("tac2006_fig12_alg1_n40");
    assert!(
        s.initial_energy.is_finite() && s.final_energy.is_finite(),
        "{s:#?}"
    );
    assert!(
        s.final_energy < s.initial_energy,
        "H must decrease under Algorithm 1: {s:#?}"
    );
}

/// Every recorded instant of a run: (t, metrics, energy, diagnostics), and the diagnostics' names.
#[derive(Default)]
struct Trace(
    Vec<(f64, flock_metrics::FlockMetrics, f64, Vec<f64>)>,
    Vec<&'static str>,
);

impl Trace {
    /// The diagnostic `name` at every record.
    fn column(&self, name: &str) -> Vec<f64> {
        let k = self
            .1
            .iter()
            .position(|&n| n == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.1));
        self.0.iter().map(|r| r.3[k]).collect()
    }
}

impl Recorder for Trace {
    type Error = std::convert::Infallible;
    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        self.1 = record.diagnostics.iter().map(|&(name, _)| name).collect();
        self.0.push((
            record.t,
            record.metrics,
            record.energy,
            record.diagnostics.iter().map(|&(_, v)| v).collect(),
        ));
        Ok(())
    }
}

fn trace_fixture(name: &str) -> (Scenario, RunSummary, Trace) {
    let scenario = fixture(name);
    let mut trace = Trace::default();
    let summary = flocking::run(&scenario, &mut trace).expect("the scenario runs");
    (scenario, summary, trace)
}

/// No recorded instant has an agent inside an obstacle (column `inside_obstacles`), and every agent
/// keeps a positive clearance (`obstacle_clearance`).
fn assert_never_inside(name: &str, trace: &Trace) -> f64 {
    let clearances = trace.column("obstacle_clearance");
    let inside = trace.column("inside_obstacles");
    let mut closest = f64::INFINITY;
    for ((t, ..), (&clearance, &inside)) in trace.0.iter().zip(clearances.iter().zip(&inside)) {
        assert_eq!(
            inside, 0.0,
            "{name}: an agent is inside an obstacle at t = {t}"
        );
        closest = closest.min(clearance);
    }
    assert!(closest > 0.0, "{name}: clearance {closest}");
    closest
}

/// CDS 03-006 Fig. 7–8: the flock splits around the six balls, squeezes between O5 and O6 and ends
/// with a giant component of about 97 of 100 agents (the report's δ₀ ≈ 0.97); no agent ever enters
/// an obstacle.
#[test]
fn tr2003_fig7_flock_passes_six_obstacles() {
    let (_, s, trace) = trace_fixture("tr2003_fig7_obstacles_n100");
    assert_never_inside("tr2003_fig7", &trace);
    let split = trace
        .0
        .iter()
        .map(|(_, m, _, _)| m.giant_component)
        .fold(1.0, f64::min);
    assert!(
        split < 0.9,
        "the flock must split at the obstacles (min C* = {split})"
    );
    assert!(
        s.metrics.giant_component >= 0.95,
        "final C* = {}",
        s.metrics.giant_component
    );
}

/// CDS 03-006 Fig. 9 and ACC 2004 Fig. 4: an initially disconnected net becomes connected after a
/// few seconds and stays connected (the report: after about 4 s).
fn assert_connects(name: &str, by: f64) {
    let (scenario, s, trace) = trace_fixture(name);
    assert!(
        trace.0[0].1.connectivity < 1.0,
        "{name}: the initial net must be disconnected"
    );
    let last_disconnected = trace
        .0
        .iter()
        .filter(|(_, m, _, _)| m.connectivity < 1.0)
        .map(|r| r.0)
        .fold(0.0, f64::max);
    assert!(
        last_disconnected <= by,
        "{name}: disconnected until t = {last_disconnected}"
    );
    let m = &s.metrics;
    assert_eq!(m.connectivity, 1.0);
    assert!(
        m.deviation_energy <= 0.03,
        "{name}: Ẽ = {}",
        m.deviation_energy
    );
    assert!(
        m.min_distance >= 0.5 * scenario.alpha.d,
        "{name}: min distance {}",
        m.min_distance
    );
    assert_eq!(m.collisions, 0);
}

/// The report: "The net becomes connected after 4 seconds"; with eq. 50's gain 1 the fixture's
/// net is connected from t = 1.5 s.
#[test]
fn tr2003_fig9_sink_connects_the_net() {
    assert_connects("tr2003_fig9_sink_n100", 4.0);
}

/// The ACC start is sparser ([−50, 50]²) and its sink weaker than Fig. 9's (c₁ = 0.02 with
/// a = 1, b = 5): it connects at t = 15.5 s.
#[test]
fn acc2004_fig4_sink_connects_the_net() {
    assert_connects("acc2004_fig4_sink_n100", 16.0);
}

/// The 3D field of obstacles: zero agents inside obstacles at every recorded instant, the flock
/// passes and ends as one connected, collision-free lattice (TAC 2006 Fig. 14–17 are in
/// `obstacle_fixtures.rs`).
fn assert_avoids_and_rejoins(name: &str) {
    let (scenario, s, trace) = trace_fixture(name);
    let closest = assert_never_inside(name, &trace);
    assert!(
        closest < BETA_RANGE_FACTOR * scenario.alpha.d,
        "{name}: the flock must meet the obstacles"
    );
    let m = &s.metrics;
    let report = format!("{name}: {s:#?}");
    assert_eq!(m.connectivity, 1.0, "{report}");
    assert_eq!(m.collisions, 0, "{report}");
    assert!(m.min_distance >= 0.85 * scenario.alpha.d, "{report}");
    assert!(m.velocity_mismatch <= 1e-2, "{report}");
}

/// r′ = 1.2 d′ = 0.72 d: an agent closer than this to an obstacle has met it.
const BETA_RANGE_FACTOR: f64 = 0.72;

/// TAC 2006 Fig. 12 and 18(b) (issue 15): Algorithm 1 breaks a connected group into at least three
/// lattices of three or more agents, each moving rigidly.
#[test]
fn tac2006_fig12_algorithm1_fragments_into_multi_agent_lattices() {
    let scenario = fixture("tac2006_fig12_alg1_n40");
    let mut sim = flocking::DynSimulation::new(&scenario).expect("valid");
    assert_eq!(
        sim.metrics().connectivity,
        1.0,
        "the group starts connected"
    );
    while sim.steps() < scenario.steps() {
        sim.step();
    }
    let components = flock_graph::Components::of(&sim.graph());
    let lattices = components.sizes().iter().filter(|&&size| size >= 3).count();
    assert!(lattices >= 3, "{:?}", components.sizes());
    assert!(
        sim.component_velocity_mismatch() <= 1e-3,
        "each component moves rigidly: {}",
        sim.component_velocity_mismatch()
    );
}

/// CDS 03-006 Fig. 9 (issue 15): at rest, the sink's flock is "mostly equilateral triangles" —
/// nine edges in ten within ±10 % of d, most triangles equilateral, no edge crossing another and
/// no more edges than TAC 2006 Theorem 5's 3n − 6.
#[test]
fn tr2003_fig9_sink_ends_on_a_lattice_of_equilateral_triangles() {
    let (_, s) = run_fixture("tr2003_fig9_sink_n100");
    let lattice = &s.lattice;
    let report = format!("{lattice}: {s:#?}");
    assert!(lattice.near_fraction() >= 0.9, "{report}");
    assert!(lattice.equilateral_fraction() >= Some(0.8), "{report}");
    assert_eq!(lattice.crossings, Some(0), "{report}");
    assert_eq!(lattice.within_edge_bound(), Some(true), "{report}");
    assert!(s.metrics.velocity_mismatch < 1e-6, "at rest: {report}");
}

/// CDS 03-006 § 9–10 on the sink of Fig. 9: the 2003 protocols record the defect factor
/// (eq. 46–47) and H_s, H_tr (eq. 48–49). With the distributed PD of eq. 50, Σ_i u_i^α = 0 makes
/// the centre of mass a damped oscillator of its own (Proposition 6): H_tr never rises and decays
/// at twice the slowest decay rate σ of s² + c₂ s + c₁ = 0 (the real part of its slow root; c₂/2
/// for the fixture's underdamped c₁ = 1, c₂ = 1), whatever the (α, α) part, read over the first
/// half of the run, before H_tr reaches round-off; the defect factor falls as the net settles into
/// its lattice.
#[test]
fn tr2003_fig9_sink_separates_translation_from_structure() {
    let (scenario, _, trace) = trace_fixture("tr2003_fig9_sink_n100");
    let Algorithm::Flocking2003(flocking::scenario::Flocking2003Params {
        translation: Some(translation),
        ..
    }) = &scenario.algorithm
    else {
        panic!("a 2003 protocol with a sink")
    };
    let (c1, c2) = (translation.c1, translation.c2);
    let discriminant = c2 * c2 - 4.0 * c1;
    let sigma = 0.5 * (c2 - discriminant.max(0.0).sqrt());
    let h_tr = trace.column("translational_energy");
    for (k, pair) in h_tr.windows(2).enumerate() {
        assert!(
            pair[1] <= pair[0] * (1.0 + 1e-9) + 1e-15,
            "H_tr rose from {} to {} at record {}",
            pair[0],
            pair[1],
            k + 1
        );
    }
    let half = h_tr.len() / 2;
    let elapsed = trace.0[half].0 - trace.0[0].0;
    let rate = (h_tr[0] / h_tr[half]).ln() / elapsed;
    assert!(
        (0.9..1.1).contains(&(rate / (2.0 * sigma))),
        "H_tr decays at {rate} over {elapsed} s; the slow mode alone gives {}",
        2.0 * sigma
    );
    let h_s = trace.column("structural_energy");
    assert!(h_s.iter().all(|&h| h.is_finite() && h >= 0.0), "{h_s:?}");
    let defect = trace.column("normalised_defect_factor");
    let settled = defect[defect.len() - 1];
    let most = defect.iter().copied().fold(0.0, f64::max);
    assert!(
        settled >= 0.0 && settled < 0.1 * most,
        "the defect factor must fall as the lattice forms: max {most}, final {settled}"
    );
}

#[test]
fn alg3_3d_mixed_obstacle_field() {
    assert_avoids_and_rejoins("alg3_3d_mixed_obstacles_n100");
}

/// Tanner, Jadbabaie & Pappas 2003: velocities align (disagreement → 0), W never increases, and
/// linked agents never collide (V_ij → ∞).
#[test]
fn tanner2003_velocities_align_without_linked_collisions() {
    let (scenario, _, trace) = trace_fixture("tanner2003_fig3_fixed_n10");
    let first = &trace.0[0];
    let last = trace.0.last().expect("records");
    let (disagreement0, disagreement) = (first.3[0], last.3[0]);
    assert!(
        disagreement <= 1e-6 * disagreement0,
        "disagreement {disagreement0} → {disagreement}"
    );
    for pair in trace.0.windows(2) {
        let (w0, w1) = (pair[0].2, pair[1].2);
        assert!(
            w1 <= w0 + 1e-9 * w0.abs(),
            "W rose from {w0} to {w1} at t = {}",
            pair[1].0
        );
    }
    let closest_linked = trace.0.iter().map(|r| r.3[1]).fold(f64::INFINITY, f64::min);
    assert!(
        closest_linked > 0.1 * scenario.alpha.d,
        "linked agents came within {closest_linked}"
    );
}

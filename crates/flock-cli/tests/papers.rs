//! Full runs of the TAC 2006 fixtures (no output), checked against what the paper shows:
//! Algorithm 2 (Figs. 10, 11, 13) flocks into one collision-free quasi α-lattice moving at one
//! velocity; Algorithm 1 from a sparse cloud (Fig. 12) fragments into rigidly moving flocks while its
//! energy H decreases.

use flock_cli::{RunSummary, Scenario, run_scenario};

use crate::common::fixture;

fn run_fixture(name: &str) -> (Scenario, RunSummary) {
    let scenario = fixture(name);
    let Ok(summary) = run_scenario(&scenario, &mut ());
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

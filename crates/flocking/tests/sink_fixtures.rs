//! The sink of ACC 2004 Fig. 4 and CDS 03-006 Fig. 9 (issue 22): the topology the ACC run ends on,
//! and why the report's position gain c₁ = 1 cannot hold a lattice near d.

use flocking::{Algorithm, DynSimulation, Scenario};

use crate::common::fixture;

/// The scenario with the sink's position gain set to `c1`.
fn with_sink_gain(mut scenario: Scenario, c1: f64) -> Scenario {
    let Algorithm::Flocking2003 {
        translation: Some(translation),
        ..
    } = &mut scenario.algorithm
    else {
        panic!("{}: a 2003 protocol with a sink", scenario.name)
    };
    translation.c1 = c1;
    scenario
}

/// ACC 2004 Fig. 4: "the topology of the flock is asymptotically invariant". The edge set is the
/// same at each of the last 301 records (t ∈ [450, 600] s; it last changes at 437.5 s) and ends
/// planar (no crossing edges) within TAC 2006 Theorem 5's 3n − 6 edges.
#[test]
fn acc2004_fig4_sink_ends_on_an_invariant_planar_topology() {
    let scenario = fixture("acc2004_fig4_sink_n100");
    let every = scenario.record_every;
    let records = scenario.steps() / every;
    let last = 301;
    let mut sim = DynSimulation::new(&scenario).expect("valid");
    while sim.steps() < (records + 1 - last) * every {
        sim.step();
    }
    let settled = sim.graph().into_owned();
    while sim.steps() < scenario.steps() {
        sim.step();
        if sim.steps().is_multiple_of(every) {
            assert!(
                *sim.graph() == settled,
                "the edge set changes at t = {}",
                sim.time()
            );
        }
    }
    let lattice = sim.lattice();
    assert_eq!(lattice.crossings, Some(0), "{lattice}");
    assert_eq!(lattice.within_edge_bound(), Some(true), "{lattice}");
}

/// CDS 03-006 Fig. 9 with eq. 50's gain c₁ = 1: the sink's pressure at the flock's centre,
/// c₁ n/(2π) per metre, exceeds what links pushing with at most b = 5 (φ_α is bounded) can bear
/// at spacing d, so within 60 s the flock is crushed — agents closer than d/10, links crossing —
/// where the fixture's c₁ = 0.02 ends on a planar lattice near d (`papers.rs`).
#[test]
fn tr2003_fig9_report_gain_crushes_the_lattice() {
    let mut scenario = with_sink_gain(fixture("tr2003_fig9_sink_n100"), 1.0);
    scenario.duration = 60.0;
    let mut sim = DynSimulation::new(&scenario).expect("valid");
    while sim.steps() < scenario.steps() {
        sim.step();
    }
    let metrics = sim.metrics();
    let lattice = sim.lattice();
    assert!(metrics.min_distance < 0.1 * scenario.alpha.d, "{metrics:?}");
    assert!(lattice.crossings > Some(100), "{lattice}");
    assert_eq!(lattice.within_edge_bound(), Some(false), "{lattice}");
}

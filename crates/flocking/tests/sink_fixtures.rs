//! The sink of ACC 2004 Fig. 4 and CDS 03-006 Fig. 9 (issue 22): the topology the ACC run ends on,
//! and what the report's position gain 1 asks of the action function.

use flocking::DynSimulation;

use crate::common::fixture;

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

/// CDS 03-006 Fig. 9 with eq. 50's gain 1, bracketed: the sink's pressure at the flock's centre,
/// n/(2π) per metre, exceeds what links pushing with at most b (φ_α is bounded) bear at spacing d
/// unless b ≳ 60. With the report's Fig. 4 pair (a = 1, b = 5), and with b = 50 alone (a = 1: the
/// offset c = |a − b|/√(4ab) moves the repulsion's onset inwards), the flock is crushed within
/// 60 s: pairs closer than d/2, links crossing. The fixture's a = 50, b = 250 (the same shape × 50)
/// ends on a planar lattice, most of its edges within ±10 % of d.
#[test]
fn tr2003_fig9_report_gain_needs_the_action_function_scaled() {
    let run = |a: f64, b: f64| {
        let mut scenario = fixture("tr2003_fig9_sink_n100");
        scenario.alpha.a = a;
        scenario.alpha.b = b;
        let mut sim = DynSimulation::new(&scenario).expect("valid");
        while sim.steps() < scenario.steps() {
            sim.step();
        }
        (scenario.alpha.d, sim.metrics(), sim.lattice())
    };
    for (a, b) in [(1.0, 5.0), (1.0, 50.0)] {
        let (d, metrics, lattice) = run(a, b);
        assert!(
            metrics.min_distance < 0.5 * d,
            "a = {a}, b = {b}: {metrics:?}"
        );
        assert!(lattice.crossings > Some(100), "a = {a}, b = {b}: {lattice}");
        assert_eq!(lattice.within_edge_bound(), Some(false), "{lattice}");
    }
    let (d, metrics, lattice) = run(50.0, 250.0);
    assert!(metrics.min_distance > 0.8 * d, "{metrics:?}");
    assert_eq!(lattice.crossings, Some(0), "{lattice}");
    assert!(lattice.near_fraction() > 0.9, "{lattice}");
}

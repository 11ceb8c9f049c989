//! `RunSummary::topology_invariant_from`: the first record from which the proximity net's edge
//! set no longer changes, on runs whose edge set is known beforehand.

use flocking::Scenario;

/// A 2D Algorithm 1 run of 10 s (records every 0.1 s) from the given positions and velocities.
fn run(positions: &str, velocities: &str) -> flocking::RunSummary {
    let text = format!(
        "Scenario(dim: 2, agents: {}, algorithm: Algorithm1, \
         initial: (positions: Explicit([{positions}]), velocities: Explicit([{velocities}])), \
         duration: 10.0)",
        positions.matches('[').count()
    );
    let scenario = Scenario::parse(&text, "topology.ron").unwrap_or_else(|e| panic!("{e}"));
    flocking::run(&scenario, &mut ()).expect("runs")
}

#[test]
fn a_lattice_at_rest_is_invariant_from_the_start() {
    // an equilateral triangle of side d = 7: an α-lattice, no force, three edges throughout
    let h = 7.0 * 3f64.sqrt() / 2.0;
    let summary = run(
        &format!("[0.0, 0.0], [7.0, 0.0], [3.5, {h}]"),
        "[0.0, 0.0], [0.0, 0.0], [0.0, 0.0]",
    );
    assert_eq!(summary.lattice.edges, 3);
    assert_eq!(summary.topology_invariant_from, 0.0);
}

#[test]
fn an_approaching_pair_is_invariant_from_the_record_where_it_links() {
    // 9.43 apart closing at 0.2 m/s: within r = 8.4 at t = 5.15 s, first recorded at t = 5.2 s;
    // the consensus term damps them into the well around d, so they stay linked
    let summary = run("[0.0, 0.0], [9.43, 0.0]", "[0.1, 0.0], [-0.1, 0.0]");
    assert_eq!(summary.lattice.edges, 1);
    assert!(
        (summary.topology_invariant_from - 5.2).abs() < 1e-9,
        "{}",
        summary.topology_invariant_from
    );
}

#[test]
fn a_pair_that_links_at_the_last_record_is_still_changing_at_the_end() {
    // linked at t = 5.15 s, first recorded at the final time 5.2 s
    let text = "Scenario(dim: 2, agents: 2, algorithm: Algorithm1, \
                initial: (positions: Explicit([[0.0, 0.0], [9.43, 0.0]]), \
                velocities: Explicit([[0.1, 0.0], [-0.1, 0.0]])), duration: 5.2)";
    let scenario = Scenario::parse(text, "topology.ron").unwrap_or_else(|e| panic!("{e}"));
    let summary = flocking::run(&scenario, &mut ()).expect("runs");
    assert_eq!(summary.topology_invariant_from, summary.t);
}

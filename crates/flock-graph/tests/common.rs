//! Helpers shared by the integration tests.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{Domain, Vector};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// A seeded random stream.
pub fn rng(seed: u64) -> Pcg64 {
    Pcg64::seed_from_u64(seed)
}

/// `n` points uniform in `offset + [−scale, scale]^m`.
pub fn cloud<V: Vector>(seed: u64, n: usize, scale: f64, offset: f64) -> Vec<V> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| V::from_fn(|_| offset + scale * (2.0 * rng.random::<f64>() - 1.0)))
        .collect()
}

/// The net built by a fresh [`NeighbourSearch`].
pub fn searched<V: Vector>(positions: &[V], r: f64) -> ProximityNet {
    let mut net = ProximityNet::new();
    NeighbourSearch::new().build(positions, r, &mut net);
    net
}

/// Asserts two nets are identical: same range, same CSR arrays, bit-identical distances.
pub fn assert_identical(actual: &ProximityNet, expected: &ProximityNet) {
    assert_eq!(
        actual.range().to_bits(),
        expected.range().to_bits(),
        "range"
    );
    assert_eq!(
        actual.graph().offsets(),
        expected.graph().offsets(),
        "offsets"
    );
    assert_eq!(
        actual.graph().neighbour_indices(),
        expected.graph().neighbour_indices(),
        "neighbours"
    );
    let bits = |net: &ProximityNet| {
        net.distances()
            .iter()
            .map(|d| d.to_bits())
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(actual), bits(expected), "distances");
}

/// Asserts the neighbour search reproduces the brute-force net exactly, and counts its pairs
/// without building it ([`assert_pair_counts`]); returns the net.
pub fn assert_search_matches_brute_force<V: Vector>(positions: &[V], r: f64) -> ProximityNet {
    let net = searched(positions, r);
    let expected = ProximityNet::brute_force(positions, r);
    assert_identical(&net, &expected);
    assert_pair_counts(&Domain::Open, positions, r, &expected);
    net
}

/// Asserts [`NeighbourSearch::count_pairs_in`] counts the edges of `expected` (the brute-force
/// net of `positions` in `domain` with range `r`): all of them, and those a predicate mixing both
/// indices accepts, each offered once as (lower, higher); within the budget of every ordered pair
/// of finite agents (n²), and refused below one test per finite agent (each is its own candidate).
pub fn assert_pair_counts<V: Vector>(
    domain: &Domain<V>,
    positions: &[V],
    r: f64,
    expected: &ProximityNet,
) {
    let graph = expected.graph();
    let picked = |i: usize, j: usize| (7 * i + 3 * j) % 5 < 2;
    let edges = || {
        (0..graph.len()).flat_map(move |i| {
            graph
                .neighbours(i)
                .iter()
                .map(move |&j| (i, j as usize))
                .filter(|&(i, j)| i < j)
        })
    };
    let finite = positions.iter().filter(|q| q.is_finite()).count();
    let mut search = NeighbourSearch::new();
    let all = search.count_pairs_in(domain, positions, r, finite * finite, |i, j| {
        assert!(i < j, "pair ({i}, {j}) offered out of order");
        true
    });
    assert_eq!(all, Some(graph.undirected_edge_count()), "every pair");
    let some = search.count_pairs_in(domain, positions, r, finite * finite, picked);
    let picked_edges = edges().filter(|&(i, j)| picked(i, j)).count();
    assert_eq!(some, Some(picked_edges), "picked pairs");
    if finite >= 2 && r > 0.0 {
        let refused = search.count_pairs_in(domain, positions, r, finite - 1, |_, _| {
            panic!("a pair tested beyond the budget")
        });
        assert_eq!(refused, None, "below one test per agent");
    }
}

//! Helpers shared by the integration tests.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::Vector;
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

/// Asserts the neighbour search reproduces the brute-force net exactly; returns the net.
pub fn assert_search_matches_brute_force<V: Vector>(positions: &[V], r: f64) -> ProximityNet {
    let net = searched(positions, r);
    assert_identical(&net, &ProximityNet::brute_force(positions, r));
    net
}

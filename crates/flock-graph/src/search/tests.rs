//! Tests of the search as a whole: nets against brute force under numberings, block lengths,
//! thread counts and reuse, and the lists kept between builds (the skin) as agents move.

use super::*;
use crate::search::skin::Skin;
use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};

/// `n` points uniform in the square [0, side]², from `seed`.
fn uniform_square(n: usize, side: f64, seed: u64) -> Vec<DVec2> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| DVec2::new(rng.random::<f64>() * side, rng.random::<f64>() * side))
        .collect()
}

/// A net built from agents stored out of order, with their numbering, is the net of the
/// agents in original order relabelled: each list names the same agents in the same order,
/// with the same distance bits (recomputed ones too, without stored distances). Sorting the
/// agents by cell makes the net of agents numbered at random no longer scattered.
#[test]
fn numbered_nets_are_the_original_nets_relabelled() {
    let mut q = uniform_square(20_000, 860.0, 5);
    q[123] = DVec2::NAN;
    let mut search = NeighbourSearch::new();
    let mut original = ProximityNet::new();
    search.build(&q, 8.4, &mut original);
    assert!(original.graph().directed_edge_count() > 4 * q.len());
    assert!(original.is_scattered());
    // the finite agents by cell, then the NaN one
    let mut order = search.cell_order(&q, 8.4).to_vec();
    assert_eq!(order.len(), q.len() - 1);
    order.push(123);
    let stored: Vec<DVec2> = order.iter().map(|&k| q[k as usize]).collect();
    let mut net = ProximityNet::new();
    net.permute(&order);
    search.build(&stored, 8.4, &mut net);
    assert!(!net.is_scattered());
    let numbering = net.numbering();
    for (s, &k) in order.iter().enumerate() {
        let k = k as usize;
        assert_eq!(numbering.original(s), k);
        assert_eq!(
            net.named_neighbours(s),
            original.graph().neighbours(k),
            "agent {k}"
        );
        let bits = |net: &ProximityNet, i: usize| -> Vec<u64> {
            net.graph()
                .edge_range(i)
                .map(|e| net.distances()[e].to_bits())
                .collect()
        };
        assert_eq!(bits(&net, s), bits(&original, k), "agent {k}");
    }
    let mut lean = ProximityNet::without_distances();
    lean.share_numbering(&net);
    search.build(&stored, 8.4, &mut lean);
    assert_eq!(lean.graph(), net.graph());
    let lengths: Vec<u64> = lean.edge_lengths(&stored).map(f64::to_bits).collect();
    let distances: Vec<u64> = net.distances().iter().map(|d| d.to_bits()).collect();
    assert_eq!(lengths, distances);
}

/// The blocks only partition the work: any block length, and any rayon pool size, gives the
/// same net, so the net does not depend on the `parallel` feature.
#[test]
fn net_is_independent_of_blocks_and_threads() {
    let mut q = uniform_square(3000, 40.0, 7);
    q[17] = DVec2::NAN;
    let expected = ProximityNet::brute_force(&q, 1.3);
    assert!(expected.graph().directed_edge_count() > q.len());
    let mut search = NeighbourSearch::new();
    let mut net = ProximityNet::new();
    for block_shift in [0, 3, 10, 12, 63] {
        search.open.build_in_blocks(&q, 1.3, &mut net, block_shift);
        assert_eq!(net, expected, "blocks of 2^{block_shift}");
    }
    // agents at random in their own order: the lists built without branching
    assert!(search.open.grid.sorted.scattered(net.numbering()));
    #[cfg(feature = "parallel")]
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| search.build(&q, 1.3, &mut net));
        assert_eq!(net, expected, "{threads} threads");
    }
}

/// A reused net is resized and overwritten, not cleared: growing, shrinking and emptying it
/// leaves no trace of the previous build, with or without distances.
#[test]
fn reused_nets_forget_the_previous_build() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    let mut cloud = |n: usize, side: f64| -> Vec<DVec3> {
        (0..n)
            .map(|_| DVec3::from_fn(|_| rng.random::<f64>() * side))
            .collect()
    };
    let configurations = [
        cloud(2000, 12.0),
        cloud(300, 4.0),
        cloud(2500, 30.0),
        cloud(1, 1.0),
        cloud(700, 3.0),
    ];
    let mut search = NeighbourSearch::new();
    let (mut full, mut lean) = (ProximityNet::new(), ProximityNet::without_distances());
    for (k, q) in configurations.iter().enumerate() {
        let expected = ProximityNet::brute_force(q, 1.1);
        search.build(q, 1.1, &mut full);
        assert_eq!(full, expected, "configuration {k}");
        search.build(q, 1.1, &mut lean);
        assert_eq!(lean.graph(), expected.graph(), "configuration {k}");
        assert!(lean.distances().is_empty());
    }
    search.build(&configurations[0], 0.0, &mut full);
    assert_eq!(full, ProximityNet::brute_force(&configurations[0], 0.0));
}

/// The blocks only partition the work: any block length and pool size gives the same net.
#[test]
fn periodic_net_is_independent_of_blocks_and_threads() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let size = DVec2::new(30.0, 20.0);
    let q: Vec<DVec2> = (0..2500)
        .map(|_| DVec2::new(rng.random::<f64>() * 30.0, rng.random::<f64>() * 20.0))
        .collect();
    let domain = Domain::Periodic { size };
    let expected = ProximityNet::brute_force_in(&domain, &q, 1.3);
    assert!(expected.graph().directed_edge_count() > q.len());
    let mut search = NeighbourSearch::new();
    let mut net = ProximityNet::new();
    for block_shift in [0, 3, 10, 12] {
        search
            .torus
            .build_in_blocks(&domain, size, &q, 1.3, &mut net, block_shift);
        assert_eq!(net, expected, "blocks of 2^{block_shift}");
    }
    // agents at random in their own order: the lists built without branching
    assert!(search.torus.grid.sorted.scattered(net.numbering()));
    #[cfg(feature = "parallel")]
    for threads in [1, 2, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| search.build_in(&domain, &q, 1.3, &mut net));
        assert_eq!(net, expected, "{threads} threads");
        let mut d = Vec::new();
        pool.install(|| search.nearest_distances_in(&domain, &q, &mut d));
        let bits: Vec<u64> = d.iter().map(|x| x.to_bits()).collect();
        let mut d1 = Vec::new();
        NeighbourSearch::new().nearest_distances_in(&domain, &q, &mut d1);
        assert_eq!(bits, d1.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
    }
}

#[test]
fn edge_lengths_of_both_kinds_of_nets_agree() {
    let q = [
        glam::DVec3::ZERO,
        glam::DVec3::new(0.3, -0.2, 0.1),
        glam::DVec3::new(1.0, 0.7, -0.4),
        glam::DVec3::new(0.3, -0.2, 0.1),
    ];
    let full = ProximityNet::brute_force(&q, 1.5);
    let mut lean = ProximityNet::without_distances();
    NeighbourSearch::new().build(&q, 1.5, &mut lean);
    assert_eq!(lean.graph(), full.graph());
    assert!(lean.distances().is_empty() && !lean.has_distances());
    let bits =
        |net: &ProximityNet| -> Vec<u64> { net.edge_lengths(&q).map(f64::to_bits).collect() };
    assert_eq!(bits(&lean), bits(&full));
    assert_eq!(
        bits(&full),
        full.distances()
            .iter()
            .map(|d| d.to_bits())
            .collect::<Vec<_>>()
    );
}

/// The allowed displacement of lists built for range `r`: √limit.
fn allowed(r: f64) -> f64 {
    let mut skin = Skin::default();
    let reach = skin.reach_for_build(r);
    skin.built(2, r, reach, 0, 10);
    skin.kept_for(2, r, 0, 10)
        .map(|kept| kept.limit.sqrt())
        .unwrap()
}

/// Every agent moved by exactly `step` in a direction of its own.
fn moved<V: glam_like::Drawn>(q: &[V], step: f64, rng: &mut rand_pcg::Pcg64) -> Vec<V> {
    q.iter().map(|&x| x.moved(step, rng)).collect()
}

mod glam_like {
    use flock_math::Vector;
    use rand::RngExt;

    /// A point moved by a given length in a direction drawn uniformly.
    pub(super) trait Drawn: Vector {
        fn moved(self, step: f64, rng: &mut rand_pcg::Pcg64) -> Self {
            let direction = loop {
                let v = Self::from_fn(|_| rng.random::<f64>() * 2.0 - 1.0);
                let l2 = v.length_squared();
                if l2 > 1e-6 && l2 <= 1.0 {
                    break v * (1.0 / l2.sqrt());
                }
            };
            self + direction * step
        }
    }

    impl Drawn for glam::DVec2 {}
    impl Drawn for glam::DVec3 {}
}

/// Agents moved by as much as the skin allows, at every build, a dense cloud in 2D and 3D:
/// each net is the brute-force net, with and without distances, while the lists built at
/// the first serve the next ones; a move just beyond the allowance rebuilds them. Lists kept
/// for a wider allowance (the whole skin) would miss pairs: checked.
fn kept_lists_serve_moving_agents<V: glam_like::Drawn>(side: f64) {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(23);
    let r = 1.0;
    let step = allowed(r);
    let mut q: Vec<V> = (0..3000)
        .map(|_| V::from_fn(|_| rng.random::<f64>() * side))
        .collect();
    let mut search = NeighbourSearch::new();
    let (mut full, mut lean) = (ProximityNet::new(), ProximityNet::without_distances());
    search.build(&q, r, &mut full);
    let start = q.clone();
    let mut missed = 0;
    for build in 1..=3 {
        // each agent within `step` of the start (a part in 10¹² less, for the rounding of
        // the move): the lists of the start serve
        q = moved(&start, step * (1.0 - 1e-12), &mut rng);
        search.build(&q, r, &mut full);
        assert_eq!(
            search.open.skin.reuses(),
            Some(2 * build - 1),
            "build {build}"
        );
        assert!(full == ProximityNet::brute_force(&q, r), "build {build}");
        search.build(&q, r, &mut lean);
        assert_eq!(lean.graph(), full.graph());
        // twice the allowance from the start: the start's lists miss pairs
        let far = moved(&start, 2.0 * step, &mut rng);
        let net = ProximityNet::brute_force(&far, r);
        missed += (0..far.len())
            .flat_map(|i| {
                net.graph()
                    .neighbours(i)
                    .iter()
                    .map(move |&j| (i, j as usize))
            })
            .filter(|&(i, j)| (start[j] - start[i]).length_squared() >= (r + 2.0 * step).powi(2))
            .count();
    }
    assert!(missed > 0, "the test wants pairs the skin could miss");
    // one agent a hair beyond the allowance: a new build
    q = start.clone();
    q[7] = q[7].moved(step * (1.0 + 1e-9), &mut rng);
    search.build(&q, r, &mut full);
    assert_eq!(search.open.skin.reuses(), Some(0));
    assert!(full == ProximityNet::brute_force(&q, r));
}

#[test]
fn kept_lists_serve_moving_agents_2d() {
    kept_lists_serve_moving_agents::<DVec2>(30.0);
}

#[test]
fn kept_lists_serve_moving_agents_3d() {
    kept_lists_serve_moving_agents::<DVec3>(8.0);
}

/// A search whose lists for `q` and `r` served two builds, and its net.
fn warm(q: &[DVec2], r: f64) -> (NeighbourSearch, ProximityNet) {
    let mut search = NeighbourSearch::new();
    let mut net = ProximityNet::new();
    for _ in 0..3 {
        search.build(q, r, &mut net);
    }
    assert_eq!(search.open.skin.reuses(), Some(2));
    (search, net)
}

/// Lists are not reused across a new numbering, another range or number of agents, an agent
/// that entered the finite positions, or a grid rebuilt for another use: each is a new
/// build, with the skin kept on.
#[test]
fn kept_lists_are_rebuilt_when_they_no_longer_apply() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let r = 1.0;
    let mut q: Vec<DVec2> = (0..2000)
        .map(|_| DVec2::new(rng.random::<f64>() * 25.0, rng.random::<f64>() * 25.0))
        .collect();
    let built_anew = |search: &NeighbourSearch| search.open.skin.reuses() == Some(0);
    // another range
    let (mut search, mut net) = warm(&q, r);
    search.build(&q, 0.9, &mut net);
    assert!(built_anew(&search));
    assert!(net == ProximityNet::brute_force(&q, 0.9));
    // one agent fewer, the others where they were
    let (mut search, mut net) = warm(&q, r);
    search.build(&q[..q.len() - 1], r, &mut net);
    assert!(built_anew(&search));
    // the grid rebuilt for a cell order
    let (mut search, mut net) = warm(&q, r);
    search.cell_order(&q, r);
    search.build(&q, r, &mut net);
    assert!(built_anew(&search));
    // an agent found again where it was lost
    let kept = q[3];
    q[3] = DVec2::NAN;
    let (mut search, mut net) = warm(&q, r);
    q[3] = kept;
    search.build(&q, r, &mut net);
    assert!(built_anew(&search));
    assert!(net == ProximityNet::brute_force(&q, r));
    // two agents a hair apart swap their storage: within the allowance, but the numbering
    // changed, and the lists are ordered by the old one
    let (a, b) = (10, 11);
    q[b] = q[a] + DVec2::new(1e-9, 0.0);
    let original = ProximityNet::brute_force(&q, r);
    let (mut search, mut net) = warm(&q, r);
    let mut order: Vec<u32> = (0..q.len() as u32).collect();
    order.swap(a, b);
    q.swap(a, b);
    net.permute(&order);
    search.build(&q, r, &mut net);
    assert!(built_anew(&search));
    // each list names the original net's agents in the original net's order
    for s in 0..q.len() {
        let k = net.numbering().original(s);
        assert_eq!(
            net.named_neighbours(s),
            original.graph().neighbours(k),
            "agent {s}"
        );
    }
}

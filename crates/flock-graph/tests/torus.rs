//! The periodic neighbour search against the brute-force minimum-image net, with agents crowded
//! against the faces and corners of the box, and the per-agent nearest-neighbour distances.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{Domain, Vector};
use glam::{DVec2, DVec3};
use proptest::prelude::*;
use rand::RngExt;

use crate::common::{assert_identical, assert_pair_counts, cloud, rng};

/// `n` agents in the box of sides `size`: a share `near` of them within `band` of a face on every
/// axis (so at the corners), the others uniform.
fn crowded<V: Vector>(seed: u64, n: usize, size: V, near: f64, band: f64) -> Vec<V> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| {
            let at_faces = rng.random::<f64>() < near;
            let q = V::from_fn(|k| {
                let l = size.coord(k);
                if at_faces {
                    let x = rng.random::<f64>() * band.min(l / 2.0);
                    if rng.random::<bool>() { x } else { l - x }
                } else {
                    rng.random::<f64>() * l
                }
            });
            // l − x may round up to l: keep the box half-open
            Domain::Periodic { size }.wrap(q)
        })
        .collect()
}

fn searched_in<V: Vector>(domain: &Domain<V>, q: &[V], r: f64) -> ProximityNet {
    let mut net = ProximityNet::new();
    NeighbourSearch::new().build_in(domain, q, r, &mut net);
    net
}

/// Builds with the search, full and lean, and checks both against the brute force; the edge
/// lengths of the lean net are the minimum-image distances. Returns the net.
fn check_against_brute_force<V: Vector>(size: V, q: &[V], r: f64) -> ProximityNet {
    let domain = Domain::Periodic { size };
    let expected = ProximityNet::brute_force_in(&domain, q, r);
    let net = searched_in(&domain, q, r);
    assert_identical(&net, &expected);
    assert_pair_counts(&domain, q, r, &expected);
    let mut lean = ProximityNet::without_distances();
    NeighbourSearch::new().build_in(&domain, q, r, &mut lean);
    assert_eq!(lean.graph(), expected.graph());
    let bits = |it: &mut dyn Iterator<Item = f64>| it.map(f64::to_bits).collect::<Vec<_>>();
    assert_eq!(
        bits(&mut lean.edge_lengths_in(&domain, q)),
        bits(&mut expected.distances().iter().copied())
    );
    // every stored distance is the minimum-image one, below r
    let g = net.graph();
    for i in 0..q.len() {
        for (e, &j) in g.edge_range(i).zip(g.neighbours(i)) {
            let d = domain.distance(q[i], q[j as usize]);
            assert_eq!(net.distances()[e].to_bits(), d.to_bits());
            assert!(d < r);
        }
    }
    net
}

fn check_crowded<V: Vector>(seed: u64, n: usize, sides: [f64; 3], r: f64, near: f64) {
    let size = V::from_fn(|k| sides[k]);
    let q: Vec<V> = crowded(seed, n, size, near, 1.5 * r);
    check_against_brute_force(size, &q, r);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn build_in_matches_brute_force_2d(
        seed in any::<u64>(),
        n in 0usize..160,
        sides in prop::array::uniform3(2.0f64..9.0),
        near in 0.0f64..1.0,
    ) {
        check_crowded::<DVec2>(seed, n, sides, 1.0, near);
    }

    #[test]
    fn build_in_matches_brute_force_3d(
        seed in any::<u64>(),
        n in 0usize..160,
        sides in prop::array::uniform3(2.0f64..7.0),
        near in 0.0f64..1.0,
    ) {
        check_crowded::<DVec3>(seed, n, sides, 1.0, near);
    }

    /// Sides below 2r too: each pair is still joined once, by its minimum image.
    #[test]
    fn any_sides_match_brute_force(
        seed in any::<u64>(),
        n in 0usize..60,
        sides in prop::array::uniform3(0.3f64..5.0),
        r in 0.1f64..3.0,
    ) {
        check_crowded::<DVec2>(seed, n, sides, r, 0.5);
        check_crowded::<DVec3>(seed, n, sides, r, 0.5);
    }
}

fn check_exact_sides<V: Vector>() {
    // A lattice of spacing r/2 puts agents on the cell faces and at distance exactly r (not an
    // edge). Sides 2r: one cell per axis (the padded cell is a little wider than r); sides 2.5r:
    // two cells per axis, whose −1 and +1 neighbours coincide.
    let r = 1.0;
    for per_side in [4_usize, 5] {
        let size = V::from_fn(|_| per_side as f64 * 0.5);
        let q: Vec<V> = (0..per_side.pow(V::DIM as u32))
            .map(|mut k| {
                V::from_fn(|_| {
                    let c = k % per_side;
                    k /= per_side;
                    c as f64 * 0.5
                })
            })
            .collect();
        let net = check_against_brute_force(size, &q, r);
        // at 0.5 along one axis: 2 per axis (one across the wrap); the plane diagonals √0.5 and
        // in 3D the cube diagonals √0.75 are in; distance r is out
        let per_axis = 2 * V::DIM;
        let diagonals = if V::DIM == 2 { 4 } else { 12 };
        let tri = if V::DIM == 3 { 8 } else { 0 };
        let g = net.graph();
        for i in 0..q.len() {
            assert_eq!(g.degree(i), per_axis + diagonals + tri, "agent {i}");
            let mut list = g.neighbours(i).to_vec();
            list.dedup();
            assert_eq!(list.len(), g.degree(i), "no duplicate edges");
        }
        // a slightly larger range takes the agents at r along an axis: the antipode once
        // (sides 2r), or both sides (sides 2.5r)
        let net = check_against_brute_force(size, &q, r * 1.000_001);
        let at_r = if per_side == 4 { V::DIM } else { 2 * V::DIM };
        assert_eq!(net.graph().degree(0), per_axis + diagonals + tri + at_r);
    }
}

#[test]
fn sides_of_exactly_two_ranges_2d() {
    check_exact_sides::<DVec2>();
}

#[test]
fn sides_of_exactly_two_ranges_3d() {
    check_exact_sides::<DVec3>();
}

fn check_open_is_build<V: Vector>() {
    for (seed, n, r) in [(1, 500, 0.2), (2, 50, 3.0), (3, 1, 1.0), (4, 0, 1.0)] {
        let mut q: Vec<V> = cloud(seed, n, 2.0, -1.0);
        if n > 10 {
            q[7] = V::from_fn(|_| f64::NAN);
        }
        let mut expected = ProximityNet::new();
        NeighbourSearch::new().build(&q, r, &mut expected);
        let net = searched_in(&Domain::Open, &q, r);
        assert_eq!(net, expected);
        assert_identical(&net, &expected);
        assert_eq!(ProximityNet::brute_force_in(&Domain::Open, &q, r), expected);
    }
}

#[test]
fn open_domain_is_build_bit_for_bit_2d() {
    check_open_is_build::<DVec2>();
}

#[test]
fn open_domain_is_build_bit_for_bit_3d() {
    check_open_is_build::<DVec3>();
}

fn check_large_and_degenerate<V: Vector>() {
    // many agents, with a large box and a long thin one
    for (sides, n, r) in [
        ([40.0, 30.0, 20.0], 4000, 1.1),
        ([100.0, 2.5, 2.5], 1500, 1.2),
    ] {
        check_crowded::<V>(9, n, sides, r, 0.3);
    }
    // few agents in a big box: the cells are merged, and the pair across the corner is found
    let size = V::from_fn(|_| 1000.0);
    let q = [
        V::from_fn(|_| 0.1),
        V::from_fn(|_| 999.95),
        V::from_fn(|_| 500.0),
    ];
    let net = check_against_brute_force(size, &q, 1.0);
    assert_eq!(net.graph().neighbours(0), &[1]);
    // non-finite agents have no neighbours; non-positive ranges give no edges
    let mut q: Vec<V> = crowded(3, 100, V::from_fn(|_| 5.0), 0.5, 1.0);
    q[4] = V::from_fn(|_| f64::NAN);
    q[9] = V::from_fn(|k| if k == 0 { f64::INFINITY } else { 1.0 });
    let net = check_against_brute_force(V::from_fn(|_| 5.0), &q, 1.0);
    assert_eq!(net.graph().degree(4), 0);
    assert_eq!(net.graph().degree(9), 0);
    for r in [0.0, -1.0, f64::NAN] {
        let net = check_against_brute_force(V::from_fn(|_| 5.0), &q, r);
        assert_eq!(net.graph().directed_edge_count(), 0);
    }
}

#[test]
fn large_thin_and_degenerate_boxes_2d() {
    check_large_and_degenerate::<DVec2>();
}

#[test]
fn large_thin_and_degenerate_boxes_3d() {
    check_large_and_degenerate::<DVec3>();
}

/// A net with a numbering lists storage indices in ascending original index, as `build` does.
#[test]
fn numbering_is_kept_on_a_torus() {
    let size = DVec2::new(12.0, 9.0);
    let domain = Domain::Periodic { size };
    let q: Vec<DVec2> = crowded(21, 600, size, 0.4, 1.5);
    let original = ProximityNet::brute_force_in(&domain, &q, 1.0);
    let order: Vec<u32> = (0..600u32).rev().collect();
    let stored: Vec<DVec2> = order.iter().map(|&k| q[k as usize]).collect();
    let mut net = ProximityNet::new();
    net.permute(&order);
    NeighbourSearch::new().build_in(&domain, &stored, 1.0, &mut net);
    for k in 0..600 {
        let s = net.numbering().stored(k);
        let listed: Vec<usize> = net
            .graph()
            .neighbours(s)
            .iter()
            .map(|&t| net.numbering().original(t as usize))
            .collect();
        let expected: Vec<usize> = original
            .graph()
            .neighbours(k)
            .iter()
            .map(|&j| j as usize)
            .collect();
        assert_eq!(listed, expected, "agent {k}");
    }
}

/// min over j ≠ i of the domain distance, by brute force (+∞ without another finite agent).
fn brute_nearest<V: Vector>(domain: &Domain<V>, q: &[V]) -> Vec<f64> {
    (0..q.len())
        .map(|i| {
            (0..q.len())
                .filter(|&j| j != i && q[i].is_finite() && q[j].is_finite())
                .map(|j| domain.distance(q[i], q[j]))
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

fn assert_nearest<V: Vector>(domain: &Domain<V>, q: &[V]) {
    let mut d = Vec::new();
    NeighbourSearch::new().nearest_distances_in(domain, q, &mut d);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&d), bits(&brute_nearest(domain, q)), "{d:?}");
}

fn check_nearest<V: Vector>(seed: u64, n: usize, sides: [f64; 3], near: f64) {
    let size = V::from_fn(|k| sides[k]);
    let mut q: Vec<V> = crowded(seed, n, size, near, 0.5);
    assert_nearest(&Domain::Periodic { size }, &q);
    assert_nearest(&Domain::Open, &q);
    if n > 3 {
        q[2] = V::from_fn(|_| f64::NAN);
        assert_nearest(&Domain::Periodic { size }, &q);
        assert_nearest(&Domain::Open, &q);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn nearest_distances_match_brute_force(
        seed in any::<u64>(),
        n in 0usize..80,
        sides in prop::array::uniform3(0.5f64..50.0),
        near in 0.0f64..1.0,
    ) {
        check_nearest::<DVec2>(seed, n, sides, near);
        check_nearest::<DVec3>(seed, n, sides, near);
    }
}

#[test]
fn nearest_distances_of_clusters_and_loners() {
    // a dense cluster and a few agents far from everything: several passes of growing reach
    let size = DVec3::new(1000.0, 800.0, 600.0);
    let mut q: Vec<DVec3> = cloud(5, 2000, 1.0, 3.0);
    q.extend([
        DVec3::new(500.0, 400.0, 300.0),
        DVec3::new(999.0, 799.0, 599.0),
    ]);
    assert_nearest(&Domain::Periodic { size }, &q);
    assert_nearest(&Domain::Open, &q);
    // coincident agents
    assert_nearest(&Domain::Periodic { size }, &[DVec3::ONE; 3]);
    assert_nearest(&Domain::Open, &[DVec2::ONE; 2]);
    assert_nearest::<DVec2>(&Domain::Open, &[]);
    assert_nearest(&Domain::Open, &[DVec2::ONE]);
}

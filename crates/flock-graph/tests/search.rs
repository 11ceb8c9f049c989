//! The cell-grid neighbour search against the brute-force net and an independent k-d tree.

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::Vector;
use glam::{DVec2, DVec3};
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use proptest::prelude::*;

use crate::common::{assert_identical, assert_search_matches_brute_force, cloud, searched};

/// Lattice points k · spacing + offset, k ∈ 0..side per axis.
fn lattice<V: Vector>(side: usize, spacing: f64, offset: f64) -> Vec<V> {
    let count = side.pow(V::DIM as u32);
    (0..count)
        .map(|mut k| {
            V::from_fn(|_| {
                let c = k % side;
                k /= side;
                offset + c as f64 * spacing
            })
        })
        .collect()
}

fn check_random_clouds<V: Vector>() {
    for (seed, n, r) in [
        (1, 300, 0.3),
        (2, 1000, 0.1),
        (3, 2500, 0.05),
        (4, 200, 2.5),
        (5, 50, 0.0001),
    ] {
        let q: Vec<V> = cloud(seed, n, 1.0, 0.0);
        let net = assert_search_matches_brute_force(&q, r);
        assert_eq!(net.graph().len(), n);
        assert_eq!(net.range(), r);
    }
    // Dense enough that the search really finds edges.
    let q: Vec<V> = cloud(6, 2000, 1.0, 0.0);
    assert!(
        assert_search_matches_brute_force(&q, 0.15)
            .graph()
            .undirected_edge_count()
            > 2000
    );
}

#[test]
fn random_clouds_match_brute_force_2d() {
    check_random_clouds::<DVec2>();
}

#[test]
fn random_clouds_match_brute_force_3d() {
    check_random_clouds::<DVec3>();
}

fn check_lattice_at_exact_range<V: Vector>() {
    // Integer spacing equal to the range: exactly at distance r, so not neighbours (strict <).
    for (spacing, offset) in [(1.0, 0.0), (0.25, -3.0), (2.0, 1024.0)] {
        let q: Vec<V> = lattice(7, spacing, offset);
        let net = assert_search_matches_brute_force(&q, spacing);
        assert_eq!(net.graph().directed_edge_count(), 0, "spacing {spacing}");
        // Slightly beyond the spacing the axis neighbours appear, and only they (√2 · spacing > r).
        let net = assert_search_matches_brute_force(&q, spacing * 1.000_001);
        let axis_edges = V::DIM * 6 * 7usize.pow(V::DIM as u32 - 1);
        assert_eq!(net.graph().undirected_edge_count(), axis_edges);
        assert!(net.distances().iter().all(|&d| d == spacing));
    }
    // A spacing that is not a binary fraction: rounding decides, both paths must agree.
    for offset in [0.0, -7.3, 1e6 + 0.3] {
        let q: Vec<V> = lattice(6, 0.1, offset);
        assert_search_matches_brute_force(&q, 0.1);
    }
}

#[test]
fn lattice_at_exact_range_2d() {
    check_lattice_at_exact_range::<DVec2>();
}

#[test]
fn lattice_at_exact_range_3d() {
    check_lattice_at_exact_range::<DVec3>();
}

fn check_duplicates<V: Vector>() {
    let mut q: Vec<V> = cloud(11, 200, 5.0, 0.0);
    let copies: Vec<V> = q.iter().step_by(3).copied().collect();
    q.extend(copies);
    q.push(q[0]);
    let net = assert_search_matches_brute_force(&q, 0.01);
    // Agent 0 has two copies: 200 and the last one.
    let last = (q.len() - 1) as u32;
    assert!(net.graph().neighbours(0).starts_with(&[200]));
    assert!(net.graph().neighbours(0).ends_with(&[last]));
    let g = net.graph();
    for i in 0..q.len() {
        for (e, &j) in g.edge_range(i).zip(g.neighbours(i)) {
            if q[j as usize] == q[i] {
                assert_eq!(net.distances()[e], 0.0);
            }
        }
    }
    // Every copy is a neighbour of its original.
    for (k, i) in (0..200).step_by(3).enumerate() {
        assert!(g.neighbours(i).contains(&((200 + k) as u32)));
    }
}

#[test]
fn duplicated_points_are_neighbours_2d() {
    check_duplicates::<DVec2>();
}

#[test]
fn duplicated_points_are_neighbours_3d() {
    check_duplicates::<DVec3>();
}

fn check_far_from_origin<V: Vector>() {
    for offset in [-1e6, 1e6, 1e9, -3.7e12] {
        let q: Vec<V> = cloud(21, 800, 1.0, offset);
        let net = assert_search_matches_brute_force(&q, 0.2);
        assert!(net.graph().directed_edge_count() > 0, "offset {offset}");
        // Pairs placed right at the range: their computed distances straddle r.
        let r = 0.5;
        let q: Vec<V> = (0..400)
            .map(|k| V::from_fn(|axis| offset + (k / 20 + axis * (k % 20)) as f64 * r))
            .collect();
        assert_search_matches_brute_force(&q, r);
    }
}

#[test]
fn negative_and_large_coordinates_2d() {
    check_far_from_origin::<DVec2>();
}

#[test]
fn negative_and_large_coordinates_3d() {
    check_far_from_origin::<DVec3>();
}

fn check_trivial_inputs<V: Vector>() {
    let net = assert_search_matches_brute_force::<V>(&[], 1.0);
    assert!(net.graph().is_empty());
    assert_eq!(net.graph().offsets(), &[0]);
    let net = assert_search_matches_brute_force(&[V::ZERO], 1.0);
    assert_eq!(net.graph().len(), 1);
    assert_eq!(net.graph().directed_edge_count(), 0);
    // Non-positive and NaN ranges: no edges, even between coincident agents.
    for r in [0.0, -1.0, f64::NAN] {
        let net = assert_search_matches_brute_force(&[V::ZERO, V::ZERO], r);
        assert_eq!(net.graph().directed_edge_count(), 0);
    }
    // An infinite range joins every pair.
    let q: Vec<V> = cloud(31, 40, 1e3, 0.0);
    let net = assert_search_matches_brute_force(&q, f64::INFINITY);
    assert_eq!(net.graph().undirected_edge_count(), 40 * 39 / 2);
}

#[test]
fn empty_single_and_degenerate_ranges_2d() {
    check_trivial_inputs::<DVec2>();
}

#[test]
fn empty_single_and_degenerate_ranges_3d() {
    check_trivial_inputs::<DVec3>();
}

fn check_spread_out<V: Vector>() {
    // Small clusters of 5 agents scattered over 1e9: a grid of side r would need ~1e18 cells.
    let centres: Vec<V> = cloud(41, 100, 1e9, 0.0);
    let jitter: Vec<V> = cloud(42, 500, 0.5, 0.0);
    let q: Vec<V> = jitter
        .iter()
        .enumerate()
        .map(|(k, &d)| centres[k % 100] + d)
        .collect();
    let net = assert_search_matches_brute_force(&q, 1.0);
    assert!(net.graph().undirected_edge_count() >= 500);
    // A thin line of agents spread far apart.
    let line: Vec<V> = (0..300)
        .map(|k| V::from_fn(|axis| if axis == 0 { (k * k) as f64 } else { 0.0 }))
        .collect();
    let net = assert_search_matches_brute_force(&line, 3.5);
    assert_eq!(net.graph().neighbours(1), &[0, 2]);
}

#[test]
fn spread_out_points_2d() {
    check_spread_out::<DVec2>();
}

#[test]
fn spread_out_points_3d() {
    check_spread_out::<DVec3>();
}

fn check_non_finite<V: Vector>() {
    let mut q: Vec<V> = cloud(51, 100, 1.0, 0.0);
    q[3] = V::from_fn(|_| f64::NAN);
    q[10] = V::from_fn(|axis| if axis == 0 { f64::INFINITY } else { 0.0 });
    q[20] = V::from_fn(|axis| {
        if axis == 1 {
            f64::NEG_INFINITY
        } else {
            f64::NAN
        }
    });
    q.push(q[3]);
    let net = assert_search_matches_brute_force(&q, 0.5);
    for i in [3, 10, 20, 100] {
        assert!(net.graph().neighbours(i).is_empty(), "agent {i}");
    }
    assert!(net.graph().directed_edge_count() > 0);
    let all_nan = vec![V::from_fn(|_| f64::NAN); 5];
    assert_eq!(
        assert_search_matches_brute_force(&all_nan, 1.0)
            .graph()
            .directed_edge_count(),
        0
    );
}

#[test]
fn nan_and_infinite_agents_have_no_neighbours_2d() {
    check_non_finite::<DVec2>();
}

#[test]
fn nan_and_infinite_agents_have_no_neighbours_3d() {
    check_non_finite::<DVec3>();
}

/// Neighbour sets from kiddo's k-d tree (strict `< r` radius query), ascending.
fn kiddo_neighbours<V: Vector, const K: usize>(positions: &[V], r: f64) -> Vec<Vec<u32>> {
    assert_eq!(K, V::DIM);
    let points: Vec<[f64; K]> = positions
        .iter()
        .map(|&q| core::array::from_fn(|k| q.coord(k)))
        .collect();
    let tree: ImmutableKdTree<f64, K> = ImmutableKdTree::new_from_slice(&points).unwrap();
    points
        .iter()
        .enumerate()
        .map(|(i, point)| {
            let mut found: Vec<u32> = tree
                .query(point)
                .within::<SquaredEuclidean<f64>>(r * r)
                .exclusive_boundaries()
                .execute()
                .into_iter()
                .map(|hit| hit.item)
                .filter(|&j| j as usize != i)
                .collect();
            found.sort_unstable();
            found
        })
        .collect()
}

fn check_against_kiddo<V: Vector, const K: usize>() {
    for (seed, n, r) in [(61, 3000, 0.15), (62, 1500, 0.3)] {
        let q: Vec<V> = cloud(seed, n, 1.0, 0.0);
        let net = searched(&q, r);
        let oracle = kiddo_neighbours::<V, K>(&q, r);
        let mut edges = 0;
        for (i, expected) in oracle.iter().enumerate() {
            assert_eq!(net.graph().neighbours(i), expected.as_slice(), "agent {i}");
            edges += expected.len();
        }
        assert!(
            edges > n,
            "too few edges ({edges}) to be a meaningful check"
        );
    }
}

#[test]
fn agrees_with_kiddo_2d() {
    check_against_kiddo::<DVec2, 2>();
}

#[test]
fn agrees_with_kiddo_3d() {
    check_against_kiddo::<DVec3, 3>();
}

fn check_reuse<V: Vector>() {
    let mut search = NeighbourSearch::new();
    let mut net = ProximityNet::new();
    for (seed, n, r) in [
        (71, 3000, 0.05),
        (72, 10, 1.0),
        (73, 0, 1.0),
        (74, 2500, 0.1),
        (75, 1, 0.5),
        (76, 400, 0.3),
    ] {
        let q: Vec<V> = cloud(seed, n, 1.0, 0.0);
        search.build(&q, r, &mut net);
        assert_identical(&net, &searched(&q, r));
        assert_identical(&net, &ProximityNet::brute_force(&q, r));
    }
}

#[test]
fn reused_search_and_net_equal_fresh_ones_2d() {
    check_reuse::<DVec2>();
}

#[test]
fn reused_search_and_net_equal_fresh_ones_3d() {
    check_reuse::<DVec3>();
}

/// A cloud from proptest's raw coordinates; `snap` puts them on a grid of step 0.25 so that many
/// pairs lie exactly at the range.
fn from_raw<V: Vector>(raw: &[[f64; 3]], snap: bool) -> Vec<V> {
    raw.iter()
        .map(|c| {
            V::from_fn(|k| {
                if snap {
                    (c[k] * 4.0).round() / 4.0
                } else {
                    c[k]
                }
            })
        })
        .collect()
}

fn raw_cloud() -> impl Strategy<Value = Vec<[f64; 3]>> {
    prop::collection::vec(prop::array::uniform3(-4.0..4.0f64), 0..120)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn search_equals_brute_force_2d(raw in raw_cloud(), r in 0.0..3.0f64, snap in any::<bool>()) {
        let r = if snap { (r * 4.0).round() / 4.0 } else { r };
        assert_search_matches_brute_force(&from_raw::<DVec2>(&raw, snap), r);
    }

    #[test]
    fn search_equals_brute_force_3d(raw in raw_cloud(), r in 0.0..3.0f64, snap in any::<bool>()) {
        let r = if snap { (r * 4.0).round() / 4.0 } else { r };
        assert_search_matches_brute_force(&from_raw::<DVec3>(&raw, snap), r);
    }

    #[test]
    fn search_equals_brute_force_far_away(raw in raw_cloud(), r in 0.01..3.0f64, offset in -1e9..1e9f64) {
        let q: Vec<DVec3> = from_raw::<DVec3>(&raw, false).into_iter().map(|p| p + DVec3::splat(offset)).collect();
        assert_search_matches_brute_force(&q, r);
    }
}

/// `x` moved by `steps` representable values (towards +∞ for positive `steps`).
fn nudge(mut x: f64, steps: i32) -> f64 {
    for _ in 0..steps.unsigned_abs() {
        let away_from_zero = (steps > 0) == (x > 0.0);
        let bits = x.to_bits();
        x = f64::from_bits(if away_from_zero { bits + 1 } else { bits - 1 });
    }
    x
}

/// Regression test for rounding at cell boundaries: pairs closer than r (as the predicate
/// computes it) whose cell coordinates, computed with a cell side of exactly r from a grid origin
/// far away, differ by 2. Without padding the cell side, the search misses them.
fn check_cell_boundary_rounding<V: Vector>() {
    let (origin, r) = (-1000.0, 0.7);
    let naive_cell = |x: f64| ((x - origin) / r).floor();
    let on_axis = |x: f64| V::from_fn(|k| if k == 0 { x } else { 0.0 });
    let mut q = vec![on_axis(origin)];
    let mut critical = 0;
    for k in 1..3000 {
        'pair: for m in -3..=3 {
            let a = nudge(origin + k as f64 * r, m);
            for mb in -3..=3 {
                let b = nudge(a + r, mb);
                if (b - a) * (b - a) < r * r && naive_cell(b) - naive_cell(a) >= 2.0 {
                    q.extend([on_axis(a), on_axis(b)]);
                    critical += 1;
                    break 'pair;
                }
            }
        }
    }
    assert!(critical > 100, "only {critical} critical pairs");
    let net = assert_search_matches_brute_force(&q, r);
    for pair in 0..critical {
        let (a, b) = (1 + 2 * pair, 2 + 2 * pair);
        assert!(
            net.graph().neighbours(a).contains(&(b as u32)),
            "pair {pair} missed"
        );
    }
}

#[test]
fn cell_boundary_rounding_far_from_the_grid_origin_2d() {
    check_cell_boundary_rounding::<DVec2>();
}

#[test]
fn cell_boundary_rounding_far_from_the_grid_origin_3d() {
    check_cell_boundary_rounding::<DVec3>();
}

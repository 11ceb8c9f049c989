//! The nearest-pair distance against the brute-force minimum.

use flock_graph::{NeighbourSearch, nearest_pair_distance};
use flock_math::Vector;
use glam::{DVec2, DVec3};

use crate::common::cloud;

/// min over all pairs of finite agents of ‖q_j − q_i‖, by brute force.
fn brute_force_min<V: Vector>(positions: &[V]) -> Option<f64> {
    let finite: Vec<V> = positions
        .iter()
        .copied()
        .filter(|q| q.is_finite())
        .collect();
    let mut best: Option<f64> = None;
    for (i, &a) in finite.iter().enumerate() {
        for &b in &finite[i + 1..] {
            let d = (b - a).length();
            best = Some(best.map_or(d, |m: f64| m.min(d)));
        }
    }
    best
}

fn assert_exact<V: Vector>(positions: &[V]) -> Option<f64> {
    let expected = brute_force_min(positions);
    let actual = nearest_pair_distance(positions);
    assert_eq!(
        actual.map(f64::to_bits),
        expected.map(f64::to_bits),
        "{actual:?} vs {expected:?}"
    );
    actual
}

fn check<V: Vector>() {
    assert_eq!(assert_exact::<V>(&[]), None);
    assert_eq!(assert_exact(&[V::ZERO]), None);
    assert_eq!(assert_exact(&[V::ZERO, V::ZERO]), Some(0.0));
    for (seed, n, scale, offset) in [
        (1, 2, 1.0, 0.0),
        (2, 300, 1.0, 0.0),
        (3, 2000, 10.0, -5.0),
        (4, 500, 1.0, 1e6),
    ] {
        let q: Vec<V> = cloud(seed, n, scale, offset);
        assert!(assert_exact(&q).unwrap() > 0.0);
    }
    // Clusters scattered far apart, and one very close pair among spread agents.
    let centres: Vec<V> = cloud(5, 50, 1e8, 0.0);
    let jitter: Vec<V> = cloud(6, 400, 1.0, 0.0);
    let clustered: Vec<V> = jitter
        .iter()
        .enumerate()
        .map(|(k, &d)| centres[k % 50] + d)
        .collect();
    assert_exact(&clustered);
    let mut spread: Vec<V> = cloud(7, 1000, 1e3, 0.0);
    spread[700] = spread[123] + V::from_fn(|k| if k == 0 { 1e-9 } else { 0.0 });
    assert!(assert_exact(&spread).unwrap() < 2e-9);
    // A line whose consecutive agents are far apart but whose closest pair is not consecutive.
    let line: Vec<V> = [0.0, 100.0, 0.5, 200.0, 300.25, 400.0]
        .iter()
        .map(|&x| V::from_fn(|k| if k == 0 { x } else { 0.0 }))
        .collect();
    assert_eq!(assert_exact(&line), Some(0.5));
    // Duplicates give 0; non-finite agents are ignored.
    let mut q: Vec<V> = cloud(8, 200, 1.0, 0.0);
    q.push(q[17]);
    assert_eq!(assert_exact(&q), Some(0.0));
    let q = [
        V::from_fn(|_| f64::NAN),
        V::ZERO,
        V::from_fn(|_| f64::INFINITY),
        V::from_fn(|_| 3.0),
    ];
    assert_eq!(
        nearest_pair_distance(&q),
        Some((9.0 * V::DIM as f64).sqrt())
    );
    assert_eq!(nearest_pair_distance(&q[..3]), None);
}

#[test]
fn nearest_pair_distance_is_exact_2d() {
    check::<DVec2>();
}

#[test]
fn nearest_pair_distance_is_exact_3d() {
    check::<DVec3>();
}

#[test]
fn reused_search_gives_the_same_minimum() {
    let mut search = NeighbourSearch::new();
    for (seed, n) in [(11, 1000), (12, 3), (13, 400)] {
        let q: Vec<DVec3> = cloud(seed, n, 1.0, 0.0);
        assert_eq!(search.nearest_pair_distance(&q), brute_force_min(&q));
    }
}

//! Tests of the flocking metrics against hand-computed states and the definitions of TAC 2006 § VIII.

use super::*;
use crate::heading::{milling, polarisation};
use approx::assert_relative_eq;
use flock_graph::Graph;
use glam::{DVec2, DVec3};

/// A triangular α-lattice patch in the plane (spacing d), lifted to V.
fn triangular_lattice<V: Vector>(rows: usize, cols: usize, d: f64) -> Vec<V> {
    let mut points = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            let x = d * (c as f64 + 0.5 * (r % 2) as f64);
            let y = d * r as f64 * 3f64.sqrt() / 2.0;
            points.push(V::from_fn(|k| [x, y, 0.0][k]));
        }
    }
    points
}

fn lattice_metrics<V: Vector>() {
    let d = 7.0;
    let q: Vec<V> = triangular_lattice(5, 6, d);
    let p = vec![V::from_fn(|k| k as f64 + 1.0); q.len()];
    let net = ProximityNet::brute_force(&q, 1.2 * d);
    let m = FlockMetrics::measure(
        &q,
        &p,
        &net,
        &MetricParams {
            d,
            collision_distance: 0.5 * d,
        },
    );
    assert_eq!(m.connectivity, 1.0);
    assert_eq!(m.giant_component, 1.0);
    assert_eq!(m.components, 1);
    assert_relative_eq!(m.deviation_energy, 0.0, epsilon = 1e-28);
    assert_eq!(m.velocity_mismatch, 0.0);
    assert_relative_eq!(m.min_distance, d, epsilon = 1e-12);
    assert_eq!(m.collisions, 0);
}

#[test]
fn alpha_lattice_is_a_perfect_flock_2d() {
    lattice_metrics::<DVec2>();
}

#[test]
fn alpha_lattice_is_a_perfect_flock_3d() {
    lattice_metrics::<DVec3>();
}

#[test]
fn connectivity_of_the_papers_examples() {
    // TAC slides: populations 1,1,1,1,96 → C = 95/99, C* = 0.96; 5 × 20 → C = 95/99, C* = 0.2
    let chain = |sizes: &[usize]| {
        let mut edges = Vec::new();
        let mut start = 0;
        for &s in sizes {
            edges.extend((start..start + s - 1).map(|i| (i, i + 1)));
            start += s;
        }
        Components::of(&Graph::from_edges(start, &edges).expect("valid edges"))
    };
    let skewed = chain(&[1, 1, 1, 1, 96]);
    assert_relative_eq!(relative_connectivity(&skewed), 95.0 / 99.0);
    assert_relative_eq!(skewed.giant_share(), 0.96);
    let even = chain(&[20; 5]);
    assert_relative_eq!(relative_connectivity(&even), 95.0 / 99.0);
    assert_relative_eq!(even.giant_share(), 0.2);
}

#[test]
fn deviation_energy_of_a_stretched_pair() {
    // two agents 8 apart with d = 7: E = (1/(2 + 1)) · 2 · 1² = 2/3, Ẽ = 2/(3 · 49)
    let q = [DVec2::ZERO, DVec2::new(8.0, 0.0)];
    let net = ProximityNet::brute_force(&q, 8.4);
    assert_relative_eq!(
        deviation_energy(&q, &net, 7.0),
        2.0 / 147.0,
        epsilon = 1e-15
    );
    assert_eq!(collisions(&q, &net, 8.1), 1);
    assert_eq!(collisions(&q, &net, 8.0), 0);
}

#[test]
fn velocity_mismatch_has_its_half() {
    // p = ±v: K = ½ (‖v‖² + ‖v‖²) = ‖v‖², K̃ = ‖v‖²/2
    let p = [DVec3::new(1.0, 2.0, 2.0), DVec3::new(-1.0, -2.0, -2.0)];
    assert_relative_eq!(velocity_mismatch(&p), 4.5);
}

#[test]
fn rigid_components_have_no_component_mismatch() {
    let graph = Graph::from_edges(4, &[(0, 1), (2, 3)]).expect("valid edges");
    let components = Components::of(&graph);
    let p = [DVec2::X, DVec2::X, DVec2::Y, DVec2::Y];
    assert_eq!(
        component_velocity_mismatch(&p, &components, &Numbering::identity()),
        0.0
    );
    assert!(velocity_mismatch(&p) > 0.1);
}

#[test]
fn cohesion_radius_and_min_distance_without_edges() {
    let q = [
        DVec2::new(-10.0, 0.0),
        DVec2::new(10.0, 0.0),
        DVec2::new(0.0, 30.0),
    ];
    let net = ProximityNet::brute_force(&q, 8.4);
    assert_relative_eq!(cohesion_radius(&q), 20.0);
    assert_relative_eq!(min_distance(&q, &net), 20.0);
    assert_eq!(
        min_distance::<DVec2>(&[], &ProximityNet::new()),
        f64::INFINITY
    );
}

#[test]
fn measure_is_the_same_with_or_without_stored_distances() {
    let q: Vec<DVec2> = (0..300)
        .map(|k| {
            let t = f64::from(k);
            DVec2::new((t * 1.7).sin() * 30.0, (t * 0.37).cos() * 30.0 + 0.1 * t)
        })
        .collect();
    let p: Vec<DVec2> = q.iter().map(|&x| DVec2::new(x.y, -x.x) * 0.01).collect();
    let params = MetricParams {
        d: 7.0,
        collision_distance: 2.0,
    };
    let full = ProximityNet::brute_force(&q, 8.4);
    let mut lean = ProximityNet::without_distances();
    flock_graph::NeighbourSearch::new().build(&q, 8.4, &mut lean);
    let (a, b) = (
        FlockMetrics::measure(&q, &p, &full, &params),
        FlockMetrics::measure(&q, &p, &lean, &params),
    );
    let bits = |m: &FlockMetrics| {
        [
            m.deviation_energy.to_bits(),
            m.min_distance.to_bits(),
            m.collisions as u64,
        ]
    };
    assert_eq!(bits(&a), bits(&b));
    assert!(a.collisions > 0, "the test wants colliding pairs");
    assert_eq!(
        a.deviation_energy.to_bits(),
        deviation_energy(&q, &full, 7.0).to_bits()
    );
    assert_eq!(a.collisions, collisions(&q, &full, 2.0));
    assert_eq!(a.min_distance.to_bits(), min_distance(&q, &full).to_bits());
    assert_eq!(a.min_distance.to_bits(), min_distance(&q, &lean).to_bits());
}

/// The agents stored in another order, with the net's numbering, give every metric the bits
/// of the agents in original order.
#[test]
fn measure_follows_the_numbering() {
    let q: Vec<DVec3> = (0..500)
        .map(|k| {
            let t = f64::from(k);
            DVec3::new((t * 1.7).sin() * 20.0, (t * 0.37).cos() * 20.0, 0.3 * t)
        })
        .collect();
    let p: Vec<DVec3> = q
        .iter()
        .map(|&x| DVec3::new(x.y, -x.x, 0.3) * 0.01)
        .collect();
    let params = MetricParams {
        d: 7.0,
        collision_distance: 2.0,
    };
    let mut search = flock_graph::NeighbourSearch::new();
    let mut net = ProximityNet::new();
    search.build(&q, 8.4, &mut net);
    let order = search.cell_order(&q, 8.4).to_vec();
    assert!(order.iter().enumerate().any(|(s, &k)| k as usize != s));
    let stored = |x: &[DVec3]| -> Vec<DVec3> { order.iter().map(|&k| x[k as usize]).collect() };
    let (q_s, p_s) = (stored(&q), stored(&p));
    let mut numbered = ProximityNet::without_distances();
    numbered.permute(&order);
    search.build(&q_s, 8.4, &mut numbered);
    let bits = |m: FlockMetrics| {
        let [a, b, c, d, e, f] = m.reals().map(f64::to_bits);
        let [g, h, i, j, k] = m.extras().map(f64::to_bits);
        [a, b, c, d, e, f, g, h, i, j, k]
    };
    let (original, renumbered) = (
        FlockMetrics::measure(&q, &p, &net, &params),
        FlockMetrics::measure(&q_s, &p_s, &numbered, &params),
    );
    assert_eq!(bits(original), bits(renumbered));
    assert_eq!(original.components, renumbered.components);
    assert_eq!(original.collisions, renumbered.collisions);
    assert!(
        original.components > 1 && original.collisions > 0,
        "{original:?}"
    );
    let mismatch = |p: &[DVec3], net: &ProximityNet| {
        component_velocity_mismatch(p, &Components::of(net.graph()), net.numbering()).to_bits()
    };
    assert_eq!(mismatch(&p, &net), mismatch(&p_s, &numbered));
    let back = FlockMetrics::from_reals(original.reals(), original.components, original.collisions);
    assert!(back.polarisation.is_nan() && back.nearest_neighbour_min.is_nan());
    assert_eq!(
        back.with_extras(original.extras()),
        original,
        "from_reals and with_extras invert reals and extras"
    );
}

#[test]
fn edge_metrics_are_the_same_with_or_without_stored_distances() {
    let q = [DVec2::ZERO, DVec2::X, DVec2::new(0.5, 3.0)];
    let full = ProximityNet::brute_force(&q, 3.5);
    let mut lean = ProximityNet::without_distances();
    flock_graph::NeighbourSearch::new().build(&q, 3.5, &mut lean);
    assert_eq!(
        deviation_energy(&q, &lean, 1.0).to_bits(),
        deviation_energy(&q, &full, 1.0).to_bits()
    );
    assert_eq!(collisions(&q, &lean, 1.5), 1);
    assert_eq!(collisions(&q, &full, 1.5), 1);
}

/// A deterministic stream of numbers in [0, 1).
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A flock about `centre` (spread ±`spread` per axis) with velocities turning about it.
fn moving_group<V: Vector>(seed: u64, n: usize, centre: V, spread: f64) -> (Vec<V>, Vec<V>) {
    let mut u = uniform(seed);
    let q: Vec<V> = (0..n)
        .map(|_| centre + V::from_fn(|_| spread * (2.0 * u() - 1.0)))
        .collect();
    let p: Vec<V> = (0..n)
        .map(|_| V::from_fn(|k| if k == 0 { 1.0 } else { 0.0 } + 0.8 * (2.0 * u() - 1.0)))
        .collect();
    (q, p)
}

/// The same flock measured in open space and cut by the faces of a periodic box (its centre
/// near a corner, so on every axis some agents are wrapped to the far side): every metric
/// agrees, so none of them reads a wrapped coordinate as a distance.
fn check_torus_matches_open<V: Vector>() {
    let size = V::from_fn(|k| [60.0, 50.0, 40.0][k]);
    let torus = Domain::Periodic { size };
    let params = MetricParams {
        d: 7.0,
        collision_distance: 2.0,
    };
    // clustered (every agent has a neighbour) and sparse (some have none: the search path)
    for (seed, n, spread) in [(1, 60, 6.0), (2, 40, 14.0), (3, 2, 1.0)] {
        let (q_open, p) = moving_group::<V>(seed, n, V::from_fn(|_| 100.0), spread);
        let corner = V::from_fn(|k| size.coord(k) - 0.7);
        let shift = corner - V::from_fn(|_| 100.0);
        let q_torus: Vec<V> = q_open.iter().map(|&x| torus.wrap(x + shift)).collect();
        assert!(
            q_torus.iter().any(|x| x.coord(0) < 10.0) && q_torus.iter().any(|x| x.coord(0) > 50.0)
                || n < 10
        );
        let open_net = ProximityNet::brute_force(&q_open, 8.4);
        let mut torus_net = ProximityNet::without_distances();
        flock_graph::NeighbourSearch::new().build_in(&torus, &q_torus, 8.4, &mut torus_net);
        let a = FlockMetrics::measure(&q_open, &p, &open_net, &params);
        let b = FlockMetrics::measure_in(&torus, &q_torus, &p, &torus_net, &params);
        assert_eq!(
            (a.components, a.collisions),
            (b.components, b.collisions),
            "seed {seed}"
        );
        // R and the milling are measured from the circular mean, a little off the mean:
        // compare with open space about the same centre, unwrapped
        let centre = torus.centre_of(q_torus.iter().copied());
        let unwrapped = q_open[0] + torus.displacement(q_torus[0], centre);
        let mean = mean_of(q_open.iter().copied());
        assert!(
            (unwrapped - mean).length() < 0.1 * spread,
            "{unwrapped:?} {mean:?}"
        );
        let a = FlockMetrics {
            cohesion_radius: radius_about(&Domain::Open, &q_open, unwrapped),
            milling: milling_about(
                &Domain::Open,
                unwrapped,
                q_open.iter().copied(),
                p.iter().copied(),
            ),
            ..a
        };
        for (x, y) in a
            .reals()
            .into_iter()
            .chain(a.extras())
            .zip(b.reals().into_iter().chain(b.extras()))
        {
            assert_relative_eq!(x, y, epsilon = 1e-9, max_relative = 1e-9);
        }
        if n > 10 {
            assert!(a.milling > 0.01 && a.polarisation > 0.3, "{a:?}");
        }
        // the metrics with the open-space formulas are wrong on the torus: the test can fail
        let naive = FlockMetrics::measure(&q_torus, &p, &torus_net, &params);
        if n > 10 {
            assert!(naive.cohesion_radius > a.cohesion_radius + 5.0);
            assert!((naive.milling - a.milling).abs() > 1e-3);
        }
    }
}

#[test]
fn torus_matches_open_space_2d() {
    check_torus_matches_open::<DVec2>();
}

#[test]
fn torus_matches_open_space_3d() {
    check_torus_matches_open::<DVec3>();
}

/// Open space is `measure`, bit for bit, and `measure` keeps the former definitions.
#[test]
fn open_domain_is_measure_bit_for_bit() {
    let (q, p) = moving_group::<DVec3>(7, 80, DVec3::ZERO, 12.0);
    let net = ProximityNet::brute_force(&q, 8.4);
    let params = MetricParams {
        d: 7.0,
        collision_distance: 2.0,
    };
    let a = FlockMetrics::measure(&q, &p, &net, &params);
    let b = FlockMetrics::measure_in(&Domain::Open, &q, &p, &net, &params);
    let bits = |m: &FlockMetrics| (m.reals().map(f64::to_bits), m.extras().map(f64::to_bits));
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a.cohesion_radius.to_bits(), cohesion_radius(&q).to_bits());
    assert_eq!(a.min_distance.to_bits(), min_distance(&q, &net).to_bits());
    assert_eq!(a.polarisation.to_bits(), polarisation(&p).to_bits());
    assert_eq!(
        a.milling.to_bits(),
        milling(&Domain::Open, &q, &p).to_bits()
    );
}

/// The nearest-neighbour distances against brute force, on the net's path (every agent has a
/// neighbour) and on the search's (loners beyond the range), in open space and on a torus.
fn check_nearest<V: Vector>() {
    let size = V::from_fn(|_| 80.0);
    let params = MetricParams {
        d: 7.0,
        collision_distance: 2.0,
    };
    for domain in [Domain::Open, Domain::Periodic { size }] {
        for (seed, n, spread) in [(11, 50, 8.0), (12, 50, 39.9)] {
            let (q, p) = moving_group::<V>(seed, n, V::from_fn(|_| 40.0), spread);
            let brute: Vec<f64> = (0..n)
                .map(|i| {
                    (0..n)
                        .filter(|&j| j != i)
                        .map(|j| domain.distance(q[i], q[j]))
                        .fold(f64::INFINITY, f64::min)
                })
                .collect();
            let mut net = ProximityNet::new();
            flock_graph::NeighbourSearch::new().build_in(&domain, &q, 8.4, &mut net);
            let isolated = (0..n).any(|i| net.graph().degree(i) == 0);
            assert_eq!(isolated, spread > 10.0, "both paths are tested");
            let m = FlockMetrics::measure_in(&domain, &q, &p, &net, &params);
            let mean = brute.iter().sum::<f64>() / n as f64;
            let least = brute.iter().copied().fold(f64::INFINITY, f64::min);
            assert_relative_eq!(m.nearest_neighbour_mean, mean, max_relative = 1e-12);
            assert_eq!(m.nearest_neighbour_min, least);
            assert_eq!(m.min_distance, least);
            assert_eq!(nearest_neighbour_distances(&domain, &q), brute);
        }
    }
}

#[test]
fn nearest_neighbours_match_brute_force_2d() {
    check_nearest::<DVec2>();
}

#[test]
fn nearest_neighbours_match_brute_force_3d() {
    check_nearest::<DVec3>();
}

#[test]
fn order_parameters_of_known_states() {
    // a mill in 3D: agents on a circle in the plane z = 5 moving tangentially
    let q: Vec<DVec3> = (0..12)
        .map(|k| {
            let a = f64::from(k) * core::f64::consts::TAU / 12.0;
            DVec3::new(a.cos(), a.sin(), 5.0) * 10.0
        })
        .collect();
    let p: Vec<DVec3> = q.iter().map(|x| DVec3::new(-x.y, x.x, 0.0) * 0.3).collect();
    assert!((milling(&Domain::Open, &q, &p) - 1.0).abs() < 1e-12);
    assert!(polarisation(&p) < 1e-12);
    // clockwise in 2D: the absolute value
    let q2: Vec<DVec2> = q.iter().map(|x| x.truncate()).collect();
    let p2: Vec<DVec2> = q2.iter().map(|x| DVec2::new(x.y, -x.x)).collect();
    assert!((milling(&Domain::Open, &q2, &p2) - 1.0).abs() < 1e-12);
    // the same mill on a torus, cut by the faces: still a mill
    let torus = Domain::Periodic {
        size: DVec2::new(30.0, 30.0),
    };
    let wrapped: Vec<DVec2> = q2.iter().map(|&x| torus.wrap(x)).collect();
    assert!((milling(&torus, &wrapped, &p2) - 1.0).abs() < 1e-9);
    assert!(milling(&Domain::Open, &wrapped, &p2) < 0.9);
    // one agent: the polarisation of its heading, no milling, no nearest neighbour
    let one = [DVec2::new(3.0, 4.0)];
    let net = ProximityNet::brute_force(&one, 8.4);
    let params = MetricParams {
        d: 7.0,
        collision_distance: 2.0,
    };
    let m = FlockMetrics::measure(&one, &[DVec2::new(0.0, 2.0)], &net, &params);
    assert_eq!((m.polarisation, m.milling), (1.0, 0.0));
    assert_eq!(
        (
            m.nearest_neighbour_mean,
            m.nearest_neighbour_min,
            m.min_distance
        ),
        (f64::INFINITY, f64::INFINITY, f64::INFINITY)
    );
    // agents at rest count in N
    assert_eq!(
        polarisation(&[DVec3::X, DVec3::ZERO, DVec3::ZERO, DVec3::Y * 2.0]),
        2f64.sqrt() / 4.0
    );
    let none = FlockMetrics::measure::<DVec2>(
        &[],
        &[],
        &ProximityNet::brute_force::<DVec2>(&[], 8.4),
        &params,
    );
    // no agent: every order measure undefined (issue 27), not a flock of zero order
    assert!(none.is_empty_flock());
    assert!(none.polarisation.is_nan() && none.milling.is_nan());
    assert!(none.nearest_neighbour_mean.is_nan());
}

//! The sweep on the torus's cells against the sweep on the proximity net: the same boids in sight,
//! the same updates to round-off (the cells sum in an order of space, the net in original index).

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{Domain, Vector};
use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

use super::birds::Bird;
use super::{Boids, BoidsParams, Sums};
use crate::{Protocol, Swarm};

/// The inputs of one sweep read on the net of the interaction range, as the sweep on the net
/// reads them: each boid's neighbours in the net's (ascending) order.
fn on_the_net<V: Vector>(model: &Boids<V>, t: f64, swarm: &Swarm<V>) -> Vec<V> {
    let mut net = ProximityNet::without_distances();
    let range = model.interaction_range();
    NeighbourSearch::new().build_in(&model.domain, &swarm.positions, range, &mut net);
    let s = model.params.speed;
    let mut q = swarm.positions.clone();
    let mut v: Vec<V> = swarm.velocities.iter().map(|&p| p / s).collect();
    let mut inputs = vec![V::ZERO; q.len()];
    for i in model.activation_order(t, q.len()) {
        let i = i as usize;
        let others = net.graph().neighbours(i).iter();
        let heading = model.turn(q[i], v[i], others.map(|&j| (q[j as usize], v[j as usize])));
        inputs[i] = heading * s;
        v[i] = heading;
        q[i] = model.domain.wrap(q[i] + inputs[i] * model.step);
    }
    inputs
}

/// `n` boids uniform in [0, `spread`) per axis of the box of side `side`, at speed 1, one of them
/// lost (non-finite) when `lost`, swept over 4 steps by the cells and by the net: the same inputs
/// to round-off (an update differs by about f_c r / N ≳ 10⁻³ where one boid in sight is missed or
/// one too many is counted).
fn cells_equal_net<V: Vector>(
    n: usize,
    (side, spread): (f64, f64),
    visual_distance: f64,
    lost: bool,
) {
    let params = BoidsParams {
        visual_distance,
        separation: visual_distance / 3.0,
        ..BoidsParams::default()
    };
    let (h, steps) = (0.5, 4);
    let domain = Domain::Periodic {
        size: V::from_fn(|_| side),
    };
    let model = Boids::new(params, h, 7, domain).expect("valid");
    let mut rng = Pcg64::seed_from_u64(n as u64);
    let positions: Vec<V> = (0..n)
        .map(|_| V::from_fn(|_| rng.random_range(0.0..spread)))
        .collect();
    let velocities = (0..n)
        .map(|_| V::from_fn(|_| rng.random_range(-1.0..1.0)).normalize_or_zero())
        .collect();
    let mut swarm = Swarm::new(positions, velocities);
    if lost {
        swarm.positions[n / 2] = V::from_fn(|_| f64::NAN);
    }
    let net = ProximityNet::without_distances();
    for k in 0..steps {
        let t = f64::from(k) * h;
        let mut inputs = vec![V::ZERO; n];
        model.controls(t, &swarm, &net, &mut inputs);
        let reference = on_the_net(&model, t, &swarm);
        for (i, (a, b)) in inputs.iter().zip(&reference).enumerate() {
            let apart = (*a - *b).length();
            assert!(apart <= 1e-12, "step {k}, boid {i}: {a:?} against {b:?}");
        }
        for (q, &p) in swarm.positions.iter_mut().zip(&inputs) {
            *q = model.domain.wrap(*q + p * h);
        }
        swarm.velocities = inputs;
    }
}

#[test]
fn the_cells_find_who_the_net_finds() {
    // 5 cells a side, in 2D and 3D
    cells_equal_net::<DVec2>(300, (20.0, 20.0), 3.0, false);
    cells_equal_net::<DVec3>(400, (20.0, 20.0), 3.0, false);
    // 2 and 1 cells a side: each cell counted once
    cells_equal_net::<DVec2>(60, (8.0, 8.0), 3.0, false);
    cells_equal_net::<DVec3>(60, (8.0, 8.0), 3.0, false);
    cells_equal_net::<DVec2>(40, (5.0, 5.0), 3.0, false);
    // a lost boid sees no one and is seen by no one
    cells_equal_net::<DVec2>(300, (20.0, 20.0), 3.0, true);
    // a few boids gathered in a corner of a large box: the cells capped at 4 a boid, far wider
    // than the sight
    cells_equal_net::<DVec2>(30, (1000.0, 12.0), 3.0, false);
    cells_equal_net::<DVec3>(30, (1000.0, 6.0), 3.0, false);
    // the workloads' densities: 200 in 100² at sight 5, 400 in 150² at sight 15
    cells_equal_net::<DVec2>(200, (100.0, 100.0), 5.0, false);
    cells_equal_net::<DVec2>(400, (150.0, 150.0), 15.0, false);
    // a flock larger than a core's caches: the sweep reads ahead, the order drawn on a second
    // thread
    cells_equal_net::<DVec2>(20_000, (1000.0, 1000.0), 5.0, false);
}

/// The bits of a sum, NaN counted as one value.
fn bits<V: Vector>(v: V) -> Vec<u64> {
    (0..V::DIM)
        .map(|axis| {
            let x = v.coord(axis);
            if x.is_nan() { u64::MAX } else { x.to_bits() }
        })
        .collect()
}

/// The sums over a run of birds without branches against the same birds counted one by one:
/// the same bits, birds exactly at the visual distance and at the separation and lost (NaN)
/// ones included.
fn sums_without_branches<V: Vector>(seed: u64) {
    let mut rng = Pcg64::seed_from_u64(seed);
    let (sight, apart) = (25.0, 4.0);
    for case in 0..500 {
        // whole coordinates: the offsets below are exact
        let origin = V::from_fn(|_| f64::from(rng.random_range(-50..50)));
        let on_axis =
            |length: f64, axis: usize| V::from_fn(|k| if k == axis { length } else { 0.0 });
        let others: Vec<Bird<V>> = (0..rng.random_range(0..24))
            .map(|k| {
                let q = match k % 6 {
                    // at the visual distance, at the separation (boundaries)
                    0 => origin + on_axis(5.0, k % V::DIM),
                    1 => origin - on_axis(2.0, k % V::DIM),
                    2 if case % 9 == 0 => V::from_fn(|_| f64::NAN),
                    _ => origin + V::from_fn(|_| rng.random_range(-8.0..8.0)),
                };
                let v = V::from_fn(|_| rng.random_range(-1.0..1.0)).normalize_or_zero();
                Bird { q, v }
            })
            .collect();
        let mut fast = Sums::ZERO;
        fast.add_all(&others, origin, sight, apart);
        let mut slow = Sums::ZERO;
        for other in &others {
            slow.add_in_sight(other.q - origin, other.v, sight, apart);
        }
        assert_eq!(fast.count, slow.count, "case {case}");
        for (a, b) in [
            (fast.cohere, slow.cohere),
            (fast.separate, slow.separate),
            (fast.matching, slow.matching),
        ] {
            assert_eq!(bits(a), bits(b), "case {case}: {a:?} against {b:?}");
        }
    }
}

#[test]
fn the_sums_without_branches_have_the_bits_of_the_rule() {
    sums_without_branches::<DVec2>(1);
    sums_without_branches::<DVec3>(2);
}

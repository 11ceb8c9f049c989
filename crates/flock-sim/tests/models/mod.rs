//! The classic models against independent implementations written here (brute force, O(n²), no
//! code of the models shared: only the keyed random streams, so that both draw the same noise),
//! and their theorems or the papers' numbers bracketed from both sides.

use approx::assert_abs_diff_eq;
use flock_math::stream::{Purpose, Streams};
use flock_math::{Domain, Vector};
use flock_protocols::{
    Arena, ArenaShape, Boids, BoidsParams, Couzin, CouzinParams, CuckerSmale, CuckerSmaleParams,
    Protocol, Swarm, Vasarhelyi, VasarhelyiParams, Vicsek, VicsekParams,
};
use flock_sim::{Integrator, Simulation};
use glam::{DVec2, DVec3};

use crate::common::random_swarm;

/// The minimum image of b − a in a box of side `side` per axis (`None`: open space).
fn offset<V: Vector>(a: V, b: V, side: Option<f64>) -> V {
    let d = b - a;
    match side {
        None => d,
        Some(l) => V::from_fn(|k| {
            let x = d.coord(k);
            x - l * (x / l).round()
        }),
    }
}

/// `q` brought into [0, L) per axis.
fn wrapped<V: Vector>(q: V, side: Option<f64>) -> V {
    match side {
        None => q,
        Some(l) => V::from_fn(|k| {
            let y = q.coord(k) - l * (q.coord(k) / l).floor();
            if y >= l { y - l } else { y }
        }),
    }
}

fn domain<V: Vector>(side: Option<f64>) -> Domain<V> {
    side.map_or(Domain::Open, |l| Domain::Periodic {
        size: V::from_fn(|_| l),
    })
}

/// A swarm with a third of the agents within 1 of a face or corner of the box [0, side)^m.
fn near_the_wrap<V: Vector>(n: usize, side: f64, speed: f64, seed: u64) -> Swarm<V> {
    let mut swarm = random_swarm::<V>(n, side / 2.0, speed, seed);
    for (i, q) in swarm.positions.iter_mut().enumerate() {
        let centred = *q + V::from_fn(|_| side / 2.0);
        *q = if i % 3 == 0 {
            // hug the faces: each coordinate within 1 of 0 or of the side
            V::from_fn(|k| {
                let x = centred.coord(k) / side; // in [0, 1)
                if x < 0.5 { x } else { side - 1.0 + x }
            })
        } else {
            centred
        };
    }
    swarm
}

fn max_gap<V: Vector>(a: &[V], b: &[V]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max)
}

/// Runs `model` from `swarm` in the domain of `side` for `steps` steps of `h` beside the
/// brute-force `reference` (step k and state to the next state), then checks that the states
/// agree: positions within `tolerance.0`, velocities within `tolerance.1`.
fn agrees_with_reference<V: Vector, P: Protocol<V>>(
    model: P,
    swarm: Swarm<V>,
    (h, side, steps): (f64, Option<f64>, u64),
    mut reference: impl FnMut(u64, &[V], &[V]) -> (Vec<V>, Vec<V>),
    tolerance: (f64, f64),
) {
    let mut sim = Simulation::new(model, Integrator::SymplecticEuler, swarm.clone(), h)
        .unwrap()
        .with_domain(domain(side))
        .unwrap();
    let (mut q, mut p) = (swarm.positions, swarm.velocities);
    for k in 0..steps {
        sim.step();
        (q, p) = reference(k, &q, &p);
    }
    let state = sim.swarm();
    let (gap_q, gap_p) = (
        max_gap(&state.positions, &q),
        max_gap(&state.velocities, &p),
    );
    assert!(gap_q < tolerance.0, "{side:?}: positions {gap_q}");
    assert!(gap_p < tolerance.1, "{side:?}: velocities {gap_p}");
}

mod boids;
mod couzin;
mod cucker_smale;
mod periodic;
mod vasarhelyi;
mod vicsek;

//! Initial conditions: seeded random clouds and explicit states, as vectors of the scenario's dimension.

use flock_math::Vector;
use flock_protocols::Swarm;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

use crate::scenario::{Cloud, Scenario};

/// The initial swarm of a validated scenario: positions, then velocities, drawn from one PCG64
/// stream seeded with `scenario.seed` (bit-identical across platforms and versions of flocking's
/// dependencies that keep PCG64).
#[must_use]
pub fn initial_swarm<V: Vector>(scenario: &Scenario) -> Swarm<V> {
    let mut rng = Pcg64::seed_from_u64(scenario.seed);
    let n = scenario.agents;
    let positions = sample(&scenario.initial.positions, n, &mut rng);
    let velocities = sample(&scenario.initial.velocities, n, &mut rng);
    Swarm::new(positions, velocities)
}

/// The vector of a validated list of DIM numbers.
#[must_use]
pub fn to_vector<V: Vector>(v: &[f64]) -> V {
    V::from_fn(|k| v[k])
}

fn sample<V: Vector>(cloud: &Cloud, n: usize, rng: &mut Pcg64) -> Vec<V> {
    match cloud {
        Cloud::Zero => vec![V::ZERO; n],
        Cloud::Box { min, max } => (0..n)
            .map(|_| V::from_fn(|k| min[k] + (max[k] - min[k]) * rng.random::<f64>()))
            .collect(),
        Cloud::Ball { centre, radius } => {
            let centre: V = to_vector(centre);
            (0..n)
                .map(|_| {
                    loop {
                        // rejection from the cube [−1, 1]^m: uniform in the unit ball
                        let x = V::from_fn(|_| 2.0 * rng.random::<f64>() - 1.0);
                        if x.length_squared() <= 1.0 {
                            break centre + x * *radius;
                        }
                    }
                })
                .collect()
        }
        Cloud::Gaussian { mean, std } => {
            let mean: V = to_vector(mean);
            (0..n)
                .map(|_| mean + V::from_fn(|_| standard_normal(rng)) * *std)
                .collect()
        }
        Cloud::Explicit(rows) => rows.iter().map(|row| to_vector(row)).collect(),
    }
}

/// A standard normal sample by the Box–Muller transform (one of the pair; simple and reproducible).
fn standard_normal(rng: &mut Pcg64) -> f64 {
    let u1 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (core::f64::consts::TAU * u2).cos()
}

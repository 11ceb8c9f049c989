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
    let positions = sample(&in_box(scenario, &scenario.initial.positions), n, &mut rng);
    let velocities = sample(&in_box(scenario, &scenario.initial.velocities), n, &mut rng);
    Swarm::new(positions, velocities)
}

/// The vector of a validated list of DIM numbers.
#[must_use]
pub fn to_vector<V: Vector>(v: &[f64]) -> V {
    V::from_fn(|k| v[k])
}

fn sample<V: Vector>(cloud: &Cloud, n: usize, rng: &mut Pcg64) -> Vec<V> {
    samples(cloud, n, rng).collect()
}

/// The initial positions of `scenario`, drawn one at a time: the positions of
/// [`initial_swarm`], in order, without holding them (validation checks 10⁸ agents against
/// the obstacles in constant memory).
pub fn initial_positions<V: Vector>(scenario: &Scenario) -> impl Iterator<Item = V> + '_ {
    let mut rng = Pcg64::seed_from_u64(scenario.seed);
    let cloud = in_box(scenario, &scenario.initial.positions);
    (0..scenario.agents).map(move |k| draw(&cloud, k, &mut rng))
}

/// The initial velocities of `scenario`, drawn one at a time as [`initial_positions`] draws the
/// positions: the velocities of [`initial_swarm`], in order (the positions are drawn first, from
/// the same stream, and dropped).
pub fn initial_velocities<V: Vector>(scenario: &Scenario) -> impl Iterator<Item = V> + '_ {
    let mut rng = Pcg64::seed_from_u64(scenario.seed);
    let positions = in_box(scenario, &scenario.initial.positions);
    let velocities = in_box(scenario, &scenario.initial.velocities);
    let n = scenario.agents;
    (0..2 * n).filter_map(move |k| {
        if k < n {
            draw::<V>(&positions, k, &mut rng);
            None
        } else {
            Some(draw(&velocities, k - n, &mut rng))
        }
    })
}

/// `cloud` with [`Cloud::Domain`] as the box [0, L) of the scenario's periodic domain.
fn in_box(scenario: &Scenario, cloud: &Cloud) -> Cloud {
    match (cloud, scenario.box_size()) {
        (Cloud::Domain, Some(size)) => Cloud::Box {
            min: vec![0.0; size.len()],
            max: size,
        },
        _ => cloud.clone(),
    }
}

/// `n` draws of `cloud` from `rng`, in order.
fn samples<'a, V: Vector>(
    cloud: &'a Cloud,
    n: usize,
    rng: &'a mut Pcg64,
) -> impl Iterator<Item = V> + 'a {
    (0..n).map(move |k| draw(cloud, k, rng))
}

/// Agent `k`'s draw of `cloud` (its row of an explicit cloud).
fn draw<V: Vector>(cloud: &Cloud, k: usize, rng: &mut Pcg64) -> V {
    match cloud {
        Cloud::Zero => V::ZERO,
        Cloud::Box { min, max } => V::from_fn(|i| min[i] + (max[i] - min[i]) * rng.random::<f64>()),
        Cloud::Ball { centre, radius } => {
            let centre: V = to_vector(centre);
            loop {
                // rejection from the cube [−1, 1]^m: uniform in the unit ball
                let x = V::from_fn(|_| 2.0 * rng.random::<f64>() - 1.0);
                if x.length_squared() <= 1.0 {
                    break centre + x * *radius;
                }
            }
        }
        Cloud::Gaussian { mean, std } => {
            let mean: V = to_vector(mean);
            mean + V::from_fn(|_| standard_normal(rng)) * *std
        }
        Cloud::Explicit(rows) => to_vector(&rows[k]),
        Cloud::Domain => unreachable!("a validated scenario's Domain cloud is its box (in_box)"),
        Cloud::Headings { speed } => loop {
            // a direction uniform on the sphere: rejection from the cube, then normalised
            let x = V::from_fn(|_| 2.0 * rng.random::<f64>() - 1.0);
            let r2 = x.length_squared();
            if r2 <= 1.0 && r2 > 1e-12 {
                break x * (*speed / r2.sqrt());
            }
        },
    }
}

/// A standard normal sample by the Box–Muller transform (one of the pair; simple and reproducible).
fn standard_normal(rng: &mut Pcg64) -> f64 {
    let u1 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (core::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use super::*;

    /// The streamed positions that validation checks are the swarm's, bit for bit, for every
    /// kind of cloud.
    #[test]
    fn initial_positions_are_the_swarms() {
        fn check<V: Vector + PartialEq + std::fmt::Debug>(scenario: &Scenario) {
            let streamed: Vec<V> = initial_positions(scenario).collect();
            assert_eq!(streamed, initial_swarm::<V>(scenario).positions);
        }
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/");
        let mut scenario =
            Scenario::load(format!("{root}tac2006_fig11_alg2_n100.ron")).expect("a fixture");
        let clouds = [
            Cloud::Zero,
            Cloud::Box {
                min: vec![-1.0, -2.0],
                max: vec![3.0, 4.0],
            },
            Cloud::Ball {
                centre: vec![1.0, 2.0],
                radius: 5.0,
            },
            Cloud::Gaussian {
                mean: vec![0.0, 1.0],
                std: 10.0,
            },
        ];
        for cloud in clouds {
            scenario.initial.positions = cloud;
            check::<DVec2>(&scenario);
        }
        let three =
            Scenario::load(format!("{root}alg3_3d_mixed_obstacles_n100.ron")).expect("a fixture");
        check::<DVec3>(&three);
        scenario.initial.positions = Cloud::Explicit(vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
        scenario.agents = 2;
        check::<DVec2>(&scenario);
    }

    /// The streamed velocities are the swarm's too, after positions of every kind (a ball's
    /// draws are rejected a varying number of times).
    #[test]
    fn initial_velocities_are_the_swarms() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/");
        for fixture in [
            "tac2006_fig11_alg2_n100",
            "couzin2002_torus_n100",
            "vicsek1995_fig2a_n400",
        ] {
            let scenario = Scenario::load(format!("{root}{fixture}.ron")).expect("a fixture");
            let streamed: Vec<DVec3> = match scenario.dim {
                3 => initial_velocities(&scenario).collect(),
                _ => {
                    let plane: Vec<DVec2> = initial_velocities(&scenario).collect();
                    assert_eq!(
                        plane,
                        initial_swarm::<DVec2>(&scenario).velocities,
                        "{fixture}"
                    );
                    continue;
                }
            };
            assert_eq!(
                streamed,
                initial_swarm::<DVec3>(&scenario).velocities,
                "{fixture}"
            );
        }
    }
}

//! Synthetic scenarios of any size, for benchmarks: n agents on a jittered α-lattice at spacing
//! d = 7 (triangular in 2D, face-centred cubic in 3D) with small random velocities, optionally
//! among a grid of ball and box obstacles that no agent touches ([`lattice_swarm`]), and the same
//! agents numbered at random ([`shuffled`]). `flocking bench` and the criterion benches time them.

use flock_math::Vector;
use flock_obstacles::ObstacleSpec;
use flock_protocols::Swarm;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// The lattice distance d of the synthetic scenarios (the papers' value).
pub const D: f64 = 7.0;

/// Seed of the jitter and of the initial velocities.
const SEED: u64 = 2006;

/// The sites of an α-lattice of spacing `spacing` (triangular in 2D, face-centred cubic in 3D),
/// at least `count` of them, in a square (cubic) patch with its lower corner at the origin.
fn lattice<V: Vector>(count: usize, spacing: f64) -> Vec<V> {
    let mut sites = Vec::with_capacity(count + 64);
    if V::DIM == 2 {
        let row = spacing * 3f64.sqrt() / 2.0;
        let cols = ((count as f64 * 2.0 / 3f64.sqrt()).sqrt().ceil() as usize).max(1);
        'rows: for r in 0.. {
            for c in 0..cols {
                if sites.len() >= count {
                    break 'rows;
                }
                let x = spacing * (c as f64 + 0.5 * (r % 2) as f64);
                sites.push(V::from_fn(|k| [x, row * r as f64][k]));
            }
        }
    } else {
        // conventional cubic cell of side √2 d with 4 sites: nearest neighbours at d
        let a = spacing * 2f64.sqrt();
        let cells = ((count as f64 / 4.0).cbrt().ceil() as usize).max(1);
        const BASIS: [[f64; 3]; 4] = [
            [0.0, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 0.0, 0.5],
            [0.0, 0.5, 0.5],
        ];
        'cells: for z in 0.. {
            for y in 0..cells {
                for x in 0..cells {
                    for b in BASIS {
                        if sites.len() >= count {
                            break 'cells;
                        }
                        let cell = [x as f64, y as f64, z as f64];
                        sites.push(V::from_fn(|k| a * (cell[k] + b[k])));
                    }
                }
            }
        }
    }
    sites
}

/// The initial swarm of n agents, and `obstacles` obstacle descriptions (alternately balls and
/// boxes, on a regular grid over the flock, none containing or touching an agent).
///
/// Agents sit on a lattice of spacing d, jittered by up to ±0.05 d per coordinate, with
/// velocities uniform in [−0.5, 0.5]^m. Lattice sites within an obstacle's reach are left empty and
/// the lattice is grown until n sites remain.
#[must_use]
pub fn lattice_swarm<V: Vector>(n: usize, obstacles: usize) -> (Swarm<V>, Vec<ObstacleSpec>) {
    let mut rng = Pcg64::seed_from_u64(SEED);
    let mut growth = 1.0;
    let (sites, specs) = loop {
        let mut sites: Vec<V> = lattice((n as f64 * growth).ceil() as usize, D);
        let specs = obstacle_grid(&sites, obstacles);
        if specs.is_empty() {
            break (sites, specs);
        }
        let reach: Vec<(V, f64)> = specs.iter().map(|s| obstacle_reach(s)).collect();
        let per_axis = obstacles_per_axis(obstacles, V::DIM);
        let (lo, step) = grid_of(&sites, per_axis);
        sites.retain(|&q| {
            // an obstacle reaches at most into the grid cells next to its own
            let cell: [isize; 3] = core::array::from_fn(|k| {
                if k < V::DIM {
                    ((q.coord(k) - lo[k]) / step[k]).floor() as isize
                } else {
                    0
                }
            });
            let span = |k: usize| if k < V::DIM { -1..=1 } else { 0..=0 };
            let axis = per_axis as isize;
            for dz in span(2) {
                for dy in span(1) {
                    for dx in span(0) {
                        let [x, y, z] = [cell[0] + dx, cell[1] + dy, cell[2] + dz];
                        if [x, y, z].iter().any(|&c| c < 0 || c >= axis) {
                            continue;
                        }
                        let index = (x + axis * (y + axis * z)) as usize;
                        if let Some(&(centre, radius)) = reach.get(index)
                            && (q - centre).length() <= radius
                        {
                            return false;
                        }
                    }
                }
            }
            true
        });
        if sites.len() >= n {
            break (sites, specs);
        }
        growth *= 1.05;
    };
    let jitter = 0.05 * D;
    let positions: Vec<V> = sites[..n]
        .iter()
        .map(|&q| q + V::from_fn(|_| jitter * (2.0 * rng.random::<f64>() - 1.0)))
        .collect();
    let velocities: Vec<V> = (0..n)
        .map(|_| V::from_fn(|_| rng.random::<f64>() - 0.5))
        .collect();
    (Swarm::new(positions, velocities), specs)
}

/// The swarm with its agents renumbered by a seeded random permutation (Fisher–Yates): as a
/// swarm drawn at random is numbered, neighbours far apart in index.
#[must_use]
pub fn shuffled<V: Vector>(swarm: Swarm<V>) -> Swarm<V> {
    let mut rng = Pcg64::seed_from_u64(SEED + 1);
    let mut order: Vec<usize> = (0..swarm.len()).collect();
    for k in (1..order.len()).rev() {
        order.swap(k, rng.random_range(0..=k));
    }
    Swarm::new(
        order.iter().map(|&i| swarm.positions[i]).collect(),
        order.iter().map(|&i| swarm.velocities[i]).collect(),
    )
}

/// The number of obstacles per axis of the grid holding `count` obstacles.
fn obstacles_per_axis(count: usize, dim: usize) -> usize {
    let mut k = (count as f64).powf(1.0 / dim as f64).round() as usize;
    while k.pow(dim as u32) < count {
        k += 1;
    }
    k.max(1)
}

/// The lower corner and cell sizes of a grid of `per_axis`^m cells over the bounding box of
/// `sites`.
fn grid_of<V: Vector>(sites: &[V], per_axis: usize) -> ([f64; 3], [f64; 3]) {
    let (lo, hi) = sites
        .iter()
        .fold((sites[0], sites[0]), |(lo, hi), &q| (lo.min(q), hi.max(q)));
    let lo = core::array::from_fn(|k| if k < V::DIM { lo.coord(k) } else { 0.0 });
    let step = core::array::from_fn(|k| {
        if k < V::DIM {
            ((hi.coord(k) - lo[k]) / per_axis as f64).max(f64::MIN_POSITIVE)
        } else {
            1.0
        }
    });
    (lo, step)
}

/// `count` obstacles at the centres of a grid over the bounding box of `sites`: balls of radius
/// min(d, spacing/5) and boxes of the same half-width, alternately.
fn obstacle_grid<V: Vector>(sites: &[V], count: usize) -> Vec<ObstacleSpec> {
    if count == 0 {
        return Vec::new();
    }
    let per_axis = obstacles_per_axis(count, V::DIM);
    let (lo, step) = grid_of(sites, per_axis);
    let size = step[..V::DIM].iter().fold(D, |s, &st| s.min(st / 5.0));
    (0..count)
        .map(|index| {
            let cell = [
                index % per_axis,
                (index / per_axis) % per_axis,
                index / (per_axis * per_axis),
            ];
            let centre: Vec<f64> = (0..V::DIM)
                .map(|k| lo[k] + (cell[k] as f64 + 0.5) * step[k])
                .collect();
            if index % 2 == 0 {
                ObstacleSpec::Ball {
                    centre,
                    radius: size,
                }
            } else {
                ObstacleSpec::Cuboid {
                    centre,
                    half_extents: vec![size; V::DIM],
                    rotation: Vec::new(),
                }
            }
        })
        .collect()
}

/// The centre of an obstacle of [`obstacle_grid`] and the radius of the ball around it that agents
/// must stay out of: its circumradius plus a margin of 0.3 d (beyond the jitter).
fn obstacle_reach<V: Vector>(spec: &ObstacleSpec) -> (V, f64) {
    match spec {
        ObstacleSpec::Ball { centre, radius } => (V::from_fn(|k| centre[k]), radius + 0.3 * D),
        ObstacleSpec::Cuboid {
            centre,
            half_extents,
            ..
        } => (
            V::from_fn(|k| centre[k]),
            half_extents[0] * (V::DIM as f64).sqrt() + 0.3 * D,
        ),
        _ => unreachable!("the benchmark only places balls and boxes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flock_obstacles::{ObstacleField, Space};
    use glam::{DVec2, DVec3};

    fn check_lattice<V: Space>() {
        let (swarm, specs) = lattice_swarm::<V>(2000, 0);
        assert_eq!(swarm.len(), 2000);
        assert!(specs.is_empty());
        let net = flock_graph::ProximityNet::brute_force(&swarm.positions, 1.2 * D);
        let mean = net.graph().directed_edge_count() as f64 / 2000.0;
        let full = if V::DIM == 2 { 6.0 } else { 12.0 };
        assert!(mean > 0.6 * full && mean <= full, "{mean} neighbours");
        let min = flock_graph::nearest_pair_distance(&swarm.positions).unwrap();
        assert!(min > 0.8 * D, "{min}");
    }

    #[test]
    fn lattice_has_the_papers_spacing_2d() {
        check_lattice::<DVec2>();
    }

    #[test]
    fn lattice_has_the_papers_spacing_3d() {
        check_lattice::<DVec3>();
    }

    #[test]
    fn shuffling_renumbers_the_same_agents() {
        let (swarm, _) = lattice_swarm::<DVec2>(3000, 0);
        let renumbered = shuffled(swarm.clone());
        // each agent's state as bits, in index order
        let states = |s: &Swarm<DVec2>| -> Vec<[u64; 4]> {
            let agents = s.positions.iter().zip(&s.velocities);
            agents
                .map(|(q, p)| [q.x, q.y, p.x, p.y].map(f64::to_bits))
                .collect()
        };
        let (mut before, mut after) = (states(&swarm), states(&renumbered));
        let moved = before.iter().zip(&after).filter(|(a, b)| a != b).count();
        assert!(moved > 2900, "only {moved} of 3000 agents renumbered");
        before.sort_unstable();
        after.sort_unstable();
        assert_eq!(before, after);
    }

    fn check_obstacles<V: Space>(n: usize, count: usize) {
        let (swarm, specs) = lattice_swarm::<V>(n, count);
        assert_eq!(swarm.len(), n);
        assert_eq!(specs.len(), count);
        let field = ObstacleField::<V>::from_specs(&specs).unwrap();
        for &q in &swarm.positions {
            assert!(field.clearance(q) > 0.0, "an agent inside an obstacle");
        }
    }

    #[test]
    fn obstacles_avoid_the_agents() {
        check_obstacles::<DVec2>(500, 1000);
        check_obstacles::<DVec2>(20_000, 1000);
        check_obstacles::<DVec3>(500, 1000);
        check_obstacles::<DVec3>(20_000, 1000);
    }
}

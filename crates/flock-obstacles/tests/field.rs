//! `ObstacleField` against a loop over all its obstacles, on random fields of ~200 mixed obstacles:
//! the same `(k, β)` lists, clearances and containing obstacles.

use flock_obstacles::{BetaAgent, Obstacle, ObstacleField, ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::common::{Rng, catalogue, convex_points, coords};

/// A random obstacle of any bounded kind near `centre`.
fn random_spec<V: Space>(rng: &mut Rng, centre: V) -> ObstacleSpec {
    loop {
        let size = rng.uniform(0.3, 2.0);
        let spec = match (rng.next_f64() * 6.0) as usize {
            0 => ObstacleSpec::Ball {
                centre: coords(centre),
                radius: size,
            },
            1 => ObstacleSpec::Cuboid {
                centre: coords(centre),
                half_extents: coords(
                    rng.point(V::ZERO, 1.0).max(-rng.point(V::ZERO, 1.0)) * size
                        + V::from_fn(|_| 0.1),
                ),
                rotation: (0..if V::DIM == 2 { 1 } else { 3 })
                    .map(|_| rng.uniform(-3.0, 3.0))
                    .collect(),
            },
            2 => {
                let n = V::DIM + 1 + (rng.next_f64() * 8.0) as usize;
                ObstacleSpec::ConvexHull {
                    points: convex_points(centre, size, n)
                        .into_iter()
                        .map(coords)
                        .collect(),
                }
            }
            3 => ObstacleSpec::Capsule {
                a: coords(centre),
                b: coords(centre + rng.direction::<V>() * (2.0 * size)),
                radius: 0.5 * size,
            },
            4 => ObstacleSpec::Segment {
                a: coords(centre),
                b: coords(centre + rng.direction::<V>() * (2.0 * size)),
            },
            _ => ObstacleSpec::Triangle {
                a: coords(centre + rng.point(V::ZERO, size)),
                b: coords(centre + rng.point(V::ZERO, size)),
                c: coords(centre + rng.point(V::ZERO, size)),
            },
        };
        if V::obstacle(&spec).is_ok() {
            return spec;
        }
    }
}

/// ~200 obstacles in a domain of half-width `half_width`, among them walls on every side.
fn random_field<V: Space>(rng: &mut Rng, half_width: f64) -> ObstacleField<V> {
    let mut specs = Vec::new();
    for k in 0..196 {
        if k % 49 == 10 {
            // A wall every ~50 obstacles: x ≥ −w, x ≤ w, y ≥ −w, y ≤ w.
            let axis = (k / 49) % V::DIM;
            let sign = if k / 49 < 2 { 1.0 } else { -1.0 };
            let normal = V::from_fn(|j| if j == axis { sign } else { 0.0 });
            specs.push(ObstacleSpec::Wall {
                point: coords(normal * -half_width),
                normal: coords(normal),
            });
        }
        let centre = rng.point(V::ZERO, half_width);
        specs.push(random_spec(rng, centre));
    }
    ObstacleField::from_specs(&specs).unwrap()
}

fn brute_force<V: Space>(
    field: &ObstacleField<V>,
    q: V,
    p: V,
    range: f64,
) -> Vec<(usize, BetaAgent<V>)> {
    field
        .obstacles()
        .iter()
        .enumerate()
        .map(|(k, obstacle)| (k, obstacle.beta_agent(q, p)))
        .filter(|(_, beta)| beta.inside || beta.distance < range)
        .collect()
}

fn check_against_brute_force<V: Space>() {
    let mut rng = Rng::new(20 + V::DIM as u64);
    let half_width = if V::DIM == 2 { 30.0 } else { 12.0 };
    let field = random_field::<V>(&mut rng, half_width);
    assert_eq!(field.len(), 200);
    let mut out = vec![(
        usize::MAX,
        BetaAgent::new(V::ZERO, V::ZERO, V::ZERO, V::ZERO, 0.0, false),
    )];
    let (mut inside, mut listed, mut walls_inside) = (0, 0, 0);
    for i in 0..1500 {
        // Random points, and the centres of obstacles' boxes (inside most of them).
        let q = if i % 3 == 0 {
            let k = (rng.next_f64() * field.len() as f64) as usize;
            match field.obstacles()[k].aabb() {
                Some((min, max)) => (min + max) * 0.5,
                None => rng.point(V::ZERO, 1.2 * half_width),
            }
        } else {
            rng.point(V::ZERO, 1.2 * half_width)
        };
        let p = rng.point(V::ZERO, 1.0);
        let range = [0.0, 0.5, 2.0, 5.0, f64::INFINITY, f64::NAN, -1.0][i % 7];
        field.beta_agents(q, p, range, &mut out);
        assert_eq!(
            out,
            brute_force(&field, q, p, range),
            "q = {q:?}, range {range}"
        );
        listed += out.len();

        let clearance = field
            .obstacles()
            .iter()
            .map(|obstacle| obstacle.signed_distance(q))
            .fold(f64::INFINITY, f64::min);
        assert_eq!(field.clearance(q), clearance, "q = {q:?}");

        let containing = field
            .obstacles()
            .iter()
            .position(|obstacle| obstacle.beta_agent(q, V::ZERO).inside);
        assert_eq!(field.containing(q), containing, "q = {q:?}");
        inside += usize::from(containing.is_some());
        walls_inside +=
            usize::from(containing.is_some_and(|k| field.obstacles()[k].aabb().is_none()));
    }
    assert!(
        inside > 300 && walls_inside > 10,
        "{inside} inside, {walls_inside} in walls"
    );
    assert!(listed > 3000, "{listed} β-agents listed");
}

#[test]
fn against_brute_force_2d() {
    check_against_brute_force::<DVec2>();
}

#[test]
fn against_brute_force_3d() {
    check_against_brute_force::<DVec3>();
}

fn check_empty<V: Space>() {
    for field in [
        ObstacleField::<V>::empty(),
        ObstacleField::default(),
        ObstacleField::new(vec![]),
    ] {
        assert!(field.is_empty());
        assert_eq!(field.len(), 0);
        let mut out = Vec::new();
        field.beta_agents(V::ZERO, V::ZERO, f64::INFINITY, &mut out);
        assert!(out.is_empty());
        assert_eq!(field.clearance(V::ZERO), f64::INFINITY);
        assert_eq!(field.containing(V::ZERO), None);
    }
}

#[test]
fn empty_2d() {
    check_empty::<DVec2>();
}

#[test]
fn empty_3d() {
    check_empty::<DVec3>();
}

/// Every shape of the catalogue, in order, through `from_specs`: the field keeps the order.
fn check_catalogue<V: Space>() {
    let specs: Vec<ObstacleSpec> = catalogue::<V>().into_iter().map(|(_, spec)| spec).collect();
    let field = ObstacleField::<V>::from_specs(&specs).unwrap();
    assert_eq!(field.len(), specs.len());
    let q = V::from_fn(|k| 0.1 * k as f64 + 7.0);
    let mut out = Vec::new();
    field.beta_agents(q, V::ZERO, f64::INFINITY, &mut out);
    let indices: Vec<usize> = out.iter().map(|(k, _)| *k).collect();
    assert_eq!(indices, (0..specs.len()).collect::<Vec<_>>());
    for ((k, beta), spec) in out.iter().zip(&specs) {
        assert_eq!(
            *beta,
            V::obstacle(spec).unwrap().beta_agent(q, V::ZERO),
            "{k}"
        );
    }
}

#[test]
fn catalogue_2d() {
    check_catalogue::<DVec2>();
}

#[test]
fn catalogue_3d() {
    check_catalogue::<DVec3>();
}

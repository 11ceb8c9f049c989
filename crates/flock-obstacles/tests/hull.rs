//! β-agents on convex polygons and polyhedra against brute force: the hull's facets enumerated from
//! the points (every line / plane through 2 / 3 of them with all the others on one side), its
//! boundary sampled densely. The projection is on the boundary and no sample is nearer; inside
//! detection agrees with the facets.

use flock_math::Vector;
use flock_obstacles::{Obstacle, ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::common::{Rng, convex_points, coords, vector};

/// The unit normal of the line (2D) or plane (3D) through `points` (2 or 3 of them).
fn hyperplane_normal<V: Vector>(points: &[V]) -> V {
    let u = points[1] - points[0];
    if V::DIM == 2 {
        vector::<V>([-u.coord(1), u.coord(0), 0.0]).normalize_or_zero()
    } else {
        let v = points[2] - points[0];
        let (u, v) = (
            [u.coord(0), u.coord(1), u.coord(2)],
            [v.coord(0), v.coord(1), v.coord(2)],
        );
        vector::<V>([
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ])
        .normalize_or_zero()
    }
}

/// A facet: outward unit normal, offset, vertices.
type Facet<V> = (V, f64, Vec<V>);

/// The facets of the hull of `points`, by brute force over all `DIM`-subsets.
fn facets<V: Vector>(points: &[V]) -> Vec<Facet<V>> {
    let n = points.len();
    let mut subsets: Vec<Vec<usize>> = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if V::DIM == 2 {
                subsets.push(vec![i, j]);
            } else {
                for k in j + 1..n {
                    subsets.push(vec![i, j, k]);
                }
            }
        }
    }
    let mut found = Vec::new();
    for subset in subsets {
        let vertices: Vec<V> = subset.iter().map(|&i| points[i]).collect();
        let normal = hyperplane_normal(&vertices);
        if normal == V::ZERO {
            continue;
        }
        let offset = normal.dot(vertices[0]);
        let sides: Vec<f64> = points.iter().map(|&x| normal.dot(x) - offset).collect();
        if sides.iter().all(|&s| s <= 1e-12) {
            found.push((normal, offset, vertices));
        } else if sides.iter().all(|&s| s >= -1e-12) {
            found.push((-normal, -offset, vertices));
        }
    }
    found
}

/// Points of the facets, `n` steps per side; and the largest gap between neighbours.
fn boundary_samples<V: Vector>(facets: &[Facet<V>], n: usize) -> (Vec<V>, f64) {
    let mut samples = Vec::new();
    let mut gap: f64 = 0.0;
    for (_, _, vertices) in facets {
        let (a, b) = (vertices[0], vertices[1]);
        gap = gap.max((b - a).length() / n as f64);
        if V::DIM == 2 {
            samples.extend((0..=n).map(|i| a + (b - a) * (i as f64 / n as f64)));
        } else {
            let c = vertices[2];
            gap = gap
                .max((c - a).length() / n as f64)
                .max((c - b).length() / n as f64);
            for i in 0..=n {
                for j in 0..=n - i {
                    let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
                    samples.push(a + (b - a) * s + (c - a) * t);
                }
            }
        }
    }
    (samples, gap)
}

fn check_against_brute_force<V: Space>(points: &[V], queries: usize, seed: u64) {
    let hull = V::obstacle(&ObstacleSpec::ConvexHull {
        points: points.iter().copied().map(coords).collect(),
    })
    .unwrap();
    let facets = facets(points);
    let (samples, gap) = boundary_samples(&facets, if V::DIM == 2 { 400 } else { 40 });
    let centre = flock_math::mean(points);
    let size = points
        .iter()
        .map(|&x| (x - centre).length())
        .fold(0.0, f64::max);
    let mut rng = Rng::new(seed);
    let mut inside = 0;
    for _ in 0..queries {
        let q = rng.point(centre, 1.5 * size);
        let beta = hull.beta_agent(q, rng.point(V::ZERO, 1.0));
        let height = |x: V| {
            facets
                .iter()
                .map(|&(n, o, _)| n.dot(x) - o)
                .fold(f64::NEG_INFINITY, f64::max)
        };
        // On the boundary: on every facet's inner side, on one of them.
        assert!(
            height(beta.position).abs() < 1e-9,
            "q̂ = {:?} off the boundary",
            beta.position
        );
        // Inside exactly when every facet has q on its inner side.
        if height(q).abs() > 1e-9 {
            assert_eq!(beta.inside, height(q) < 0.0, "q = {q:?}");
        }
        inside += usize::from(beta.inside);
        // No boundary sample nearer than q̂; the nearest sample within the sampling gap of it.
        let sampled = samples
            .iter()
            .map(|&s| (s - q).length())
            .fold(f64::INFINITY, f64::min);
        assert!(
            sampled >= beta.distance - 1e-9,
            "q = {q:?}: sample at {sampled} < {}",
            beta.distance
        );
        assert!(
            sampled <= beta.distance + gap,
            "q = {q:?}: samples {sampled} > {} + {gap}",
            beta.distance
        );
        // Inside, the depth is the distance to the nearest facet plane.
        if beta.inside {
            assert!((beta.distance + height(q)).abs() < 1e-9, "q = {q:?}");
        }
    }
    assert!(inside > 0, "{inside} inside");
}

#[test]
fn polygons_against_brute_force() {
    for (n, seed) in [(3, 1), (4, 2), (7, 3), (16, 4)] {
        let points = convex_points::<DVec2>(DVec2::new(0.7, -1.2), 1.5, n);
        check_against_brute_force(&points, 400, seed);
    }
    let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y].map(|v| v * 2.0 - DVec2::ONE);
    check_against_brute_force(&square, 400, 5);
}

#[test]
fn polyhedra_against_brute_force() {
    for (n, seed) in [(4, 1), (9, 2), (16, 3)] {
        let points = convex_points::<DVec3>(DVec3::new(0.7, -1.2, 0.4), 1.5, n);
        check_against_brute_force(&points, 150, seed);
    }
    let cube: Vec<DVec3> = (0..8)
        .map(|k| {
            DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64) * 2.0
                - DVec3::ONE
        })
        .collect();
    check_against_brute_force(&cube, 150, 4);
}

/// The hull is closed: an α-agent on a vertex or on an edge or face is inside, its own β-agent.
fn check_agent_on_boundary<V: Space>() {
    let points = convex_points::<V>(V::ZERO, 1.0, 8);
    let hull = V::obstacle(&ObstacleSpec::ConvexHull {
        points: points.iter().copied().map(coords).collect(),
    })
    .unwrap();
    for q in [points[0], (points[0] + points[1]) * 0.5] {
        let beta = hull.beta_agent(q, V::ZERO);
        assert!(beta.inside);
        assert!(beta.distance < 1e-12, "{}", beta.distance);
    }
}

#[test]
fn agent_on_boundary_2d() {
    check_agent_on_boundary::<DVec2>();
}

#[test]
fn agent_on_boundary_3d() {
    check_agent_on_boundary::<DVec3>();
}

/// parry2d-f64 0.31.1 projects some points inside a convex polygon (by EPA) on a point well inside
/// it (here 0.135 away, when the boundary is 1.16 away); the β-agent of an inside α-agent is the
/// foot of the perpendicular on the nearest edge, computed from the edge lines.
#[test]
fn regression_parry_epa_inside_polygon() {
    let points: Vec<DVec2> = (0..7)
        .map(|k| {
            let t = k as f64 * 0.9 + 0.1;
            DVec2::new(2.0 * t.cos() + 0.3, 1.5 * t.sin() - 0.2)
        })
        .collect();
    let polygon = flock_obstacles::Obstacle2d::convex_hull(&points).unwrap();
    let q = DVec2::new(0.673_267_326_732_673, -0.038_834_951_456_310_66);
    let beta = polygon.beta_agent(q, DVec2::ZERO);
    let facets = facets(&points);
    let depth = facets
        .iter()
        .map(|&(n, o, _)| o - n.dot(q))
        .fold(f64::INFINITY, f64::min);
    assert!(beta.inside);
    assert!((depth - 1.160_637_788_898_412).abs() < 1e-9, "{depth}");
    assert!(
        (beta.distance - depth).abs() < 1e-12,
        "{} != {depth}",
        beta.distance
    );
}

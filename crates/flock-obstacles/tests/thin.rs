//! Zero-thickness obstacles: segments (2D thin walls, 3D rods) against the closed form, 3D triangle
//! plates against a dense sampling; the 2D triangle is the solid convex polygon.

use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d, ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::common::{Rng, assert_close, coords, vector};

fn check_segment<V: Space>() {
    let (a, b) = (
        vector::<V>([-1.0, 0.5, -0.5]),
        vector::<V>([1.0, -1.0, 1.0]),
    );
    let segment = V::obstacle(&ObstacleSpec::Segment {
        a: coords(a),
        b: coords(b),
    })
    .unwrap();
    let u = (b - a).normalize_or_zero();
    let mut rng = Rng::new(5);
    for _ in 0..2000 {
        let q = rng.point(V::ZERO, 3.0);
        let p = rng.point(V::ZERO, 1.0);
        let beta = segment.beta_agent(q, p);
        let t = (q - a).dot(b - a) / (b - a).length_squared();
        let position = a + (b - a) * t.clamp(0.0, 1.0);
        assert_close(beta.position, position, 1e-12);
        assert_close(beta.normal, (q - position).normalize_or_zero(), 1e-12);
        assert!(!beta.inside);
        let on_edge = 0.0 < t && t < 1.0;
        assert_close(
            beta.velocity,
            if on_edge { u * u.dot(p) } else { V::ZERO },
            1e-12,
        );
        let mu = if on_edge && V::DIM == 2 { 1.0 } else { 0.0 };
        assert_eq!(beta.mu, mu);
    }
    // On the segment: inside, its own β-agent, with a normal orthogonal to it.
    let q = a + (b - a) * 0.25;
    let p = vector::<V>([0.5, 1.0, -1.0]);
    let beta = segment.beta_agent(q, p);
    assert!(beta.inside);
    assert!(beta.distance < 1e-12);
    assert!(beta.normal.dot(u).abs() < 1e-12 && (beta.normal.length() - 1.0).abs() < 1e-12);
    assert_close(beta.velocity, u * u.dot(p), 1e-12);
}

#[test]
fn segment_2d() {
    check_segment::<DVec2>();
}

#[test]
fn segment_3d() {
    check_segment::<DVec3>();
}

#[test]
fn plate_against_samples() {
    let (a, b, c) = (
        DVec3::new(-1.0, -1.0, 0.5),
        DVec3::new(1.5, -0.5, -0.5),
        DVec3::new(0.0, 1.5, 0.25),
    );
    let plate = Obstacle3d::triangle(a, b, c).unwrap();
    let n = 200;
    let samples: Vec<DVec3> = (0..=n)
        .flat_map(|i| {
            (0..=n - i)
                .map(move |j| a + (b - a) * (i as f64 / n as f64) + (c - a) * (j as f64 / n as f64))
        })
        .collect();
    let normal = (b - a).cross(c - a).normalize();
    let mut rng = Rng::new(6);
    for _ in 0..200 {
        let q = rng.point(DVec3::ZERO, 2.5);
        let beta = plate.beta_agent(q, DVec3::ZERO);
        assert!(!beta.inside);
        // q̂ on the plate: in its plane, barycentric coordinates in [0, 1].
        assert!(normal.dot(beta.position - a).abs() < 1e-12);
        let sampled = samples
            .iter()
            .map(|&s| s.distance(q))
            .fold(f64::INFINITY, f64::min);
        assert!(sampled >= beta.distance - 1e-9, "q = {q:?}");
        assert!(sampled <= beta.distance + 0.03, "q = {q:?}");
    }
    // On the plate: inside, with the plate's normal; the velocity is P p.
    let q = (a + b + c) / 3.0;
    let p = DVec3::new(0.3, 0.7, -1.1);
    let beta = plate.beta_agent(q, p);
    assert!(beta.inside);
    assert_eq!(beta.normal, normal);
    assert_close(beta.velocity, p - normal * normal.dot(p), 1e-15);
    // Both sides are boundary: the normal points to the α-agent's side.
    let above = plate.beta_agent(q + normal, p);
    let below = plate.beta_agent(q - normal, p);
    assert_close(above.normal, normal, 1e-12);
    assert_close(below.normal, -normal, 1e-12);
    assert_close(above.position, below.position, 1e-12);
}

#[test]
fn triangle_2d_is_solid() {
    let (a, b, c) = (
        DVec2::new(-1.0, -1.0),
        DVec2::new(1.5, -0.5),
        DVec2::new(0.0, 1.5),
    );
    let triangle = Obstacle2d::triangle(a, b, c).unwrap();
    let hull = Obstacle2d::convex_hull(&[c, a, b]).unwrap();
    let mut rng = Rng::new(8);
    let mut inside = 0;
    for _ in 0..500 {
        let q = rng.point(DVec2::ZERO, 2.5);
        let p = rng.point(DVec2::ZERO, 1.0);
        assert_eq!(triangle.beta_agent(q, p), hull.beta_agent(q, p));
        inside += usize::from(triangle.beta_agent(q, p).inside);
    }
    assert!(inside > 20);
}

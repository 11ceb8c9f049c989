//! β-agents on capsules against the closed form (`q̂ = s + R (q − s)/‖q − s‖`, `s` the closest point
//! of the axis) and against a dense sampling of the boundary; the velocity per feature.

use flock_math::Vector;
use flock_obstacles::{Obstacle, ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::common::{Rng, assert_close, coords, vector};

const RADIUS: f64 = 0.6;

fn axis<V: Vector>() -> (V, V) {
    (vector([-1.0, -0.5, 0.5]), vector([1.5, 0.5, -0.5]))
}

/// The point of `[a, b]` closest to `x`, and whether it is inside the segment.
fn closest_on_axis<V: Vector>(a: V, b: V, x: V) -> (V, bool) {
    let t = (x - a).dot(b - a) / (b - a).length_squared();
    (a + (b - a) * t.clamp(0.0, 1.0), 0.0 < t && t < 1.0)
}

fn check_closed_form<V: Space>() {
    let (a, b) = axis::<V>();
    let capsule = V::obstacle(&ObstacleSpec::Capsule {
        a: coords(a),
        b: coords(b),
        radius: RADIUS,
    })
    .unwrap();
    let u = (b - a).normalize_or_zero();
    let mut rng = Rng::new(3);
    let (mut sides, mut caps, mut inside) = (0, 0, 0);
    for _ in 0..3000 {
        let q = rng.point((a + b) * 0.5, 3.0);
        let p = rng.point(V::ZERO, 1.0);
        let beta = capsule.beta_agent(q, p);
        let (s, on_side) = closest_on_axis(a, b, q);
        let rho = (q - s).length();
        let n = (q - s) / rho;
        assert_close(beta.position, s + n * RADIUS, 1e-12);
        assert_close(beta.normal, n, 1e-12);
        assert!((beta.distance - (rho - RADIUS).abs()).abs() < 1e-12);
        assert_eq!(beta.inside, rho <= RADIUS, "q = {q:?}");
        let mu = RADIUS / rho;
        let tangent = p - n * n.dot(p);
        let (velocity, expected_mu) = if !on_side {
            caps += 1;
            (tangent * mu, mu)
        } else if V::DIM == 2 {
            sides += 1;
            (tangent, 1.0)
        } else {
            sides += 1;
            let axial = u * u.dot(p);
            (axial + (tangent - axial) * mu, mu)
        };
        assert_close(beta.velocity, velocity, 1e-12);
        assert!((beta.mu - expected_mu).abs() < 1e-12);
        inside += usize::from(beta.inside);
    }
    assert!(
        sides > 100 && caps > 100 && inside > 20,
        "{sides} {caps} {inside}"
    );
}

#[test]
fn closed_form_2d() {
    check_closed_form::<DVec2>();
}

#[test]
fn closed_form_3d() {
    check_closed_form::<DVec3>();
}

/// Boundary samples: random points about the capsule pushed radially from the axis to distance `R`
/// (every boundary point is the image of a point of the plane or space).
fn boundary_samples<V: Vector>(a: V, b: V) -> Vec<V> {
    let mut rng = Rng::new(17);
    (0..if V::DIM == 2 { 20_000 } else { 200_000 })
        .map(|_| {
            let x = rng.point((a + b) * 0.5, 2.5);
            let (c, _) = closest_on_axis(a, b, x);
            c + (x - c).normalize_or_zero() * RADIUS
        })
        .collect()
}

fn check_against_samples<V: Space>() {
    let (a, b) = axis::<V>();
    let capsule = V::obstacle(&ObstacleSpec::Capsule {
        a: coords(a),
        b: coords(b),
        radius: RADIUS,
    })
    .unwrap();
    let samples = boundary_samples(a, b);
    let mut rng = Rng::new(4);
    for _ in 0..100 {
        let q = rng.point((a + b) * 0.5, 2.5);
        let beta = capsule.beta_agent(q, V::ZERO);
        let (c, _) = closest_on_axis(a, b, beta.position);
        assert!(((beta.position - c).length() - RADIUS).abs() < 1e-12);
        let sampled = samples
            .iter()
            .map(|&s| (s - q).length())
            .fold(f64::INFINITY, f64::min);
        assert!(sampled >= beta.distance - 1e-9, "q = {q:?}");
        assert!(
            sampled <= beta.distance + 0.05,
            "q = {q:?}: {sampled} vs {}",
            beta.distance
        );
    }
}

#[test]
fn against_samples_2d() {
    check_against_samples::<DVec2>();
}

#[test]
fn against_samples_3d() {
    check_against_samples::<DVec3>();
}

/// On the axis every direction is closest: the β-agent is a boundary point at distance `R`, inside,
/// with `μ = 1` and `p̂ = P p`.
fn check_agent_on_axis<V: Space>() {
    let (a, b) = axis::<V>();
    let capsule = V::obstacle(&ObstacleSpec::Capsule {
        a: coords(a),
        b: coords(b),
        radius: RADIUS,
    })
    .unwrap();
    for q in [a, (a + b) * 0.5] {
        let p = vector::<V>([0.3, -0.2, 0.9]);
        let beta = capsule.beta_agent(q, p);
        assert!(beta.inside);
        assert!((beta.distance - RADIUS).abs() < 1e-12);
        assert!((beta.normal.length() - 1.0).abs() < 1e-12);
        assert_eq!(beta.mu, 1.0);
        assert_close(beta.velocity, p - beta.normal * beta.normal.dot(p), 1e-15);
    }
}

#[test]
fn agent_on_axis_2d() {
    check_agent_on_axis::<DVec2>();
}

#[test]
fn agent_on_axis_3d() {
    check_agent_on_axis::<DVec3>();
}

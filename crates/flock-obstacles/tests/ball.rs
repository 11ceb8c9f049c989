//! β-agents on balls against the closed forms of Olfati-Saber (IEEE TAC 51(3) 2006):
//! `μ = R/‖q − y‖`, `a = (q − y)/‖q − y‖`, `q̂ = μ q + (1 − μ) y`, `p̂ = μ (I − a aᵀ) p`.

use approx::{assert_abs_diff_eq, assert_relative_eq};
use flock_math::Vector;
use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
use glam::{DVec2, DVec3};

use crate::common::{assert_close, first_axis, grid, velocity};

const RADIUS: f64 = 2.0;

fn centre<V: Vector>() -> V {
    V::from_fn(|axis| 1.5 - 0.75 * axis as f64)
}

fn check_closed_form<V: Vector, O: Obstacle<V>>() {
    let y = centre::<V>();
    let ball = O::ball(y, RADIUS).unwrap();
    let (mut inside, mut outside) = (0, 0);
    for (index, q) in grid(y, 5.0, 12).enumerate() {
        let p = velocity::<V>(index);
        let beta = ball.beta_agent(q, p);
        let norm = (q - y).length();
        let mu = RADIUS / norm;
        let a = (q - y) / norm;

        assert_relative_eq!(beta.mu, mu, max_relative = 1e-14);
        assert_close(beta.normal, a, 1e-14);
        assert_close(beta.position, q * mu + y * (1.0 - mu), 1e-13);
        assert_close(beta.velocity, (p - a * a.dot(p)) * mu, 1e-13);
        assert_abs_diff_eq!(beta.distance, (norm - RADIUS).abs(), epsilon = 1e-13);
        assert_eq!(beta.inside, norm <= RADIUS, "q = {q:?}");
        if beta.inside {
            inside += 1;
        } else {
            outside += 1;
        }
    }
    assert!(
        inside > 0 && outside > 0,
        "{inside} inside, {outside} outside"
    );
}

#[test]
fn closed_form_2d() {
    check_closed_form::<DVec2, Obstacle2d>();
}

#[test]
fn closed_form_3d() {
    check_closed_form::<DVec3, Obstacle3d>();
}

/// `q̂` on the sphere, `a` a unit normal, `p̂` tangent; `μ < 1` outside, `μ > 1` inside.
fn check_geometry<V: Vector, O: Obstacle<V>>() {
    let y = centre::<V>();
    let ball = O::ball(y, RADIUS).unwrap();
    for (index, q) in grid(y, 4.0, 10).enumerate() {
        let beta = ball.beta_agent(q, velocity(index));
        assert_relative_eq!((beta.position - y).length(), RADIUS, max_relative = 1e-14);
        assert_relative_eq!(beta.normal.length(), 1.0, max_relative = 1e-14);
        assert_abs_diff_eq!(beta.velocity.dot(beta.normal), 0.0, epsilon = 1e-13);
        assert!(beta.mu.is_finite() && beta.mu > 0.0);
        assert_eq!(beta.mu < 1.0, !beta.inside, "q = {q:?}, mu = {}", beta.mu);
    }
}

#[test]
fn geometry_2d() {
    check_geometry::<DVec2, Obstacle2d>();
}

#[test]
fn geometry_3d() {
    check_geometry::<DVec3, Obstacle3d>();
}

/// `p̂ = μ P p` is the velocity of `q̂` as the α-agent moves with `p`: a central difference of `q̂`
/// along `p` matches it.
fn check_velocity_is_derivative<V: Vector, O: Obstacle<V>>() {
    let y = centre::<V>();
    let ball = O::ball(y, RADIUS).unwrap();
    let h = 1e-6;
    for (index, q) in grid(y, 5.0, 8).enumerate() {
        let p = velocity::<V>(index);
        let ahead = ball.beta_agent(q + p * h, p).position;
        let behind = ball.beta_agent(q - p * h, p).position;
        assert_close(
            ball.beta_agent(q, p).velocity,
            (ahead - behind) / (2.0 * h),
            1e-6,
        );
    }
}

#[test]
fn velocity_is_derivative_2d() {
    check_velocity_is_derivative::<DVec2, Obstacle2d>();
}

#[test]
fn velocity_is_derivative_3d() {
    check_velocity_is_derivative::<DVec3, Obstacle3d>();
}

/// At the centre every boundary point is closest (parry returns NaN there): the β-agent is placed
/// on the first axis, inside, with `μ = 1`.
fn check_agent_at_centre<V: Vector, O: Obstacle<V>>() {
    let y = centre::<V>();
    let e1 = first_axis::<V>();
    let p = velocity::<V>(3);
    let beta = O::ball(y, RADIUS).unwrap().beta_agent(y, p);
    assert!(beta.inside);
    assert_eq!(beta.normal, e1);
    assert_eq!(beta.position, y + e1 * RADIUS);
    assert_eq!(beta.mu, 1.0);
    assert_eq!(beta.velocity, p - e1 * p.coord(0));
    assert_eq!(beta.distance, RADIUS);
}

#[test]
fn agent_at_centre_2d() {
    check_agent_at_centre::<DVec2, Obstacle2d>();
}

#[test]
fn agent_at_centre_3d() {
    check_agent_at_centre::<DVec3, Obstacle3d>();
}

/// The ball is closed: an α-agent on the sphere is inside, and is its own β-agent.
fn check_agent_on_boundary<V: Vector, O: Obstacle<V>>() {
    let y = centre::<V>();
    let last_axis = V::from_fn(|axis| if axis + 1 == V::DIM { 1.0 } else { 0.0 });
    let q = y + last_axis * RADIUS;
    let beta = O::ball(y, RADIUS).unwrap().beta_agent(q, velocity(0));
    assert!(beta.inside);
    assert_close(beta.position, q, 1e-15);
    assert_close(beta.normal, last_axis, 1e-15);
    assert_eq!(beta.mu, 1.0);
    assert_abs_diff_eq!(beta.distance, 0.0, epsilon = 1e-15);
}

#[test]
fn agent_on_boundary_2d() {
    check_agent_on_boundary::<DVec2, Obstacle2d>();
}

#[test]
fn agent_on_boundary_3d() {
    check_agent_on_boundary::<DVec3, Obstacle3d>();
}

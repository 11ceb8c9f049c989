//! [`BetaAgent::new`] and the β-agent as data.

use approx::assert_abs_diff_eq;
use flock_obstacles::{BetaAgent, Obstacle, Obstacle2d};
use glam::{DVec2, DVec3};

#[test]
fn velocity_is_scaled_tangent_projection() {
    let a = DVec3::new(2.0, -1.0, 2.0) / 3.0;
    let p = DVec3::new(0.3, 1.7, -2.2);
    let beta = BetaAgent::new(DVec3::ONE, p, DVec3::ZERO, a, 0.25, false);
    assert_abs_diff_eq!(beta.velocity.dot(a), 0.0, epsilon = 1e-15);
    assert_abs_diff_eq!(beta.velocity, (p - a * a.dot(p)) * 0.25, epsilon = 1e-15);
    assert_abs_diff_eq!(beta.distance, 3.0_f64.sqrt(), epsilon = 1e-15);
    assert_eq!(
        (beta.position, beta.normal, beta.mu, beta.inside),
        (DVec3::ZERO, a, 0.25, false)
    );
}

#[test]
fn round_trips_through_ron() {
    let disc = Obstacle2d::ball(DVec2::new(4.0, 0.0), 1.0).unwrap();
    let beta = disc.beta_agent(DVec2::ZERO, DVec2::new(1.0, 2.0));
    let text = ron::to_string(&beta).unwrap();
    assert!(text.contains("position:(3.0,0.0)"), "{text}");
    assert_eq!(ron::from_str::<BetaAgent<DVec2>>(&text).unwrap(), beta);
}

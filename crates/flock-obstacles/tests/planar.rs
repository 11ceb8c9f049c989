//! 2D and 3D agree on planar inputs: a 3D obstacle symmetric about `z = 0`, seen by agents in that
//! plane, induces the 2D β-agents with `z = 0` — balls and walls bit for bit; boxes turned about z
//! and polygon prisms tall enough that their top and bottom never matter, capsules and segments in
//! the plane, to rounding (`μ` differs for capsule sides and segments, where 3D sees curvature
//! around the axis that 2D has not; the velocity agrees).

use flock_obstacles::{BetaAgent, Obstacle, Obstacle2d, Obstacle3d};
use glam::{DVec2, DVec3};

use crate::common::{assert_close, grid, velocity};

fn assert_agree(flat: BetaAgent<DVec2>, solid: BetaAgent<DVec3>) {
    assert_close(solid.position, flat.position.extend(0.0), 1e-15);
    assert_close(solid.normal, flat.normal.extend(0.0), 1e-15);
    assert_close(solid.velocity, flat.velocity.extend(0.0), 1e-15);
    assert_eq!(solid.mu, flat.mu);
    assert_eq!(solid.distance, flat.distance);
    assert_eq!(solid.inside, flat.inside);
}

fn check(flat: &Obstacle2d, solid: &Obstacle3d) {
    for (index, q) in grid(DVec2::new(0.5, -0.25), 5.0, 16).enumerate() {
        let p = velocity::<DVec2>(index);
        assert_agree(
            flat.beta_agent(q, p),
            solid.beta_agent(q.extend(0.0), p.extend(0.0)),
        );
    }
}

#[test]
fn balls_agree() {
    let centre = DVec2::new(1.0, -0.5);
    check(
        &Obstacle2d::ball(centre, 2.5).unwrap(),
        &Obstacle3d::ball(centre.extend(0.0), 2.5).unwrap(),
    );
}

#[test]
fn walls_agree() {
    let (point, normal) = (DVec2::new(-1.0, 2.0), DVec2::new(3.0, -1.0));
    check(
        &Obstacle2d::wall(point, normal).unwrap(),
        &Obstacle3d::wall(point.extend(0.0), normal.extend(0.0)).unwrap(),
    );
}

#[test]
fn agents_at_ball_centres_agree() {
    let centre = DVec2::new(1.0, -0.5);
    let p = DVec2::new(0.3, -0.7);
    assert_agree(
        Obstacle2d::ball(centre, 2.5).unwrap().beta_agent(centre, p),
        Obstacle3d::ball(centre.extend(0.0), 2.5)
            .unwrap()
            .beta_agent(centre.extend(0.0), p.extend(0.0)),
    );
}

/// `flat` and `solid` agree to rounding at the planar points; `μ` too when `same_mu`.
fn check_close(flat: &Obstacle2d, solid: &Obstacle3d, same_mu: bool) {
    for (index, q) in grid(DVec2::new(0.5, -0.25), 5.0, 24).enumerate() {
        let p = velocity::<DVec2>(index);
        let (flat, solid) = (
            flat.beta_agent(q, p),
            solid.beta_agent(q.extend(0.0), p.extend(0.0)),
        );
        assert_close(solid.position, flat.position.extend(0.0), 1e-12);
        assert_close(solid.normal, flat.normal.extend(0.0), 1e-12);
        // Near a capsule's axis μ = R/ρ is large, and so is the rounding of 3D's circumferential part.
        assert_close(
            solid.velocity,
            flat.velocity.extend(0.0),
            1e-12 * (1.0 + solid.mu),
        );
        assert!((solid.distance - flat.distance).abs() < 1e-12);
        assert_eq!(solid.inside, flat.inside, "q = {q:?}");
        if same_mu {
            assert_eq!(solid.mu, flat.mu, "q = {q:?}");
        }
    }
}

#[test]
fn turned_boxes_agree() {
    let (centre, half_extents, angle) = (DVec2::new(1.0, -0.5), DVec2::new(2.0, 1.0), 0.7);
    check_close(
        &Obstacle2d::cuboid(centre, half_extents, angle).unwrap(),
        &Obstacle3d::cuboid(
            centre.extend(0.0),
            half_extents.extend(100.0),
            DVec3::Z * angle,
        )
        .unwrap(),
        true,
    );
}

#[test]
fn polygon_prisms_agree() {
    let polygon: Vec<DVec2> = (0..7)
        .map(|k| {
            let t = k as f64 * 0.9 + 0.1;
            DVec2::new(2.0 * t.cos() + 0.3, 1.5 * t.sin() - 0.2)
        })
        .collect();
    let prism: Vec<DVec3> = polygon
        .iter()
        .flat_map(|v| [v.extend(-100.0), v.extend(100.0)])
        .collect();
    check_close(
        &Obstacle2d::convex_hull(&polygon).unwrap(),
        &Obstacle3d::convex_hull(&prism).unwrap(),
        true,
    );
}

#[test]
fn capsules_and_segments_agree() {
    let (a, b) = (DVec2::new(-2.0, 0.5), DVec2::new(1.5, -1.0));
    check_close(
        &Obstacle2d::capsule(a, b, 0.75).unwrap(),
        &Obstacle3d::capsule(a.extend(0.0), b.extend(0.0), 0.75).unwrap(),
        false,
    );
    check_close(
        &Obstacle2d::segment(a, b).unwrap(),
        &Obstacle3d::segment(a.extend(0.0), b.extend(0.0)).unwrap(),
        false,
    );
}

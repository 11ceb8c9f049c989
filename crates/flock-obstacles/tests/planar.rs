//! 2D and 3D agree on planar inputs: a 3D obstacle symmetric about `z = 0`, seen by agents in that
//! plane, induces the 2D β-agents with `z = 0`.

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

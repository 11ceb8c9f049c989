//! The β-agents (TAC 2006, Section VII) an α-agent induces on every kind of obstacle, in 2D.
//!
//! `cargo run -p flock-obstacles --example beta_agents`

use flock_obstacles::{Obstacle, Obstacle2d};
use glam::DVec2;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let obstacles = [
        ("ball", Obstacle2d::ball(DVec2::new(10.0, 0.0), 3.0)?),
        ("wall", Obstacle2d::wall(DVec2::new(0.0, -5.0), DVec2::Y)?),
        (
            "cuboid",
            Obstacle2d::cuboid(DVec2::new(4.0, 6.0), DVec2::new(2.0, 1.0), 0.4)?,
        ),
        (
            "convex hull",
            Obstacle2d::convex_hull(&[
                DVec2::new(-3.0, 0.0),
                DVec2::new(-1.0, -1.0),
                DVec2::new(0.0, 2.0),
                DVec2::new(-2.0, 3.0),
            ])?,
        ),
        (
            "capsule",
            Obstacle2d::capsule(DVec2::new(6.0, -3.0), DVec2::new(9.0, -2.0), 0.5)?,
        ),
        (
            "segment",
            Obstacle2d::segment(DVec2::new(4.0, 3.0), DVec2::new(7.0, 3.0))?,
        ),
    ];
    let (q, p) = (DVec2::new(4.0, 1.0), DVec2::new(1.0, 0.5));
    for (name, obstacle) in &obstacles {
        let beta = obstacle.beta_agent(q, p);
        println!(
            "{name:>11}: q̂ = ({:7.3}, {:7.3}), normal = ({:6.3}, {:6.3}), μ = {:.4}, \
             p̂ = ({:6.3}, {:6.3}), distance = {:.4}, inside = {}",
            beta.position.x,
            beta.position.y,
            beta.normal.x,
            beta.normal.y,
            beta.mu,
            beta.velocity.x,
            beta.velocity.y,
            beta.distance,
            beta.inside
        );
    }
    Ok(())
}

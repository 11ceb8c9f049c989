//! The β-agents (TAC 2006, Section VII) an α-agent induces on a ball and on a wall.
//!
//! `cargo run -p flock-obstacles --example beta_agents`

use flock_obstacles::{Obstacle, Obstacle2d};
use glam::DVec2;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ball = Obstacle2d::ball(DVec2::new(10.0, 0.0), 3.0)?;
    let wall = Obstacle2d::wall(DVec2::new(0.0, -5.0), DVec2::Y)?;
    let (q, p) = (DVec2::new(4.0, 1.0), DVec2::new(1.0, 0.5));
    for (name, obstacle) in [("ball", &ball), ("wall", &wall)] {
        let beta = obstacle.beta_agent(q, p);
        println!(
            "{name}: q̂ = {:?}, normal = {:?}, μ = {:.4}, p̂ = {:?}, distance = {:.4}, inside = {}",
            beta.position, beta.normal, beta.mu, beta.velocity, beta.distance, beta.inside
        );
    }
    Ok(())
}

//! Many obstacles from a RON description, culled by their bounding boxes: the β-neighbours of a few
//! α-agents (Algorithm 3's `r′`), their clearance, and which obstacle contains them.
//!
//! `cargo run -p flock-obstacles --example obstacle_field`

use flock_obstacles::{ObstacleField, ObstacleSpec};
use glam::DVec3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let specs: Vec<ObstacleSpec> = ron::from_str(
        "[
            Ball(centre: (10.0, 0.0, 0.0), radius: 2.0),
            Wall(point: (0.0, 0.0, -5.0), normal: (0.0, 0.0, 1.0)),
            Cuboid(centre: (0.0, 8.0, 0.0), half_extents: (3.0, 1.0, 2.0), rotation: (0.0, 0.0, 0.5)),
            ConvexHull(points: [(-6.0, 0.0, 0.0), (-4.0, 0.0, 0.0), (-5.0, 2.0, 0.0), (-5.0, 1.0, 2.0)]),
            Capsule(a: (0.0, -6.0, -2.0), b: (0.0, -6.0, 2.0), radius: 1.0),
            Triangle(a: (20.0, 0.0, 0.0), b: (20.0, 4.0, 0.0), c: (20.0, 0.0, 4.0)),
        ]",
    )?;
    let field = ObstacleField::<DVec3>::from_specs(&specs)?;
    let range = 4.0;
    let mut betas = Vec::new();
    for q in [
        DVec3::new(7.0, 0.5, 0.0),
        DVec3::new(-3.0, 1.0, 0.5),
        DVec3::new(0.5, -6.0, 0.0),
        DVec3::new(30.0, 30.0, 30.0),
    ] {
        field.beta_agents(q, DVec3::new(1.0, 1.0, 1.0), range, &mut betas);
        println!(
            "α-agent at {q}: clearance {:.3}, inside {:?}",
            field.clearance(q),
            field.containing(q).map(|k| specs[k].kind())
        );
        for (k, beta) in &betas {
            println!(
                "  β-agent on obstacles[{k}] ({}): q̂ = {:.3}, distance {:.3}, μ = {:.3}, p̂ = {:.3}",
                specs[*k].kind(),
                beta.position,
                beta.distance,
                beta.mu,
                beta.velocity
            );
        }
    }
    Ok(())
}

//! Convex obstacles and their β-agents (Olfati-Saber, IEEE TAC 51(3) 2006, "Flocking with obstacle
//! avoidance"), projected with parry in 2D and 3D.
//!
//! An α-agent `i` at `q_i` with velocity `p_i` sees obstacle `O_k` through a β-agent: the closest
//! point `q̂_{i,k} = argmin_{x ∈ O_k} ‖x − q_i‖`, moving with `p̂_{i,k}`, the time derivative of
//! `q̂_{i,k}` — the paper's `μ P p_i`, `P = I − a_k a_kᵀ`, on balls and flat faces.
//!
//! - [`ObstacleSpec`]: an obstacle as a scenario writes it — ball, wall, cuboid, convex hull,
//!   capsule, segment, triangle.
//! - [`Space`]: `DVec2` or `DVec3` with its obstacle type; [`Space::obstacle`] builds one from a
//!   spec, validated ([`ObstacleError`] names the field at fault).
//! - [`Obstacle`]: the trait generic code calls, [`Obstacle::beta_agent`],
//!   [`Obstacle::signed_distance`], [`Obstacle::aabb`].
//! - [`BetaAgent`]: the β-agent's position, outward normal, velocity, `μ`, distance and whether the
//!   α-agent is inside; the velocity rule per feature (face, edge, vertex, curved) is on its page.
//! - [`ConvexObstacle`]: the shapes, written once for both dimensions; [`Obstacle2d`] /
//!   [`Obstacle3d`] are its instances, projected by parry2d-f64 / parry3d-f64.
//! - [`ObstacleField`]: many obstacles culled by a bounding-volume hierarchy:
//!   [`ObstacleField::beta_agents`], [`ObstacleField::clearance`], [`ObstacleField::containing`].

mod ball;
mod basis;
pub mod beta_agent;
mod bvh;
mod capsule;
pub mod convex;
mod cuboid;
mod dim2;
mod dim3;
pub mod error;
pub mod field;
pub mod obstacle;
mod parry_calls;
mod polytope;
mod shapes;
pub mod space;
pub mod spec;
mod thin;
mod wall;

pub use beta_agent::BetaAgent;
pub use convex::ConvexObstacle;
pub use dim2::Obstacle2d;
pub use dim3::Obstacle3d;
pub use error::ObstacleError;
pub use field::ObstacleField;
pub use obstacle::Obstacle;
pub use space::Space;
pub use spec::ObstacleSpec;

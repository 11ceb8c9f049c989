//! Convex obstacles and their β-agents (Olfati-Saber, IEEE TAC 51(3) 2006, "Flocking with obstacle
//! avoidance"), projected with parry in 2D and 3D.
//!
//! An α-agent `i` at `q_i` with velocity `p_i` sees obstacle `O_k` through a β-agent: the closest
//! point `q̂_{i,k} = argmin_{x ∈ O_k} ‖x − q_i‖`, moving with `p̂_{i,k} = μ P p_i`, `P = I − a_k a_kᵀ`.
//!
//! - [`Obstacle`]: the trait generic code (`V: Vector`) calls, [`Obstacle::beta_agent`].
//! - [`BetaAgent`]: the β-agent's position, outward normal, velocity and `μ`.
//! - [`Obstacle2d`] / [`Obstacle3d`]: balls and walls (half-spaces), projected by parry2d-f64 /
//!   parry3d-f64.
//! - [`ObstacleError`]: why a constructor refused its input.

mod ball;
pub mod beta_agent;
pub mod dim2;
pub mod dim3;
pub mod error;
pub mod obstacle;
mod wall;

pub use beta_agent::BetaAgent;
pub use dim2::Obstacle2d;
pub use dim3::Obstacle3d;
pub use error::ObstacleError;
pub use obstacle::Obstacle;

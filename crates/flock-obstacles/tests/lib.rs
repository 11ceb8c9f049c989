//! Integration tests of flock-obstacles: each contract written once for `V: Vector` and run in 2D
//! and 3D.

mod ball;
mod beta_agent;
mod common;
mod errors;
mod planar;
mod wall;

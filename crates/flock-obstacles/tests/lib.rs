//! Integration tests of flock-obstacles: each contract written once for `V: Vector` and run in 2D
//! and 3D.

mod ball;
mod beta_agent;
mod capsule;
mod common;
mod contract;
mod cuboid;
mod errors;
mod field;
mod hull;
mod planar;
mod projection_properties;
mod spec;
mod thin;
mod wall;

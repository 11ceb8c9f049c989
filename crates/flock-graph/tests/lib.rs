//! Integration tests of flock-graph: one binary, one module per concept.

mod common;

mod components;
mod graph;
mod laplacian;
mod nearest;
mod search;
mod stress;
mod torus;

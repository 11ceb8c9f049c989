//! Figures of parameter sweeps: phase diagrams (`flocking sweep plot`).

pub mod phase;

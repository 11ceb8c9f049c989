//! Figures of parameter sweeps: phase diagrams ([`phase`]), drawn from a sweep's directory as
//! `flocking sweep plot` draws them ([`plot`]), its values named as the scenario writes them
//! ([`shown`]).

pub mod phase;
pub mod plot;
pub mod shown;

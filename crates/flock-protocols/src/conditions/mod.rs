//! Real conditions: delay, packet loss and a communication range between agents, noisy sensing,
//! sampled control, limited and lagged actuation, wind and process noise, and faults.
//!
//! [`Conditions`] is what a scenario says ([`config`]); every part is optional and off by
//! default, and with none set a [`Simulation`](crate::Simulation) runs the ideal loop.

pub mod config;

pub use config::{
    Actuation, Communication, Conditions, Delayed, Disturbance, Failure, FaultMode, Faults, Loss,
    Noise, SampledControl, Sensing, WhenLost, Wind,
};

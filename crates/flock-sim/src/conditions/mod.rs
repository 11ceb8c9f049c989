//! Real conditions: delay, packet loss and a communication range between agents, noisy sensing,
//! sampled control, limited and lagged actuation, wind and process noise, and faults.
//!
//! - [`Conditions`] is what a scenario says ([`config`]); every part is optional and off by
//!   default, and with none set a [`Simulation`](crate::Simulation) runs the ideal loop.
//! - [`Simulation::with_conditions`](crate::Simulation::with_conditions) runs them in the one
//!   step of every run ([`step`](crate::step)): fail ([`faults`]) → sense ([`noise`]) →
//!   communicate ([`history`], [`links`]) → control (the protocol's
//!   [`LocalForm`](flock_protocols::LocalForm)) → actuate ([`actuation`]) → disturb and
//!   integrate; what they carry from step to step is a [`Stage`].
//! - Every random draw is keyed by purpose, agent or link, and step ([`flock_math::stream`]), so a run is
//!   bit-identical for any thread count and after a resume from a [`ConditionsState`]
//!   ([`checkpoint`]).
//! - [`bytes_per_agent`]: the memory the conditions keep per agent (mostly the delay line,
//!   [`delay_line_bytes_per_agent`]).

pub mod actuation;
pub mod checkpoint;
pub mod config;
pub mod faults;
pub mod history;
pub mod links;
pub mod noise;
pub mod stage;

pub use checkpoint::{ConditionsState, LinkState};
pub use config::{
    Actuation, Communication, Conditions, Delayed, Disturbance, Failure, FaultMode, Faults, Loss,
    Noise, SampledControl, Sensing, WhenLost, Wind,
};
pub use stage::{Stage, bytes_per_agent, delay_line_bytes_per_agent};

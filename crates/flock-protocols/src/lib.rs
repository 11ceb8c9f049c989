//! Flocking protocols as implementations of one [`Protocol`] trait, and their time integration.
//!
//! - [`Algorithm1`], [`Algorithm2`]: Olfati-Saber, IEEE TAC 51(3) 2006, Algorithms 1 and 2, built on
//!   the [`AlphaInteraction`] (eq. 23) and [`NavigationalFeedback`] to a [`GammaAgent`].
//! - [`Simulation`]: fixed-step [`Integrator`]s (symplectic Euler by default, RK4) that rebuild the
//!   proximity net at every evaluation.
//! - [`Swarm`]: positions and velocities of n double integrators.

pub mod alpha;
pub mod gamma;
pub mod integrator;
pub mod olfati_saber2006;
pub mod protocol;
pub mod swarm;

pub use alpha::{AlphaInteraction, AlphaParams};
pub use gamma::{Feedback, GammaAgent, NavigationalFeedback, Path};
pub use integrator::{Integrator, Simulation};
pub use olfati_saber2006::{Algorithm1, Algorithm2};
pub use protocol::Protocol;
pub use swarm::Swarm;

//! Flocking protocols as implementations of one [`Protocol`] trait, and their time integration.
//!
//! - [`Algorithm1`], [`Algorithm2`], [`Algorithm3`]: Olfati-Saber, IEEE TAC 51(3) 2006, built on the
//!   [`AlphaInteraction`] (eq. 23), the [`BetaInteraction`] with obstacles (eq. 67) and the
//!   [`NavigationalFeedback`] to a [`GammaAgent`].
//! - [`AlphaAlpha`] ((α,α,1), (α,α,2) and its approximation, CDS 03-006 2003 eq. 34–36),
//!   [`StressForm`] (ACC 2004 eq. 39), [`Flocking2003`] with a sink, [`ObstacleFlocking2003`]
//!   (eq. 54–58) and [`TannerJadbabaiePappas`] (Tanner, Jadbabaie & Pappas 2003, eq. 5).
//! - [`Simulation`]: fixed-step [`Integrator`]s (symplectic Euler by default, RK4) that rebuild the
//!   proximity net at every evaluation.
//! - [`Swarm`]: positions and velocities of n double integrators.

pub mod alpha;
pub mod beta;
pub mod gamma;
pub mod integrator;
pub mod olfati_saber2003;
pub mod olfati_saber2003_tracking;
pub mod olfati_saber2004;
pub mod olfati_saber2006;
pub mod protocol;
pub mod swarm;
pub mod tanner2003;

pub use alpha::{AlphaInteraction, AlphaParams};
pub use beta::{BetaInteraction, BetaParams};
pub use gamma::{Feedback, GammaAgent, NavigationalFeedback, Path};
pub use integrator::{Integrator, Simulation};
pub use olfati_saber2003::{
    AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, BallObstacle, Flocking2003, ObstacleFlocking2003,
    ObstacleParams, influence_map_lipschitz,
};
pub use olfati_saber2003_tracking::{CentralisedTracking2003, TranslationalController};
pub use olfati_saber2004::StressForm;
pub use olfati_saber2006::{Algorithm1, Algorithm2, Algorithm3};
pub use protocol::Protocol;
pub use swarm::Swarm;
pub use tanner2003::{
    DisconnectedGraph, SplitMix64, TannerJadbabaiePappas, random_connected_graph,
};

//! Flocking protocols as implementations of one [`Protocol`] trait: each law computes u_i from
//! what agent i perceives (its [`LocalForm`], over [`Perceived`] states) or from the whole state.
//! The loop that runs them in time — the step, its real conditions, vehicles and integrators — is
//! the crate `flock-sim`.
//!
//! - [`Algorithm1`], [`Algorithm2`], [`Algorithm3`]: Olfati-Saber, IEEE TAC 51(3) 2006, built on the
//!   [`AlphaInteraction`] (eq. 23), the [`BetaInteraction`] with obstacles (eq. 67) and the
//!   [`NavigationalFeedback`] to a [`GammaAgent`].
//! - [`AlphaAlpha`] ((α,α,1), (α,α,2) and its approximation, CDS 03-006 2003 eq. 34–36),
//!   [`StressForm`] (ACC 2004 eq. 39), its reading as Reynolds's three rules
//!   ([`AlphaAlpha::reynolds_reading`], ACC 2004 § 4: [`AgentReading`], [`StressRegime`]),
//!   [`Flocking2003`] with a sink, [`ObstacleFlocking2003`]
//!   (eq. 54–58) and [`TannerJadbabaiePappas`] (Tanner, Jadbabaie & Pappas 2003, eq. 5).
//! - [`Consensus`]: velocity matching (seed 000 eq. 9) on a fixed graph or the proximity net.
//! - The classic models: [`CuckerSmale`] (Cucker & Smale 2007), [`Vicsek`] (Vicsek et al. 1995),
//!   [`Boids`] (Reynolds 1987, as the ABM frameworks' benchmark declares it) and [`Couzin`]
//!   (Couzin et al. 2002); the last three set velocities with their own [`Update`]. [`Vasarhelyi`]
//!   (Vásárhelyi et al. 2018, the drones' model) tracks its desired velocity as an acceleration.
//! - [`Swarm`]: positions and velocities of n double integrators.
//! - [`AlphaConfig`], [`BetaConfig`], [`AvoidanceGains`]: parameters as a scenario writes them,
//!   with the papers' defaults; [`ParamError`] names a parameter outside its domain.
//!
//! Features: `parallel` (default; rayon, bit-identical results for any thread count),
//! `obstacles` (default; Algorithm 3 and the 2003 obstacle protocol, through flock-obstacles and
//! parry), `serde` (the parameter types read and written as the `flocking` crate's scenarios).

pub mod alpha;
#[cfg(feature = "obstacles")]
pub mod beta;
pub mod consensus;
pub mod couzin2002;
pub mod cucker_smale2007;
pub mod error;
pub mod gamma;
pub mod olfati_saber2003;
#[cfg(feature = "obstacles")]
pub mod olfati_saber2003_tracking;
pub mod olfati_saber2004;
pub mod olfati_saber2004_reynolds;
pub mod olfati_saber2006;
pub mod protocol;
pub mod reynolds1987;
pub mod swarm;
pub mod tanner2003;
pub mod vasarhelyi2018;
pub mod vicsek1995;

pub use alpha::{AlphaConfig, AlphaInteraction, AlphaParams};
#[cfg(feature = "obstacles")]
pub use beta::{BetaConfig, BetaInteraction, BetaParams};
pub use consensus::Consensus;
pub use couzin2002::{Blend, BlindCone, CollectiveState, Couzin, CouzinParams};
pub use cucker_smale2007::{CuckerSmale, CuckerSmaleParams};
pub use error::{ParamError, check, plain_value};
pub use gamma::{
    Feedback, GAMMA_POSITION_ERROR, GAMMA_VELOCITY_ERROR, GammaAgent, NavigationalFeedback,
    critical_damping,
};
pub use olfati_saber2003::{
    AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, AvoidanceGains, Flocking2003, ObstacleParams,
    influence_map_lipschitz,
};
#[cfg(feature = "obstacles")]
pub use olfati_saber2003::{BallObstacle, ObstacleFlocking2003};
#[cfg(feature = "obstacles")]
pub use olfati_saber2003_tracking::{CentralisedTracking2003, TranslationalController};
pub use olfati_saber2004::StressForm;
pub use olfati_saber2004_reynolds::{
    AgentReading, NEUTRAL_STRESS, RegimeCounts, ReynoldsRules, StressRegime,
};
#[cfg(feature = "obstacles")]
pub use olfati_saber2006::Algorithm3;
pub use olfati_saber2006::{Algorithm1, Algorithm2};
pub use protocol::{DynProtocol, LocalForm, Perceived, Perceptions, Protocol, Update};
pub use reynolds1987::{Boids, BoidsParams};
pub use swarm::Swarm;
pub use tanner2003::{
    DisconnectedGraph, SplitMix64, TannerJadbabaiePappas, random_connected_graph,
};
pub use vasarhelyi2018::{Arena, ArenaShape, Vasarhelyi, VasarhelyiParams};
pub use vicsek1995::{Vicsek, VicsekParams, planar};

//! Numerical health of a run: after every step, each agent's position and velocity must be finite
//! and no agent may move farther than the interaction range r in one step (a runaway: the net can
//! no longer resolve its neighbours, and an explicit integrator has left its stability region).

use std::fmt;

use flock_graph::Numbering;
use flock_math::Vector;
use flock_protocols::Swarm;
use rayon::prelude::*;

use crate::scenario::Scenario;
use crate::stability::largest_stable_step;

/// What went wrong with one agent.
#[derive(Clone, Debug, PartialEq)]
pub enum Fault {
    /// A coordinate of the position or the velocity is NaN or ±∞.
    NotFinite {
        /// `"position"` or `"velocity"`.
        quantity: &'static str,
        /// The vector, as printed.
        value: String,
    },
    /// ‖p_i‖ h > r: the agent crosses more than an interaction range per step.
    Runaway {
        /// ‖p_i‖.
        speed: f64,
        /// r / h, the largest speed the step resolves.
        limit: f64,
    },
}

/// A numerical blow-up: the step, the first agent (lowest index) at fault and the likely cause.
#[derive(Clone, Debug, PartialEq)]
pub struct NumericalError {
    /// The step after which the state is bad (1-based: the state after `steps` steps).
    pub steps: u64,
    /// Its time t = steps · h.
    pub t: f64,
    /// The agent.
    pub agent: usize,
    /// What is wrong with it.
    pub fault: Fault,
    /// The likely cause and its fix.
    pub cause: String,
}

impl fmt::Display for NumericalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "numerical blow-up at step {} (t = {}): agent {} ",
            self.steps, self.t, self.agent
        )?;
        match &self.fault {
            Fault::NotFinite { quantity, value } => {
                write!(f, "has a non-finite {quantity} {value}")?;
            }
            Fault::Runaway { speed, limit } => write!(
                f,
                "runs away at speed {speed:.6e}, above r/h = {limit:.6e} (it would cross more than the interaction range in one step)"
            )?,
        }
        write!(f, ". Likely cause: {}", self.cause)
    }
}

impl std::error::Error for NumericalError {}

/// The health check run after every step.
#[derive(Debug)]
pub struct Health;

impl Health {
    /// Checks the state of `scenario` after `steps` steps, `swarm` stored as `numbering` says
    /// (errors name the agent's original index).
    ///
    /// # Errors
    /// The first agent whose position or velocity is not finite, or whose speed exceeds r/h.
    pub fn check<V: Vector>(
        scenario: &Scenario,
        steps: u64,
        swarm: &Swarm<V>,
        numbering: &Numbering,
    ) -> Result<(), NumericalError> {
        let h = scenario.step;
        let limit = scenario.range() / h;
        let limit_squared = limit * limit;
        // In parallel, but always the agent at fault of lowest original index.
        let fault = swarm
            .positions
            .par_iter()
            .zip(&swarm.velocities)
            .enumerate()
            .filter_map(|(i, (&q, &p))| {
                let fault = if !q.is_finite() {
                    Fault::NotFinite {
                        quantity: "position",
                        value: format!("{q:?}"),
                    }
                } else if !p.is_finite() {
                    Fault::NotFinite {
                        quantity: "velocity",
                        value: format!("{p:?}"),
                    }
                } else if p.length_squared() > limit_squared {
                    Fault::Runaway {
                        speed: p.length(),
                        limit,
                    }
                } else {
                    return None;
                };
                Some((numbering.original(i), fault))
            })
            .min_by_key(|&(agent, _)| agent);
        match fault {
            None => Ok(()),
            Some((agent, fault)) => Err(NumericalError {
                steps,
                t: steps as f64 * h,
                agent,
                fault,
                cause: likely_cause(scenario),
            }),
        }
    }
}

/// The step against the estimated stability limit, else the gains.
fn likely_cause(scenario: &Scenario) -> String {
    let h = scenario.step;
    match largest_stable_step(scenario) {
        Some(stable) if h > stable => format!(
            "the step h = {h} exceeds the largest stable step ≈ {stable:.3e} estimated from the stiffness of the potential; set `step` to at most {stable:.3e}"
        ),
        Some(stable) => format!(
            "the forces grew beyond what the step resolves although h = {h} is below the estimated stable step ≈ {stable:.3e} (agents driven together, e.g. by strong navigation or obstacle gains); lower `step` or the gains c1"
        ),
        None => format!(
            "the forces grew beyond what the step h = {h} resolves (agents driven together, where the potential is stiffest); lower `step` or the gains"
        ),
    }
}

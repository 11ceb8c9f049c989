//! The numerical health of a simulated state ([`Simulation::check_health`](crate::Simulation::check_health)):
//! each agent's position and velocity must be finite and no agent may move farther than the
//! interaction range r in one step h (a runaway: the net can no longer resolve its neighbours,
//! and an explicit integrator has left its stability region).

use core::fmt;

use flock_graph::Numbering;
use flock_math::Vector;
use flock_math::parallel::map_chunks;

use flock_protocols::Swarm;

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

/// The first agent at fault (lowest original index) and its fault.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentFault {
    /// The agent's original index.
    pub agent: usize,
    /// What is wrong with it.
    pub fault: Fault,
}

impl fmt::Display for AgentFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "agent {} ", self.agent)?;
        match &self.fault {
            Fault::NotFinite { quantity, value } => {
                write!(f, "has a non-finite {quantity} {value}")
            }
            Fault::Runaway { speed, limit } => write!(
                f,
                "runs away at speed {speed:.6e}, above r/h = {limit:.6e} (it would cross more than the interaction range in one step)"
            ),
        }
    }
}

impl std::error::Error for AgentFault {}

/// Agents per parallel chunk of the check.
const CHUNK: usize = 8192;

/// The fault of lowest original index of a state stored as `numbering` says, with `limit` the
/// largest speed allowed (r / h); `None` when every agent is healthy.
pub(crate) fn first_fault<V: Vector>(
    swarm: &Swarm<V>,
    numbering: &Numbering,
    limit: f64,
) -> Option<AgentFault> {
    let limit_squared = limit * limit;
    let fault_of = |q: V, p: V| {
        if !q.is_finite() {
            Some(Fault::NotFinite {
                quantity: "position",
                value: format!("{q:?}"),
            })
        } else if !p.is_finite() {
            Some(Fault::NotFinite {
                quantity: "velocity",
                value: format!("{p:?}"),
            })
        } else if p.length_squared() > limit_squared {
            Some(Fault::Runaway {
                speed: p.length(),
                limit,
            })
        } else {
            None
        }
    };
    // in parallel chunks, but always the agent at fault of lowest original index
    map_chunks(swarm.len(), CHUNK, |stored| {
        stored
            .filter_map(|s| {
                let fault = fault_of(swarm.positions[s], swarm.velocities[s])?;
                Some(AgentFault {
                    agent: numbering.original(s),
                    fault,
                })
            })
            .min_by_key(|f| f.agent)
    })
    .into_iter()
    .flatten()
    .min_by_key(|f| f.agent)
}

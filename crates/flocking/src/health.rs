//! [`NumericalError`]: a run's state blew up — the step, the agent, what is wrong with it
//! ([`Simulation::check_health`](flock_sim::Simulation::check_health)) and the likely cause,
//! from the stable-step estimate ([`largest_stable_step`]).

use std::fmt;

use flock_sim::AgentFault;

use crate::scenario::Scenario;
use crate::stability::largest_stable_step;
use crate::time::time_text;

pub use flock_sim::Fault;

/// A numerical blow-up: the step, the first agent (lowest index) at fault and the likely cause.
#[derive(Clone, Debug, PartialEq)]
pub struct NumericalError {
    /// The step after which the state is bad (the state after `steps` steps).
    pub steps: u64,
    /// Its time t = steps · h.
    pub t: f64,
    /// The step h, which fixes how many decimals of t are printed.
    pub step: f64,
    /// The agent (original index) and what is wrong with it.
    pub fault: AgentFault,
    /// The likely cause and its fix.
    pub cause: String,
}

impl NumericalError {
    /// The blow-up `fault` of `scenario` after `steps` steps, at time `t`, with its likely cause.
    #[must_use]
    pub fn new(scenario: &Scenario, steps: u64, t: f64, fault: AgentFault) -> Self {
        Self {
            steps,
            t,
            step: scenario.step,
            fault,
            cause: likely_cause(scenario),
        }
    }
}

impl fmt::Display for NumericalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "numerical blow-up at step {} (t = {}): {}. Likely cause: {}",
            self.steps,
            time_text(self.t, self.step),
            self.fault,
            self.cause
        )
    }
}

impl std::error::Error for NumericalError {}

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

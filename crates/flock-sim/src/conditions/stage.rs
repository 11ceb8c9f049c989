//! The state the real conditions carry from step to step ([`Stage`]), agent by agent, and what
//! they cost in memory ([`bytes_per_agent`]). The step that runs them is the simulation's own
//! ([`Simulation::step`](crate::Simulation::step)): each stage of it finds here what it keeps
//! (the failed agents, the delay line, the links, the delivered accelerations, the gusts).

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::Vector;
use flock_math::stream::Streams;

use super::actuation::Lag;
use super::config::{Conditions, FaultMode, Loss, Noise, WhenLost, period_steps, whole_steps};
use super::faults;
use super::history::History;
use super::links::Link;
use super::noise::{OrnsteinUhlenbeck, SensorNoise};
use crate::checks::perception_field;
use crate::permutation::permute_in_place;
use flock_protocols::ParamError;

/// The readings of the last step, for the diagnostics columns.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Readings {
    /// The fraction of candidate links lost at the last control update.
    pub links_lost: f64,
    /// The mean age (s) of the neighbour states used at the last control update.
    pub information_age: f64,
    /// Agents whose commanded acceleration was clipped at the last step.
    pub at_acceleration_limit: f64,
    /// Agents whose speed was clipped at the last step.
    pub at_speed_limit: f64,
}

/// The conditions of a run and everything they carry from step to step, agent by agent in the
/// order the simulation stores them (by cell when they were numbered at random: the net's
/// [`Numbering`](flock_graph::Numbering)). Every draw is keyed by original indices and every list is in ascending
/// original index, so the bits do not depend on that order; each re-sort moves the state
/// with the agents.
#[derive(Debug)]
pub struct Stage<V> {
    pub(crate) conditions: Conditions,
    pub(crate) streams: Streams,
    pub(crate) h: f64,
    pub(crate) delay: u64,
    pub(crate) jitter: u64,
    pub(crate) sensor_period: u64,
    pub(crate) control_period: u64,
    /// Whether a condition changes what agents perceive: the local path.
    pub(crate) perceives: bool,
    /// A communication range other than the interaction range, for which a net is built.
    pub(crate) own_range: Option<f64>,
    pub(crate) sensor: Option<SensorNoise>,
    pub(crate) lag: Option<Lag>,
    pub(crate) gusts: Option<OrnsteinUhlenbeck>,
    // the state carried between steps (checkpointed)
    pub(crate) started: bool,
    pub(crate) noise: Vec<(V, V)>,
    /// The measured states of the last D + 1 steps, the newest the current one (no agent's
    /// when no condition changes perception).
    pub(crate) history: History<V>,
    /// What each receiver keeps of its links (empty when links keep nothing).
    pub(crate) links: Vec<Vec<Link<V>>>,
    pub(crate) delivered: Vec<V>,
    pub(crate) gust: Vec<V>,
    pub(crate) failed: Vec<bool>,
    pub(crate) readings: Readings,
    // scratch
    pub(crate) search: NeighbourSearch,
    pub(crate) net: ProximityNet,
}

/// The longest delay D (delay + jitter) in steps of `conditions` at step `h` (0 without
/// communication).
///
/// # Errors
/// A delay or jitter that is not a whole number of steps.
pub fn depth(conditions: &Conditions, h: f64) -> Result<u64, ParamError> {
    Ok(match &conditions.communication {
        Some(c) => whole_steps("delay", c.delay, h)? + whole_steps("jitter", c.jitter, h)?,
        None => 0,
    })
}

/// The bytes per agent that `conditions` keep in a `dim`-dimensional run at step `h`, as
/// [`Stage::new`] allocates them: the delay line (D + 1 measured states of 2·dim f64, the newest
/// the current one, when a condition changes perception, else none), the Ornstein–Uhlenbeck
/// sensor offsets, the input (and apart from it the delivered acceleration with a lag or sampled
/// control), per-agent gusts, the failure flag,
/// and each receiver's list of links (its entries not counted: ≤ one per neighbour) for
/// Gilbert–Elliott loss or `Hold`.
#[must_use]
pub fn bytes_per_agent(conditions: &Conditions, dim: usize, h: f64) -> usize {
    if conditions.is_ideal() {
        return 0;
    }
    let vector = dim * 8;
    let ornstein_uhlenbeck = conditions
        .sensing
        .is_some_and(|s| matches!(s.noise, Noise::OrnsteinUhlenbeck { .. }));
    let gusts = conditions
        .disturbance
        .as_ref()
        .and_then(|d| d.wind.as_ref())
        .is_some_and(|w| w.gust > 0.0 && w.per_agent);
    let links = keeps_links(conditions);
    delay_line_bytes_per_agent(conditions, dim, h)
        + usize::from(ornstein_uhlenbeck) * 2 * vector
        + (1 + usize::from(holds_delivered(conditions)) + usize::from(gusts)) * vector
        + 1
        + usize::from(links) * size_of::<Vec<Link<V0>>>()
}

/// The part of [`bytes_per_agent`] that the delay line holds: D + 1 measured states of 2·dim
/// f64 (D the delay and jitter in steps) when a condition changes perception, else none.
#[must_use]
pub fn delay_line_bytes_per_agent(conditions: &Conditions, dim: usize, h: f64) -> usize {
    if conditions.is_ideal() || perception_field(conditions).is_none() {
        return 0;
    }
    (depth(conditions, h).unwrap_or(0) as usize + 1) * 2 * dim * 8
}

/// Whether the delivered accelerations are kept apart from the commanded inputs: with a lag
/// (its state), or with sampled control (the input is held, clipped afresh at each step).
pub(crate) fn holds_delivered(conditions: &Conditions) -> bool {
    conditions.actuation.and_then(|a| a.lag).is_some() || conditions.control.is_some()
}

/// A vector type for the size of a list of links (a `Vec`'s size does not depend on it).
type V0 = glam::DVec2;

/// Whether receivers keep a state per link: for Gilbert–Elliott loss or `Hold` when lost.
pub(crate) fn keeps_links(conditions: &Conditions) -> bool {
    conditions.communication.is_some_and(|m| {
        matches!(m.loss, Loss::GilbertElliott { .. })
            || matches!(m.when_lost, WhenLost::Hold { .. })
    })
}

impl<V: Vector> Stage<V> {
    /// The stage of `conditions` (validated) for `n` agents at step `h`, with `seed`; `range` is
    /// the protocol's interaction range.
    ///
    /// # Errors
    /// As [`Conditions::validate`].
    pub fn new(
        conditions: &Conditions,
        seed: u64,
        n: usize,
        h: f64,
        range: f64,
    ) -> Result<Self, ParamError> {
        conditions.validate(n, V::DIM, h)?;
        let c = conditions;
        let (delay, jitter) = match &c.communication {
            Some(m) => (
                whole_steps("delay", m.delay, h)?,
                whole_steps("jitter", m.jitter, h)?,
            ),
            None => (0, 0),
        };
        let sensor_period = match c.sensing.as_ref().and_then(|s| s.rate) {
            Some(rate) => period_steps("rate", rate, h)?,
            None => 1,
        };
        let control_period = match &c.control {
            Some(s) => period_steps("rate", s.rate, h)?,
            None => 1,
        };
        let own_range = c
            .communication
            .and_then(|m| m.range)
            .filter(|&r| r != range);
        let wind = c.disturbance.as_ref().and_then(|d| d.wind.as_ref());
        let gusts = wind
            .filter(|w| w.gust > 0.0)
            .map(|w| OrnsteinUhlenbeck::new(w.gust, w.correlation_time, h));
        let gust_count = match wind {
            Some(w) if w.gust > 0.0 => {
                if w.per_agent {
                    n
                } else {
                    1
                }
            }
            _ => 0,
        };
        let perceives = perception_field(c).is_some();
        let sensor = c
            .sensing
            .map(|s| SensorNoise::new(&s.noise, sensor_period as f64 * h));
        // receivers keep a state per link for Gilbert–Elliott loss or `Hold`: none otherwise
        let keeps_links = keeps_links(c);
        let (depth, agents) = if perceives {
            (delay + jitter, n)
        } else {
            (0, 0)
        };
        // an error, not an abort, when the delay line cannot be had (issue 49)
        let history = History::new(depth, agents).map_err(|_| {
            let bytes = n as u64 * delay_line_bytes_per_agent(c, V::DIM, h) as u64;
            ParamError::out_of_memory(
                "conditions.communication.delay",
                c.communication.map_or(0.0, |m| m.delay),
                (
                    "the delay line (every agent's states over the delay and jitter)",
                    bytes,
                ),
                "a shorter delay (or jitter), or fewer agents",
            )
        })?;
        Ok(Self {
            conditions: c.clone(),
            streams: Streams::new(seed),
            h,
            delay,
            jitter,
            sensor_period,
            control_period,
            perceives,
            own_range,
            sensor,
            lag: c.actuation.and_then(|a| a.lag).map(|tau| Lag::new(tau, h)),
            gusts,
            started: false,
            // white noise is drawn afresh at each update: only Ornstein–Uhlenbeck offsets are kept
            noise: vec![
                (V::ZERO, V::ZERO);
                if matches!(sensor, Some(SensorNoise::OrnsteinUhlenbeck { .. })) {
                    n
                } else {
                    0
                }
            ],
            history,
            links: vec![Vec::new(); if keeps_links { n } else { 0 }],
            delivered: vec![V::ZERO; if holds_delivered(c) { n } else { 0 }],
            gust: vec![V::ZERO; gust_count],
            failed: vec![false; n],
            readings: Readings::default(),
            search: NeighbourSearch::new(),
            net: ProximityNet::without_distances(),
        })
    }

    /// Whether step `k` is a control update (every step, but every control period under sampled
    /// control).
    pub(crate) fn controls_at(&self, k: u64) -> bool {
        k.is_multiple_of(self.control_period)
    }

    /// The conditions.
    #[must_use]
    pub const fn conditions(&self) -> &Conditions {
        &self.conditions
    }

    fn mode(&self) -> FaultMode {
        self.conditions
            .faults
            .as_ref()
            .map_or(FaultMode::Removed, |f| f.mode)
    }

    /// Whether agent `i` computes and receives an input (working, or failed silent).
    pub(crate) fn moves(&self, i: usize) -> bool {
        !self.failed[i] || faults::moves(self.mode())
    }

    /// Whether the others hear agent `j` (working, or failed frozen).
    pub(crate) fn is_heard(&self, j: usize) -> bool {
        !self.failed[j] || faults::heard(self.mode())
    }

    /// Which agents have failed (in storage order), when the conditions have `faults`: the
    /// `failed` column of the trajectory and `final.csv` once in original order
    /// ([`Simulation::failed`](crate::Simulation::failed)), whose sum is the `failed` diagnostic.
    #[must_use]
    pub fn failed(&self) -> Option<&[bool]> {
        self.conditions.faults.is_some().then_some(&self.failed[..])
    }

    /// The agents removed from the run (failed in mode `Removed`; in storage order), if any.
    #[must_use]
    pub fn removed(&self) -> Option<&[bool]> {
        (self.mode() == FaultMode::Removed && self.failed.iter().any(|&f| f))
            .then_some(&self.failed[..])
    }

    /// Whether each agent has a gust of its own (else one gust is shared, or there is none).
    pub(crate) fn gusts_per_agent(&self) -> bool {
        self.gust.len() > 1
    }

    /// Moves each agent's state with the agents: what agent `from(s)` carried goes to index s,
    /// for every s (`from` a permutation of the agents). The delay line, the sensor offsets,
    /// the links kept, the delivered accelerations, per-agent gusts and the failure
    /// flags move, each in place (no array is held twice); what is shared or drawn afresh does
    /// not. Before the first step every agent carries the same (zero) state: nothing moves.
    pub(crate) fn permute(&mut self, from: impl Fn(usize) -> usize + Copy) {
        if !self.started {
            return;
        }
        for (q, p) in &mut self.history.slots {
            permute_in_place(q, from);
            permute_in_place(p, from);
        }
        permute_in_place(&mut self.delivered, from);
        if self.gusts_per_agent() {
            permute_in_place(&mut self.gust, from);
        }
        permute_in_place(&mut self.noise, from);
        permute_in_place(&mut self.links, from);
        permute_in_place(&mut self.failed, from);
    }

    /// The diagnostics columns of the conditions that are on, the same at every record.
    #[must_use]
    pub fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        let c = &self.conditions;
        let r = &self.readings;
        let mut columns = Vec::new();
        if c.communication.is_some() {
            columns.push(("links_lost", r.links_lost));
            columns.push(("information_age", r.information_age));
        }
        if let Some(a) = &c.actuation {
            if a.max_acceleration.is_some() {
                columns.push(("at_acceleration_limit", r.at_acceleration_limit));
            }
            if a.max_speed.is_some() {
                columns.push(("at_speed_limit", r.at_speed_limit));
            }
        }
        if c.faults.is_some() {
            let failed = self.failed.iter().filter(|&&f| f).count();
            columns.push(("failed", failed as f64));
        }
        columns
    }
}

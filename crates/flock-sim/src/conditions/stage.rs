//! The conditioned step, in the order a vehicle lives it: **fail → sense → communicate →
//! control → actuate → disturb and integrate** ([`Stage::step`]). The protocols take no part but
//! to compute u_i from what agent i perceives ([`LocalForm`]), or, when no condition changes
//! what agents perceive, from the true state ([`Protocol::controls`]).

use flock_graph::{NeighbourSearch, Numbering, ProximityNet};
use flock_math::interrupt::cuts_short;
use flock_math::{Domain, Vector};

use super::actuation::{Lag, clip};
use super::config::{
    Conditions, Delayed, FaultMode, Loss, Noise, WhenLost, period_steps, whole_steps,
};
use super::faults;
use super::history::{History, Slot};
use super::links::{Held, Link, lost};
use super::noise::{OrnsteinUhlenbeck, SensorNoise};
use crate::Integrator;
use crate::permutation::permute_in_place;
use crate::simulation::{advance, controls_in};
use crate::vehicle::{Fleet, VehicleKind};
use flock_math::stream::{Purpose, Streams, link_word_count, word_uniform, word_up_to};
use flock_protocols::error::ParamError;
use flock_protocols::{LocalForm, Perceived, Perceptions, Protocol, Swarm, Update};

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
/// [`Numbering`]). Every draw is keyed by original indices and every list is in ascending
/// original index, so the bits do not depend on that order; each re-sort moves the state
/// with the agents.
#[derive(Debug)]
pub struct Stage<V> {
    pub(crate) conditions: Conditions,
    pub(crate) streams: Streams,
    h: f64,
    delay: u64,
    jitter: u64,
    sensor_period: u64,
    control_period: u64,
    /// Whether a condition changes what agents perceive: the local path.
    perceives: bool,
    /// A communication range other than the interaction range, for which a net is built.
    own_range: Option<f64>,
    sensor: Option<SensorNoise>,
    lag: Option<Lag>,
    gusts: Option<OrnsteinUhlenbeck>,
    // the state carried between steps (checkpointed)
    pub(crate) started: bool,
    pub(crate) noise: Vec<(V, V)>,
    /// The measured states of the last D + 1 steps, the newest the current one (no agent's
    /// when no condition changes perception).
    pub(crate) history: History<V>,
    /// What each receiver keeps of its links (empty when links keep nothing).
    pub(crate) links: Vec<Vec<Link<V>>>,
    pub(crate) inputs: Vec<V>,
    pub(crate) delivered: Vec<V>,
    pub(crate) gust: Vec<V>,
    pub(crate) failed: Vec<bool>,
    pub(crate) readings: Readings,
    // scratch
    search: NeighbourSearch,
    net: ProximityNet,
}

/// The field of a condition that acts on an acceleration (actuation limits and lag, wind,
/// process noise), which a model that sets velocities cannot take.
#[must_use]
pub fn acceleration_field(conditions: &Conditions) -> Option<&'static str> {
    if conditions.actuation.is_some() {
        Some("conditions.actuation")
    } else if conditions.disturbance.is_some() {
        Some("conditions.disturbance")
    } else {
        None
    }
}

/// Refuses the conditions a `vehicle` cannot take: a disturbance for a vehicle that takes no
/// external acceleration, and a speed limit, which the vehicle's own limits replace.
///
/// # Errors
/// The field of the condition refused.
pub fn check_vehicle(conditions: &Conditions, vehicle: &dyn VehicleKind) -> Result<(), ParamError> {
    if conditions.disturbance.is_some() && !vehicle.takes_disturbance() {
        return Err(ParamError::new(
            "conditions.disturbance",
            "set",
            format!(
                "is an external acceleration, and a {} takes none on its reference point",
                vehicle.name()
            ),
            "remove the disturbance for this vehicle, or use one that takes it (PointMass, Quadrotor)",
        ));
    }
    if conditions.actuation.and_then(|a| a.max_speed).is_some() {
        return Err(ParamError::new(
            "conditions.actuation.max_speed",
            "set",
            format!(
                "clips a point mass's speed; a {}'s own limits bound its speed",
                vehicle.name()
            ),
            "remove max_speed and set the vehicle's speed limits",
        ));
    }
    Ok(())
}

/// Whether `conditions` change what agents perceive (their own or others' states), and the
/// field that does.
#[must_use]
pub fn perception_field(conditions: &Conditions) -> Option<&'static str> {
    if conditions.communication.is_some() {
        Some("conditions.communication")
    } else if conditions.sensing.is_some() {
        Some("conditions.sensing")
    } else {
        match &conditions.faults {
            Some(f) if f.mode != FaultMode::Frozen => Some("conditions.faults.mode"),
            _ => None,
        }
    }
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
fn holds_delivered(conditions: &Conditions) -> bool {
    conditions.actuation.and_then(|a| a.lag).is_some() || conditions.control.is_some()
}

/// A vector type for the size of a list of links (a `Vec`'s size does not depend on it).
type V0 = glam::DVec2;

/// Whether receivers keep a state per link: for Gilbert–Elliott loss or `Hold` when lost.
fn keeps_links(conditions: &Conditions) -> bool {
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
            inputs: vec![V::ZERO; n],
            delivered: vec![V::ZERO; if holds_delivered(c) { n } else { 0 }],
            gust: vec![V::ZERO; gust_count],
            failed: vec![false; n],
            readings: Readings::default(),
            search: NeighbourSearch::new(),
            net: ProximityNet::without_distances(),
        })
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
    fn moves(&self, i: usize) -> bool {
        !self.failed[i] || faults::moves(self.mode())
    }

    /// Whether the others hear agent `j` (working, or failed frozen).
    fn is_heard(&self, j: usize) -> bool {
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
    /// the links kept, the inputs and delivered accelerations, per-agent gusts and the failure
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
        permute_in_place(&mut self.inputs, from);
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

    /// One step h from step `k` of the true state `swarm` whose proximity net is `net` (agents
    /// stored as its numbering says): fail → sense → communicate → control → actuate → disturb
    /// and integrate; with a `fleet`, its vehicles follow the delivered accelerations under the
    /// disturbance.
    #[allow(clippy::too_many_arguments)]
    pub fn step<P: Protocol<V> + ?Sized>(
        &mut self,
        protocol: &P,
        domain: &Domain<V>,
        swarm: &mut Swarm<V>,
        net: &ProximityNet,
        k: u64,
        integrator: Integrator,
        fleet: Option<&mut Fleet<V>>,
    ) {
        let numbering = net.numbering();
        if let Some(f) = &self.conditions.faults {
            faults::update(f, &self.streams, k, self.h, numbering, &mut self.failed);
        }
        if self.perceives {
            self.sense(swarm, numbering, k);
        }
        if k.is_multiple_of(self.control_period) {
            match protocol.local_form().filter(|_| self.perceives) {
                Some(local) => self.communicate_and_control(protocol, local, domain, swarm, net, k),
                None => {
                    let t = k as f64 * self.h;
                    controls_in(protocol, domain, t, swarm, net, &mut self.inputs);
                }
            }
            for i in 0..self.inputs.len() {
                if !self.moves(i) {
                    self.inputs[i] = V::ZERO;
                }
            }
        }
        self.actuate();
        match (protocol.update(), fleet) {
            (Update::Acceleration, Some(fleet)) => self.drive(fleet, swarm, domain, numbering, k),
            (Update::Acceleration, None) => {
                self.disturb_and_integrate(swarm, domain, numbering, k, integrator);
            }
            (update, _) => self.set_velocities(swarm, domain, update),
        }
        self.started = true;
    }

    /// Sense: each agent's measured state is its true state plus the sensor noise, refreshed
    /// every sensor period and held between (the true state at every step without sensing),
    /// written into the delay line's slot of step `k`; at the first step, into every slot.
    fn sense(&mut self, swarm: &Swarm<V>, numbering: &Numbering, k: u64) {
        let started = self.started;
        self.measure(swarm, numbering, k);
        if !started {
            self.history.fill_from(k);
        }
    }

    /// The measured state of step `k`, into its slot of the delay line.
    fn measure(&mut self, swarm: &Swarm<V>, numbering: &Numbering, k: u64) {
        let (slot, before) = self.history.newest(k);
        let Some(sensor) = self.sensor else {
            copy_states(slot, &swarm.positions, &swarm.velocities);
            return;
        };
        if self.started && !k.is_multiple_of(self.sensor_period) {
            // held: the state of step k − 1 (already in place when D = 0)
            if let Some(before) = before {
                copy_states(slot, &before.0, &before.1);
            }
            return;
        }
        let (started, streams) = (self.started, &self.streams);
        let (positions, velocities) = (&mut slot.0, &mut slot.1);
        let measure = |i: usize, q: &mut V, p: &mut V, previous: Option<(V, V)>| {
            let agent = numbering.original(i) as u64;
            let mut draws = streams.draws(Purpose::Sensing, agent, k);
            let (xi_q, xi_p) = (draws.normal_vector(), draws.normal_vector());
            let offsets = sensor.update(previous, xi_q, xi_p);
            *q = swarm.positions[i] + offsets.0;
            *p = swarm.velocities[i] + offsets.1;
            offsets
        };
        if self.noise.is_empty() {
            let n = positions.len();
            for_each_agent(positions, velocities, &mut vec![(); n], |i, q, p, ()| {
                measure(i, q, p, None);
                0
            });
        } else {
            for_each_agent(positions, velocities, &mut self.noise, |i, q, p, noise| {
                *noise = measure(i, q, p, started.then_some(*noise));
                0
            });
        }
    }

    /// Communicate and control: each moving agent i hears its candidates (fixed graph
    /// neighbours, within the communication range if one is given; or, for a protocol of the
    /// proximity net, the agents within the communication range, by default the interaction
    /// range, at their true positions; less the failed agents not heard), each packet delayed
    /// by τ (+ jitter), lost by the loss model, dropped or replaced by the last value received;
    /// u_i = local_input(t, own, heard), computed for [`CONTROL_BLOCK`] receivers at a time
    /// ([`LocalForm::local_inputs`]).
    fn communicate_and_control<P: Protocol<V> + ?Sized>(
        &mut self,
        protocol: &P,
        local: &dyn LocalForm<V>,
        domain: &Domain<V>,
        swarm: &Swarm<V>,
        net: &ProximityNet,
        k: u64,
    ) {
        let n = swarm.len();
        let numbering = net.numbering();
        if let Some(range) = self
            .own_range
            .filter(|_| protocol.interaction_graph().is_none())
        {
            // its lists in ascending original index, as the simulation's net lists them
            self.net.share_numbering(net);
            self.search
                .build_in(domain, &swarm.positions, range, &mut self.net);
        }
        let candidates = protocol
            .interaction_graph()
            .unwrap_or(if self.own_range.is_some() {
                self.net.graph()
            } else {
                net.graph()
            });
        let comm = self.conditions.communication.unwrap_or_default();
        let graph_range = comm
            .range
            .filter(|_| protocol.interaction_graph().is_some());
        let t = k as f64 * self.h;
        let mut links = core::mem::take(&mut self.links);
        let mut inputs = core::mem::take(&mut self.inputs);
        let this = &*self;
        // the state of the neighbours without jitter, all of the same step, and the receivers'
        // own states
        let delayed = this.history.slot(k, this.delay);
        let own_lag = if comm.delayed == Delayed::All {
            this.delay
        } else {
            0
        };
        let own_states = this.history.slot(k, own_lag);
        let all_heard = this.conditions.faults.is_none();
        let loss_by_length = matches!(comm.loss, Loss::Distance { .. });
        // a proximity net lists no agent as its own neighbour
        let unfiltered =
            all_heard && graph_range.is_none() && protocol.interaction_graph().is_none();
        let original = |j: usize| numbering.original(j) as u32;
        // the loss probability of links that are memoryless: each packet lost or not by its
        // link's own word of the step, heard as sent `delay` steps ago, nothing kept of the link
        let memoryless = match comm.loss {
            Loss::None => Some(0.0),
            Loss::Bernoulli { p } => Some(p),
            Loss::Distance { .. } | Loss::GilbertElliott { .. } => None,
        }
        .filter(|_| this.jitter == 0 && !comm.symmetric && !keeps_links(&this.conditions));
        // the words of the jitter and loss draws of the links into the moving receivers of
        // `block`, into `words`, receiver after receiver (the candidates of each counted before
        // any leaves the list: the first words are the same); a purpose not drawn leaves its
        // words empty
        let draw_words = |block: core::ops::Range<usize>, words: &mut [Vec<u32>; 2]| {
            let receivers = block
                .filter(|&i| this.moves(i))
                .map(|i| (u64::from(original(i)), candidates.neighbours(i).len()));
            let [jitter_words, loss_words] = words;
            for (purpose, drawn, words) in [
                (Purpose::Jitter, this.jitter > 0, jitter_words),
                (Purpose::Loss, comm.loss_per_link(), loss_words),
            ] {
                words.clear();
                if drawn {
                    this.streams
                        .link_words(purpose, k, receivers.clone(), words);
                }
            }
        };
        // receiver i's own perceived state and what it hears, appended to `heard`: candidates,
        // each packet delayed, lost, dropped or replaced by the last value received
        let receive = |i: usize,
                       mut links_i: Option<&mut Vec<Link<V>>>,
                       js: &mut Vec<u32>,
                       [jitter_words, loss_words]: [&[u32]; 2],
                       old: &mut Vec<Link<V>>,
                       heard: &mut Vec<Perceived<V>>| {
            let own = Perceived {
                agent: original(i),
                position: own_states.0[i],
                velocity: own_states.1[i],
            };
            // the candidates heard, in ascending original index (a net's and a graph's lists
            // are): the list itself unless
            // failed agents or a communication range leave some out
            let list = candidates.neighbours(i);
            let js: &[u32] = if unfiltered {
                list
            } else {
                js.clear();
                js.extend(list.iter().copied().filter(|&j| {
                    j as usize != i
                        && (all_heard || this.is_heard(j as usize))
                        // a fixed graph's link is cut beyond an explicit communication range
                        && graph_range.is_none_or(|rc| {
                            domain
                                .displacement(swarm.positions[i], swarm.positions[j as usize])
                                .length_squared()
                                < rc * rc
                        })
                }));
                js
            };
            debug_assert!(js.is_sorted_by_key(|&j| original(j as usize)));
            let first = heard.len();
            // the loop after this one decides the same, one option at a time, at more cost; here
            // each candidate is written and kept if its packet arrives, without a branch on the
            // loss draw (lost packets come at random: the branch would be mispredicted)
            if let Some(p) = memoryless {
                debug_assert!(links_i.is_none(), "memoryless links keep nothing");
                heard.resize(first + js.len(), own);
                let mut end = first;
                for (m, &ju) in js.iter().enumerate() {
                    let ju = ju as usize;
                    heard[end] = Perceived {
                        agent: original(ju),
                        position: domain.image_near(own.position, delayed.0[ju]),
                        velocity: delayed.1[ju],
                    };
                    let dropped = loss_words.get(m).is_some_and(|&w| word_uniform(w) < p);
                    end += usize::from(!dropped);
                }
                heard.truncate(end);
                let used = heard.len() - first;
                let counts = Counts {
                    candidates: js.len(),
                    lost: js.len() - used,
                    age: used as u64 * k.min(this.delay),
                    used,
                };
                return (own, counts);
            }
            old.clear();
            if let Some(links_i) = links_i.as_deref_mut() {
                old.append(links_i);
            }
            let (mut lost_count, mut age_sum) = (0usize, 0u64);
            // the link from i's m-th candidate takes word m of i's words of the step
            for (m, &ju) in js.iter().enumerate() {
                let (ju, j) = (ju as usize, original(ju as usize));
                // what i keeps of the link (Gilbert–Elliott's channel, the state held), when
                // links keep anything; senders by original index, ascending as the list
                let mut link = links_i.is_some().then(|| {
                    old.binary_search_by_key(&j, |l| l.sender)
                        .map_or(Link::new(j), |s| old[s])
                });
                let lag = if this.jitter > 0 {
                    this.delay + word_up_to(jitter_words[m], this.jitter)
                } else {
                    this.delay
                };
                // a symmetric loss draws once for the unordered pair, both ends alike
                let draw = || {
                    if comm.symmetric {
                        let (a, b) = (original(i) as usize, j as usize);
                        let pair = (a.min(b) * n + a.max(b)) as u64;
                        this.streams.uniform(Purpose::Loss, pair, k)
                    } else {
                        word_uniform(loss_words[m])
                    }
                };
                // the link's length, read by distance loss only
                let length = if loss_by_length {
                    domain
                        .displacement(swarm.positions[i], swarm.positions[ju])
                        .length()
                } else {
                    f64::NAN
                };
                let mut no_channel = None;
                let channel = link.as_mut().map_or(&mut no_channel, |l| &mut l.channel);
                let dropped = lost(&comm.loss, draw, k, this.h, length, channel);
                let stamp = k.saturating_sub(lag);
                let used = if dropped {
                    lost_count += 1;
                    match (comm.when_lost, link.and_then(|l| l.held)) {
                        (WhenLost::Hold { max_age }, Some(held))
                            if (k - held.stamp) as f64 * this.h <= max_age * (1.0 + 1e-12) =>
                        {
                            Some(held)
                        }
                        _ => None,
                    }
                } else {
                    let (position, velocity) = if lag == this.delay {
                        (delayed.0[ju], delayed.1[ju])
                    } else {
                        this.history.at(k, lag, ju)
                    };
                    let held = Held {
                        position,
                        velocity,
                        stamp,
                    };
                    if let Some(link) = link.as_mut() {
                        link.held = Some(held);
                    }
                    Some(held)
                };
                if let Some(held) = used {
                    age_sum += k - held.stamp.min(k);
                    heard.push(Perceived {
                        agent: j,
                        position: domain.image_near(own.position, held.position),
                        velocity: held.velocity,
                    });
                }
                if let (Some(links_i), Some(link)) = (links_i.as_deref_mut(), link) {
                    links_i.push(link);
                }
            }
            let counts = Counts {
                candidates: js.len(),
                lost: lost_count,
                age: age_sum,
                used: heard.len() - first,
            };
            (own, counts)
        };
        let counts = control_blocks(&mut inputs, &mut links, |start, inputs, mut links, w| {
            let Scratch {
                js,
                words,
                old,
                owns,
                heard,
                ends,
                receivers,
                out,
            } = w;
            heard.clear();
            owns.clear();
            ends.clear();
            receivers.clear();
            let mut counts = Counts::default();
            draw_words(start..start + inputs.len(), words);
            // where the words of the next moving receiver start
            let mut at = 0;
            for (r, u) in inputs.iter_mut().enumerate() {
                let i = start + r;
                let links_i = links.as_deref_mut().map(|l| &mut l[r]);
                if !this.moves(i) {
                    if let Some(links_i) = links_i {
                        links_i.clear();
                    }
                    *u = V::ZERO;
                    continue;
                }
                let its_words = words.each_ref().map(|w| w.get(at..).unwrap_or_default());
                at += link_word_count(candidates.neighbours(i).len());
                let (own, received) = receive(i, links_i, js, its_words, old, heard);
                counts = counts + received;
                owns.push(own);
                ends.push(heard.len());
                receivers.push(r);
            }
            // the receivers' offsets above follow the receivers `draw_words` drew for
            debug_assert!(
                words.iter().all(|w| w.is_empty() || w.len() == at),
                "every moving receiver's words read where they were drawn"
            );
            out.clear();
            out.resize(owns.len(), V::ZERO);
            let block = Perceptions { owns, heard, ends };
            local.local_inputs(t, block, out);
            for (&r, &u) in receivers.iter().zip(out.iter()) {
                inputs[r] = u;
            }
            counts
        });
        self.links = links;
        self.inputs = inputs;
        self.readings.links_lost = ratio(counts.lost as f64, counts.candidates);
        self.readings.information_age = ratio(counts.age as f64 * self.h, counts.used);
    }

    /// Actuate: the commanded acceleration clipped to a_max, then the first-order lag. The
    /// delivered accelerations replace the inputs when no input is held past this step (no lag,
    /// control at every step: [`holds_delivered`]).
    fn actuate(&mut self) {
        let actuation = self.conditions.actuation.unwrap_or_default();
        let mut clipped = 0usize;
        let in_place = self.delivered.is_empty();
        for i in 0..self.inputs.len() {
            let (u, at_limit) = clip(self.inputs[i], actuation.max_acceleration);
            clipped += usize::from(at_limit);
            let moves = self.moves(i);
            let delivered = if in_place {
                &mut self.inputs[i]
            } else {
                &mut self.delivered[i]
            };
            *delivered = match self.lag {
                Some(lag) => lag.advance(*delivered, u),
                None => u,
            };
            if !moves {
                *delivered = V::ZERO;
            }
        }
        self.readings.at_acceleration_limit = clipped as f64;
    }

    /// The accelerations delivered at this step (after [`Stage::actuate`]).
    fn delivered(&self) -> &[V] {
        if self.delivered.is_empty() {
            &self.inputs
        } else {
            &self.delivered
        }
    }

    /// Disturb and integrate: wind w_i = mean + gusts, and with the process noise σ √h ξ
    /// (Euler–Maruyama), symplectic Euler p ← p + h (a + w) + σ √h ξ, ‖p‖ clipped to v_max,
    /// q ← q + h p. With [`Integrator::Rk4`] the held acceleration is integrated exactly,
    /// q ← q + h p + ½ h² (a + w), p ← p + h (a + w) + σ √h ξ (the delivered acceleration is
    /// constant over the step: Runge–Kutta stages would re-evaluate nothing). Agents that do not
    /// move (failed, frozen or removed) keep their position with zero velocity.
    fn disturb_and_integrate(
        &mut self,
        swarm: &mut Swarm<V>,
        domain: &Domain<V>,
        numbering: &Numbering,
        k: u64,
        integrator: Integrator,
    ) {
        let h = self.h;
        self.advance_gusts(numbering, k);
        let max_speed = self.conditions.actuation.and_then(|a| a.max_speed);
        let this = &*self;
        let Swarm {
            positions,
            velocities,
        } = swarm;
        let n = positions.len();
        let clipped = for_each_agent(positions, velocities, &mut vec![(); n], |i, q, p, ()| {
            if !this.moves(i) {
                *p = V::ZERO;
                return 0;
            }
            let (wind, noise) = this.disturbance(i, numbering, k);
            let a = this.delivered()[i] + wind;
            let (next_p, clipped) = clip(*p + a * h + noise, max_speed);
            *q = match integrator {
                Integrator::SymplecticEuler => domain.wrap(*q + next_p * h),
                Integrator::Rk4 => domain.wrap(*q + *p * h + a * (0.5 * h * h)),
            };
            *p = next_p;
            usize::from(clipped)
        });
        self.readings.at_speed_limit = clipped as f64;
    }

    /// Disturb and integrate with vehicles: each moving agent's vehicle follows its delivered
    /// acceleration under the external acceleration wind + σ ξ/√h (the process noise's kick
    /// σ √h ξ spread over the step); agents that do not move keep their place and state.
    fn drive(
        &mut self,
        fleet: &mut Fleet<V>,
        swarm: &mut Swarm<V>,
        domain: &Domain<V>,
        numbering: &Numbering,
        k: u64,
    ) {
        self.advance_gusts(numbering, k);
        let this = &*self;
        let disturbance = |i: usize| {
            let (wind, noise) = this.disturbance(i, numbering, k);
            wind + noise * (1.0 / this.h)
        };
        let moves = |i: usize| this.moves(i);
        let delivered = this.delivered();
        fleet.advance(
            this.h,
            domain,
            swarm,
            delivered,
            disturbance,
            moves,
            numbering,
        );
    }

    /// The wind gusts of step `k` (Ornstein–Uhlenbeck, started in its stationary law): one
    /// for all, or one per agent keyed by its original index.
    fn advance_gusts(&mut self, numbering: &Numbering, k: u64) {
        let Some(gusts) = self.gusts else {
            return;
        };
        let per_agent = self.gusts_per_agent();
        for (g, x) in self.gust.iter_mut().enumerate() {
            let key = if per_agent { numbering.original(g) } else { g };
            let xi = self
                .streams
                .draws(Purpose::Wind, key as u64, k)
                .normal_vector();
            *x = if self.started {
                gusts.advance(*x, xi)
            } else {
                gusts.stationary(xi)
            };
        }
    }

    /// Agent i's disturbance at step `k`: the wind w_i = mean + gusts (an acceleration) and the
    /// process noise's velocity kick σ √h ξ (Euler–Maruyama), keyed by its original index.
    fn disturbance(&self, i: usize, numbering: &Numbering, k: u64) -> (V, V) {
        let Some(disturbance) = &self.conditions.disturbance else {
            return (V::ZERO, V::ZERO);
        };
        let mean = disturbance
            .wind
            .as_ref()
            .map_or(V::ZERO, |w| V::from_fn(|d| w.mean[d]));
        let wind = match self.gust.len() {
            0 => mean,
            1 => mean + self.gust[0],
            _ => mean + self.gust[i],
        };
        let kick = disturbance.process_noise * self.h.sqrt();
        let noise = if kick > 0.0 {
            let xi: V = self
                .streams
                .draws(Purpose::ProcessNoise, numbering.original(i) as u64, k)
                .normal_vector();
            xi * kick
        } else {
            V::ZERO
        };
        (wind, noise)
    }

    /// Integrate, for a model that sets velocities: its own update ([`advance`]) with the input
    /// delivered; agents that do not move keep their position with zero velocity. In parallel
    /// with the `parallel` feature (each agent's update reads its own state alone).
    fn set_velocities(&self, swarm: &mut Swarm<V>, domain: &Domain<V>, update: Update) {
        let delivered = self.delivered();
        let n = swarm.len();
        for_each_agent(
            &mut swarm.positions,
            &mut swarm.velocities,
            &mut vec![(); n],
            |i, q, p, ()| {
                (*q, *p) = if self.moves(i) {
                    advance(update, domain, self.h, *q, *p, delivered[i])
                } else {
                    (*q, V::ZERO)
                };
                0
            },
        );
    }
}

/// The states `q` and `p` copied into `slot`, in parallel with the `parallel` feature (the
/// delay line's slots are cold: at 10⁶ agents and two threads, copied on one thread they cost
/// about 2 % of a step with a delay alone).
fn copy_states<V: Vector>(slot: &mut Slot<V>, q: &[V], p: &[V]) {
    let n = q.len();
    for_each_agent(
        &mut slot.0,
        &mut slot.1,
        &mut vec![(); n],
        |i, qi, pi, ()| {
            (*qi, *pi) = (q[i], p[i]);
            0
        },
    );
}

/// `x / n`, 0 when `n` is 0.
fn ratio(x: f64, n: usize) -> f64 {
    if n == 0 { 0.0 } else { x / n as f64 }
}

/// `f(i, &mut a[i], &mut b[i], &mut c[i])` for every agent i (the three slices of one length;
/// `&mut vec![(); n]` for one unused, which allocates nothing), in parallel with the `parallel`
/// feature, and the sum of what `f` returns (a count: the same for any split).
fn for_each_agent<A: Send, B: Send, C: Send>(
    a: &mut [A],
    b: &mut [B],
    c: &mut [C],
    f: impl Fn(usize, &mut A, &mut B, &mut C) -> usize + Sync + Send,
) -> usize {
    debug_assert!(a.len() == b.len() && b.len() == c.len());
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        a.par_iter_mut()
            .zip(b.par_iter_mut())
            .zip(c.par_iter_mut())
            .enumerate()
            .with_min_len(1024)
            .map(|(i, ((a, b), c))| f(i, a, b, c))
            .sum()
    }
    #[cfg(not(feature = "parallel"))]
    a.iter_mut()
        .zip(b.iter_mut())
        .zip(c.iter_mut())
        .enumerate()
        .map(|(i, ((a, b), c))| f(i, a, b, c))
        .sum()
}

/// The counts of one control update, summed over the receivers.
#[derive(Clone, Copy, Debug, Default)]
struct Counts {
    /// Candidate links.
    candidates: usize,
    /// Candidate links whose packet was lost.
    lost: usize,
    /// The ages (steps) of the states used.
    age: u64,
    /// States used.
    used: usize,
}

impl core::ops::Add for Counts {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            candidates: self.candidates + o.candidates,
            lost: self.lost + o.lost,
            age: self.age + o.age,
            used: self.used + o.used,
        }
    }
}

/// Receivers are controlled in blocks of this many consecutive agents, their inputs computed
/// together ([`LocalForm::local_inputs`]: the pair terms of a block go through one batch).
const CONTROL_BLOCK: usize = 64;

/// What a worker reuses from block to block (the buffers keep their capacity): one receiver's
/// candidates `js`, the words of its links' jitter and loss draws and last step's links `old`,
/// and the block's moving receivers — their own perceived states, the states each heard
/// (`heard[ends[r − 1]..ends[r]]`), their places in the block and their inputs.
#[derive(Default)]
struct Scratch<V> {
    js: Vec<u32>,
    words: [Vec<u32>; 2],
    old: Vec<Link<V>>,
    owns: Vec<Perceived<V>>,
    heard: Vec<Perceived<V>>,
    ends: Vec<usize>,
    receivers: Vec<usize>,
    out: Vec<V>,
}

/// The counts of `f(start, inputs, links, scratch)` summed over the blocks of
/// [`CONTROL_BLOCK`] receivers from `start`, `f` setting each receiver's input in `inputs`,
/// with `links` their kept links (`None` when `links` is empty: links keep nothing). In
/// parallel with the `parallel` feature, each worker's scratch passed from block to block (`f`'s
/// result must not depend on what it held before).
fn control_blocks<V: Vector>(
    inputs: &mut [V],
    links: &mut [Vec<Link<V>>],
    f: impl Fn(usize, &mut [V], Option<&mut [Vec<Link<V>>]>, &mut Scratch<V>) -> Counts + Sync + Send,
) -> Counts {
    // an interrupt that cuts the step short leaves the blocks not yet begun (the step is torn)
    let f = |start, u: &mut [V], l, w: &mut Scratch<V>| {
        if cuts_short() {
            Counts::default()
        } else {
            f(start, u, l, w)
        }
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        let blocks = inputs
            .par_chunks_mut(CONTROL_BLOCK)
            .enumerate()
            .with_min_len(4);
        if links.is_empty() {
            blocks
                .map_init(Scratch::default, |w, (b, u)| {
                    f(b * CONTROL_BLOCK, u, None, w)
                })
                .reduce(Counts::default, core::ops::Add::add)
        } else {
            blocks
                .zip(links.par_chunks_mut(CONTROL_BLOCK))
                .map_init(Scratch::default, |w, ((b, u), l)| {
                    f(b * CONTROL_BLOCK, u, Some(l), w)
                })
                .reduce(Counts::default, core::ops::Add::add)
        }
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut w = Scratch::default();
        let mut links = links.chunks_mut(CONTROL_BLOCK);
        inputs
            .chunks_mut(CONTROL_BLOCK)
            .enumerate()
            .map(|(b, u)| f(b * CONTROL_BLOCK, u, links.next(), &mut w))
            .fold(Counts::default(), core::ops::Add::add)
    }
}

/// `f(i, &mut items[i], scratch)` for every item, in parallel with the `parallel` feature; in
/// index order. Each worker's `scratch` is made by `init` and passed from item to item (its
/// buffers keep their capacity): `f`'s result must not depend on what it held before.
pub(crate) fn map_agents_mut<S: Send, W, T: Send>(
    items: &mut [S],
    init: impl Fn() -> W + Sync + Send,
    f: impl Fn(usize, &mut S, &mut W) -> T + Sync + Send,
) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .map_init(init, |w, (i, s)| f(i, s, w))
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut w = init();
        items
            .iter_mut()
            .enumerate()
            .map(|(i, s)| f(i, s, &mut w))
            .collect()
    }
}

//! Fixed-step time integration of the closed loop q̇ = p, ṗ = u(t, q, p), with the net rebuilt at
//! every evaluation of u.

use std::borrow::Cow;

use flock_graph::{Components, Graph, NeighbourSearch, ProximityNet};
use flock_math::interrupt::cuts_short;
use flock_math::parallel::{fill_indexed, join};
use flock_math::{Domain, Vector};
use flock_metrics::{FlockMetrics, LatticeSummary, MetricParams, component_velocity_mismatch};

use crate::conditions::stage::{self, Stage, map_agents_mut, perception_field};
use crate::conditions::{Conditions, ConditionsState};
use crate::health::{AgentFault, first_fault};
use crate::permutation::permute_in_place;
use crate::vehicle::{DynVehicle, Fleet, VehicleKind};
use flock_protocols::error::{ParamError, check};
use flock_protocols::{LocalForm, Perceived, Protocol, Swarm, Update};

/// The integration scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Integrator {
    /// Semi-implicit (symplectic) Euler: p ← p + h u(t, q, p), then q ← q + h p. First order,
    /// one net per step, and free of the energy drift of explicit Euler.
    #[default]
    SymplecticEuler,
    /// Classical fourth-order Runge–Kutta: four evaluations of u (four nets) per step.
    Rk4,
}

/// Steps between two re-sorts of agents stored in space order.
const RESORT_EVERY: u64 = 16;

/// A protocol integrated in time from an initial swarm with a fixed step.
///
/// The proximity net of the current state is kept up to date, so metrics and energies can be read
/// between steps without another neighbour search.
///
/// When the agents are numbered at random (their net [`ProximityNet::is_scattered`]) and the
/// protocol [`Protocol::follows_numbering`], the simulation stores them in the order of the
/// search's cells, so that neighbours are near in memory, and re-sorts them every 16 steps
/// ([`Simulation::stored_by_cell`]). That storage is internal: every state, graph, energy, metric
/// and diagnostic the simulation gives is of the agents in original order, with the bits of a
/// simulation that kept them in that order.
///
/// Under real conditions ([`Simulation::with_conditions`]) each step is the conditioned stage
/// ([`Stage::step`]); agents numbered at random are stored by cell there too, their conditions'
/// state moving with them at each re-sort. An agent *removed* by a fault
/// stays in the state at the position where it failed, with zero velocity; the metrics leave it
/// out (they are those of the other agents, of their proximity net and of the interaction graph
/// without it), while the protocol's energy and diagnostics still see the whole state.
///
/// # Example
/// ```
/// use flock_metrics::MetricParams;
/// use flock_protocols::{
///     Algorithm2, AlphaInteraction, AlphaParams, GammaAgent, NavigationalFeedback, Swarm,
/// };
/// use flock_sim::{Integrator, Simulation};
/// use glam::DVec2;
///
/// // four agents at rest on a line, drawn to a static γ-agent at the origin (TAC 2006 Algorithm 2)
/// let q = (0..4).map(|i| DVec2::new(6.0 * f64::from(i), 0.0)).collect();
/// let swarm = Swarm::new(q, vec![DVec2::ZERO; 4]);
/// let gamma = GammaAgent::Static { position: DVec2::ZERO };
/// let protocol = Algorithm2 {
///     alpha: AlphaInteraction::new(AlphaParams::default(), 1.0, 1.0)?,
///     navigation: NavigationalFeedback::linear(gamma, 0.05, 0.4),
/// };
/// let mut sim = Simulation::new(protocol, Integrator::SymplecticEuler, swarm, 0.01)?;
/// let h0 = sim.energy();
/// for _ in 0..1000 {
///     sim.step();
/// }
/// assert!(sim.energy() < h0); // Theorem 3: H does not increase
/// let metrics = sim.metrics(&MetricParams { d: 7.0, collision_distance: 1.75 });
/// assert_eq!(metrics.connectivity, 1.0);
/// # Ok::<(), flock_protocols::ParamError>(())
/// ```
#[derive(Debug)]
pub struct Simulation<V, P> {
    protocol: P,
    integrator: Integrator,
    step: f64,
    steps: u64,
    swarm: Swarm<V>,
    search: NeighbourSearch,
    net: ProximityNet,
    inputs: Vec<V>,
    rk: Option<RungeKuttaScratch<V>>,
    /// The real conditions of the run, `None` for the ideal run ([`Simulation::with_conditions`]).
    conditions: Option<Box<Stage<V>>>,
    /// Open space or a periodic box ([`Simulation::with_domain`]).
    domain: Domain<V>,
    /// The agents' vehicles, `None` for point masses ([`Simulation::with_vehicle`]).
    fleet: Option<Box<Fleet<V>>>,
    /// Whether an interrupt cut a step short after it changed the state ([`Simulation::is_torn`]).
    torn: bool,
}

/// What [`Simulation::observe`] measures of a state.
#[derive(Clone, Debug, PartialEq)]
pub struct Observation {
    /// The flocking metrics.
    pub metrics: FlockMetrics,
    /// The protocol's energy.
    pub energy: f64,
    /// The protocol's diagnostics, named ([`Protocol::diagnostics`]).
    pub diagnostics: Vec<(&'static str, f64)>,
}

/// Moves every per-agent array of a run with its agent, index s getting what index `from(s)`
/// held: the swarm, gathered into `spare` and swapped in when `spare` holds one vector per agent
/// (the ideal run's inputs, free between steps), otherwise permuted in place as the conditions'
/// state and the vehicles' states are (a conditioned run keeps no inputs there, and holds the
/// delay line: no array is held twice).
fn move_agents<V: Vector>(
    swarm: &mut Swarm<V>,
    spare: &mut Vec<V>,
    stage: Option<&mut Stage<V>>,
    fleet: Option<&mut Fleet<V>>,
    from: impl Fn(usize) -> usize + Copy + Sync,
) {
    for x in [&mut swarm.positions, &mut swarm.velocities] {
        if spare.len() == x.len() {
            fill_indexed(spare, |s| x[from(s)]);
            core::mem::swap(x, spare);
        } else {
            permute_in_place(x, from);
        }
    }
    if let Some(stage) = stage {
        stage.permute(from);
    }
    if let Some(fleet) = fleet {
        fleet.permute(from);
    }
}

/// An empty net for `protocol`: without distances when it does not read them.
fn empty_net<V: Vector, P: Protocol<V>>(protocol: &P) -> ProximityNet {
    if protocol.uses_net_distances() {
        ProximityNet::new()
    } else {
        ProximityNet::without_distances()
    }
}

/// Buffers of the Runge–Kutta stages, allocated once.
#[derive(Debug)]
struct RungeKuttaScratch<V> {
    stage: Swarm<V>,
    net: ProximityNet,
    sum_q: Vec<V>,
    sum_p: Vec<V>,
}

impl<V: Vector, P: Protocol<V>> Simulation<V, P> {
    /// A simulation at t = 0 from `swarm`, advancing by `step > 0`.
    ///
    /// # Errors
    /// A step that is not positive and finite (field `step`), a protocol whose interaction range
    /// is not (`interaction_range`), or an agent whose position or velocity is not finite
    /// (`positions[i]`, `velocities[i]`).
    pub fn new(
        protocol: P,
        integrator: Integrator,
        swarm: Swarm<V>,
        step: f64,
    ) -> Result<Self, ParamError> {
        check::positive("step", step)?;
        check::positive("interaction_range", protocol.interaction_range())?;
        for (name, vectors) in [
            ("positions", &swarm.positions),
            ("velocities", &swarm.velocities),
        ] {
            if let Some(i) = vectors.iter().position(|v| !v.is_finite()) {
                return Err(ParamError::new(
                    format!("{name}[{i}]"),
                    vectors[i],
                    "is not finite",
                    "start every agent at a finite position with a finite velocity",
                ));
            }
        }
        let n = swarm.len();
        let rk = (integrator == Integrator::Rk4).then(|| RungeKuttaScratch {
            stage: swarm.clone(),
            net: empty_net(&protocol),
            sum_q: vec![V::ZERO; n],
            sum_p: vec![V::ZERO; n],
        });
        let mut simulation = Self {
            net: empty_net(&protocol),
            protocol,
            integrator,
            step,
            steps: 0,
            swarm,
            search: NeighbourSearch::new(),
            inputs: vec![V::ZERO; n],
            rk,
            conditions: None,
            domain: Domain::Open,
            fleet: None,
            torn: false,
        };
        simulation.rebuild_net();
        Ok(simulation)
    }

    /// A simulation resumed after `steps` steps, at t = steps · h, from the state `swarm` those
    /// steps reached: stepping it gives bit-identical states to the uninterrupted simulation, since
    /// the state (q, p) and the step count are all a simulation carries between steps.
    ///
    /// # Errors
    /// As [`Simulation::new`].
    pub fn resume(
        protocol: P,
        integrator: Integrator,
        swarm: Swarm<V>,
        step: f64,
        steps: u64,
    ) -> Result<Self, ParamError> {
        Ok(Self {
            steps,
            ..Self::new(protocol, integrator, swarm, step)?
        })
    }

    /// The protocol.
    #[must_use]
    pub const fn protocol(&self) -> &P {
        &self.protocol
    }

    /// The time step h.
    #[must_use]
    pub const fn step_size(&self) -> f64 {
        self.step
    }

    /// The current state, agents in original order: borrowed when they are stored so, otherwise
    /// a copy in that order.
    #[must_use]
    pub fn swarm(&self) -> Cow<'_, Swarm<V>> {
        let numbering = self.net.numbering();
        if numbering.is_identity() {
            return Cow::Borrowed(&self.swarm);
        }
        let ordered = |x: &[V]| numbering.ordered(x).collect();
        Cow::Owned(Swarm {
            positions: ordered(&self.swarm.positions),
            velocities: ordered(&self.swarm.velocities),
        })
    }

    /// The proximity net's graph of the current state, agents in original order (node k is agent
    /// k): borrowed when they are stored so, otherwise relabelled.
    #[must_use]
    pub fn graph(&self) -> Cow<'_, Graph> {
        let numbering = self.net.numbering();
        if numbering.is_identity() {
            return Cow::Borrowed(self.net.graph());
        }
        Cow::Owned(self.net.graph().in_original_order(numbering))
    }

    /// Whether the agents are stored by cell (they were numbered at random; see [`Simulation`]).
    #[must_use]
    pub fn stored_by_cell(&self) -> bool {
        !self.net.numbering().is_identity()
    }

    /// The flocking metrics of the current state (TAC 2006 Section VIII); `params.collision_distance`
    /// must not exceed the interaction range (every colliding pair is then an edge of the net).
    #[must_use]
    ///
    /// For a protocol with an [interaction graph](Protocol::interaction_graph), C, C* and the
    /// components are those of that graph; the other metrics are of the proximity net.
    pub fn metrics(&self, params: &MetricParams) -> FlockMetrics {
        if let Some(removed) = self.conditions.as_ref().and_then(|c| c.removed()) {
            return self.metrics_without(removed, params);
        }
        let metrics = FlockMetrics::measure_in(
            &self.domain,
            &self.swarm.positions,
            &self.swarm.velocities,
            &self.net,
            params,
        );
        match self.protocol.interaction_graph() {
            Some(graph) => metrics.with_connectivity_of(&Components::of(graph)),
            None => metrics,
        }
    }

    /// The lattice of the current state (CDS 03-006 Fig. 9, TAC 2006 Theorem 5): its edges, those
    /// within `tolerance` · d of the desired distance `d`, its triangles and, in 2D, the bound
    /// 3n − 6 and the crossing edges.
    #[must_use]
    pub fn lattice(&self, d: f64, tolerance: f64) -> LatticeSummary {
        LatticeSummary::measure_in(&self.domain, &self.swarm.positions, &self.net, d, tolerance)
    }

    /// The protocol's energy at the current state.
    #[must_use]
    pub fn energy(&self) -> f64 {
        self.protocol.energy(self.time(), &self.swarm, &self.net)
    }

    /// The protocol's own diagnostics of the current state ([`Protocol::diagnostics`]).
    #[must_use]
    ///
    /// With [conditions](Simulation::with_conditions), their columns follow: `links_lost` and
    /// `information_age` (communication), `at_acceleration_limit`, `at_speed_limit` (actuation
    /// limits) and `failed` (faults).
    pub fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        let mut columns = self
            .protocol
            .diagnostics(self.time(), &self.swarm, &self.net);
        if let Some(stage) = &self.conditions {
            columns.extend(stage.diagnostics());
        }
        if let Some(fleet) = &self.fleet {
            columns.extend(fleet.diagnostics());
        }
        columns
    }

    /// Everything a recorded step measures: the metrics, the energy (computed concurrently, each
    /// with the bits it has alone) and the diagnostics.
    #[must_use]
    pub fn observe(&self, params: &MetricParams) -> Observation {
        let (metrics, energy) = join(|| self.metrics(params), || self.energy());
        Observation {
            metrics,
            energy,
            diagnostics: self.diagnostics(),
        }
    }

    /// The velocity mismatch of each agent against the mean velocity of its own component of the
    /// net (of the [interaction graph](Protocol::interaction_graph), if any), per agent: ½ Σ_i ‖p_i − p̄_{c(i)}‖² / n (0 when every component moves rigidly).
    #[must_use]
    pub fn component_velocity_mismatch(&self) -> f64 {
        let graph = self
            .protocol
            .interaction_graph()
            .unwrap_or(self.net.graph());
        component_velocity_mismatch(
            &self.swarm.velocities,
            &Components::of(graph),
            self.net.numbering(),
        )
    }

    /// Checks the current state: every position and velocity finite, every speed at most r/h.
    ///
    /// # Errors
    /// The agent at fault of lowest original index.
    pub fn check_health(&self) -> Result<(), AgentFault> {
        let limit = self.protocol.interaction_range() / self.step;
        match first_fault(&self.swarm, self.net.numbering(), limit) {
            None => Ok(()),
            Some(fault) => Err(fault),
        }
    }

    /// The simulation in `domain`: on a periodic box every agent is wrapped into the box after
    /// each step, the net holds the pairs within r by the minimum image, and a protocol that does
    /// not measure displacements in the domain itself ([`Protocol::measures_in_domain`]) computes
    /// each agent's input from its [`LocalForm`] with every neighbour at its image nearest the
    /// agent. Agents stored by cell are put back in original order to be wrapped, and sorted
    /// again by the cells of the torus when they are scattered. `Domain::Open` changes nothing.
    ///
    /// # Errors
    /// A side of the box not positive and finite or shorter than 2r (`domain.size`), or a protocol
    /// that needs its local form on a torus and has none (`domain`).
    pub fn with_domain(mut self, domain: Domain<V>) -> Result<Self, ParamError> {
        if let Domain::Periodic { size } = domain {
            let r = self.protocol.interaction_range();
            for k in 0..V::DIM {
                let side = size.coord(k);
                check::positive(&format!("domain.size[{k}]"), side)?;
                check::require(
                    side >= 2.0 * r,
                    &format!("domain.size[{k}]"),
                    side,
                    &format!(
                        "is shorter than twice the interaction range r = {r} (an agent would see another agent's two images)"
                    ),
                    &format!("make every side of the box at least {}", 2.0 * r),
                )?;
            }
            if !self.protocol.measures_in_domain() && self.protocol.local_form().is_none() {
                return Err(ParamError::new(
                    "domain",
                    "Periodic",
                    "needs each agent's input from what it perceives (its local form), and this protocol has none",
                    "run this protocol in open space (domain: Open)",
                ));
            }
            self.back_to_original_order();
            for q in &mut self.swarm.positions {
                *q = domain.wrap(*q);
            }
        }
        self.domain = domain;
        self.rebuild_net();
        Ok(self)
    }

    /// Puts the agents stored by cell back in original order, with their conditions' and
    /// vehicles' states, and leaves an empty net (its numbering gone) that
    /// [`Simulation::rebuild_net`] must rebuild.
    fn back_to_original_order(&mut self) {
        if self.stored_by_cell() {
            let numbering = self.net.numbering();
            // index k now holds agent k, which was stored at `stored(k)`
            move_agents(
                &mut self.swarm,
                &mut self.inputs,
                self.conditions.as_deref_mut(),
                self.fleet.as_deref_mut(),
                |k| numbering.stored(k),
            );
        }
        self.net = empty_net(&self.protocol);
    }

    /// The domain.
    #[must_use]
    pub const fn domain(&self) -> &Domain<V> {
        &self.domain
    }

    /// The simulation of agents that are `vehicle`s ([`vehicle`](crate::vehicle)): the
    /// protocol's input u_i is the commanded acceleration of agent i's reference point, which
    /// its vehicle follows through its controller and dynamics, integrated at the vehicle's inner
    /// step. Every agent starts in its vehicle's equilibrium ([`Vehicle::start`](crate::Vehicle::start),
    /// which may change its velocity), or, resuming, in the checkpointed `states` (original
    /// order). Agents numbered at random are stored by cell as in the ideal run, each vehicle's
    /// state moving with its agent.
    ///
    /// # Errors
    /// As [`Fleet::new`]; a protocol that sets velocities (`vehicle`: it has no acceleration to
    /// command), the integrator RK4 (`integrator`: a vehicle integrates its own dynamics), or a
    /// condition the vehicle cannot take ([`Simulation::with_conditions`]).
    pub fn with_vehicle(
        mut self,
        vehicle: DynVehicle<V>,
        states: Option<Vec<f64>>,
    ) -> Result<Self, ParamError> {
        check_vehicle_loop(
            self.protocol.update().sets_velocity(),
            self.integrator,
            &*vehicle,
        )?;
        self.back_to_original_order();
        let fleet = Fleet::new(vehicle, &mut self.swarm, self.step, states)?;
        if let Some(stage) = &self.conditions {
            stage::check_vehicle(stage.conditions(), fleet.vehicle())?;
        }
        self.fleet = Some(Box::new(fleet));
        self.rebuild_net();
        Ok(self)
    }

    /// The vehicles' states in original order ([`Fleet::states`], agent i at
    /// `[i * k..(i + 1) * k]`), `None` for point masses: borrowed when the agents are stored in
    /// original order, otherwise a copy in that order.
    #[must_use]
    pub fn vehicle_states(&self) -> Option<Cow<'_, [f64]>> {
        let fleet = self.fleet.as_ref()?;
        let width = fleet.vehicle().state_columns().len();
        Some(
            self.net
                .numbering()
                .rows_in_original_order(fleet.states(), width),
        )
    }

    /// The agents' vehicles, `None` for point masses.
    #[must_use]
    pub fn fleet(&self) -> Option<&Fleet<V>> {
        self.fleet.as_deref()
    }

    /// Which agents have failed (original order), when the simulation runs under conditions
    /// with `faults` ([`Stage::failed`](crate::conditions::stage::Stage::failed)); `None` otherwise.
    /// Borrowed when the agents are stored in original order, otherwise a copy in that order.
    #[must_use]
    pub fn failed(&self) -> Option<Cow<'_, [bool]>> {
        let failed = self.conditions.as_ref().and_then(|c| c.failed())?;
        Some(self.net.numbering().rows_in_original_order(failed, 1))
    }

    /// The simulation under real `conditions` (validated for its agents, dimension and step),
    /// every random draw keyed from `seed`. With `Conditions::default()` it is the ideal
    /// simulation, unchanged. Agents numbered at random are stored by cell as in the ideal run
    /// (every draw of the conditions is keyed by original indices, so the bits are those of the
    /// agents kept in original order).
    ///
    /// When no condition changes what agents perceive (no communication or sensing section, no
    /// silent or removed faults), inputs are [`Protocol::controls`] of the true state; otherwise
    /// each agent's input is its protocol's [`LocalForm`] of what it perceives.
    ///
    /// # Errors
    /// A parameter outside its domain ([`Conditions::validate`]), or a condition that changes
    /// perception for a protocol without a local form (named by that condition's field).
    pub fn with_conditions(
        mut self,
        conditions: &Conditions,
        seed: u64,
    ) -> Result<Self, ParamError> {
        // the ideal run allocates no stage (nothing to validate: every part is unset)
        if conditions.is_ideal() {
            return Ok(self);
        }
        let n = self.swarm.len();
        let range = self.protocol.interaction_range();
        // the stage holds its own inputs and integrates itself: the ideal loop's buffers go
        // before it is allocated (at the peak of memory), and the agents into original order
        // (the net's first build sorts them again when scattered)
        self.back_to_original_order();
        self.inputs = Vec::new();
        self.rk = None;
        let stage = Stage::new(conditions, seed, n, self.step, range)?;
        if self.protocol.update().sets_velocity()
            && let Some(field) = stage::acceleration_field(conditions)
        {
            return Err(ParamError::new(
                field,
                "set",
                "acts on an acceleration, and this model sets its agents' velocities directly",
                "remove this condition for this model (conditions on perception, sampling and faults apply)",
            ));
        }
        if let Some(fleet) = &self.fleet {
            stage::check_vehicle(conditions, fleet.vehicle())?;
        }
        if let Some(field) = perception_field(conditions)
            && self.protocol.local_form().is_none()
        {
            return Err(ParamError::new(
                field,
                "set",
                "changes what each agent perceives, and this protocol has no local form (u_i from what agent i perceives)",
                "remove this condition, or use a distributed protocol (Algorithms 1-3, Consensus)",
            ));
        }
        self.conditions = Some(Box::new(stage));
        self.rebuild_net();
        Ok(self)
    }

    /// The state of the conditions to checkpoint (`None` for the ideal run): with the swarm and
    /// the step count, all a resumed run needs to continue with the same bits.
    #[must_use]
    pub fn conditions_state(&self) -> Option<ConditionsState> {
        self.conditions
            .as_ref()
            .map(|c| c.state(self.net.numbering()))
    }

    /// Restores the checkpointed state of the conditions into a simulation resumed with the same
    /// conditions ([`Simulation::resume`], then [`Simulation::with_conditions`]).
    ///
    /// # Errors
    /// A simulation without conditions (field `conditions`), or a state of another run.
    pub fn restore_conditions(&mut self, state: ConditionsState) -> Result<(), ParamError> {
        match self.conditions.as_mut() {
            Some(stage) => stage.restore(state, self.net.numbering()),
            None => Err(ParamError::new(
                "conditions",
                "none",
                "are not set on this simulation",
                "call with_conditions with the run's conditions first",
            )),
        }
    }

    /// The metrics of the agents not removed (removed agents stay in the state, at the
    /// position where they failed, with zero velocity, but leave every metric).
    /// `removed` is in storage order; the agents kept are measured in original order.
    fn metrics_without(&self, removed: &[bool], params: &MetricParams) -> FlockMetrics {
        let numbering = self.net.numbering();
        let kept: Vec<usize> = numbering
            .stored_of(0..removed.len())
            .filter(|&s| !removed[s])
            .collect();
        if kept.is_empty() {
            // every agent removed: undefined, also on a fixed interaction graph
            return FlockMetrics::EMPTY;
        }
        let pick = |x: &[V]| kept.iter().map(|&s| x[s]).collect::<Vec<V>>();
        let (q, p) = (pick(&self.swarm.positions), pick(&self.swarm.velocities));
        let mut net = empty_net(&self.protocol);
        let r = self.protocol.interaction_range();
        NeighbourSearch::new().build_in(&self.domain, &q, r, &mut net);
        let metrics = FlockMetrics::measure_in(&self.domain, &q, &p, &net, params);
        match self.protocol.interaction_graph() {
            // a fixed graph's agents stay in original order: storage index = original index
            Some(graph) => {
                let mut index = vec![usize::MAX; removed.len()];
                for (new, &old) in kept.iter().enumerate() {
                    index[old] = new;
                }
                let edges: Vec<(usize, usize)> = kept
                    .iter()
                    .flat_map(|&i| graph.neighbours(i).iter().map(move |&j| (i, j as usize)))
                    .filter(|&(i, j)| i < j && !removed[j])
                    .map(|(i, j)| (index[i], index[j]))
                    .collect();
                match Graph::from_edges(kept.len(), &edges) {
                    Ok(sub) => metrics.with_connectivity_of(&Components::of(&sub)),
                    Err(_) => metrics,
                }
            }
            None => metrics,
        }
    }

    /// The number of steps taken.
    #[must_use]
    pub const fn steps(&self) -> u64 {
        self.steps
    }

    /// The current time t = steps · h (not accumulated, so it carries no round-off).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.steps as f64 * self.step
    }

    /// Advances the state by one step h: the ideal step, or with
    /// [conditions](Simulation::with_conditions) the conditioned one (fail → sense → communicate
    /// → control → actuate → disturb and integrate, [`Stage::step`]).
    ///
    /// An interrupt that [cuts the step short](flock_math::interrupt::cuts_short) (a Ctrl-C
    /// during a step of more than half a second) stops its long loops. Cut while the inputs are
    /// computed, before the state changes, the step is not taken: the state and the step count
    /// stay those of the steps taken. Cut inside a vehicle's inner steps or the conditions'
    /// stage, which change the state as they go, it leaves the state between two steps: the
    /// simulation is then [torn](Simulation::is_torn) and takes no more steps.
    pub fn step(&mut self) {
        if self.torn {
            return;
        }
        let taken = if let Some(stage) = self.conditions.as_mut() {
            stage.step(
                &self.protocol,
                &self.domain,
                &mut self.swarm,
                &self.net,
                self.steps,
                self.integrator,
                self.fleet.as_deref_mut(),
            );
            self.torn = cuts_short();
            !self.torn
        } else if self.fleet.is_some() {
            let t = self.time();
            controls_in(
                &self.protocol,
                &self.domain,
                t,
                &self.swarm,
                &self.net,
                &mut self.inputs,
            );
            if cuts_short() {
                return;
            }
            if let Some(fleet) = self.fleet.as_mut() {
                let (h, domain) = (self.step, &self.domain);
                fleet.advance(
                    h,
                    domain,
                    &mut self.swarm,
                    &self.inputs,
                    |_| V::ZERO,
                    |_| true,
                    self.net.numbering(),
                );
            }
            self.torn = cuts_short();
            !self.torn
        } else {
            match (self.protocol.update(), self.integrator) {
                (Update::Acceleration, Integrator::Rk4) => self.runge_kutta(),
                // a model that sets velocities has its own update, whatever the integrator
                (update, _) => self.explicit_update(update),
            }
        };
        if taken {
            self.steps += 1;
            self.rebuild_net();
        }
    }

    /// Whether an interrupt cut a step short after it had changed the state
    /// ([`Simulation::step`]): the state is then between two steps, neither of which it is, and
    /// the simulation takes no more steps.
    #[must_use]
    pub const fn is_torn(&self) -> bool {
        self.torn
    }

    /// Builds the net of the current state; agents stored in space order are re-sorted every
    /// [`RESORT_EVERY`] steps first, and agents in original order found scattered in memory are
    /// sorted, when the protocol follows the numbering. (Agents once sorted wait for the next
    /// re-sort even if still scattered, e.g. thousands in one cell: no sort at every step.)
    fn rebuild_net(&mut self) {
        let r = self.protocol.interaction_range();
        let sorts =
            self.protocol.follows_numbering() && self.protocol.interaction_graph().is_none();
        let sorted = !self.net.numbering().is_identity();
        if sorts && sorted && self.steps.is_multiple_of(RESORT_EVERY) {
            self.sort_by_cell();
        }
        self.search
            .build_in(&self.domain, &self.swarm.positions, r, &mut self.net);
        if sorts && !sorted && self.net.is_scattered() {
            self.sort_by_cell();
            self.search
                .build_in(&self.domain, &self.swarm.positions, r, &mut self.net);
        }
    }

    /// Stores the agents in the order of the search's cells (agents with a non-finite position
    /// last, in their storage order) and renumbers the nets, which must then be rebuilt.
    fn sort_by_cell(&mut self) {
        let q = &self.swarm.positions;
        let r = self.protocol.interaction_range();
        let cells = self.search.cell_order_in(&self.domain, q, r);
        let completed: Vec<u32>;
        let order = if cells.len() == q.len() {
            cells
        } else {
            let lost = (0..q.len()).filter(|&i| !q[i].is_finite());
            completed = cells
                .iter()
                .copied()
                .chain(lost.map(|i| i as u32))
                .collect();
            &completed
        };
        move_agents(
            &mut self.swarm,
            &mut self.inputs,
            self.conditions.as_deref_mut(),
            self.fleet.as_deref_mut(),
            |s| order[s] as usize,
        );
        self.net.permute(order);
        if let Some(rk) = self.rk.as_mut() {
            rk.net.share_numbering(&self.net);
        }
    }

    /// One explicit step: symplectic Euler for an acceleration, or the model's own update
    /// ([`advance`]); positions wrapped into a periodic box. Returns whether the step was taken
    /// (not when an interrupt cut the inputs short: the state is then unchanged).
    fn explicit_update(&mut self, update: Update) -> bool {
        let (t, h) = (self.time(), self.step);
        controls_in(
            &self.protocol,
            &self.domain,
            t,
            &self.swarm,
            &self.net,
            &mut self.inputs,
        );
        if cuts_short() {
            return false;
        }
        let domain = self.domain;
        let Swarm {
            positions,
            velocities,
        } = &mut self.swarm;
        let apply = |((q, p), &u): ((&mut V, &mut V), &V)| {
            (*q, *p) = advance(update, &domain, h, *q, *p, u);
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            positions
                .par_iter_mut()
                .zip(velocities.par_iter_mut())
                .zip(self.inputs.par_iter())
                .with_min_len(4096)
                .for_each(apply);
        }
        #[cfg(not(feature = "parallel"))]
        positions
            .iter_mut()
            .zip(velocities.iter_mut())
            .zip(&self.inputs)
            .for_each(apply);
        true
    }

    /// y ← y + (h/6)(k₁ + 2k₂ + 2k₃ + k₄) with y = (q, p) and k = (p, u(t, q, p)). Returns
    /// whether the step was taken (not when an interrupt cut an evaluation of the inputs short:
    /// y is then unchanged).
    fn runge_kutta(&mut self) -> bool {
        const WEIGHTS: [f64; 4] = [1.0, 2.0, 2.0, 1.0];
        const NEXT_OFFSETS: [f64; 3] = [0.5, 0.5, 1.0];
        let (t, h) = (self.time(), self.step);
        let range = self.protocol.interaction_range();
        let Some(rk) = self.rk.as_mut() else {
            unreachable!("Runge–Kutta buffers exist for Integrator::Rk4");
        };
        let y = &mut self.swarm;
        rk.sum_q.fill(V::ZERO);
        rk.sum_p.fill(V::ZERO);
        // stage 1 evaluates at y itself, whose net is already built
        rk.stage.velocities.copy_from_slice(&y.velocities);
        controls_in(
            &self.protocol,
            &self.domain,
            t,
            y,
            &self.net,
            &mut self.inputs,
        );
        for (stage, weight) in WEIGHTS.into_iter().enumerate() {
            // here rk.stage.velocities holds p_s and self.inputs holds u_s
            for i in 0..y.len() {
                rk.sum_q[i] += rk.stage.velocities[i] * weight;
                rk.sum_p[i] += self.inputs[i] * weight;
            }
            let Some(&offset) = NEXT_OFFSETS.get(stage) else {
                break;
            };
            for i in 0..y.len() {
                let (p_s, u_s) = (rk.stage.velocities[i], self.inputs[i]);
                rk.stage.positions[i] = y.positions[i] + p_s * (offset * h);
                rk.stage.velocities[i] = y.velocities[i] + u_s * (offset * h);
            }
            self.search
                .build_in(&self.domain, &rk.stage.positions, range, &mut rk.net);
            controls_in(
                &self.protocol,
                &self.domain,
                t + offset * h,
                &rk.stage,
                &rk.net,
                &mut self.inputs,
            );
        }
        if cuts_short() {
            return false;
        }
        for i in 0..y.len() {
            y.positions[i] = self.domain.wrap(y.positions[i] + rk.sum_q[i] * (h / 6.0));
            y.velocities[i] += rk.sum_p[i] * (h / 6.0);
        }
        true
    }
}

/// Refuses a `vehicle` in a loop that cannot drive it: a protocol that sets velocities
/// ([`Update::sets_velocity`]: it has no acceleration to command), or the `integrator` RK4 (a
/// vehicle integrates its own dynamics at its inner step).
///
/// # Errors
/// The field refused: `vehicle` or `integrator`.
pub fn check_vehicle_loop(
    sets_velocity: bool,
    integrator: Integrator,
    vehicle: &dyn VehicleKind,
) -> Result<(), ParamError> {
    if sets_velocity {
        return Err(ParamError::new(
            "vehicle",
            vehicle.name(),
            "needs a commanded acceleration, and this model sets its agents' velocities directly",
            "use vehicle: PointMass for this model, or an acceleration protocol",
        ));
    }
    if integrator == Integrator::Rk4 {
        return Err(ParamError::new(
            "integrator",
            "Rk4",
            "is not used with a vehicle, which integrates its own dynamics at its inner step",
            "remove integrator (or write SymplecticEuler) with this vehicle",
        ));
    }
    Ok(())
}

/// One agent's state after a step h of the loop's integrate stage, from its input u:
/// symplectic Euler p ← p + h u, q ← q + h p for an acceleration, or the model's own update
/// ([`Update`]); q wrapped into the box of a periodic `domain`.
#[inline]
#[must_use]
pub fn advance<V: Vector>(update: Update, domain: &Domain<V>, h: f64, q: V, p: V, u: V) -> (V, V) {
    match update {
        Update::Acceleration => {
            let p = p + u * h;
            (domain.wrap(q + p * h), p)
        }
        Update::TurnThenMove => (domain.wrap(q + u * h), u),
        Update::MoveThenTurn => (domain.wrap(q + p * h), u),
    }
}

/// Every agent's input at time `t`: [`Protocol::controls`] of the state, or on a torus, for a
/// protocol that does not measure in the domain itself, its [`LocalForm`] with every neighbour in
/// the net at its image nearest the agent ([`Domain::image_near`]), in ascending index.
pub(crate) fn controls_in<V: Vector, P: Protocol<V> + ?Sized>(
    protocol: &P,
    domain: &Domain<V>,
    t: f64,
    swarm: &Swarm<V>,
    net: &ProximityNet,
    inputs: &mut [V],
) {
    match protocol.local_form() {
        Some(local) if domain.is_periodic() && !protocol.measures_in_domain() => {
            local_controls(local, domain, t, swarm, net, inputs);
        }
        _ => protocol.controls(t, swarm, net, inputs),
    }
}

/// u_i = local_input(t, own, heard) with the true states, neighbours at their nearest image,
/// in the net's order (ascending original index), each agent named by its original index.
fn local_controls<V: Vector>(
    local: &dyn LocalForm<V>,
    domain: &Domain<V>,
    t: f64,
    swarm: &Swarm<V>,
    net: &ProximityNet,
    inputs: &mut [V],
) {
    let (q, p) = (&swarm.positions, &swarm.velocities);
    let numbering = net.numbering();
    let perceived = |i: usize, position: V| Perceived {
        agent: numbering.original(i) as u32,
        position,
        velocity: p[i],
    };
    // each worker's heard list, reused from agent to agent
    map_agents_mut(inputs, Vec::new, |i, u, heard| {
        // an interrupt that cuts the step short leaves the agents not yet begun
        if cuts_short() {
            return;
        }
        heard.clear();
        heard.extend(
            net.graph()
                .neighbours(i)
                .iter()
                .map(|&j| perceived(j as usize, domain.image_near(q[i], q[j as usize]))),
        );
        *u = local.local_input(t, &perceived(i, q[i]), heard);
    });
}

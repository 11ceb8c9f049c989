//! A run in time ([`Simulation`]): the swarm, its proximity net, the protocol, the integrator,
//! and the run's conditions and vehicles; what it measures of its state. The step itself is
//! [`step`](crate::step); where the agents are stored, the private module `storage`.

use std::borrow::Cow;

use flock_graph::{Components, Graph, NeighbourSearch, ProximityNet};
use flock_math::parallel::join;
use flock_math::{Domain, Vector};
use flock_metrics::{FlockMetrics, LatticeSummary, MetricParams, component_velocity_mismatch};
use flock_protocols::error::{ParamError, check};
use flock_protocols::{Protocol, Swarm};

use crate::checks::{
    check_acceleration_conditions, check_local_form, check_vehicle, check_vehicle_loop,
};
use crate::conditions::{Conditions, ConditionsState, Stage};
use crate::health::{AgentFault, first_fault};
use crate::integrator::Integrator;
use crate::step::perceive::{Percepts, Sensed};
use crate::vehicle::{DynVehicle, Fleet};

/// Buffers of the Runge–Kutta stages, allocated once.
#[derive(Debug)]
pub(crate) struct RungeKuttaScratch<V> {
    pub(crate) stage: Swarm<V>,
    pub(crate) net: ProximityNet,
    pub(crate) sum_q: Vec<V>,
    pub(crate) sum_p: Vec<V>,
}

/// An empty net for `protocol`: without distances when it does not read them.
pub(crate) fn empty_net<V: Vector, P: Protocol<V>>(protocol: &P) -> ProximityNet {
    if protocol.uses_net_distances() {
        ProximityNet::new()
    } else {
        ProximityNet::without_distances()
    }
}

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
/// Under real conditions ([`Simulation::with_conditions`]) each stage of the step has work to do
/// ([`Simulation::step`]); agents numbered at random are stored by cell there too, their conditions'
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
    pub(crate) protocol: P,
    pub(crate) integrator: Integrator,
    pub(crate) step: f64,
    pub(crate) steps: u64,
    pub(crate) swarm: Swarm<V>,
    pub(crate) search: NeighbourSearch,
    pub(crate) net: ProximityNet,
    /// Whether `net` is of an earlier state: after the steps of a protocol whose controls do not
    /// read it ([`Simulation::current_net`]).
    pub(crate) net_stale: bool,
    pub(crate) inputs: Vec<V>,
    pub(crate) rk: Option<RungeKuttaScratch<V>>,
    /// The real conditions of the run, `None` for the ideal run ([`Simulation::with_conditions`]).
    pub(crate) conditions: Option<Box<Stage<V>>>,
    /// Open space or a periodic box ([`Simulation::with_domain`]).
    pub(crate) domain: Domain<V>,
    /// The agents' vehicles, `None` for point masses ([`Simulation::with_vehicle`]).
    pub(crate) fleet: Option<Box<Fleet<V>>>,
    /// Whether an interrupt cut a step short after it changed the state ([`Simulation::is_torn`]).
    pub(crate) torn: bool,
    /// Every agent's perception, gathered for a controller that takes them all at once or for
    /// [`Simulation::perceive`].
    pub(crate) percepts: Percepts<V>,
    /// The step begun by [`Simulation::perceive`], to be finished by [`Simulation::act`].
    pub(crate) pending: Option<Sensed<V>>,
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
            net_stale: false,
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
            percepts: Percepts::default(),
            pending: None,
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
        match self.current_net() {
            Cow::Borrowed(net) if numbering.is_identity() => Cow::Borrowed(net.graph()),
            net if numbering.is_identity() => Cow::Owned(net.graph().clone()),
            net => Cow::Owned(net.graph().in_original_order(numbering)),
        }
    }

    /// The proximity net of the current state: the one kept, or, after steps of a protocol whose
    /// controls do not read it ([`Protocol::controls_read_net`]), one built for this read.
    pub(crate) fn current_net(&self) -> Cow<'_, ProximityNet> {
        if !self.net_stale {
            return Cow::Borrowed(&self.net);
        }
        let mut net = empty_net(&self.protocol);
        let range = self.protocol.interaction_range();
        NeighbourSearch::new().build_in(&self.domain, &self.swarm.positions, range, &mut net);
        Cow::Owned(net)
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
        self.metrics_on(&self.current_net(), params)
    }

    /// [`Simulation::metrics`] of the current state's `net`.
    fn metrics_on(&self, net: &ProximityNet, params: &MetricParams) -> FlockMetrics {
        if let Some(removed) = self.conditions.as_ref().and_then(|c| c.removed()) {
            return self.metrics_without(removed, params);
        }
        let metrics = FlockMetrics::measure_in(
            &self.domain,
            &self.swarm.positions,
            &self.swarm.velocities,
            net,
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
        let net = self.current_net();
        LatticeSummary::measure_in(&self.domain, &self.swarm.positions, &net, d, tolerance)
    }

    /// The protocol's energy at the current state.
    #[must_use]
    pub fn energy(&self) -> f64 {
        self.energy_on(&self.current_net())
    }

    /// [`Simulation::energy`] of the current state's `net`.
    fn energy_on(&self, net: &ProximityNet) -> f64 {
        self.protocol.energy(self.time(), &self.swarm, net)
    }

    /// The protocol's own diagnostics of the current state ([`Protocol::diagnostics`]).
    #[must_use]
    ///
    /// With [conditions](Simulation::with_conditions), their columns follow: `links_lost` and
    /// `information_age` (communication), `at_acceleration_limit`, `at_speed_limit` (actuation
    /// limits) and `failed` (faults).
    pub fn diagnostics(&self) -> Vec<(&'static str, f64)> {
        self.diagnostics_on(&self.current_net())
    }

    /// [`Simulation::diagnostics`] of the current state's `net`.
    fn diagnostics_on(&self, net: &ProximityNet) -> Vec<(&'static str, f64)> {
        let mut columns = self.protocol.diagnostics(self.time(), &self.swarm, net);
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
        let net = self.current_net();
        let (metrics, energy) = join(|| self.metrics_on(&net, params), || self.energy_on(&net));
        Observation {
            metrics,
            energy,
            diagnostics: self.diagnostics_on(&net),
        }
    }

    /// The velocity mismatch of each agent against the mean velocity of its own component of the
    /// net (of the [interaction graph](Protocol::interaction_graph), if any), per agent: ½ Σ_i ‖p_i − p̄_{c(i)}‖² / n (0 when every component moves rigidly).
    #[must_use]
    pub fn component_velocity_mismatch(&self) -> f64 {
        let net = self.current_net();
        let graph = self.protocol.interaction_graph().unwrap_or(net.graph());
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
    /// each agent's input from its [`LocalForm`](flock_protocols::LocalForm) with every neighbour at its image nearest the
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
            check_vehicle(stage.conditions(), fleet.vehicle())?;
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
    /// each agent's input is its protocol's [`LocalForm`](flock_protocols::LocalForm) of what it perceives.
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
        // the agents go into original order (the net's first build sorts them again when
        // scattered); under conditions RK4 takes no stages of its own (the input is held over
        // the step, see step::integrate): its buffers go before the stage is allocated
        self.back_to_original_order();
        self.rk = None;
        self.inputs.fill(V::ZERO);
        let stage = Stage::new(conditions, seed, n, self.step, range)?;
        check_acceleration_conditions(self.protocol.update().sets_velocity(), conditions)?;
        if let Some(fleet) = &self.fleet {
            check_vehicle(conditions, fleet.vehicle())?;
        }
        check_local_form(conditions, self.protocol.local_form().is_some())?;
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
            .map(|c| c.state(self.net.numbering(), &self.inputs))
    }

    /// Restores the checkpointed state of the conditions into a simulation resumed with the same
    /// conditions ([`Simulation::resume`], then [`Simulation::with_conditions`]).
    ///
    /// # Errors
    /// A simulation without conditions (field `conditions`), or a state of another run.
    pub fn restore_conditions(&mut self, state: ConditionsState) -> Result<(), ParamError> {
        match self.conditions.as_mut() {
            Some(stage) => stage.restore(state, self.net.numbering(), &mut self.inputs),
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
}

//! [`DynSimulation`]: the simulation of a scenario behind one type, whatever its dimension and
//! protocol (chosen at run time from the scenario), with its state as plain `f64` rows;
//! [`MapProtocol`]: the scenario's protocol replaced by one built from it (e.g. u_i computed
//! elsewhere, the range, energy and diagnostics kept), in either dimension.

use std::borrow::Cow;

use flock_graph::Graph;
use flock_metrics::{EDGE_TOLERANCE, FlockMetrics, LatticeSummary, MetricParams};
use flock_obstacles::Space;
use flock_protocols::check::MAX_VALUE;
use flock_protocols::{DynProtocol, ParamError, Swarm};
use flock_sim::conditions::ConditionsState;
use flock_sim::{AgentFault, Observation, Simulation};
use glam::{DVec2, DVec3};

use crate::error::ScenarioError;
use crate::health::NumericalError;
use crate::initial::{initial_swarm, to_vector};
use crate::perception::Perception;
use crate::scenario::Scenario;
use crate::vehicle::VehicleSpace;
use flock_sim::step::perceive::Percepts;

/// The whole state of a run after some steps: what a checkpoint keeps so that the run can be
/// resumed bit-identically (a simulation carries nothing else between steps).
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    /// The number of steps taken.
    pub steps: u64,
    /// H at t = 0 (for the run's summary).
    pub initial_energy: f64,
    /// The positions, `dim` coordinates per agent, agents in original order.
    pub positions: Vec<f64>,
    /// The velocities, `dim` coordinates per agent.
    pub velocities: Vec<f64>,
    /// The state of the run's conditions (delay line, links, noise, lag, faults) as RON, empty
    /// for an ideal run ([`flock_sim::conditions::ConditionsState`]).
    pub conditions: String,
    /// The vehicles' states ([`State::vehicle`]), empty for point masses.
    pub vehicle: Vec<f64>,
}

impl Start {
    /// Checks the state a run continues from as a scenario's start is checked, before anything
    /// is built from it (issue 49: a checkpoint forged or damaged, its hash made to match, was
    /// continued from NaN or 10³⁰⁰, or refused only once the run's directory was being
    /// rewritten): every position finite, inside the periodic box (as the run wraps it) or in
    /// open space within ±(10⁹ + steps · r), as far as a start within ±10⁹ can get when no agent
    /// moves more than the interaction range r in one step; every velocity finite, no speed above
    /// r/h (what the run's health check lets through); every vehicle state finite within ±10⁹.
    /// The lengths of the rows are checked by [`DynSimulation::resume`], the state of the
    /// conditions by [`ConditionsState`]'s restore.
    ///
    /// # Errors
    /// The first value refused: `positions[i]`, `velocities[i]` or `vehicle[k]` of the checkpoint.
    pub fn check(&self, scenario: &Scenario) -> Result<(), ScenarioError> {
        let dim = scenario.dim.max(1);
        let (r, h) = (scenario.range(), scenario.step);
        let refused = |field: String, value: &[f64], why: String| {
            Err(ScenarioError::invalid(
                field,
                value,
                why,
                "the checkpoint is damaged: start the run again (flocking run SCENARIO --out DIR --force)",
            ))
        };
        let reach = MAX_VALUE + self.steps as f64 * r;
        let size = scenario.box_size();
        for (i, q) in self.positions.chunks_exact(dim).enumerate() {
            let outside = match &size {
                Some(size) => q.iter().zip(size).any(|(&x, &l)| !(0.0..l).contains(&x)),
                None => q.iter().any(|x| !(x.is_finite() && x.abs() <= reach)),
            };
            if outside {
                let domain = match &size {
                    Some(size) => {
                        format!("the periodic box {size:?}, where the run keeps every agent")
                    }
                    None => format!(
                        "±{reach:e}, the farthest a run from a start within ±{MAX_VALUE:e} gets in {} steps of at most r = {r}",
                        self.steps
                    ),
                };
                return refused(
                    format!("positions[{i}]"),
                    q,
                    format!("is not within {domain}"),
                );
            }
        }
        let fastest = r / h;
        for (i, p) in self.velocities.chunks_exact(dim).enumerate() {
            let speed = p.iter().map(|x| x * x).sum::<f64>().sqrt();
            if speed.is_nan() || speed > fastest {
                return refused(
                    format!("velocities[{i}]"),
                    p,
                    format!(
                        "is not a speed of at most r/h = {fastest:e}, which every step of a run keeps"
                    ),
                );
            }
        }
        if let Some(k) = self
            .vehicle
            .iter()
            .position(|x| !(x.is_finite() && x.abs() <= MAX_VALUE))
        {
            return refused(
                format!("vehicle[{k}]"),
                &self.vehicle[k..=k],
                format!("is not a vehicle's state value, finite within ±{MAX_VALUE:e}"),
            );
        }
        Ok(())
    }
}

/// A state as plain numbers: n rows of `dim` coordinates, agents in original order.
#[derive(Clone, Debug, PartialEq)]
pub struct State<'a> {
    /// The dimension, 2 or 3.
    pub dim: usize,
    /// The positions: agent i at `positions[i * dim..(i + 1) * dim]`.
    pub positions: Cow<'a, [f64]>,
    /// The velocities, as the positions.
    pub velocities: Cow<'a, [f64]>,
    /// The names of each agent's vehicle state beyond its reference point's position and
    /// velocity ([`Vehicle::state_columns`](flock_sim::Vehicle::state_columns)), empty
    /// for point masses.
    pub vehicle_columns: &'static [&'static str],
    /// The vehicles' states: agent i's at `vehicle[i * k..(i + 1) * k]`, k the number of
    /// `vehicle_columns`.
    pub vehicle: Cow<'a, [f64]>,
    /// Which agents have failed, agent i at `failed[i]`, when the scenario's conditions have
    /// `faults` (the `failed` column of the trajectory and `final.csv`); `None` otherwise.
    pub failed: Option<Cow<'a, [bool]>>,
}

impl State<'_> {
    /// The number of agents.
    #[must_use]
    pub fn agents(&self) -> usize {
        self.positions.len() / self.dim.max(1)
    }

    /// The state as owned rows.
    #[must_use]
    pub fn into_owned(self) -> State<'static> {
        State {
            dim: self.dim,
            positions: Cow::Owned(self.positions.into_owned()),
            velocities: Cow::Owned(self.velocities.into_owned()),
            vehicle_columns: self.vehicle_columns,
            vehicle: Cow::Owned(self.vehicle.into_owned()),
            failed: self.failed.map(|f| Cow::Owned(f.into_owned())),
        }
    }
}

/// A change of the protocol a [`DynSimulation`] simulates, the same in 2D and 3D: the scenario's
/// protocol in, the protocol to simulate out — typically a wrapper that computes the inputs u_i
/// its own way and keeps the scenario's interaction range, energy and diagnostics (the Python
/// package's `controls=`). [`ScenarioProtocol`] changes nothing.
pub trait MapProtocol {
    /// The protocol to simulate in place of `protocol`, the scenario's, in dimension `V::DIM`.
    fn map<V: Space + bytemuck::Pod>(&self, protocol: DynProtocol<V>) -> DynProtocol<V>;
}

/// The scenario's own protocol, unchanged: the [`MapProtocol`] of [`DynSimulation::new`].
#[derive(Clone, Copy, Debug, Default)]
pub struct ScenarioProtocol;

impl MapProtocol for ScenarioProtocol {
    fn map<V: Space + bytemuck::Pod>(&self, protocol: DynProtocol<V>) -> DynProtocol<V> {
        protocol
    }
}

/// A [`MapProtocol`] as a trait object, its two dimensions spelled out: what the builders of
/// [`DynSimulation`] take, so that they (the simulation loop and every protocol) are compiled
/// once, here, rather than again in every crate for every map (issue 51: 848k LLVM lines in
/// flock-cli's library when they were generic over the map).
pub(crate) trait MapBoth {
    /// [`MapProtocol::map`] in the plane.
    fn map_2d(&self, protocol: DynProtocol<DVec2>) -> DynProtocol<DVec2>;
    /// [`MapProtocol::map`] in space.
    fn map_3d(&self, protocol: DynProtocol<DVec3>) -> DynProtocol<DVec3>;
}

impl<M: MapProtocol> MapBoth for M {
    fn map_2d(&self, protocol: DynProtocol<DVec2>) -> DynProtocol<DVec2> {
        self.map(protocol)
    }

    fn map_3d(&self, protocol: DynProtocol<DVec3>) -> DynProtocol<DVec3> {
        self.map(protocol)
    }
}

/// The vectors of a dimension a [`DynSimulation`] is built in, with the map of that dimension.
trait Dimension: Space + bytemuck::Pod + VehicleSpace {
    /// `map` applied to `protocol` in this dimension.
    fn mapped(map: &dyn MapBoth, protocol: DynProtocol<Self>) -> DynProtocol<Self>;
}

impl Dimension for DVec2 {
    fn mapped(map: &dyn MapBoth, protocol: DynProtocol<Self>) -> DynProtocol<Self> {
        map.map_2d(protocol)
    }
}

impl Dimension for DVec3 {
    fn mapped(map: &dyn MapBoth, protocol: DynProtocol<Self>) -> DynProtocol<Self> {
        map.map_3d(protocol)
    }
}

/// What a [`DynSimulation`] asks of the simulation it holds, in either dimension.
trait Dynamic: Send {
    fn step(&mut self);
    fn is_torn(&self) -> bool;
    fn steps(&self) -> u64;
    fn time(&self) -> f64;
    fn state(&self) -> State<'_>;
    fn graph(&self) -> Cow<'_, Graph>;
    fn stored_by_cell(&self) -> bool;
    fn metrics(&self, params: &MetricParams) -> FlockMetrics;
    fn energy(&self) -> f64;
    fn observe(&self, params: &MetricParams) -> Observation;
    fn component_velocity_mismatch(&self) -> f64;
    fn lattice(&self, d: f64, tolerance: f64) -> LatticeSummary;
    fn check_health(&self) -> Result<(), AgentFault>;
    fn conditions_state(&self) -> Option<ConditionsState>;
    fn restore_conditions(&mut self, state: ConditionsState) -> Result<(), ParamError>;
    fn perceive(&mut self, perception: &mut Perception) -> bool;
    fn act(&mut self, inputs: &[f64]);
    fn protocol_inputs(&mut self, out: &mut [f64]) -> bool;
}

/// The rows of vectors `V` (each `V::DIM` contiguous `f64`).
fn rows<V: Space + bytemuck::Pod>(vectors: Cow<'_, [V]>) -> Cow<'_, [f64]> {
    match vectors {
        Cow::Borrowed(v) => Cow::Borrowed(bytemuck::cast_slice(v)),
        Cow::Owned(v) => Cow::Owned(bytemuck::cast_slice(&v).to_vec()),
    }
}

impl<V: Space + bytemuck::Pod> Dynamic for Simulation<V, DynProtocol<V>> {
    fn step(&mut self) {
        Simulation::step(self);
    }

    fn is_torn(&self) -> bool {
        Simulation::is_torn(self)
    }

    fn steps(&self) -> u64 {
        Simulation::steps(self)
    }

    fn time(&self) -> f64 {
        Simulation::time(self)
    }

    fn state(&self) -> State<'_> {
        let (positions, velocities) = match self.swarm() {
            Cow::Borrowed(swarm) => (
                Cow::Borrowed(&swarm.positions[..]),
                Cow::Borrowed(&swarm.velocities[..]),
            ),
            Cow::Owned(swarm) => (Cow::Owned(swarm.positions), Cow::Owned(swarm.velocities)),
        };
        let (vehicle_columns, vehicle) = match (self.fleet(), self.vehicle_states()) {
            (Some(fleet), Some(states)) => (fleet.vehicle().state_columns(), states),
            _ => (&[][..], Cow::Borrowed(&[][..])),
        };
        State {
            dim: V::DIM,
            positions: rows(positions),
            velocities: rows(velocities),
            vehicle_columns,
            vehicle,
            failed: self.failed(),
        }
    }

    fn graph(&self) -> Cow<'_, Graph> {
        Simulation::graph(self)
    }

    fn stored_by_cell(&self) -> bool {
        Simulation::stored_by_cell(self)
    }

    fn metrics(&self, params: &MetricParams) -> FlockMetrics {
        Simulation::metrics(self, params)
    }

    fn energy(&self) -> f64 {
        Simulation::energy(self)
    }

    fn observe(&self, params: &MetricParams) -> Observation {
        Simulation::observe(self, params)
    }

    fn component_velocity_mismatch(&self) -> f64 {
        Simulation::component_velocity_mismatch(self)
    }

    fn lattice(&self, d: f64, tolerance: f64) -> LatticeSummary {
        Simulation::lattice(self, d, tolerance)
    }

    fn check_health(&self) -> Result<(), AgentFault> {
        Simulation::check_health(self)
    }

    fn conditions_state(&self) -> Option<ConditionsState> {
        Simulation::conditions_state(self)
    }

    fn restore_conditions(&mut self, state: ConditionsState) -> Result<(), ParamError> {
        Simulation::restore_conditions(self, state)
    }

    fn perceive(&mut self, perception: &mut Perception) -> bool {
        if Simulation::perceive(self).is_none() {
            return false;
        }
        let t = self.time();
        if let Some(all) = self.perceived() {
            perception.fill(t, all.perceptions(), self.protocol().local_form());
        }
        true
    }

    fn act(&mut self, inputs: &[f64]) {
        let stored: Vec<V> = match Simulation::perceive(self) {
            Some(all) => all
                .perceptions()
                .owns
                .iter()
                .map(|own| {
                    let i = own.agent as usize;
                    to_vector(&inputs[i * V::DIM..(i + 1) * V::DIM])
                })
                .collect(),
            None => Vec::new(),
        };
        Simulation::act(self, &stored);
    }

    fn protocol_inputs(&mut self, out: &mut [f64]) -> bool {
        let Some(n) = self.perceived().map(Percepts::len) else {
            return false;
        };
        let mut stored = vec![V::ZERO; n];
        Simulation::protocol_inputs(self, &mut stored);
        if let Some(all) = self.perceived() {
            for (u, own) in stored.iter().zip(all.perceptions().owns) {
                let i = own.agent as usize;
                for (k, x) in out[i * V::DIM..(i + 1) * V::DIM].iter_mut().enumerate() {
                    *x = u.coord(k);
                }
            }
        }
        true
    }
}

/// The simulation of a scenario, in its dimension, with its protocol: one type for every scenario,
/// whose state and measurements are plain numbers, agents always in original order.
///
/// # Example
/// ```
/// use flocking::{DynSimulation, Scenario};
///
/// # std::env::set_current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).unwrap(); // the workspace root
/// let scenario = Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
/// let mut sim = DynSimulation::new(&scenario)?;
/// let h0 = sim.energy();
/// for _ in 0..200 {
///     sim.step();
/// }
/// assert_eq!(sim.time(), 2.0);
/// assert!(sim.energy() < h0);
/// let state = sim.state();
/// assert_eq!((state.dim, state.agents()), (2, 100));
/// let metrics = sim.metrics();
/// assert!(metrics.connectivity > 0.0 && metrics.connectivity <= 1.0);
/// # Ok::<(), flocking::ScenarioError>(())
/// ```
pub struct DynSimulation {
    inner: Box<dyn Dynamic>,
    dim: usize,
    agents: usize,
    metric_params: MetricParams,
    scenario: Scenario,
}

impl std::fmt::Debug for DynSimulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DynSimulation")
            .field("scenario", &self.scenario.name)
            .field("dim", &self.dim)
            .field("agents", &self.agents)
            .field("steps", &self.steps())
            .finish_non_exhaustive()
    }
}

impl DynSimulation {
    /// The simulation of `scenario` at t = 0, from its initial condition.
    ///
    /// # Errors
    /// An invalid scenario.
    pub fn new(scenario: &Scenario) -> Result<Self, ScenarioError> {
        Self::new_with(scenario, &ScenarioProtocol)
    }

    /// [`DynSimulation::new`] simulating the protocol `map` makes of the scenario's.
    ///
    /// # Errors
    /// An invalid scenario.
    pub fn new_with<M: MapProtocol>(scenario: &Scenario, map: &M) -> Result<Self, ScenarioError> {
        Self::new_mapped(scenario, map)
    }

    /// [`DynSimulation::new_with`], compiled once for every map.
    fn new_mapped(scenario: &Scenario, map: &dyn MapBoth) -> Result<Self, ScenarioError> {
        scenario.validate()?;
        match scenario.dim {
            2 => Self::of(scenario, initial_swarm::<DVec2>(scenario), 0, None, map),
            _ => Self::of(scenario, initial_swarm::<DVec3>(scenario), 0, None, map),
        }
    }

    /// The simulation of `scenario` after `steps` steps, at t = steps · h, from the state given
    /// as rows (`dim` coordinates per agent, agents in original order): an explicit initial
    /// state (`steps` = 0), or one to continue from.
    ///
    /// # Errors
    /// An invalid scenario, rows of another size than the scenario's agents in its dimension
    /// (field `agents`), or a coordinate that is not finite.
    pub fn from_state(
        scenario: &Scenario,
        positions: &[f64],
        velocities: &[f64],
        steps: u64,
    ) -> Result<Self, ScenarioError> {
        Self::from_state_with(scenario, positions, velocities, steps, &ScenarioProtocol)
    }

    /// [`DynSimulation::from_state`] simulating the protocol `map` makes of the scenario's.
    ///
    /// # Errors
    /// As [`DynSimulation::from_state`].
    pub fn from_state_with<M: MapProtocol>(
        scenario: &Scenario,
        positions: &[f64],
        velocities: &[f64],
        steps: u64,
        map: &M,
    ) -> Result<Self, ScenarioError> {
        Self::from_rows(scenario, positions, velocities, steps, None, map)
    }

    /// [`DynSimulation::from_state_with`], the vehicles in `vehicle` states if given (else each
    /// started in its equilibrium).
    fn from_rows(
        scenario: &Scenario,
        positions: &[f64],
        velocities: &[f64],
        steps: u64,
        vehicle: Option<Vec<f64>>,
        map: &dyn MapBoth,
    ) -> Result<Self, ScenarioError> {
        scenario.validate()?;
        let size = scenario.agents * scenario.dim;
        for (name, rows) in [("positions", positions), ("velocities", velocities)] {
            if rows.len() != size {
                return Err(ScenarioError::invalid(
                    "agents",
                    scenario.agents,
                    format!(
                        "the state holds {} coordinates of {name} where {} agents in {}D need {size}",
                        rows.len(),
                        scenario.agents,
                        scenario.dim
                    ),
                    "give one row of dim coordinates per agent (or change agents)",
                ));
            }
        }
        match scenario.dim {
            2 => Self::of(
                scenario,
                swarm_of::<DVec2>(positions, velocities),
                steps,
                vehicle,
                map,
            ),
            _ => Self::of(
                scenario,
                swarm_of::<DVec3>(positions, velocities),
                steps,
                vehicle,
                map,
            ),
        }
    }

    /// The simulation of `scenario` from its initial condition (`start` `None`), or continued
    /// from the checkpoint `start` ([`DynSimulation::resume_with`]), simulating the protocol
    /// `map` makes of the scenario's.
    ///
    /// # Errors
    /// As [`DynSimulation::new`] or [`DynSimulation::resume_with`].
    pub fn build_with<M: MapProtocol>(
        scenario: &Scenario,
        start: Option<&Start>,
        map: &M,
    ) -> Result<Self, ScenarioError> {
        Self::build_mapped(scenario, start, map)
    }

    /// [`DynSimulation::build_with`], compiled once for every map.
    pub(crate) fn build_mapped(
        scenario: &Scenario,
        start: Option<&Start>,
        map: &dyn MapBoth,
    ) -> Result<Self, ScenarioError> {
        match start {
            None => Self::new_mapped(scenario, map),
            Some(start) => Self::resume_mapped(scenario, start, map),
        }
    }

    /// The simulation continued from `start`, a checkpoint of the same scenario: stepping it
    /// gives the bits of the uninterrupted run.
    ///
    /// # Errors
    /// As [`DynSimulation::from_state`].
    ///
    /// A run with conditions continues from the state of its conditions the checkpoint keeps
    /// (delay line, links, noise, lag, faults), so the random conditions keep their bits too.
    pub fn resume(scenario: &Scenario, start: &Start) -> Result<Self, ScenarioError> {
        Self::resume_with(scenario, start, &ScenarioProtocol)
    }

    /// [`DynSimulation::resume`] simulating the protocol `map` makes of the scenario's.
    ///
    /// # Errors
    /// As [`DynSimulation::from_state`], a state [`Start::check`] refuses, or a checkpoint
    /// without a readable state of the scenario's conditions (field `conditions`) or with one of
    /// another run (`conditions_state.…`).
    pub fn resume_with<M: MapProtocol>(
        scenario: &Scenario,
        start: &Start,
        map: &M,
    ) -> Result<Self, ScenarioError> {
        Self::resume_mapped(scenario, start, map)
    }

    /// [`DynSimulation::resume_with`], compiled once for every map.
    fn resume_mapped(
        scenario: &Scenario,
        start: &Start,
        map: &dyn MapBoth,
    ) -> Result<Self, ScenarioError> {
        scenario.validate()?;
        start.check(scenario)?;
        let (q, p) = (&start.positions, &start.velocities);
        let vehicle = (!start.vehicle.is_empty()).then(|| start.vehicle.clone());
        let mut sim = Self::from_rows(scenario, q, p, start.steps, vehicle, map)?;
        if scenario.conditions.is_ideal() {
            return Ok(sim);
        }
        let refused = |why: String| {
            ScenarioError::invalid(
                "conditions",
                "(the checkpoint's state)",
                why,
                "start the run again without --resume",
            )
        };
        let state: ConditionsState = ron::from_str(&start.conditions).map_err(|e| {
            refused(format!(
                "the checkpoint holds no readable state of the conditions ({e})"
            ))
        })?;
        sim.inner.restore_conditions(state)?;
        Ok(sim)
    }

    /// The simulation in vectors `V`: generic over the dimension only, so compiled twice, in
    /// this crate.
    fn of<V: Dimension>(
        scenario: &Scenario,
        swarm: Swarm<V>,
        steps: u64,
        vehicle_states: Option<Vec<f64>>,
        map: &dyn MapBoth,
    ) -> Result<Self, ScenarioError> {
        let protocol = V::mapped(map, scenario.protocol::<V>()?);
        let agents = swarm.len();
        let mut sim =
            Simulation::resume(protocol, scenario.integrator, swarm, scenario.step, steps)?
                .with_domain(scenario.domain())?;
        if let Some(vehicle) = V::vehicle(&scenario.vehicle)? {
            sim = sim.with_vehicle(vehicle, vehicle_states)?;
        }
        let sim = sim.with_conditions(&scenario.conditions, scenario.seed)?;
        Ok(Self {
            inner: Box::new(sim),
            dim: V::DIM,
            agents,
            metric_params: MetricParams {
                d: scenario.alpha.d,
                collision_distance: scenario.collision_distance(),
            },
            scenario: scenario.clone(),
        })
    }

    /// The scenario simulated.
    #[must_use]
    pub const fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The dimension, 2 or 3.
    #[must_use]
    pub const fn dim(&self) -> usize {
        self.dim
    }

    /// The number of agents.
    #[must_use]
    pub const fn agents(&self) -> usize {
        self.agents
    }

    /// Advances the state by one step h. An interrupt ([`crate::interrupt`]) may cut a long step
    /// short: then the step is not taken (the state and [`DynSimulation::steps`] stay those of
    /// the steps taken), or, cut inside a vehicle's inner steps or the conditions' stage, the
    /// simulation is [torn](DynSimulation::is_torn) ([`Simulation::step`]).
    pub fn step(&mut self) {
        self.inner.step();
    }

    /// The first half of a step for a controller outside the loop (a policy, an environment's
    /// agent): fail → sense → communicate, and what every agent perceives, into `perception`
    /// ([`Simulation::perceive`]). False, `perception` untouched, at a step without a control
    /// update (sampled control: the inputs are held) or when the simulation is torn.
    pub fn perceive(&mut self, perception: &mut Perception) -> bool {
        self.inner.perceive(perception)
    }

    /// The second half of the step [`DynSimulation::perceive`] began (begun here if it was
    /// not): every agent's input from `inputs` (n rows of dim, original order; ignored at a step
    /// without a control update), then actuate → integrate ([`Simulation::act`]).
    ///
    /// # Panics
    /// When `inputs` holds fewer than n × dim numbers at a control update.
    pub fn act(&mut self, inputs: &[f64]) {
        self.inner.act(inputs);
    }

    /// What the scenario's protocol would command for the perceptions of
    /// [`DynSimulation::perceive`], into `out` (n rows of dim, original order): the inputs a
    /// [`DynSimulation::step`] applies, bit for bit ([`Simulation::protocol_inputs`]). False,
    /// `out` untouched, when no perception is pending.
    pub fn protocol_inputs(&mut self, out: &mut [f64]) -> bool {
        self.inner.protocol_inputs(out)
    }

    /// Whether an interrupt cut a step short after it had changed the state: the state is then
    /// between two steps and must not be recorded, and the simulation takes no more steps.
    #[must_use]
    pub fn is_torn(&self) -> bool {
        self.inner.is_torn()
    }

    /// The number of steps taken.
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.inner.steps()
    }

    /// The current time t = steps · h.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.inner.time()
    }

    /// The current state, agents in original order (borrowed when the simulation stores them so).
    #[must_use]
    pub fn state(&self) -> State<'_> {
        self.inner.state()
    }

    /// The proximity net's graph of the current state, agents in original order.
    #[must_use]
    pub fn graph(&self) -> Cow<'_, Graph> {
        self.inner.graph()
    }

    /// Whether the simulation stores the agents by cell (they were numbered at random); the state
    /// and every measurement are in original order either way.
    #[must_use]
    pub fn stored_by_cell(&self) -> bool {
        self.inner.stored_by_cell()
    }

    /// The flocking metrics of the current state (TAC 2006 Section VIII) with the scenario's d and
    /// collision distance.
    #[must_use]
    pub fn metrics(&self) -> FlockMetrics {
        self.inner.metrics(&self.metric_params)
    }

    /// The protocol's energy H at the current state.
    #[must_use]
    pub fn energy(&self) -> f64 {
        self.inner.energy()
    }

    /// The metrics, the energy and the protocol's named diagnostics of the current state,
    /// computed together (what a recorded step measures).
    #[must_use]
    pub fn observe(&self) -> Observation {
        self.inner.observe(&self.metric_params)
    }

    /// The velocity mismatch against each agent's own component, per agent.
    #[must_use]
    pub fn component_velocity_mismatch(&self) -> f64 {
        self.inner.component_velocity_mismatch()
    }

    /// The lattice of the current state: edges, those within ±10 % of d, triangles and, in 2D,
    /// TAC 2006 Theorem 5's bound 3n − 6 and the crossing edges.
    #[must_use]
    pub fn lattice(&self) -> LatticeSummary {
        self.inner.lattice(self.metric_params.d, EDGE_TOLERANCE)
    }

    /// Checks the current state: finite, and no agent faster than r/h.
    ///
    /// # Errors
    /// The agent at fault of lowest original index, with the step, the time and the likely cause.
    pub fn check_health(&self) -> Result<(), NumericalError> {
        self.inner
            .check_health()
            .map_err(|fault| NumericalError::new(&self.scenario, self.steps(), self.time(), fault))
    }

    /// The state after the steps taken, as a checkpoint keeps it (with H(0) = `initial_energy`).
    #[must_use]
    pub fn start(&self, initial_energy: f64) -> Start {
        let state = self.state();
        Start {
            steps: self.steps(),
            initial_energy,
            positions: state.positions.into_owned(),
            velocities: state.velocities.into_owned(),
            conditions: self
                .inner
                .conditions_state()
                .map(|c| ron::to_string(&c).unwrap_or_default())
                .unwrap_or_default(),
            vehicle: state.vehicle.into_owned(),
        }
    }
}

/// The swarm of rows (validated lengths).
fn swarm_of<V: Space>(positions: &[f64], velocities: &[f64]) -> Swarm<V> {
    let vectors = |rows: &[f64]| rows.chunks_exact(V::DIM).map(to_vector::<V>).collect();
    Swarm::new(vectors(positions), vectors(velocities))
}

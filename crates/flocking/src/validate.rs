//! Validation of a parsed scenario: every value inside the domain the theory needs. The domain of
//! each parameter type is checked by the type itself (`flock-protocols`: [`AlphaConfig`],
//! [`BetaConfig`], [`AvoidanceGains`], [`GammaAgent`]); this module adds what only the whole
//! scenario knows (the dimension of its vectors, its agents, obstacles and graph).
//!
//! [`AlphaConfig`]: flock_protocols::AlphaConfig
//! [`BetaConfig`]: flock_protocols::BetaConfig
//! [`AvoidanceGains`]: flock_protocols::AvoidanceGains

use flock_graph::{Components, Graph};
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use flock_protocols::check::{
    self, Check, MAX_VALUE, WHY_BOUNDED, length, non_negative, positive, require,
};
use flock_protocols::{GammaAgent, ParamError};
use glam::{DVec2, DVec3};

use crate::error::ScenarioError;
use crate::estimate::START_COUNT_BUDGET;
use crate::initial::{initial_positions, initial_velocities};
use crate::scenario::{Algorithm, Cloud, DomainSpec, FixedGraph, Point, Scenario};
use crate::stability::coincident_start;

/// The most agents accepted: flocking keeps about 250 bytes per agent (docs/performance.md).
pub const MAX_AGENTS: usize = 100_000_000;

/// The most steps a run may take (duration / step): 10¹² steps of one agent take days.
pub const MAX_STEPS: f64 = 1e12;

/// `v` has `dim` finite coordinates within ±10⁹.
fn vector(field: &str, v: &[f64], dim: usize) -> Check {
    require(
        v.len() == dim,
        field,
        v,
        &format!(
            "has {} components but the scenario has dim = {dim}",
            v.len()
        ),
        &format!(
            "give exactly {dim} numbers, e.g. [{}]",
            vec!["0.0"; dim].join(", ")
        ),
    )?;
    check::coordinates(field, v)
}

/// The problems of a scenario: every independent check runs and records its error, so that one
/// edit (say `dim: 2` to `dim: 3`) shows every value it invalidates at once.
#[derive(Default)]
struct Problems(Vec<ScenarioError>);

impl Problems {
    /// Records the error of one check, if any.
    fn check(&mut self, outcome: Result<(), impl Into<ScenarioError>>) {
        if let Err(e) = outcome {
            self.0.push(e.into());
        }
    }
}

impl Scenario {
    /// Checks every value against its domain.
    ///
    /// # Errors
    /// Every invalid value, each with its field, why and the fix: the one error, or
    /// [`ScenarioError::Several`] in the order of the checks.
    pub fn validate(&self) -> Result<(), ScenarioError> {
        let mut problems = Problems::default();
        self.validate_values(&mut problems);
        if problems.0.is_empty() {
            if matches!(self.algorithm, Algorithm::Tanner(_)) {
                problems.check(self.validate_distinct_start());
            }
            problems.check(self.validate_obstacles());
            problems.check(self.validate_speeds());
        }
        let mut errors = problems.0;
        match errors.len() {
            0 => Ok(()),
            1 => Err(errors.remove(0)),
            _ => Err(ScenarioError::Several(errors)),
        }
    }

    /// Everything but what needs the initial state or the obstacles built; with a wrong `dim`
    /// nothing else (every vector would be wrong).
    fn validate_values(&self, problems: &mut Problems) {
        let dim = self.dim;
        problems.check(require(
            dim == 2 || dim == 3,
            "dim",
            dim,
            "flocking simulates the plane or space",
            "set dim: 2 or dim: 3",
        ));
        if !problems.0.is_empty() {
            return;
        }
        problems.check(self.validate_agents());
        problems.check(self.alpha.validate().map_err(|e| e.within("alpha")));
        problems.check(self.validate_time());
        problems.check(require(
            self.record_every >= 1,
            "record_every",
            self.record_every,
            "must be ≥ 1",
            "record every 1 or more steps",
        ));
        if let Some(c) = self.collision_distance {
            problems.check(positive("collision_distance", c).and_then(|()| {
                require(
                    c <= self.range(),
                    "collision_distance",
                    c,
                    &format!("exceeds the interaction range r = {}", self.range()),
                    "choose a collision distance at most r (default d/4)",
                )
            }));
        }
        self.validate_algorithm(problems);
        self.validate_cloud(problems, "initial.positions", &self.initial.positions);
        self.validate_cloud(problems, "initial.velocities", &self.initial.velocities);
        self.validate_conditions(problems);
        if self.validate_time().is_ok() {
            let vehicle = match self.dim {
                2 => self.validate_vehicle::<glam::DVec2>(),
                _ => self.validate_vehicle::<glam::DVec3>(),
            };
            if vehicle.is_ok() {
                problems.check(self.validate_work());
            }
            problems.check(vehicle);
        }
        if let Some(times) = &self.snapshots {
            problems.check(self.validate_snapshots(times));
        }
    }

    /// Snapshot times ≥ 0, increasing, and not too many to draw (a time beyond the end, as after
    /// shortening a run, is drawn at its last record).
    fn validate_snapshots(&self, times: &[f64]) -> Check {
        require(
            !times.is_empty() && times.len() <= crate::scenario::MAX_SNAPSHOTS,
            "snapshots",
            times.len(),
            &format!(
                "is the number of times; it must be 1 to {}",
                crate::scenario::MAX_SNAPSHOTS
            ),
            "list the times to draw, e.g. snapshots: [0.0, 4.0, 30.0], or leave it out for six even ones",
        )?;
        for (k, &t) in times.iter().enumerate() {
            require(
                t.is_finite() && t >= 0.0,
                &format!("snapshots[{k}]"),
                t,
                "is not a time of the run",
                "give a time ≥ 0 in seconds (one beyond the end is drawn at the last record)",
            )?;
            if k > 0 {
                require(
                    t > times[k - 1],
                    &format!("snapshots[{k}]"),
                    t,
                    &format!("does not follow {} s", times[k - 1]),
                    "list the times in increasing order",
                )?;
            }
        }
        Ok(())
    }

    /// The conditions' own domains ([`Conditions::validate`](flock_sim::Conditions::validate),
    /// whose delays and periods are whole numbers of a valid step), and a protocol able to compute
    /// u_i from one agent's perception when a condition makes agents perceive different worlds.
    fn validate_conditions(&self, problems: &mut Problems) {
        if self.conditions.is_ideal() {
            return;
        }
        if self.validate_time().is_ok() {
            problems.check(self.conditions.validate(self.agents, self.dim, self.step));
        }
        if let Err(refusal) =
            flock_sim::checks::check_local_form(&self.conditions, self.algorithm.has_local_form())
        {
            // issue 49: the cutoff is what gives Cucker–Smale a local form
            let refusal = if self.algorithm.couples_every_pair() {
                ParamError {
                    why: "makes each agent perceive its own world (delayed, lost, noisy or missing neighbours), but Cucker–Smale without a cutoff couples every pair, which no agent perceives".to_owned(),
                    fix: "set algorithm.cutoff (each agent then sums over the neighbours it perceives within it), or remove this condition".to_owned(),
                    ..refusal
                }
            } else {
                refusal
            };
            problems.check(Err::<(), _>(refusal));
        }
        problems.check(flock_sim::checks::check_acceleration_conditions(
            self.algorithm.sets_velocity(),
            &self.conditions,
        ));
    }

    /// The vehicle in the scenario's dimension: its parameters, its inner step against the step,
    /// the protocol and integrator that drive it, and the conditions it can take
    /// (docs/vehicles.md).
    fn validate_vehicle<V: crate::vehicle::VehicleSpace>(&self) -> Result<(), ScenarioError> {
        let Some(vehicle) = V::vehicle(&self.vehicle)? else {
            return Ok(());
        };
        let sets_velocity = self.algorithm.sets_velocity();
        flock_sim::checks::check_vehicle_loop(sets_velocity, self.integrator, &*vehicle)?;
        flock_sim::vehicle::check_inner_step(&*vehicle, self.step)?;
        flock_sim::checks::check_vehicle(&self.conditions, &*vehicle)?;
        Ok(())
    }

    /// No agent faster than r/h, the speed at which the run's health check stops it (it would
    /// cross more than the interaction range r in one step): neither a model that sets every
    /// agent's speed (Vicsek's v₀, Couzin's and the boids' speed) nor any agent of the start
    /// (issue 49: such runs validated, then failed at their first step as a "numerical blow-up",
    /// with the wrong fix).
    fn validate_speeds(&self) -> Result<(), ScenarioError> {
        let (r, h) = (self.range(), self.step);
        let fastest = r / h;
        if let Some((field, speed)) = self.algorithm.set_speed() {
            require(
                speed <= fastest,
                field,
                speed,
                &format!(
                    "moves every agent {speed} × step {h} = {} a step, farther than its interaction range r = {r}: it would pass every neighbour it sees within a step, which the run stops as a blow-up",
                    speed * h
                ),
                &format!(
                    "use a speed of at most r / step = {fastest}, or a step of at most r / speed = {}",
                    r / speed
                ),
            )?;
        }
        let fastest_start = match self.dim {
            2 => fastest_agent(initial_velocities::<DVec2>(self)),
            _ => fastest_agent(initial_velocities::<DVec3>(self)),
        };
        match fastest_start {
            Some((i, speed)) if speed.is_nan() || speed > fastest => Err(ScenarioError::invalid(
                "initial.velocities",
                format!("agent {i} at speed {speed}"),
                format!(
                    "is faster than r/h = {fastest}: it would cross more than the interaction range r = {r} ({}) in its first step, which the run stops as a blow-up",
                    self.range_field()
                ),
                format!(
                    "start slower (at most {fastest}), or take a shorter step or a longer {}",
                    self.range_field()
                ),
            )),
            _ => Ok(()),
        }
    }

    /// The field that sets the interaction range r of [`Scenario::range`].
    fn range_field(&self) -> &'static str {
        match &self.algorithm {
            Algorithm::CuckerSmale(p) if p.cutoff.is_some() => "algorithm.cutoff",
            Algorithm::Vicsek(_) => "algorithm.r",
            Algorithm::Boids(_) => "algorithm.visual_distance",
            Algorithm::Couzin(_) => "algorithm.delta_r_a",
            Algorithm::Vasarhelyi(_) => "algorithm.r_c",
            _ => "alpha.r",
        }
    }

    /// The work of one step at most what the estimate counts ([`START_COUNT_BUDGET`], 2³²): the
    /// pairs of a model that couples every pair, the inner steps of every agent's vehicle (issue
    /// 49: Cucker–Smale without a cutoff at 30,000 agents took 13 s a step, an inner step of
    /// 10⁻³⁰⁰ s never ended, both estimated at seconds).
    fn validate_work(&self) -> Check {
        let budget = START_COUNT_BUDGET as f64;
        let n = self.agents as f64;
        if self.algorithm.couples_every_pair() {
            let pairs = n * (n - 1.0) / 2.0;
            // n(n − 1)/2 ≤ budget
            let most = ((1.0 + (1.0 + 8.0 * budget).sqrt()) / 2.0).floor();
            require(
                pairs <= budget,
                "agents",
                self.agents,
                &format!(
                    "couple every pair under Cucker–Smale without a cutoff: {pairs:.3e} pairs a step, more than the 2^32 ({budget:.3e}) one step may take"
                ),
                &format!(
                    "give algorithm.cutoff (each agent then sums over its neighbours within it), or at most {most} agents"
                ),
            )?;
        }
        let inner = self.vehicle.inner_steps(self.step);
        require(
            n * inner <= budget,
            "vehicle.inner_step",
            self.vehicle.inner_step().unwrap_or_default(),
            &format!(
                "makes {n} agents × {inner:e} inner steps = {:.3e} vehicle steps in each step, more than the 2^32 ({budget:.3e}) one step may take",
                n * inner
            ),
            &format!(
                "choose an inner step of at least {:e} s, or fewer agents",
                self.step * n / budget
            ),
        )
    }

    fn validate_agents(&self) -> Check {
        require(
            self.agents >= 1,
            "agents",
            self.agents,
            "a flock needs at least one agent",
            "set agents to n ≥ 1",
        )?;
        require(
            self.agents <= MAX_AGENTS,
            "agents",
            self.agents,
            &format!(
                "exceeds {MAX_AGENTS}: at about 250 bytes per agent the state alone needs {:.0} GB",
                self.agents as f64 * 250e-9
            ),
            "split the swarm into runs of at most 10^8 agents",
        )
    }

    fn validate_time(&self) -> Check {
        positive("step", self.step)?;
        positive("duration", self.duration)?;
        require(
            self.step <= self.duration,
            "step",
            self.step,
            &format!("is longer than the duration {}", self.duration),
            "choose a step smaller than the duration (the papers use 0.01–0.03 s)",
        )?;
        require(
            self.duration / self.step <= MAX_STEPS,
            "step",
            self.step,
            &format!(
                "gives {:e} steps over the duration {}, more than the {MAX_STEPS:e} a run may take",
                self.duration / self.step,
                self.duration
            ),
            "choose a larger step or a shorter duration (the papers use steps of 0.01–0.03 s)",
        )
    }

    fn validate_algorithm(&self, problems: &mut Problems) {
        let within = |prefix: &'static str| move |e: ParamError| e.within(prefix);
        match &self.algorithm {
            Algorithm::Algorithm1 => {}
            Algorithm::Algorithm2(p) => {
                problems.check(positive("algorithm.c1", p.c1));
                problems.check(positive("algorithm.c2", p.c2));
                self.validate_gamma(problems, "algorithm.gamma", &p.gamma);
            }
            Algorithm::Algorithm3(p) => {
                problems.check(positive("algorithm.c1", p.c1));
                if let Some(c2) = p.c2 {
                    problems.check(positive("algorithm.c2", c2));
                }
                self.validate_gamma(problems, "algorithm.gamma", &p.gamma);
                problems.check(
                    p.beta
                        .validate(self.alpha.d)
                        .map_err(within("algorithm.beta")),
                );
            }
            Algorithm::Flocking2003(p) => {
                problems.check(non_negative("algorithm.c1", p.c1));
                problems.check(require(
                    self.alpha.a < self.alpha.b,
                    "alpha.a",
                    self.alpha.a,
                    &format!(
                        "must be below alpha.b = {}: the 2003 potential (eq. 29) needs b > a > 0",
                        self.alpha.b
                    ),
                    "use e.g. a: 1.0, b: 5.0",
                ));
                if let Some(delta) = p.delta {
                    problems.check(check::unit_interval("algorithm.delta", delta));
                }
                problems.check(require(
                    p.power >= 1,
                    "algorithm.power",
                    p.power,
                    "the influence map needs k ≥ 1",
                    "use power: 1 (C¹) or more",
                ));
                if let Some(t) = &p.translation {
                    problems.check(non_negative("algorithm.translation.c1", t.c1));
                    problems.check(positive("algorithm.translation.c2", t.c2));
                    self.validate_gamma(problems, "algorithm.translation.gamma", &t.gamma);
                }
                if let Some(a) = &p.avoidance {
                    problems.check(a.validate().map_err(within("algorithm.avoidance")));
                    for (k, spec) in self.obstacles.iter().enumerate() {
                        problems.check(require(
                            matches!(spec, ObstacleSpec::Ball { .. }),
                            &format!("obstacles[{k}]"),
                            spec.kind(),
                            "the 2003 obstacle protocol handles balls only (seed 004 § 11)",
                            "use Ball obstacles, or Algorithm3 for other convex shapes",
                        ));
                    }
                }
            }
            Algorithm::Tanner(p) => problems.check(self.validate_fixed_graph(&p.graph, true)),
            Algorithm::Consensus(p) => {
                let graph = p
                    .graph
                    .as_ref()
                    .map_or(Ok(()), |graph| self.validate_fixed_graph(graph, false));
                if graph.is_ok() {
                    // the gain: Consensus's constructor refuses it, named
                    problems.check(self.protocol_builds());
                }
                problems.check(graph);
            }
            // the models: built, their constructor checks their parameters
            model => {
                if let Algorithm::Vasarhelyi(_) = model {
                    problems.check(require(
                        self.domain.is_open(),
                        "domain",
                        &self.domain,
                        "the Vásárhelyi model flies in an arena with walls in open space",
                        "use domain: Open (the default) and set the arena with arena_side",
                    ));
                }
                problems.check(self.protocol_builds());
            }
        }
        self.validate_domain(problems);
    }

    /// The protocol built: its constructor checks its parameters, each named (the conditions it
    /// cannot take are refused above, once).
    fn protocol_builds(&self) -> Result<(), ScenarioError> {
        match self.dim {
            2 => self.ideal_protocol::<DVec2>().map(|_| ()),
            _ => self.ideal_protocol::<DVec3>().map(|_| ()),
        }
    }

    /// A periodic box: one side per dimension, each positive and at least twice the interaction
    /// range; no obstacles on a torus (an obstacle would need its images).
    fn validate_domain(&self, problems: &mut Problems) {
        let size = match &self.domain {
            DomainSpec::Open => return,
            DomainSpec::Periodic { size } => {
                if let Err(e) = vector("domain.size", size, self.dim) {
                    problems.check(Err::<(), _>(e));
                    return;
                }
                size.clone()
            }
            DomainSpec::PeriodicAtDensity { density } => {
                if let Err(e) = positive("domain.density", *density) {
                    problems.check(Err::<(), _>(e));
                    return;
                }
                if self.agents == 0 {
                    // the box of no agents has no side: `agents` is the one error to fix
                    return;
                }
                self.box_size().unwrap_or_default()
            }
        };
        let r = self.range();
        let short = |side: f64| {
            format!(
                "gives a box side {side}, shorter than twice the interaction range r = {r}: an agent would see two images of another"
            )
        };
        match &self.domain {
            DomainSpec::PeriodicAtDensity { density } => {
                let agents = self.agents as f64;
                let most = agents / (2.0 * r).powi(self.dim as i32);
                let least = agents / MAX_VALUE.powi(self.dim as i32);
                problems.check(
                    require(
                        size.iter().all(|&side| side >= 2.0 * r),
                        "domain.density",
                        density,
                        &short(size[0]),
                        &format!(
                            "use a density of at most {most} for {} agents, or more agents",
                            self.agents
                        ),
                    )
                    .and_then(|()| {
                        // issue 49: validated, then refused by the run as `domain.size[0]`
                        require(
                            size.iter().all(|&side| side <= MAX_VALUE),
                            "domain.density",
                            density,
                            &format!(
                                "gives a box side {:e}, beyond the {MAX_VALUE:e} any length may have, {WHY_BOUNDED}",
                                size[0]
                            ),
                            &format!(
                                "use a density of at least {least:e} for {} agents",
                                self.agents
                            ),
                        )
                    }),
                );
            }
            _ => {
                for (k, &side) in size.iter().enumerate() {
                    let field = format!("domain.size[{k}]");
                    problems.check(positive(&field, side).and_then(|()| {
                        require(
                            side >= 2.0 * r,
                            &field,
                            side,
                            &short(side),
                            &format!("make every side at least {}", 2.0 * r),
                        )
                    }));
                }
            }
        }
        problems.check(require(
            self.obstacles.is_empty(),
            "obstacles",
            self.obstacles.len(),
            "are not supported on a periodic domain (an obstacle would need its images across the wrap)",
            "remove the obstacles, or use domain: Open",
        ));
        problems.check(require(
            self.algorithm.gamma().is_none(),
            "domain",
            "periodic",
            "has no γ-agent support: the navigational feedback measures q_i − q_r in open space, and on a torus the γ-agent would need its nearest image",
            "use an algorithm without a γ-agent on a periodic domain (Algorithm1, Consensus, the models), or domain: Open",
        ));
    }

    /// A fixed graph on the agents; `connected` for the Tanner law (Assumption IV.2).
    fn validate_fixed_graph(&self, graph: &FixedGraph, connected: bool) -> Check {
        match graph {
            FixedGraph::Random { extra } => {
                check::finite("algorithm.graph.extra", *extra)?;
                require(
                    (0.0..=1.0).contains(extra),
                    "algorithm.graph.extra",
                    extra,
                    "is a probability",
                    "use a value in [0, 1]",
                )
            }
            FixedGraph::Edges(edges) => {
                let graph = Graph::from_edges(self.agents, edges).map_err(|e| {
                    ParamError::new(
                        "algorithm.graph",
                        edges.len(),
                        e.to_string(),
                        "list edges (i, j) with i ≠ j < agents",
                    )
                })?;
                let components = Components::of(&graph).count();
                require(
                    components == 1 || !connected,
                    "algorithm.graph",
                    format!("{components} components"),
                    "the Tanner law needs a connected graph",
                    "add edges joining the components",
                )
            }
        }
    }

    /// No two agents of a Tanner scenario start at the same point, where the potential
    /// d²/z² + ln(z²/d²) − 1 of a linked pair is infinite.
    fn validate_distinct_start(&self) -> Result<(), ScenarioError> {
        match coincident_start(self) {
            None => Ok(()),
            Some((i, j)) => Err(ScenarioError::invalid(
                "initial.positions",
                format!("agents {i} and {j}"),
                "start at the same point, where the Tanner potential d²/z² + ln(z²/d²) − 1 of a linked pair is infinite",
                "give every agent its own position",
            )),
        }
    }

    /// Obstacles are well formed in the scenario's dimension, seen by the algorithm, and no agent
    /// starts inside one.
    fn validate_obstacles(&self) -> Result<(), ScenarioError> {
        if self.obstacles.is_empty() {
            return Ok(());
        }
        require(
            self.algorithm.uses_obstacles(),
            "obstacles",
            format!("{} obstacle(s)", self.obstacles.len()),
            "this algorithm does not see obstacles",
            "use Algorithm3 (or Flocking2003 with avoidance), or remove the obstacles",
        )?;
        match self.dim {
            2 => self.validate_start_outside::<DVec2>(),
            _ => self.validate_start_outside::<DVec3>(),
        }
    }

    fn validate_start_outside<V: Space>(&self) -> Result<(), ScenarioError> {
        let field =
            ObstacleField::<V>::from_specs(&self.obstacles).map_err(ScenarioError::Obstacle)?;
        // One position at a time: 10⁸ agents are checked without holding them.
        for (i, q) in initial_positions::<V>(self).enumerate() {
            if let Some(k) = field.containing(q) {
                return Err(ScenarioError::invalid(
                    "initial.positions",
                    format!(
                        "agent {i} at {:?}",
                        (0..V::DIM).map(|k| q.coord(k)).collect::<Vec<_>>()
                    ),
                    format!(
                        "starts inside obstacles[{k}] ({})",
                        self.obstacles[k].kind()
                    ),
                    "move the initial cloud or the obstacle so that every agent starts outside",
                ));
            }
        }
        Ok(())
    }

    /// The γ-agent's vectors have the scenario's dimension and are finite; a path is well formed.
    fn validate_gamma(&self, problems: &mut Problems, field: &str, gamma: &GammaAgent<Point>) {
        for (name, v) in gamma.vectors() {
            problems.check(vector(&format!("{field}.{name}"), v, self.dim));
        }
        problems.check(gamma.validate_path().map_err(|e| e.within(field)));
    }

    fn validate_cloud(&self, problems: &mut Problems, field: &str, cloud: &Cloud) {
        let dim = self.dim;
        match cloud {
            Cloud::Zero => {}
            Cloud::Box { min, max } => {
                let (lower, upper) = (
                    vector(&format!("{field}.min"), min, dim),
                    vector(&format!("{field}.max"), max, dim),
                );
                let both = lower.is_ok() && upper.is_ok();
                problems.check(lower);
                problems.check(upper);
                if both {
                    problems.check(require(
                        min.iter().zip(max).all(|(lo, hi)| lo <= hi),
                        &format!("{field}.max"),
                        max,
                        &format!("is below min = {min:?} in some component"),
                        "make every component of max ≥ the same component of min",
                    ));
                }
            }
            Cloud::Ball { centre, radius } => {
                problems.check(vector(&format!("{field}.centre"), centre, dim));
                problems.check(length(&format!("{field}.radius"), *radius));
            }
            Cloud::Gaussian { mean, std } => {
                problems.check(vector(&format!("{field}.mean"), mean, dim));
                problems.check(length(&format!("{field}.std"), *std));
            }
            Cloud::Domain => problems.check(require(
                self.box_size().is_some(),
                field,
                "Domain",
                "draws uniformly in the periodic box, and the scenario's domain is open",
                "give a periodic domain (domain: Periodic(size: [...]) or PeriodicAtDensity(density: ...)), or another cloud such as Box(min: [...], max: [...])",
            )),
            Cloud::Headings { speed } => {
                problems.check(length(&format!("{field}.speed"), *speed));
            }
            Cloud::Explicit(rows) => {
                problems.check(require(
                    rows.len() == self.agents,
                    field,
                    format!("{} vectors", rows.len()),
                    &format!("the scenario has agents = {}", self.agents),
                    "give one vector per agent, or change agents",
                ));
                // the first wrong row of each kind is enough: a list of n rows would repeat itself
                if let Some(e) = rows
                    .iter()
                    .enumerate()
                    .find_map(|(i, row)| vector(&format!("{field}[{i}]"), row, dim).err())
                {
                    problems.0.push(e.into());
                }
            }
        }
    }
}

/// The fastest of `velocities` (its index and speed), `None` for none; a speed that is not a
/// number counts as the fastest.
pub(crate) fn fastest_agent<V: Space>(velocities: impl Iterator<Item = V>) -> Option<(usize, f64)> {
    velocities
        .map(|p| p.length())
        .enumerate()
        .reduce(|a, b| if b.1 > a.1 || b.1.is_nan() { b } else { a })
}

//! The protocol of a scenario, built once for its dimension: the one place that turns the
//! scenario's algorithm into a [`DynProtocol`].

use flock_graph::Graph;
use flock_math::{Bump, Domain, TannerPotential};
use flock_obstacles::{ObstacleField, ObstacleSpec, Space};
use flock_protocols::{
    Algorithm1, Algorithm2, Algorithm3, AlphaAlpha, AlphaAlphaParams, BallObstacle,
    BetaInteraction, Boids, Consensus, Couzin, CuckerSmale, DynProtocol, Flocking2003, GammaAgent,
    NavigationalFeedback, ObstacleFlocking2003, ObstacleParams, ParamError, Protocol,
    TannerJadbabaiePappas, Vasarhelyi, Vicsek, random_connected_graph,
};
use flock_sim::Conditions;

use crate::error::ScenarioError;
use crate::initial::to_vector;
use crate::scenario::{
    Algorithm, ConsensusParams, DomainSpec, FixedGraph, Point, Scenario, TannerParams,
};

/// The γ-agent of a validated scenario in vectors `V`.
#[must_use]
pub fn gamma_agent<V: Space>(gamma: &GammaAgent<Point>) -> GammaAgent<V> {
    gamma.map(|v| to_vector(v))
}

impl Scenario {
    /// The scenario's protocol with vectors `V` (of the scenario's dimension). The scenario must
    /// be valid ([`Scenario::validate`]).
    ///
    /// # Errors
    /// A parameter, obstacle or graph the protocol refuses (which [`Scenario::validate`] reports
    /// first), with its field.
    pub fn protocol<V: Space>(&self) -> Result<DynProtocol<V>, ScenarioError> {
        let protocol = self.ideal_protocol::<V>()?;
        check_local_form(&self.conditions, protocol.as_ref())?;
        Ok(protocol)
    }

    /// The (α, α) protocol of a `Flocking2003` scenario (its (α, α) part, without the
    /// translational controller and the obstacles), `None` for the other algorithms: what
    /// [`AlphaAlpha::reynolds_reading`] reads (ACC 2004 § 4).
    #[must_use]
    pub fn alpha_alpha(&self) -> Option<AlphaAlpha> {
        let Algorithm::Flocking2003(p) = &self.algorithm else {
            return None;
        };
        let (a, b, d, r) = (self.alpha.a, self.alpha.b, self.alpha.d, self.range());
        let params = AlphaAlphaParams {
            bump: Bump::influence_map(p.delta.unwrap_or(d / r), p.power),
            ..AlphaAlphaParams::new(d, r, a, b)
        };
        Some(AlphaAlpha::new(params, p.form, p.c1))
    }

    /// The protocol of the algorithm, whatever the conditions.
    pub(crate) fn ideal_protocol<V: Space>(&self) -> Result<DynProtocol<V>, ScenarioError> {
        let alpha_config = &self.alpha;
        let within =
            |prefix: &'static str| move |e: ParamError| ScenarioError::from(e.within(prefix));
        let alpha = alpha_config.interaction().map_err(within("alpha"))?;
        let (d, r) = (alpha_config.d, self.range());
        Ok(match &self.algorithm {
            Algorithm::Algorithm1 => Box::new(Algorithm1 { alpha }),
            Algorithm::Algorithm2(p) => {
                let navigation =
                    NavigationalFeedback::linear(gamma_agent::<V>(&p.gamma), p.c1, p.c2);
                Box::new(Algorithm2 { alpha, navigation })
            }
            Algorithm::Algorithm3(p) => {
                let beta = &p.beta;
                let c2 =
                    p.c2.unwrap_or_else(|| flock_protocols::critical_damping(p.c1));
                let navigation =
                    NavigationalFeedback::bounded(gamma_agent::<V>(&p.gamma), p.c1, c2);
                let field = ObstacleField::<V>::from_specs(&self.obstacles)
                    .map_err(ScenarioError::Obstacle)?;
                let interaction = BetaInteraction::new(
                    field,
                    beta.params(d),
                    alpha_config.epsilon,
                    beta.c1,
                    beta.damping(),
                )
                .map_err(within("algorithm.beta"))?;
                Box::new(Algorithm3 {
                    flock: Algorithm2 { alpha, navigation },
                    beta: interaction,
                })
            }
            Algorithm::Flocking2003(p) => {
                let alpha = self.alpha_alpha().unwrap_or_else(|| unreachable!());
                let params = *alpha.params();
                let translation = p
                    .translation
                    .as_ref()
                    .map(|t| NavigationalFeedback::linear(gamma_agent::<V>(&t.gamma), t.c1, t.c2));
                let flocking = Flocking2003 { alpha, translation };
                match p.avoidance {
                    None => Box::new(flocking),
                    Some(gains) => Box::new(ObstacleFlocking2003 {
                        flocking,
                        obstacles: self.balls()?,
                        params: ObstacleParams::new(&params, gains),
                    }),
                }
            }
            Algorithm::Tanner(_) => {
                let law =
                    TannerJadbabaiePappas::new(self.tanner_graph()?, TannerPotential::new(d), r)
                        .map_err(|e| tanner_graph_error(e.to_string()))?;
                Box::new(law)
            }
            Algorithm::Consensus(p) => {
                let consensus = match p.graph {
                    None => Consensus::proximity(p.gain, r),
                    Some(_) => Consensus::fixed(p.gain, self.tanner_graph()?, r),
                };
                Box::new(consensus.map_err(within("algorithm"))?)
            }
            Algorithm::CuckerSmale(params) => {
                // the net's range without a cutoff: a cutoff is checked as itself (issue 49: a
                // negative one was named `algorithm.range`)
                Box::new(
                    CuckerSmale::new(*params, alpha_config.range(), self.agents, self.domain())
                        .map_err(within("algorithm"))?,
                )
            }
            Algorithm::Vicsek(params) => Box::new(
                Vicsek::new(*params, self.step, self.seed, self.domain())
                    .map_err(within("algorithm"))?,
            ),
            Algorithm::Boids(params) => Box::new(
                Boids::new(*params, self.step, self.seed, self.domain())
                    .map_err(within("algorithm"))?,
            ),
            Algorithm::Couzin(params) => Box::new(
                Couzin::new(*params, self.step, self.seed, self.domain())
                    .map_err(within("algorithm"))?,
            ),
            Algorithm::Vasarhelyi(params) => {
                Box::new(Vasarhelyi::new(params.clone()).map_err(within("algorithm"))?)
            }
        })
    }

    /// The scenario's domain in vectors `V` (of the scenario's dimension).
    #[must_use]
    pub fn domain<V: Space>(&self) -> Domain<V> {
        match self.box_size() {
            None => Domain::Open,
            Some(size) => Domain::Periodic {
                size: to_vector(&size),
            },
        }
    }

    /// The sides of the scenario's periodic box, `None` in open space.
    #[must_use]
    pub fn box_size(&self) -> Option<Vec<f64>> {
        match &self.domain {
            DomainSpec::Open => None,
            DomainSpec::Periodic { size } => Some(size.clone()),
            DomainSpec::PeriodicAtDensity { density } => {
                let side = (self.agents as f64 / density).powf(1.0 / self.dim as f64);
                Some(vec![side; self.dim])
            }
        }
    }

    /// The fixed graph of a scenario: the Tanner law's, or that of [`Algorithm::Consensus`] on a
    /// fixed graph (the empty graph on the agents for other algorithms).
    ///
    /// # Errors
    /// Edges that do not form a graph on the agents.
    pub fn tanner_graph(&self) -> Result<Graph, ScenarioError> {
        match self.fixed_graph() {
            Some(FixedGraph::Random { extra }) => {
                Ok(random_connected_graph(self.agents, *extra, self.seed))
            }
            Some(FixedGraph::Edges(edges)) => {
                Graph::from_edges(self.agents, edges).map_err(|e| tanner_graph_error(e.to_string()))
            }
            None => Ok(Graph::empty(self.agents)),
        }
    }

    /// The fixed graph the scenario's algorithm interacts on, if it has one (the Tanner law;
    /// consensus on a fixed graph).
    #[must_use]
    pub fn fixed_graph(&self) -> Option<&FixedGraph> {
        match &self.algorithm {
            Algorithm::Tanner(TannerParams { graph })
            | Algorithm::Consensus(ConsensusParams {
                graph: Some(graph), ..
            }) => Some(graph),
            _ => None,
        }
    }

    /// The scenario's obstacles as the balls of the 2003 obstacle protocol.
    fn balls<V: Space>(&self) -> Result<Vec<BallObstacle<V>>, ScenarioError> {
        self.obstacles
            .iter()
            .enumerate()
            .map(|(k, spec)| match spec {
                ObstacleSpec::Ball { centre, radius } => {
                    BallObstacle::new(to_vector(centre), *radius)
                        .map_err(|e| ScenarioError::Obstacle(e.at(k)))
                }
                other => Err(ScenarioError::invalid(
                    format!("obstacles[{k}]"),
                    other.kind(),
                    "the 2003 obstacle protocol handles balls only (seed 004 § 11)",
                    "use Ball obstacles, or Algorithm3 for other convex shapes",
                )),
            })
            .collect()
    }
}

/// Refuses a protocol with no [`LocalForm`](flock_protocols::LocalForm) under a perception
/// condition ([`check_local_form`](flock_sim::checks::check_local_form)), naming the condition.
///
/// # Errors
/// The condition, why (the protocol needs the whole flock's state) and the fix.
pub fn check_local_form<V: Space>(
    conditions: &Conditions,
    protocol: &dyn Protocol<V>,
) -> Result<(), ScenarioError> {
    Ok(flock_sim::checks::check_local_form(
        conditions,
        protocol.local_form().is_some(),
    )?)
}

/// A Tanner graph the law refuses.
fn tanner_graph_error(why: String) -> ScenarioError {
    ScenarioError::invalid(
        "algorithm.graph",
        "",
        why,
        "give a connected graph of edges (i, j) with i ≠ j < agents",
    )
}

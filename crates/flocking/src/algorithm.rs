//! The protocol of a scenario, [`Algorithm`]: each variant holds its parameters' struct, written
//! as a struct variant (`algorithm: Vicsek(eta: 2.0)`). The classic models hold the parameter
//! types of `flock-protocols` ([`VicsekParams`], [`CouzinParams`], …), whose serde gives their
//! names and defaults, declared once with the model; the Olfati-Saber, Tanner and consensus
//! protocols hold the structs of this module, whose vectors are the scenario's lists of `dim`
//! numbers.

use serde::{Deserialize, Serialize};

use flock_protocols::{
    AlphaAlphaForm, AvoidanceGains, BetaConfig, BoidsParams, CouzinParams, CuckerSmaleParams,
    GammaAgent, VasarhelyiParams, VicsekParams,
};

use crate::struct_variant::struct_variant_enum;

/// A vector as a scenario writes it: a list of `dim` numbers (`[1.0, 2.0]`).
pub type Point = Vec<f64>;

struct_variant_enum! {
/// The protocol of a scenario.
#[derive(Clone, Debug, PartialEq)]
pub enum Algorithm {
    /// Algorithm 1 of TAC 2006: α-interaction alone.
    Algorithm1,
    /// Algorithm 2 of TAC 2006: α-interaction plus navigational feedback −c₁(q_i − q_r) − c₂(p_i − p_r).
    Algorithm2(Algorithm2Params),
    /// Algorithm 3 of TAC 2006: α-interaction, β-agents on the scenario's obstacles, and the bounded
    /// navigational feedback −c₁ σ₁(q_i − q_r) − c₂(p_i − p_r).
    Algorithm3(Algorithm3Params),
    /// The 2003 (α, α) protocols (Caltech CDS 03-006, eq. 34–36) with the potential of eq. 29
    /// (`alpha.a < alpha.b`), an optional translational controller (sink, eq. 50, or velocity
    /// tracking) and optional avoidance of the scenario's ball obstacles (eq. 54–58).
    Flocking2003(Flocking2003Params),
    /// The Tanner–Jadbabaie–Pappas law on a fixed connected graph (seed 001 eq. 5), with the pair
    /// potential d²/z² + ln(z²/d²) − 1 of desired distance `alpha.d`.
    Tanner(TannerParams),
    /// Velocity consensus u_i = c Σ_{j∈N_i} (p_j − p_i) (CDS 03-006, seed 000 eq. 9): on the
    /// proximity net of range r by default, or on a fixed graph. The protocol of the delay and
    /// sampled-data theorems of Olfati-Saber & Murray (IEEE TAC 49(9), 2004).
    Consensus(ConsensusParams),
    /// The Cucker–Smale model (IEEE TAC 52(5), 2007): ṗ_i = (λ/N) Σ_j ψ(‖q_j − q_i‖)(p_j − p_i),
    /// ψ(r) = K/(σ² + r²)^β, every pair (`CuckerSmale(beta: 0.25)`; [`CuckerSmaleParams`]).
    CuckerSmale(CuckerSmaleParams),
    /// The Vicsek model (PRL 75, 1995): constant speed v₀, the neighbours' mean heading within
    /// r plus uniform noise in [−η/2, η/2]; planar (`Vicsek(eta: 2.0)`; [`VicsekParams`]).
    Vicsek(VicsekParams),
    /// Reynolds's boids as the ABM frameworks' benchmark declares them (`Boids(visual_distance:
    /// 5.0)`; every parameter defaults to the declaration's, [`BoidsParams`]).
    Boids(BoidsParams),
    /// The zone model of Couzin et al. (J. theor. Biol. 218, 2002) (`Couzin(delta_r_o: 1.0,
    /// delta_r_a: 14.0)`; the others default to the paper's values, [`CouzinParams`]).
    Couzin(CouzinParams),
    /// The drones' model of Vásárhelyi et al. (Science Robotics 3(20), 2018): repulsion,
    /// alignment under a braking curve, self-propulsion and shill agents on the walls of an
    /// arena, summed into a desired velocity cut at v^max and tracked as u = (v_d − v)/τ
    /// (`Vasarhelyi()`: every parameter defaults to the optimised set for v^flock = 6 m/s,
    /// [`VasarhelyiParams`]; SI units, m and s).
    Vasarhelyi(VasarhelyiParams),
}
}

/// The parameters of [`Algorithm::Algorithm2`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Algorithm2Params {
    /// The γ-agent.
    pub gamma: GammaAgent<Point>,
    /// Position gain c₁ > 0.
    pub c1: f64,
    /// Velocity gain c₂ > 0.
    pub c2: f64,
}

/// The parameters of [`Algorithm::Algorithm3`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Algorithm3Params {
    /// The γ-agent.
    pub gamma: GammaAgent<Point>,
    /// Position gain c₁^γ > 0.
    pub c1: f64,
    /// Velocity gain c₂^γ > 0; default 2√c₁^γ (critically damped).
    #[serde(default)]
    pub c2: Option<f64>,
    /// The β-interaction.
    #[serde(default)]
    pub beta: BetaConfig,
}

/// The parameters of [`Algorithm::Flocking2003`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Flocking2003Params {
    /// Which of the three protocols.
    pub form: AlphaAlphaForm,
    /// The consensus gain c₁ ≥ 0 of Σ_j (p_j − p_i).
    pub c1: f64,
    /// The flat part δ ∈ (0, 1) of the influence map ρ; default d/r.
    #[serde(default)]
    pub delta: Option<f64>,
    /// The power k ≥ 1 of the influence map (C^k smooth).
    #[serde(default = "default_power")]
    pub power: i32,
    /// The translational controller −c₁(q_i − q_r) − c₂(p_i − p_r) to a γ-agent.
    #[serde(default)]
    pub translation: Option<Translation>,
    /// β- and γ-agents on the scenario's obstacles (balls only).
    #[serde(default)]
    pub avoidance: Option<AvoidanceGains>,
}

fn default_power() -> i32 {
    1
}

/// The parameters of [`Algorithm::Tanner`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TannerParams {
    /// The neighbouring graph.
    #[serde(default)]
    pub graph: FixedGraph,
}

/// The parameters of [`Algorithm::Consensus`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConsensusParams {
    /// The gain c > 0.
    pub gain: f64,
    /// A fixed graph (node k agent k, connected or not); `None`: the proximity net.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub graph: Option<FixedGraph>,
}

/// A translational controller of the 2003 protocols: a sink (static γ-agent, eq. 50) or velocity
/// tracking (a γ-agent in uniform motion with c₁ = 0, eq. 65–66).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Translation {
    /// The γ-agent (q_d, p_d).
    pub gamma: GammaAgent<Point>,
    /// Position gain c₁ ≥ 0.
    pub c1: f64,
    /// Velocity gain c₂ > 0.
    pub c2: f64,
}

/// A fixed graph on the agents (node k agent k): the neighbouring graph of the Tanner law, or the
/// graph of [`Algorithm::Consensus`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum FixedGraph {
    /// A random spanning tree plus every other pair with probability `extra`, from the scenario's seed.
    Random {
        /// Probability of each extra edge, in [0, 1].
        extra: f64,
    },
    /// The given undirected edges (i, j); the Tanner law needs a connected graph.
    Edges(Vec<(usize, usize)>),
}

/// The fixed graph's former name, when only the Tanner law had one.
pub type TannerGraph = FixedGraph;

impl Default for FixedGraph {
    fn default() -> Self {
        Self::Random { extra: 0.2 }
    }
}

impl Algorithm {
    /// The γ-agent the algorithm steers towards, if it has one.
    #[must_use]
    pub fn gamma(&self) -> Option<&GammaAgent<Point>> {
        match self {
            Self::Algorithm2(p) => Some(&p.gamma),
            Self::Algorithm3(p) => Some(&p.gamma),
            Self::Flocking2003(p) => p.translation.as_ref().map(|t| &t.gamma),
            _ => None,
        }
    }

    /// Whether the algorithm's protocol has a local form (u_i from what agent i perceives,
    /// [`LocalForm`](flock_protocols::LocalForm)), as the conditions that make agents perceive
    /// different worlds need: every algorithm a scenario can name is distributed. A centralised
    /// one (such as `CentralisedTracking2003`, which needs the centre of mass) would answer false.
    #[must_use]
    pub fn has_local_form(&self) -> bool {
        match self {
            Self::CuckerSmale(p) => p.cutoff.is_some(),
            _ => true,
        }
    }

    /// The speed a model sets every agent to (Vicsek's v₀, Couzin's and the boids' speed), with
    /// its field; `None` for the algorithms whose speeds follow from accelerations.
    #[must_use]
    pub fn set_speed(&self) -> Option<(&'static str, f64)> {
        match self {
            Self::Vicsek(p) => Some(("algorithm.v0", p.v0)),
            Self::Boids(p) => Some(("algorithm.speed", p.speed)),
            Self::Couzin(p) => Some(("algorithm.speed", p.speed)),
            _ => None,
        }
    }

    /// The step of the model's paper, with its source, for the models whose rules are maps of
    /// one step (their noise, turning and speed are per step, so another step is another
    /// model): Vicsek et al. 1995's Δt = 1 (eq. 1, x_i(t + Δt) = x_i(t) + v_i(t) Δt), the
    /// boids' step of 1 (the ABM frameworks' declaration moves a boid `speed` per step), Couzin
    /// et al. 2002's τ = 0.1 s as the public reimplementations take it (jiwy2020's `dt = 0.1`;
    /// the paper itself was not read, docs/models.md). `None` for the algorithms written as
    /// differential equations.
    #[must_use]
    pub fn paper_step(&self) -> Option<(f64, &'static str)> {
        match self {
            Self::Vicsek(_) => Some((1.0, "Vicsek et al. 1995 take Δt = 1 (eq. 1)")),
            Self::Boids(_) => Some((
                1.0,
                "the boids' declaration (ABMFrameworksComparison) moves a boid `speed` per step of 1",
            )),
            Self::Couzin(_) => Some((
                0.1,
                "Couzin et al. 2002's τ = 0.1 s as its reimplementations take it (jiwy2020 dt = 0.1)",
            )),
            _ => None,
        }
    }

    /// Whether the algorithm couples every pair of agents at every step, whatever their
    /// distance (Cucker–Smale without a cutoff): a step's work is n(n − 1)/2 pairs.
    #[must_use]
    pub fn couples_every_pair(&self) -> bool {
        matches!(self, Self::CuckerSmale(p) if p.cutoff.is_none())
    }

    /// Whether the algorithm draws random numbers of its own (Vicsek's and Couzin's angular
    /// noise, the boids' activation order).
    #[must_use]
    pub fn draws_at_random(&self) -> bool {
        match self {
            Self::Vicsek(p) => p.eta > 0.0,
            Self::Couzin(p) => p.noise > 0.0,
            Self::Boids(_) => true,
            _ => false,
        }
    }

    /// Whether the algorithm draws normal random numbers of its own (Couzin's angular noise).
    #[must_use]
    pub fn draws_normals(&self) -> bool {
        matches!(self, Self::Couzin(p) if p.noise > 0.0)
    }

    /// Whether the algorithm is one of the classic models (Cucker–Smale, Vicsek, boids, Couzin,
    /// Vásárhelyi; docs/models.md) rather than Olfati-Saber's, Tanner's or consensus.
    #[must_use]
    pub fn is_classic_model(&self) -> bool {
        self.sets_velocity() || matches!(self, Self::CuckerSmale(_) | Self::Vasarhelyi(_))
    }

    /// Whether the algorithm is a model that sets its agents' velocities (Vicsek, boids, Couzin),
    /// rather than an acceleration.
    #[must_use]
    pub fn sets_velocity(&self) -> bool {
        matches!(self, Self::Vicsek(_) | Self::Boids(_) | Self::Couzin(_))
    }

    /// Whether the algorithm sees the scenario's obstacles.
    #[must_use]
    pub fn uses_obstacles(&self) -> bool {
        match self {
            Self::Algorithm3(_) => true,
            Self::Flocking2003(p) => p.avoidance.is_some(),
            _ => false,
        }
    }

    /// The Cucker–Smale parameters of [`Algorithm::CuckerSmale`].
    #[must_use]
    pub fn cucker_smale(&self) -> Option<CuckerSmaleParams> {
        match self {
            Self::CuckerSmale(p) => Some(*p),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Vicsek`].
    #[must_use]
    pub fn vicsek(&self) -> Option<VicsekParams> {
        match self {
            Self::Vicsek(p) => Some(*p),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Boids`].
    #[must_use]
    pub fn boids(&self) -> Option<BoidsParams> {
        match self {
            Self::Boids(p) => Some(*p),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Vasarhelyi`].
    #[must_use]
    pub fn vasarhelyi(&self) -> Option<VasarhelyiParams> {
        match self {
            Self::Vasarhelyi(p) => Some(p.clone()),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Couzin`].
    #[must_use]
    pub fn couzin(&self) -> Option<CouzinParams> {
        match self {
            Self::Couzin(p) => Some(*p),
            _ => None,
        }
    }
}

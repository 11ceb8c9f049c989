//! Scenario files: what a run simulates, read from RON, validated, and written back resolved.
//!
//! A scenario names the dimension, the algorithm and its parameters, the gains, the γ-agent, the
//! initial condition, the step, the duration and how often to record. Every parameter with a value in
//! the papers defaults to it (d = 7, r = 1.2 d, ε = 0.1, a = b = 5, h = 0.2; TAC 2006 Section VIII):
//! the defaults are those of the parameter types of `flock-protocols` ([`AlphaConfig`],
//! [`BetaConfig`], [`AvoidanceGains`]), which the scenario composes.

use std::path::Path;
use std::str::FromStr;

use ron::extensions::Extensions;
use serde::{Deserialize, Serialize};

use flock_obstacles::ObstacleSpec;
use flock_protocols::{
    AlphaAlphaForm, AlphaConfig, ArenaShape, AvoidanceGains, BetaConfig, Blend, BlindCone,
    BoidsParams, CouzinParams, CuckerSmaleParams, GammaAgent, VasarhelyiParams, VicsekParams,
    critical_damping,
};
use flock_sim::{Conditions, Integrator};

use crate::error::ScenarioError;
use crate::vehicle::VehicleSpec;

/// The collision distance as a fraction of d, by default (TAC 2006 counts pairs closer than d/4).
pub const COLLISION_FRACTION: f64 = 0.25;

/// A simulation scenario, as written in a `.ron` file.
///
/// # Example
/// ```
/// use flocking::Scenario;
///
/// let scenario: Scenario = r#"Scenario(
///     dim: 2,
///     agents: 20,
///     algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.05, c2: 0.4),
///     initial: (positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0])),
///     duration: 1.0,
/// )"#.parse()?;
/// assert_eq!(scenario.range(), 8.4); // r = 1.2 d, d = 7 by default
/// assert_eq!(scenario.steps(), 100);
/// assert!(scenario.warnings().is_empty());
/// // a bad value is refused with its field, its value, why and the fix
/// let error = "Scenario(dim: 4, agents: 1, algorithm: Algorithm1, initial: (positions: Zero), duration: 1.0)"
///     .parse::<Scenario>()
///     .unwrap_err();
/// assert_eq!(error.field().as_deref(), Some("dim"));
/// # Ok::<(), flocking::ScenarioError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// A short name, used in summaries.
    #[serde(default)]
    pub name: String,
    /// What the scenario reproduces and why its parameters are what they are.
    #[serde(default)]
    pub description: String,
    /// The dimension m of the space: 2 or 3.
    pub dim: usize,
    /// The number of α-agents n ≥ 1.
    pub agents: usize,
    /// Seed of the random initial condition (PCG64 stream).
    #[serde(default)]
    pub seed: u64,
    /// The protocol.
    pub algorithm: Algorithm,
    /// The space the agents live in: `Open` (the default, not written) or a periodic box.
    #[serde(default, skip_serializing_if = "DomainSpec::is_open")]
    pub domain: DomainSpec,
    /// What each agent is: `PointMass` (the default, not written) or a vehicle whose reference
    /// point follows the protocol's commanded acceleration (docs/vehicles.md).
    #[serde(default, skip_serializing_if = "VehicleSpec::is_point_mass")]
    pub vehicle: VehicleSpec,
    /// Parameters and gains of the α-interaction.
    #[serde(default)]
    pub alpha: AlphaConfig,
    /// The initial positions and velocities.
    pub initial: Initial,
    /// The integration scheme.
    #[serde(default)]
    pub integrator: Integrator,
    /// The fixed time step h > 0 (the papers use 0.01–0.03 s).
    #[serde(default = "default_step")]
    pub step: f64,
    /// The simulated time T > 0.
    pub duration: f64,
    /// Record metrics and trajectory every this many steps (≥ 1); the last step is always recorded.
    #[serde(default = "default_record_every")]
    pub record_every: u64,
    /// Two agents closer than this collide; default d/4, and at most r.
    #[serde(default)]
    pub collision_distance: Option<f64>,
    /// Convex obstacles, seen through β-agents by the algorithms that avoid obstacles.
    #[serde(default)]
    pub obstacles: Vec<ObstacleSpec>,
    /// The real conditions of the run (delay, loss, noise, sampled control, actuation limits,
    /// wind, faults; docs/conditions.md), every part optional; absent (and not written) for the
    /// ideal run.
    #[serde(default, skip_serializing_if = "Conditions::is_ideal")]
    pub conditions: Conditions,
    /// The times (s) at which `flocking plot` draws the snapshots: where things happen (a net
    /// becoming a flock, a split, a rejoin), each drawn at the record nearest it (one beyond the
    /// end at the last record); ≥ 0, increasing, at most [`MAX_SNAPSHOTS`]. `None` (not
    /// written): six times spread evenly over the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<Vec<f64>>,
}

/// The most snapshot times a scenario may ask for (a figure of three rows of four panels).
pub const MAX_SNAPSHOTS: usize = 12;

/// A vector as a scenario writes it: a list of `dim` numbers (`[1.0, 2.0]`).
pub type Point = Vec<f64>;

/// The protocol of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Algorithm {
    /// Algorithm 1 of TAC 2006: α-interaction alone.
    Algorithm1,
    /// Algorithm 2 of TAC 2006: α-interaction plus navigational feedback −c₁(q_i − q_r) − c₂(p_i − p_r).
    Algorithm2 {
        /// The γ-agent.
        gamma: GammaAgent<Point>,
        /// Position gain c₁ > 0.
        c1: f64,
        /// Velocity gain c₂ > 0.
        c2: f64,
    },
    /// Algorithm 3 of TAC 2006: α-interaction, β-agents on the scenario's obstacles, and the bounded
    /// navigational feedback −c₁ σ₁(q_i − q_r) − c₂(p_i − p_r).
    Algorithm3 {
        /// The γ-agent.
        gamma: GammaAgent<Point>,
        /// Position gain c₁^γ > 0.
        c1: f64,
        /// Velocity gain c₂^γ > 0; default 2√c₁^γ (critically damped).
        #[serde(default)]
        c2: Option<f64>,
        /// The β-interaction.
        #[serde(default)]
        beta: BetaConfig,
    },
    /// The 2003 (α, α) protocols (Caltech CDS 03-006, eq. 34–36) with the potential of eq. 29
    /// (`alpha.a < alpha.b`), an optional translational controller (sink, eq. 50, or velocity
    /// tracking) and optional avoidance of the scenario's ball obstacles (eq. 54–58).
    Flocking2003 {
        /// Which of the three protocols.
        form: AlphaAlphaForm,
        /// The consensus gain c₁ ≥ 0 of Σ_j (p_j − p_i).
        c1: f64,
        /// The flat part δ ∈ (0, 1) of the influence map ρ; default d/r.
        #[serde(default)]
        delta: Option<f64>,
        /// The power k ≥ 1 of the influence map (C^k smooth).
        #[serde(default = "default_power")]
        power: i32,
        /// The translational controller −c₁(q_i − q_r) − c₂(p_i − p_r) to a γ-agent.
        #[serde(default)]
        translation: Option<Translation>,
        /// β- and γ-agents on the scenario's obstacles (balls only).
        #[serde(default)]
        avoidance: Option<AvoidanceGains>,
    },
    /// The Tanner–Jadbabaie–Pappas law on a fixed connected graph (seed 001 eq. 5), with the pair
    /// potential d²/z² + ln(z²/d²) − 1 of desired distance `alpha.d`.
    Tanner {
        /// The neighbouring graph.
        #[serde(default)]
        graph: FixedGraph,
    },
    /// Velocity consensus u_i = c Σ_{j∈N_i} (p_j − p_i) (CDS 03-006, seed 000 eq. 9): on the
    /// proximity net of range r by default, or on a fixed graph. The protocol of the delay and
    /// sampled-data theorems of Olfati-Saber & Murray (IEEE TAC 49(9), 2004).
    Consensus {
        /// The gain c > 0.
        gain: f64,
        /// A fixed graph (node k agent k, connected or not); `None`: the proximity net.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        graph: Option<FixedGraph>,
    },
    /// The Cucker–Smale model (IEEE TAC 52(5), 2007): ṗ_i = (λ/N) Σ_j ψ(‖q_j − q_i‖)(p_j − p_i),
    /// ψ(r) = K/(σ² + r²)^β, every pair (`CuckerSmale(beta: 0.25)`; [`CuckerSmaleParams`]).
    CuckerSmale {
        /// The coupling λ > 0 (default 1).
        #[serde(default = "one")]
        lambda: f64,
        /// The kernel's scale K > 0 (default 1).
        #[serde(default = "one")]
        k: f64,
        /// The kernel's offset σ > 0 (default 1).
        #[serde(default = "one")]
        sigma: f64,
        /// The kernel's decay β ≥ 0: unconditional flocking for β < 1/2.
        beta: f64,
        /// A cut-off of ψ; `None` (the paper): every pair interacts.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        cutoff: Option<f64>,
    },
    /// The Vicsek model (PRL 75, 1995): constant speed v₀, the neighbours' mean heading within
    /// r plus uniform noise in [−η/2, η/2]; planar (`Vicsek(eta: 2.0)`; [`VicsekParams`]).
    Vicsek {
        /// The speed v₀ > 0 (default 0.03, the paper's Fig. 2).
        #[serde(default = "vicsek_v0")]
        v0: f64,
        /// The interaction radius r > 0 (default 1, the paper's unit).
        #[serde(default = "one")]
        r: f64,
        /// The noise amplitude η ∈ [0, 2π].
        eta: f64,
    },
    /// Reynolds's boids as the ABM frameworks' benchmark declares them (`Boids(visual_distance:
    /// 5.0)`; every parameter defaults to the declaration's, [`BoidsParams`]).
    Boids {
        /// The speed s > 0 (default 1).
        #[serde(default = "one")]
        speed: f64,
        /// The cohesion weight (default 0.03).
        #[serde(default = "boids_cohere")]
        cohere_factor: f64,
        /// Neighbours closer than this are pushed away (default 1).
        #[serde(default = "one")]
        separation: f64,
        /// The separation weight (default 0.015).
        #[serde(default = "boids_separate")]
        separate_factor: f64,
        /// The alignment weight (default 0.05).
        #[serde(default = "boids_match")]
        match_factor: f64,
        /// The visual distance (default 5, the declaration's "small"; 15 "large").
        #[serde(default = "boids_vision")]
        visual_distance: f64,
    },
    /// The zone model of Couzin et al. (J. theor. Biol. 218, 2002) (`Couzin(delta_r_o: 1.0,
    /// delta_r_a: 14.0)`; the others default to the paper's values, [`CouzinParams`]).
    Couzin {
        /// The radius r_r of the zone of repulsion (default 1).
        #[serde(default = "one")]
        r_r: f64,
        /// The width Δr_o ≥ 0 of the zone of orientation.
        delta_r_o: f64,
        /// The width Δr_a ≥ 0 of the zone of attraction.
        delta_r_a: f64,
        /// The field of perception α in degrees (default 270).
        #[serde(default = "couzin_field")]
        field_of_perception: f64,
        /// The largest turning rate θ in degrees per second (default 40).
        #[serde(default = "couzin_turning")]
        turning_rate: f64,
        /// The speed s (default 3).
        #[serde(default = "couzin_speed")]
        speed: f64,
        /// The standard deviation σ (rad) of the angular noise (default 0.05).
        #[serde(default = "couzin_noise")]
        noise: f64,
        /// How d_o and d_a are combined: `Unit` (default) or `Raw` ([`Blend`]).
        #[serde(default)]
        blend: Blend,
        /// Which zones the blind cone hides: `Everywhere` (default) or `BeyondRepulsion`
        /// ([`BlindCone`]).
        #[serde(default)]
        blind_cone: BlindCone,
    },
    /// The drones' model of Vásárhelyi et al. (Science Robotics 3(20), 2018): repulsion,
    /// alignment under a braking curve, self-propulsion and shill agents on the walls of an
    /// arena, summed into a desired velocity cut at v^max and tracked as u = (v_d − v)/τ
    /// (`Vasarhelyi()`: every parameter defaults to the optimised set for v^flock = 6 m/s,
    /// [`VasarhelyiParams`]; SI units, m and s).
    Vasarhelyi {
        /// The flocking speed v^flock (default 6 m/s).
        #[serde(default = "vas_v_flock")]
        v_flock: f64,
        /// The repulsion range r_0^rep (default 25 m).
        #[serde(default = "vas_r0_rep")]
        r0_rep: f64,
        /// The repulsion gain p^rep (default 0.13 s⁻¹).
        #[serde(default = "vas_p_rep")]
        p_rep: f64,
        /// The alignment's stopping-point offset r_0^frict (default 85.3 m).
        #[serde(default = "vas_r0_frict")]
        r0_frict: f64,
        /// The alignment coefficient C^frict (default 0.05).
        #[serde(default = "vas_c_frict")]
        c_frict: f64,
        /// The alignment's velocity slack v^frict (default 0.63 m/s).
        #[serde(default = "vas_v_frict")]
        v_frict: f64,
        /// The alignment's braking gain p^frict (default 3.2 s⁻¹).
        #[serde(default = "vas_p_frict")]
        p_frict: f64,
        /// The alignment's braking acceleration a^frict (default 4.16 m s⁻²).
        #[serde(default = "vas_a_frict")]
        a_frict: f64,
        /// The walls' stopping-point offset r_0^shill (default 0.3 m).
        #[serde(default = "vas_r0_shill")]
        r0_shill: f64,
        /// The shill agents' speed v^shill (default 13.6 m/s).
        #[serde(default = "vas_v_shill")]
        v_shill: f64,
        /// The walls' braking gain p^shill (default 3.55 s⁻¹).
        #[serde(default = "vas_p_shill")]
        p_shill: f64,
        /// The walls' braking acceleration a^shill (default 3.02 m s⁻²).
        #[serde(default = "vas_a_shill")]
        a_shill: f64,
        /// The cut v^max of the desired velocity (default 8 m/s).
        #[serde(default = "vas_v_max")]
        v_max: f64,
        /// The communication range r_c, the interaction range (default 100 m).
        #[serde(default = "vas_r_c")]
        r_c: f64,
        /// The relaxation time τ of the velocity (default 1 s).
        #[serde(default = "vas_tau")]
        tau: f64,
        /// The largest acceleration a^max (default 6 m s⁻²).
        #[serde(default = "vas_a_max")]
        a_max: f64,
        /// The collision distance r^coll of φ^coll (default 3 m; the scenario's default
        /// collision distance too).
        #[serde(default = "vas_r_coll")]
        r_coll: f64,
        /// The arena's shape (default `Square`: a cube in 3D).
        #[serde(default)]
        arena_shape: ArenaShape,
        /// The square's side or the circle's diameter (default 250 m).
        #[serde(default = "vas_arena_side")]
        arena_side: f64,
        /// The arena's centre (`dim` numbers); default the origin.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        arena_centre: Option<Point>,
    },
}

// The models' defaults, from their parameter types (one definition of each value).
fn one() -> f64 {
    1.0
}
fn vicsek_v0() -> f64 {
    0.03
}
fn boids_cohere() -> f64 {
    BoidsParams::default().cohere_factor
}
fn boids_separate() -> f64 {
    BoidsParams::default().separate_factor
}
fn boids_match() -> f64 {
    BoidsParams::default().match_factor
}
fn boids_vision() -> f64 {
    BoidsParams::default().visual_distance
}
fn couzin_field() -> f64 {
    CouzinParams::default().field_of_perception
}
fn couzin_turning() -> f64 {
    CouzinParams::default().turning_rate
}
fn couzin_speed() -> f64 {
    CouzinParams::default().speed
}
fn couzin_noise() -> f64 {
    CouzinParams::default().noise
}
fn vas_v_flock() -> f64 {
    VasarhelyiParams::default().v_flock
}
fn vas_r0_rep() -> f64 {
    VasarhelyiParams::default().r0_rep
}
fn vas_p_rep() -> f64 {
    VasarhelyiParams::default().p_rep
}
fn vas_r0_frict() -> f64 {
    VasarhelyiParams::default().r0_frict
}
fn vas_c_frict() -> f64 {
    VasarhelyiParams::default().c_frict
}
fn vas_v_frict() -> f64 {
    VasarhelyiParams::default().v_frict
}
fn vas_p_frict() -> f64 {
    VasarhelyiParams::default().p_frict
}
fn vas_a_frict() -> f64 {
    VasarhelyiParams::default().a_frict
}
fn vas_r0_shill() -> f64 {
    VasarhelyiParams::default().r0_shill
}
fn vas_v_shill() -> f64 {
    VasarhelyiParams::default().v_shill
}
fn vas_p_shill() -> f64 {
    VasarhelyiParams::default().p_shill
}
fn vas_a_shill() -> f64 {
    VasarhelyiParams::default().a_shill
}
fn vas_v_max() -> f64 {
    VasarhelyiParams::default().v_max
}
fn vas_r_c() -> f64 {
    VasarhelyiParams::default().r_c
}
fn vas_tau() -> f64 {
    VasarhelyiParams::default().tau
}
fn vas_a_max() -> f64 {
    VasarhelyiParams::default().a_max
}
fn vas_r_coll() -> f64 {
    VasarhelyiParams::default().r_coll
}
/// The arena side of the fixture and the default (250 m; see docs/models.md for its source).
pub const VASARHELYI_ARENA_SIDE: f64 = 250.0;
fn vas_arena_side() -> f64 {
    VASARHELYI_ARENA_SIDE
}

impl Algorithm {
    /// The Cucker–Smale parameters of [`Algorithm::CuckerSmale`].
    #[must_use]
    pub fn cucker_smale(&self) -> Option<CuckerSmaleParams> {
        match *self {
            Self::CuckerSmale {
                lambda,
                k,
                sigma,
                beta,
                cutoff,
            } => Some(CuckerSmaleParams {
                lambda,
                k,
                sigma,
                beta,
                cutoff,
            }),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Vicsek`].
    #[must_use]
    pub fn vicsek(&self) -> Option<VicsekParams> {
        match *self {
            Self::Vicsek { v0, r, eta } => Some(VicsekParams { v0, r, eta }),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Boids`].
    #[must_use]
    pub fn boids(&self) -> Option<BoidsParams> {
        match *self {
            Self::Boids {
                speed,
                cohere_factor,
                separation,
                separate_factor,
                match_factor,
                visual_distance,
            } => Some(BoidsParams {
                speed,
                cohere_factor,
                separation,
                separate_factor,
                match_factor,
                visual_distance,
            }),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Vasarhelyi`].
    #[must_use]
    pub fn vasarhelyi(&self) -> Option<VasarhelyiParams> {
        match *self {
            Self::Vasarhelyi {
                v_flock,
                r0_rep,
                p_rep,
                r0_frict,
                c_frict,
                v_frict,
                p_frict,
                a_frict,
                r0_shill,
                v_shill,
                p_shill,
                a_shill,
                v_max,
                r_c,
                tau,
                a_max,
                r_coll,
                ..
            } => Some(VasarhelyiParams {
                v_flock,
                r0_rep,
                p_rep,
                r0_frict,
                c_frict,
                v_frict,
                p_frict,
                a_frict,
                r0_shill,
                v_shill,
                p_shill,
                a_shill,
                v_max,
                r_c,
                tau,
                a_max,
                r_coll,
            }),
            _ => None,
        }
    }

    /// The parameters of [`Algorithm::Couzin`].
    #[must_use]
    pub fn couzin(&self) -> Option<CouzinParams> {
        match *self {
            Self::Couzin {
                r_r,
                delta_r_o,
                delta_r_a,
                field_of_perception,
                turning_rate,
                speed,
                noise,
                blend,
                blind_cone,
            } => Some(CouzinParams {
                r_r,
                delta_r_o,
                delta_r_a,
                field_of_perception,
                turning_rate,
                speed,
                noise,
                blend,
                blind_cone,
            }),
            _ => None,
        }
    }
}

/// The space of a scenario.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum DomainSpec {
    /// ℝ^m.
    #[default]
    Open,
    /// The torus [0, L₁) × … × [0, L_m): positions wrapped after each step, every distance the
    /// minimum image, the centre of mass the circular mean per axis.
    Periodic {
        /// The sides (L₁, …, L_m), each at least twice the interaction range.
        size: Vec<f64>,
    },
    /// The square or cube periodic box that holds the agents at number `density` ρ: side
    /// L = (n/ρ)^(1/m), so that a sweep over `agents` keeps the density fixed (Vicsek et al. 1995
    /// Fig. 2(a)).
    PeriodicAtDensity {
        /// Agents per unit area (2D) or volume (3D), > 0.
        density: f64,
    },
}

impl DomainSpec {
    /// Whether the domain is open space.
    #[must_use]
    pub fn is_open(&self) -> bool {
        matches!(self, Self::Open)
    }
}

impl Algorithm {
    /// The γ-agent the algorithm steers towards, if it has one.
    #[must_use]
    pub fn gamma(&self) -> Option<&GammaAgent<Point>> {
        match self {
            Self::Algorithm2 { gamma, .. } | Self::Algorithm3 { gamma, .. } => Some(gamma),
            Self::Flocking2003 { translation, .. } => translation.as_ref().map(|t| &t.gamma),
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
            Self::Algorithm1
            | Self::Algorithm2 { .. }
            | Self::Algorithm3 { .. }
            | Self::Flocking2003 { .. }
            | Self::Tanner { .. }
            | Self::Consensus { .. }
            | Self::Vicsek { .. }
            | Self::Boids { .. }
            | Self::Couzin { .. }
            | Self::Vasarhelyi { .. } => true,
            Self::CuckerSmale { cutoff, .. } => cutoff.is_some(),
        }
    }

    /// The speed a model sets every agent to (Vicsek's v₀, Couzin's and the boids' speed), with
    /// its field; `None` for the algorithms whose speeds follow from accelerations.
    #[must_use]
    pub fn set_speed(&self) -> Option<(&'static str, f64)> {
        match *self {
            Self::Vicsek { v0, .. } => Some(("algorithm.v0", v0)),
            Self::Boids { speed, .. } | Self::Couzin { speed, .. } => {
                Some(("algorithm.speed", speed))
            }
            _ => None,
        }
    }

    /// Whether the algorithm couples every pair of agents at every step, whatever their
    /// distance (Cucker–Smale without a cutoff): a step's work is n(n − 1)/2 pairs.
    #[must_use]
    pub fn couples_every_pair(&self) -> bool {
        matches!(self, Self::CuckerSmale { cutoff: None, .. })
    }

    /// Whether the algorithm draws random numbers of its own (Vicsek's and Couzin's angular
    /// noise, the boids' activation order).
    #[must_use]
    pub fn draws_at_random(&self) -> bool {
        match *self {
            Self::Vicsek { eta, .. } => eta > 0.0,
            Self::Couzin { noise, .. } => noise > 0.0,
            Self::Boids { .. } => true,
            _ => false,
        }
    }

    /// Whether the algorithm draws normal random numbers of its own (Couzin's angular noise).
    #[must_use]
    pub fn draws_normals(&self) -> bool {
        matches!(*self, Self::Couzin { noise, .. } if noise > 0.0)
    }

    /// Whether the algorithm is one of the classic models (Cucker–Smale, Vicsek, boids, Couzin,
    /// Vásárhelyi; docs/models.md) rather than Olfati-Saber's, Tanner's or consensus.
    #[must_use]
    pub fn is_classic_model(&self) -> bool {
        self.sets_velocity() || matches!(self, Self::CuckerSmale { .. } | Self::Vasarhelyi { .. })
    }

    /// Whether the algorithm is a model that sets its agents' velocities (Vicsek, boids, Couzin),
    /// rather than an acceleration.
    #[must_use]
    pub fn sets_velocity(&self) -> bool {
        matches!(
            self,
            Self::Vicsek { .. } | Self::Boids { .. } | Self::Couzin { .. }
        )
    }

    /// Whether the algorithm sees the scenario's obstacles.
    #[must_use]
    pub fn uses_obstacles(&self) -> bool {
        matches!(
            self,
            Self::Algorithm3 { .. }
                | Self::Flocking2003 {
                    avoidance: Some(_),
                    ..
                }
        )
    }
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

fn default_power() -> i32 {
    1
}

/// The initial condition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Initial {
    /// Where the agents start.
    pub positions: Cloud,
    /// How fast they start; default at rest.
    #[serde(default)]
    pub velocities: Cloud,
}

/// A set of n vectors: seeded random, or explicit.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Cloud {
    /// All zero.
    #[default]
    Zero,
    /// Uniform in the box [min, max].
    Box {
        /// Lower corner.
        min: Vec<f64>,
        /// Upper corner.
        max: Vec<f64>,
    },
    /// Uniform in the ball of `radius` around `centre`.
    Ball {
        /// Centre.
        centre: Vec<f64>,
        /// Radius > 0.
        radius: f64,
    },
    /// Independent normal components with mean `mean` and standard deviation `std`.
    Gaussian {
        /// Mean.
        mean: Vec<f64>,
        /// Standard deviation > 0.
        std: f64,
    },
    /// One vector per agent.
    Explicit(Vec<Vec<f64>>),
    /// Uniform in the scenario's periodic box (a periodic domain only).
    Domain,
    /// Vectors of one length `speed` in directions uniform on the circle or sphere: the random
    /// headings the constant-speed models start from (Vicsek et al. 1995, Couzin et al. 2002).
    Headings {
        /// The length ≥ 0 of every vector.
        speed: f64,
    },
}

fn default_step() -> f64 {
    0.01
}

fn default_record_every() -> u64 {
    10
}

impl Scenario {
    /// Reads and validates a scenario file. Defaults left unset stay unset (`alpha.r` is `None`
    /// and follows `alpha.d`); [`Scenario::resolved`] fills them in, [`Scenario::to_ron`] keeps them
    /// unset and writes their values in comments.
    ///
    /// # Errors
    /// When the file cannot be read, is not valid RON for a scenario (the error gives the line and
    /// column), or fails [`Scenario::validate`].
    pub fn load(path: impl AsRef<Path>) -> Result<Self, ScenarioError> {
        let path = path.as_ref();
        let text = crate::input::read_text(path).map_err(|message| ScenarioError::Io {
            path: path.display().to_string(),
            message,
        })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and validates scenario text; `origin` names it in errors.
    ///
    /// # Errors
    /// As [`Scenario::load`].
    pub fn parse(text: &str, origin: &str) -> Result<Self, ScenarioError> {
        let text = crate::input::without_bom(text);
        let scenario: Self = crate::input::ron_options()
            .from_str(text)
            .map_err(|e| ScenarioError::syntax(origin, text, &e))?;
        scenario.validate().map_err(|e| e.placed(origin, text))?;
        Ok(scenario)
    }

    /// The scenario with every default written out (r = 1.2 d, the collision distance d/4, the
    /// gains and distances of Algorithm 3, the flat part of the 2003 influence map).
    #[must_use]
    pub fn resolved(mut self) -> Self {
        let d = self.alpha.d;
        let r = self.range();
        self.alpha.r = Some(r);
        self.collision_distance = Some(self.collision_distance());
        match &mut self.algorithm {
            Algorithm::Algorithm3 { c1, c2, beta, .. } => {
                c2.get_or_insert(critical_damping(*c1));
                *beta = beta.resolved(d);
            }
            Algorithm::Flocking2003 { delta, .. } => {
                delta.get_or_insert(d / r);
            }
            _ => {}
        }
        self
    }

    /// The interaction range r: `alpha.r` (default 1.2 d), or the model's own (Vicsek's r, the
    /// boids' visual distance plus 2 s h, Couzin's r_a, Cucker–Smale's cut-off when it has one,
    /// Vásárhelyi's communication range r_c).
    #[must_use]
    pub fn range(&self) -> f64 {
        match self.algorithm {
            Algorithm::CuckerSmale { cutoff, .. } => cutoff.unwrap_or_else(|| self.alpha.range()),
            Algorithm::Vicsek { r, .. } => r,
            Algorithm::Boids {
                visual_distance,
                speed,
                ..
            } => visual_distance + 2.0 * speed * self.step,
            Algorithm::Couzin {
                r_r,
                delta_r_o,
                delta_r_a,
                ..
            } => r_r + delta_r_o + delta_r_a,
            Algorithm::Vasarhelyi { r_c, .. } => r_c,
            _ => self.alpha.range(),
        }
    }

    /// The collision distance: as given, or by default d/4 (TAC 2006), and for the models of
    /// their own spacing the boids' `separation`, Couzin's zone of repulsion r_r, Vásárhelyi's
    /// r^coll, and r/4 for Vicsek's point particles.
    #[must_use]
    pub fn collision_distance(&self) -> f64 {
        self.collision_distance
            .unwrap_or_else(|| match self.algorithm {
                Algorithm::Boids { separation, .. } => separation.min(self.range()),
                Algorithm::Couzin { r_r, .. } => r_r,
                Algorithm::Vasarhelyi { r_coll, .. } => r_coll,
                Algorithm::Vicsek { r, .. } => COLLISION_FRACTION * r,
                _ => COLLISION_FRACTION * self.alpha.d,
            })
    }

    /// Whether a run of the scenario draws random numbers as it steps (its algorithm's or its
    /// conditions'; a random initial state is drawn before the first step).
    #[must_use]
    pub fn draws_at_random(&self) -> bool {
        self.algorithm.draws_at_random() || self.conditions.draws_at_random()
    }

    /// Whether a run of the scenario draws random numbers per link (jitter, packet loss that is
    /// not symmetric).
    #[must_use]
    pub fn draws_per_link(&self) -> bool {
        self.conditions.draws_per_link()
    }

    /// Whether a run of the scenario draws normal random numbers as it steps (Couzin's angular
    /// noise, sensing noise, wind gusts, process noise).
    #[must_use]
    pub fn draws_normals(&self) -> bool {
        self.algorithm.draws_normals() || self.conditions.draws_normals()
    }

    /// The number of steps ⌈T / h⌉ (rounded to the nearest when T/h is within round-off of an integer).
    #[must_use]
    pub fn steps(&self) -> u64 {
        let ratio = self.duration / self.step;
        let nearest = ratio.round();
        if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) {
            nearest as u64
        } else {
            ratio.ceil() as u64
        }
    }

    /// The scenario as RON text. Defaults left unset stay unset, so that a scenario read back
    /// from it still moves them with the values they follow (r with d); each is written resolved in
    /// a comment at the top (`// alpha.r: 8.4 (default 1.2 d)`). Reading the text back gives this
    /// scenario, and writing that gives the same text.
    ///
    /// # Errors
    /// Never for a validated scenario; the RON serializer's error otherwise.
    pub fn to_ron(&self) -> Result<String, ron::Error> {
        let config = ron::ser::PrettyConfig::new().extensions(Extensions::IMPLICIT_SOME);
        let text = ron::ser::to_string_pretty(self, config)?;
        let defaults = self.unset_defaults();
        if defaults.is_empty() {
            return Ok(text);
        }
        let (first, rest) = text.split_once('\n').unwrap_or((&text, ""));
        let mut out = format!(
            "{first}\n// Defaults left unset, which follow the values they depend on; resolved:\n"
        );
        for (path, value) in defaults {
            let rule = match path.as_str() {
                "alpha.r" => "default 1.2 d",
                "collision_distance" => "default d/4",
                "algorithm.c2" => "default 2 √c1, critically damped",
                "algorithm.delta" => "default d/r",
                _ => "default from alpha.d",
            };
            out.push_str(&format!("// {path}: {value} ({rule})\n"));
        }
        out.push_str(rest);
        Ok(out)
    }

    /// The defaults this scenario leaves unset, by path, with the values [`Scenario::resolved`]
    /// gives them.
    #[must_use]
    pub fn unset_defaults(&self) -> Vec<(String, serde_json::Value)> {
        fn walk(
            path: &str,
            unset: &serde_json::Value,
            resolved: &serde_json::Value,
            out: &mut Vec<(String, serde_json::Value)>,
        ) {
            use serde_json::Value;
            match (unset, resolved) {
                (Value::Null, value) if !value.is_null() => {
                    out.push((path.to_owned(), value.clone()));
                }
                (Value::Object(a), Value::Object(b)) => {
                    for (key, value) in a {
                        let inner =
                            if key.starts_with(|c: char| c.is_ascii_uppercase()) && a.len() == 1 {
                                path.to_owned()
                            } else if path.is_empty() {
                                key.clone()
                            } else {
                                format!("{path}.{key}")
                            };
                        if let Some(other) = b.get(key) {
                            walk(&inner, value, other, out);
                        }
                    }
                }
                _ => {}
            }
        }
        let tree = |s: &Self| serde_json::to_value(s).unwrap_or_default();
        let mut out = Vec::new();
        walk("", &tree(self), &tree(&self.clone().resolved()), &mut out);
        out
    }
}

/// Parses and validates scenario text ([`Scenario::parse`] with the origin `<string>`).
impl FromStr for Scenario {
    type Err = ScenarioError;

    fn from_str(text: &str) -> Result<Self, ScenarioError> {
        Self::parse(text, "<string>")
    }
}

//! Warnings about a valid scenario that is likely to go wrong: a step too large for the stiffness
//! of the potential, and agents that start at the same point.
//!
//! # The step estimate
//! Near any configuration the closed loop linearises to q̈ = −K q − Γ q̇, with K and Γ Laplacian-like
//! matrices of the net. Along a pair at distance z the α-force is
//! F(z) = c₁^α φ_α(‖z‖_σ) z / √(1 + ε z²) (TAC 2006 eq. 23), so a pair contributes the stiffness
//! k = max_z max(|F′(z)|, |F(z)/z|) (radial and transverse), sampled on (0, r]. With at most `deg`
//! neighbours per agent, λ_max(K) ≤ 2 deg k + k_γ + k_β, where k_γ = c₁^γ (the linear and the
//! bounded feedback have slope ≤ c₁) and k_β is the same sampled bound for φ_β (eq. 56), and
//! λ_max(Γ) ≤ 2 deg c₂^α + c₂^γ + c₂^β (a_ij ≤ 1). For the mode q̈ = −ω² q − γ q̇:
//! - symplectic Euler is stable iff h²ω² + 2hγ < 4, i.e. h < (√(γ² + 4ω²) − γ)/ω²;
//! - RK4 is stable for h |λ| ≲ 2.5 with |λ| ≤ max(ω, γ) the largest eigenvalue modulus.
//!
//! `deg` is the larger of the kissing number of the α-lattice (6 in the plane, 12 in space) and
//! the largest degree of the initial net. The estimate covers the TAC 2006 algorithms; the 2003
//! protocols and the Tanner law (whose potential is unbounded at contact) get none.

use std::fmt;

use flock_graph::{NeighbourSearch, ProximityNet};
use flock_math::{Bump, BumpedAction, SigmaNorm, UnevenSigmoid, Vector};
use glam::{DVec2, DVec3};

use flock_protocols::{Integrator, critical_damping};

use crate::initial::initial_swarm;
use crate::scenario::{Algorithm, Scenario};

/// A valid scenario that is likely to go wrong, with the field, the value, why and the fix.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// The field, as a path.
    pub field: String,
    /// The value given.
    pub value: String,
    /// Why it is likely to go wrong.
    pub why: String,
    /// How to fix it.
    pub fix: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "warning: `{}` = {}: {}. Fix: {}.",
            self.field, self.value, self.why, self.fix
        )
    }
}

/// Samples of (0, r] for the largest slope of a pair force.
const SAMPLES: usize = 4000;

/// The RK4 stability radius used (its region reaches 2.78 on the real axis, 2.83 on the imaginary).
const RK4_RADIUS: f64 = 2.5;

/// The largest stable step of `scenario` estimated as in the module documentation (`None` for the
/// 2003 protocols and the Tanner law). The scenario must be valid.
#[must_use]
pub fn largest_stable_step(scenario: &Scenario) -> Option<f64> {
    stable_step(scenario, || StartNet::of(scenario).degree)
}

/// [`largest_stable_step`] with the initial net's largest degree from `degree`, asked only for
/// the algorithms the estimate covers.
fn stable_step(scenario: &Scenario, degree: impl FnOnce() -> usize) -> Option<f64> {
    let a = &scenario.alpha;
    let (gamma_c1, gamma_c2, beta) = match &scenario.algorithm {
        Algorithm::Algorithm1 => (0.0, 0.0, None),
        Algorithm::Algorithm2 { c1, c2, .. } => (*c1, *c2, None),
        Algorithm::Algorithm3 { c1, c2, beta, .. } => {
            (*c1, c2.unwrap_or(critical_damping(*c1)), Some(beta))
        }
        Algorithm::Flocking2003 { .. } | Algorithm::Tanner { .. } => return None,
    };
    let sigma = SigmaNorm::new(a.epsilon);
    let r = scenario.range();
    let phi_alpha = BumpedAction::alpha(
        UnevenSigmoid::new(a.a, a.b),
        Bump::tac(a.h),
        sigma.of_length(a.d),
        sigma.of_length(r),
    );
    let k_alpha = a.c1 * pair_stiffness(&phi_alpha, &sigma, r);
    let (k_beta, c2_beta) = beta.map_or((0.0, 0.0), |beta| {
        let d_beta = beta.distance(a.d);
        let phi_beta = BumpedAction::beta(Bump::tac(beta.h), sigma.of_length(d_beta));
        (
            beta.c1 * pair_stiffness(&phi_beta, &sigma, beta.range(a.d)),
            beta.damping(),
        )
    });
    let kissing = if scenario.dim == 2 { 6 } else { 12 };
    let deg = degree().max(kissing) as f64;
    let omega2 = 2.0 * deg * k_alpha + gamma_c1 + k_beta;
    let damping = 2.0 * deg * a.c2 + gamma_c2 + c2_beta;
    let step = match scenario.integrator {
        Integrator::SymplecticEuler => {
            ((damping * damping + 4.0 * omega2).sqrt() - damping) / omega2
        }
        Integrator::Rk4 => RK4_RADIUS / omega2.sqrt().max(damping),
    };
    step.is_finite().then_some(step)
}

/// max over z ∈ (0, range] of |F′(z)| and |F(z)/z| for F(z) = φ(‖z‖_σ) z / √(1 + ε z²).
fn pair_stiffness(phi: &BumpedAction, sigma: &SigmaNorm, range: f64) -> f64 {
    let force = |z: f64| {
        let (s, scale) = sigma.norm_and_gradient_scale(z * z);
        phi.action_and_bump(s).0 * scale * z
    };
    let dz = range / SAMPLES as f64;
    (1..=SAMPLES)
        .map(|k| {
            let z = k as f64 * dz;
            let slope = (force(z) - force(z - dz)).abs() / dz;
            slope.max((force(z) / z).abs())
        })
        .fold(0.0, f64::max)
}

/// What the initial state tells: the largest degree of its net and the first pair of agents at
/// the same point, from one draw of the initial swarm.
struct StartNet {
    /// The largest number of neighbours within r.
    degree: usize,
    /// The first pair (i < j) closer than 10⁻⁹ d: for the σ-norm and its gradient, one point.
    coincident: Option<(usize, usize)>,
}

impl StartNet {
    /// The initial net of a valid `scenario`.
    fn of(scenario: &Scenario) -> Self {
        match scenario.dim {
            2 => Self::in_dim::<DVec2>(scenario),
            _ => Self::in_dim::<DVec3>(scenario),
        }
    }

    fn in_dim<V: Vector>(scenario: &Scenario) -> Self {
        let q = initial_swarm::<V>(scenario).positions;
        let mut net = ProximityNet::without_distances();
        NeighbourSearch::new().build(&q, scenario.range(), &mut net);
        let graph = net.graph();
        Self {
            degree: (0..q.len())
                .map(|i| graph.neighbours(i).len())
                .max()
                .unwrap_or(0),
            coincident: coincident_pair(&q, scenario.alpha.d),
        }
    }
}

/// The first pair of agents (i < j) of a valid `scenario` that start closer than 10⁻⁹ d.
pub(crate) fn coincident_start(scenario: &Scenario) -> Option<(usize, usize)> {
    match scenario.dim {
        2 => coincident_pair(
            &initial_swarm::<DVec2>(scenario).positions,
            scenario.alpha.d,
        ),
        _ => coincident_pair(
            &initial_swarm::<DVec3>(scenario).positions,
            scenario.alpha.d,
        ),
    }
}

/// The first pair (i < j) of `q` closer than 10⁻⁹ d, from a search at that range: cheap however
/// dense the agents are, unlike the net at range r (a dense start can have thousands of
/// neighbours per agent within r).
fn coincident_pair<V: Vector>(q: &[V], d: f64) -> Option<(usize, usize)> {
    let mut net = ProximityNet::without_distances();
    NeighbourSearch::new().build(q, 1e-9 * d, &mut net);
    let graph = net.graph();
    (0..q.len()).find_map(|i| {
        let j = graph
            .neighbours(i)
            .iter()
            .map(|&j| j as usize)
            .find(|&j| j > i)?;
        Some((i, j))
    })
}

impl Scenario {
    /// The warnings of a valid scenario: a step above the estimated stability limit
    /// ([`largest_stable_step`]) and agents that start at the same point.
    #[must_use]
    pub fn warnings(&self) -> Vec<Warning> {
        let mut warnings = Vec::new();
        let start = StartNet::of(self);
        if let Some(stable) = stable_step(self, || start.degree)
            && self.step > stable
        {
            warnings.push(Warning {
                field: "step".to_owned(),
                value: self.step.to_string(),
                why: format!(
                    "exceeds the largest stable step ≈ {stable:.3e} estimated from the stiffness of the potential and the gains, so the run is likely to blow up"
                ),
                fix: format!("set `step` to at most {stable:.3e} (the papers use 0.01)"),
            });
        }
        let pair = start.coincident;
        if let Some((i, j)) = pair {
            warnings.push(Warning {
                field: "initial.positions".to_owned(),
                value: format!("agents {i} and {j}"),
                why: "start at the same point, where n_ij = σ_ε(q_j − q_i) vanishes: the α-force cannot separate them".to_owned(),
                fix: "give distinct positions (or a Box/Ball/Gaussian cloud, whose points are distinct)".to_owned(),
            });
        }
        warnings
    }
}

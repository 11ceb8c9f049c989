//! Warnings about a valid scenario that is likely to go wrong (part of [`Scenario::warnings`]): a
//! step too large for the stiffness of the potential, and agents that start at the same point.
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
//! the largest degree of the initial net.
//!
//! The 2003 protocols (CDS 03-006 eq. 34–36) pull along unit vectors, F(z) = g(z) n_ij, so
//! |F(z)/z| = |g(z)|/z grows without bound as two agents meet: their pair stiffness is sampled on
//! [d/4 or the collision distance, r), the distances of every configuration the run does not
//! count as a collision; the consensus term is unweighted (λ_max(Γ) ≤ 2 deg c₁), the translational
//! PD adds c₁ and c₂ of its own, and ball obstacles the slopes c₃(a + b) of their β- and γ-terms
//! (eq. 54, radial) and c₄.
//!
//! The Tanner law (seed 001 eq. 5) has a potential unbounded at contact, but Theorem IV.4 bounds
//! the distance of linked agents below by z* with V(z*) = W(0) (W is non-increasing); its pair
//! stiffness is sampled on [z*, 3 d] (beyond, |V″| < 2/z² is small), `deg` is the largest degree
//! of its fixed graph, and the velocity consensus −Σ_{j∼i}(v_i − v_j) gives λ_max(Γ) ≤ 2 deg.
//!
//! Consensus (seed 000 eq. 9) is first order in the velocities, ṗ = −c (L ⊗ I) p: explicit
//! (symplectic) Euler is stable iff h c λ_max(L) < 2, RK4 for h c λ_max ≲ 2.5. λ_max is that of
//! the fixed graph's Laplacian, computed exactly ([`laplacian_eigenvalues`]) up to
//! [`EXACT_SPECTRUM_NODES`] agents and bounded by 2 · max degree beyond; on the proximity net it
//! is bounded by 2 deg with `deg` as above.
//!
//! # The conditions' warnings
//! - Sampled control with period T = 1/rate (zero-order hold): for consensus the input is
//!   constant over a period, so p_{k+1} = (I − c T L) p_k exactly, which converges iff
//!   c T λ_max(L) < 2; for the other protocols T must stay below the largest stable step above
//!   (the step estimate with T in place of h).
//! - Delay τ with [`Delayed::All`]: consensus ṗ = −c L p(t − τ) converges iff
//!   τ < π / (2 c λ_max(L)) (Olfati-Saber & Murray, IEEE TAC 49(9), 2004, its time-delay result;
//!   not among the seeds): in the eigenbasis of L each mode obeys ẋ = −c λ x(t − τ), whose roots
//!   stay in the left half-plane iff c λ τ < π/2. The largest delay, τ + jitter, is checked.

use core::f64::consts::PI;

use flock_graph::{
    NeighbourSearch, ProximityNet, laplacian_eigenvalues, weighted_laplacian_eigenvalues,
    weights_from_distances,
};
use flock_math::{
    Bump, BumpedAction, Potential, SigmaNorm, TannerPotential, UnevenSigmoid, Vector,
};
use flock_sim::conditions::Delayed;
use glam::{DVec2, DVec3};

use flock_protocols::{AlphaAlpha, AlphaAlphaParams, TannerJadbabaiePappas, critical_damping};
use flock_sim::Integrator;

use crate::initial::initial_swarm;
use crate::scenario::{Algorithm, Flocking2003Params, Scenario};
use crate::warning::Warning;

/// Samples of (0, r] for the largest slope of a pair force.
const SAMPLES: usize = 4000;

/// The RK4 stability radius used (its region reaches 2.78 on the real axis, 2.83 on the imaginary).
const RK4_RADIUS: f64 = 2.5;

/// The largest stable step of `scenario` estimated as in the module documentation. The scenario
/// must be valid.
#[must_use]
pub fn largest_stable_step(scenario: &Scenario) -> Option<f64> {
    stable_step(scenario, || StartNet::of(scenario).degree)
}

/// The most agents whose fixed graph's Laplacian spectrum is computed exactly (dense Jacobi,
/// O(n³)); beyond, λ_max is bounded by 2 · max degree.
pub const EXACT_SPECTRUM_NODES: usize = 200;

/// λ_max(L) of the graph a consensus scenario runs on, and whether it is exact: the fixed graph's
/// ([`EXACT_SPECTRUM_NODES`]), else 2 · its max degree; on the proximity net 2 `deg` (the larger
/// of the lattice's kissing number and the initial net's largest degree). `None` for the other
/// algorithms.
fn consensus_lambda_max(scenario: &Scenario, deg: impl FnOnce() -> f64) -> Option<(f64, bool)> {
    let Algorithm::Consensus(consensus) = &scenario.algorithm else {
        return None;
    };
    if consensus.graph.is_none() {
        return Some((2.0 * deg(), false));
    }
    let graph = scenario.tanner_graph().ok()?;
    if graph.len() <= EXACT_SPECTRUM_NODES {
        let lambda = laplacian_eigenvalues(&graph);
        return Some((lambda.last().copied().unwrap_or(0.0), true));
    }
    let max_degree = (0..graph.len()).map(|i| graph.degree(i)).max();
    Some((2.0 * max_degree.unwrap_or(0) as f64, false))
}

/// λ_max(L) of a consensus scenario, as [`largest_stable_step`] estimates it, and whether it
/// is exact (the Laplacian of a fixed graph of at most [`EXACT_SPECTRUM_NODES`] agents).
#[must_use]
pub fn consensus_laplacian_max(scenario: &Scenario) -> Option<(f64, bool)> {
    let kissing = if scenario.dim == 2 { 6 } else { 12 };
    consensus_lambda_max(scenario, || {
        StartNet::of(scenario).degree.max(kissing) as f64
    })
}

/// The delay τ* below which the linearised velocity consensus of a TAC 2006 flock (Algorithms
/// 1–3) at `positions` is stable when every state is delayed ([`Delayed::All`]):
/// τ* = π / (2 λ_max(c₂^α L_a(q) + c₂^γ I)) = π / (2 (c₂^α λ_max(L_a(q)) + c₂^γ)).
///
/// Near a lattice the velocity part of the protocol is ṗ = −(c₂^α L̂_a(q) + c₂^γ I)(p − p_r)
/// (TAC 2006 eq. 23 and 59, relative to the γ-agent's velocity p_r), with the spatial
/// adjacency a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) (eq. 11) on the net at range r; delayed, each of its
/// modes ẋ = −λ x(t − τ) is stable iff λ τ < π/2 (Olfati-Saber & Murray, IEEE TAC 49(9),
/// 2004). It leaves out the position terms, which a delay destabilises too; β-agents are left
/// out. `positions` are n rows of `scenario.dim` coordinates (a [`crate::State`]'s). `None` for
/// the other algorithms.
#[must_use]
pub fn velocity_consensus_delay_bound(scenario: &Scenario, positions: &[f64]) -> Option<f64> {
    let gamma_c2 = match &scenario.algorithm {
        Algorithm::Algorithm1 => 0.0,
        Algorithm::Algorithm2(p) => p.c2,
        Algorithm::Algorithm3(p) => p.c2.unwrap_or(critical_damping(p.c1)),
        _ => return None,
    };
    let a = &scenario.alpha;
    let r = scenario.range();
    let net = match scenario.dim {
        2 => ProximityNet::brute_force(&rows::<DVec2>(positions), r),
        _ => ProximityNet::brute_force(&rows::<DVec3>(positions), r),
    };
    let sigma = SigmaNorm::new(a.epsilon);
    let (bump, r_alpha) = (Bump::tac(a.h), sigma.of_length(r));
    let weights = weights_from_distances(&net, |z| bump.value(sigma.of_length(z) / r_alpha));
    let lambda = weighted_laplacian_eigenvalues(net.graph(), &weights);
    let largest = a.c2 * lambda.last().copied().unwrap_or(0.0) + gamma_c2;
    (largest > 0.0).then(|| PI / (2.0 * largest))
}

/// n rows of `V::DIM` coordinates as vectors.
fn rows<V: Vector>(positions: &[f64]) -> Vec<V> {
    positions
        .chunks_exact(V::DIM)
        .map(|row| V::from_fn(|k| row[k]))
        .collect()
}

/// The stiffness ω² and damping γ bounds of the linearised closed loop.
struct Stiffness {
    omega2: f64,
    damping: f64,
}

/// [`largest_stable_step`] with the initial net's largest degree from `degree`, asked only for
/// the algorithms whose bound depends on it.
fn stable_step(scenario: &Scenario, degree: impl FnOnce() -> usize) -> Option<f64> {
    let kissing = if scenario.dim == 2 { 6 } else { 12 };
    let deg = || degree().max(kissing) as f64;
    let radius = match scenario.integrator {
        Integrator::SymplecticEuler => 2.0,
        Integrator::Rk4 => RK4_RADIUS,
    };
    match &scenario.algorithm {
        // discrete-time maps with their own step: no continuous dynamics to resolve
        Algorithm::Vicsek(_) | Algorithm::Boids(_) | Algorithm::Couzin(_) => {
            return None;
        }
        // ṗ = −(λ/N) L_ψ p with ψ ≤ K/σ^{2β}: by Gershgorin λ_max ≤ 2 λ K (N − 1) / (N σ^{2β})
        Algorithm::CuckerSmale(p) => {
            let lambda = 2.0 * p.lambda * p.k / (p.sigma * p.sigma).powf(p.beta);
            let step = radius / lambda;
            return (step.is_finite() && step > 0.0).then_some(step);
        }
        // v̇ = (v_d − v)/τ: damping up to (1 + C^frict deg)/τ (self-propulsion's derivative
        // across the heading is at most 1 at the flocking speed, each neighbour's alignment
        // C^frict), stiffness up to p^rep deg/τ (the linear repulsion)
        Algorithm::Vasarhelyi(p) => {
            let degree = deg();
            let damping = (1.0 + p.c_frict * degree) / p.tau;
            let omega2 = p.p_rep * degree / p.tau;
            let step = match scenario.integrator {
                Integrator::SymplecticEuler if omega2 > 0.0 => {
                    ((damping * damping + 4.0 * omega2).sqrt() - damping) / omega2
                }
                Integrator::SymplecticEuler => 2.0 / damping,
                Integrator::Rk4 => RK4_RADIUS / omega2.sqrt().max(damping),
            };
            return (step.is_finite() && step > 0.0).then_some(step);
        }
        _ => {}
    }
    if let Algorithm::Consensus(consensus) = &scenario.algorithm {
        let (lambda, _) = consensus_lambda_max(scenario, deg)?;
        let step = radius / (consensus.gain * lambda);
        return (step.is_finite() && step > 0.0).then_some(step);
    }
    let Stiffness { omega2, damping } = match &scenario.algorithm {
        Algorithm::Flocking2003(_) => stiffness_2003(scenario, deg()),
        Algorithm::Tanner(_) => stiffness_tanner(scenario)?,
        _ => stiffness_tac(scenario, deg()),
    };
    let step = match scenario.integrator {
        Integrator::SymplecticEuler => {
            ((damping * damping + 4.0 * omega2).sqrt() - damping) / omega2
        }
        Integrator::Rk4 => RK4_RADIUS / omega2.sqrt().max(damping),
    };
    (step.is_finite() && step > 0.0).then_some(step)
}

/// The bounds of the TAC 2006 algorithms (Algorithms 1–3).
fn stiffness_tac(scenario: &Scenario, deg: f64) -> Stiffness {
    let a = &scenario.alpha;
    let (gamma_c1, gamma_c2, beta) = match &scenario.algorithm {
        Algorithm::Algorithm2(p) => (p.c1, p.c2, None),
        Algorithm::Algorithm3(p) => (p.c1, p.c2.unwrap_or(critical_damping(p.c1)), Some(&p.beta)),
        _ => (0.0, 0.0, None),
    };
    let sigma = SigmaNorm::new(a.epsilon);
    let r = scenario.range();
    let phi_alpha = BumpedAction::alpha(
        UnevenSigmoid::new(a.a, a.b),
        Bump::tac(a.h),
        sigma.of_length(a.d),
        sigma.of_length(r),
    );
    let k_alpha = a.c1 * slope_bound(sigma_force(&phi_alpha, &sigma), 0.0, r);
    let (k_beta, c2_beta) = beta.map_or((0.0, 0.0), |beta| {
        let d_beta = beta.distance(a.d);
        let phi_beta = BumpedAction::beta(Bump::tac(beta.h), sigma.of_length(d_beta));
        (
            beta.c1 * slope_bound(sigma_force(&phi_beta, &sigma), 0.0, beta.range(a.d)),
            beta.damping(),
        )
    });
    Stiffness {
        omega2: 2.0 * deg * k_alpha + gamma_c1 + k_beta,
        damping: 2.0 * deg * a.c2 + gamma_c2 + c2_beta,
    }
}

/// The bounds of the 2003 (α, α) protocols, with their translational controller and obstacles.
fn stiffness_2003(scenario: &Scenario, deg: f64) -> Stiffness {
    let Algorithm::Flocking2003(Flocking2003Params {
        form,
        c1,
        delta,
        power,
        translation,
        avoidance,
    }) = &scenario.algorithm
    else {
        unreachable!("the 2003 bounds of another algorithm");
    };
    let a = &scenario.alpha;
    let r = scenario.range();
    let params = AlphaAlphaParams {
        bump: Bump::influence_map(delta.unwrap_or(a.d / r), *power),
        ..AlphaAlphaParams::new(a.d, r, a.a, a.b)
    };
    let alpha = AlphaAlpha::new(params, *form, *c1);
    let closest = scenario.collision_distance().min(r);
    // the pair force stops at r: sample below it
    let k_alpha = slope_bound(|z| alpha.pair_action(z), closest, r * (1.0 - 1e-9));
    let (t_c1, t_c2) = translation.as_ref().map_or((0.0, 0.0), |t| (t.c1, t.c2));
    // φ_β and φ_γ are branches of the uneven sigmoid ½[(a + b)σ₁(z + c) + (a − b)], of slope
    // at most (a + b)/2 (σ₁′ ≤ 1): the two terms of eq. 54 add c₃(a + b)
    let (k_obstacle, c4) = match avoidance {
        Some(gains) if !scenario.obstacles.is_empty() => (gains.c3 * (a.a + a.b), gains.c4),
        _ => (0.0, 0.0),
    };
    Stiffness {
        omega2: 2.0 * deg * k_alpha + t_c1 + k_obstacle,
        damping: 2.0 * deg * c1 + t_c2 + c4,
    }
}

/// The bounds of the Tanner law, from its fixed graph and the collision bound of W(0); `None`
/// when the graph cannot be built.
fn stiffness_tanner(scenario: &Scenario) -> Option<Stiffness> {
    let graph = scenario.tanner_graph().ok()?;
    let d = scenario.alpha.d;
    let law = TannerJadbabaiePappas::new(graph, TannerPotential::new(d), scenario.range()).ok()?;
    let w0 = match scenario.dim {
        2 => law.lyapunov(&initial_swarm::<DVec2>(scenario)),
        _ => law.lyapunov(&initial_swarm::<DVec3>(scenario)),
    };
    let closest = law.collision_bound(w0);
    let deg = (0..law.graph().len())
        .map(|i| law.graph().degree(i))
        .max()
        .unwrap_or(0) as f64;
    let potential = law.pair_potential();
    let k = slope_bound(|z| potential.action(z), closest, 3.0 * d.max(closest));
    Some(Stiffness {
        omega2: 2.0 * deg * k,
        damping: 2.0 * deg,
    })
}

/// F(z) = φ(‖z‖_σ) z / √(1 + ε z²), the TAC 2006 pair force of action φ at distance z.
fn sigma_force<'a>(phi: &'a BumpedAction, sigma: &'a SigmaNorm) -> impl Fn(f64) -> f64 + 'a {
    move |z: f64| {
        let (s, scale) = sigma.norm_and_gradient_scale(z * z);
        phi.action_and_bump(s).0 * scale * z
    }
}

/// max over z ∈ (lo, hi] of |F′(z)| (by differences over [`SAMPLES`] cells) and |F(z)/z|.
fn slope_bound(force: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    let dz = (hi - lo) / SAMPLES as f64;
    (1..=SAMPLES)
        .map(|k| {
            let z = lo + k as f64 * dz;
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
    /// The stability warnings of a valid scenario ([`Scenario::warnings`] gives them all): a step
    /// above the estimated stability limit ([`largest_stable_step`]), the conditions' and agents
    /// that start at the same point.
    pub(crate) fn stability_warnings(&self) -> Vec<Warning> {
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
        warnings.extend(self.condition_warnings(|| start.degree));
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

impl Scenario {
    /// The warnings of the conditions (module documentation): a control period too long for the
    /// gains, and a delay of every state beyond the consensus bound.
    fn condition_warnings(&self, degree: impl Fn() -> usize) -> Vec<Warning> {
        let mut warnings = Vec::new();
        let kissing = if self.dim == 2 { 6 } else { 12 };
        let deg = || degree().max(kissing) as f64;
        let consensus = match &self.algorithm {
            Algorithm::Consensus(p) => {
                consensus_lambda_max(self, deg).map(|(lambda, exact)| (p.gain, lambda, exact))
            }
            _ => None,
        };
        let of_lambda = |exact: bool| {
            if exact {
                "λ_max(L) of the fixed graph"
            } else {
                "the bound 2 · max degree on λ_max(L)"
            }
        };
        if let Some(control) = &self.conditions.control {
            let period = 1.0 / control.rate;
            let limit = match consensus {
                Some((c, lambda, exact)) => Some((
                    2.0 / (c * lambda),
                    format!(
                        "gives a control period T = {period} s with c T λ_max(L) = {:.3} ≥ 2 \
                         (c = {c}, {} = {lambda:.4}): sampled consensus p_(k+1) = (I − c T L) p_k \
                         diverges",
                        c * period * lambda,
                        of_lambda(exact)
                    ),
                )),
                None => stable_step(self, &degree).map(|stable| {
                    (
                        stable,
                        format!(
                            "gives a control period T = {period} s above the largest stable \
                             step ≈ {stable:.3e} estimated from the stiffness of the potential \
                             and the gains: the input held over T is likely to blow the run up"
                        ),
                    )
                }),
            };
            if let Some((limit, why)) = limit
                && period >= limit
            {
                warnings.push(Warning {
                    field: "conditions.control.rate".to_owned(),
                    value: control.rate.to_string(),
                    why,
                    fix: format!(
                        "use a rate above {:.4} Hz (a period below {limit:.4e} s)",
                        1.0 / limit
                    ),
                });
            }
        }
        if let (Some(communication), Some((c, lambda, exact))) =
            (&self.conditions.communication, consensus)
            && communication.delayed == Delayed::All
        {
            let tau = communication.delay + communication.jitter;
            let bound = PI / (2.0 * c * lambda);
            if tau >= bound {
                warnings.push(Warning {
                    field: "conditions.communication.delay".to_owned(),
                    value: communication.delay.to_string(),
                    why: format!(
                        "with jitter, delays every state by up to τ = {tau} s ≥ π/(2 c λ_max) = \
                         {bound:.4} s (c = {c}, {} = {lambda:.4}): consensus with delay \
                         (Olfati-Saber & Murray 2004) diverges",
                        of_lambda(exact)
                    ),
                    fix: format!("keep delay + jitter below {bound:.4} s, or lower the gain"),
                });
            }
        }
        warnings
    }
}

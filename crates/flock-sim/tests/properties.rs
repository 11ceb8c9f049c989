//! Property tests of Algorithm 1 on random swarms and random α-parameters, in 2D and 3D: momentum
//! (Σ_i u_i = 0, and Σ_i p_i constant along symplectic Euler), translation and rotation invariance
//! and permutation equivariance of the inputs u.
//!
//! Every tolerance is a round-off bound, computed per case from the state, not a fixed epsilon.
//! With u = 2⁻⁵³ the unit round-off and m the dimension:
//!
//! - A pair term of agent i is t_ij = c₁ g_ij + c₂ c_ij, g_ij = φ_α(‖q_j − q_i‖_σ) σ_ε(q_j − q_i)
//!   and c_ij = a_ij (p_j − p_i); its size is s_ij = c₁‖g_ij‖ + c₂‖c_ij‖ and S_i = Σ_j s_ij.
//! - Summing k terms errs by at most γ_k = k u times the sum of their sizes, componentwise, so
//!   by √m k u times the sum of their norms.
//! - Evaluating one pair term (a square root, a cosine, a few products) errs by at most 32 u times
//!   its a-priori size b‖σ_ε‖ c₁ + ‖p_j − p_i‖ c₂ (|φ_α| ≤ b, 0 ≤ a_ij ≤ 1).
//! - Moving the inputs of a pair term by δq (positions) and δp (velocities) moves it by at most
//!   c₁ L_g δq + c₂ (L_a ‖p_j − p_i‖ δq + 2 δp), with the Lipschitz constants of the pair term
//!   L_g = (½(a + b) + b π / (2 (1 − h) r_α)) min(1/ε, 4r²) + b and of the adjacency
//!   L_a = π / (2 (1 − h) r_α) min(1/√ε, 2r) (|φ′| ≤ ½(a + b), |ρ_h′| ≤ π / (2(1 − h)),
//!   ‖σ_ε(x)‖² ≤ min(1/ε, ‖x‖²), ‖∇σ_ε‖ ≤ 1). A pair within δq of the range r counts too: its
//!   term vanishes at r and is within that bound of 0.

use flock_graph::ProximityNet;
use flock_math::{SigmaNorm, Vector};
use flock_protocols::{Algorithm1, AlphaInteraction, AlphaParams, Protocol, Swarm};
use flock_sim::{Integrator, Simulation};
use glam::{DMat2, DQuat, DVec2, DVec3};
use proptest::prelude::*;

/// The unit round-off of f64.
const U: f64 = f64::EPSILON / 2.0;

/// A random Algorithm 1 and swarm: α-parameters in their domain, n agents in a cube sized so that
/// the net has edges, velocities in [−3, 3]^m.
#[derive(Clone, Debug)]
struct Case {
    params: AlphaParams,
    c1: f64,
    c2: f64,
    /// Half-width of the cube of the positions, in units of d · n^(1/m).
    spread: f64,
    /// Positions and velocities in [−1, 1]³, the first m coordinates used.
    positions: Vec<[f64; 3]>,
    velocities: Vec<[f64; 3]>,
}

impl Case {
    fn protocol(&self) -> Algorithm1 {
        Algorithm1 {
            alpha: AlphaInteraction::new(self.params, self.c1, self.c2)
                .expect("valid α-parameters"),
        }
    }

    fn swarm<V: Vector>(&self) -> Swarm<V> {
        let n = self.positions.len() as f64;
        let half = self.spread * self.params.d * n.powf(1.0 / V::DIM as f64);
        let q = self.positions.iter().map(|x| V::from_fn(|k| half * x[k]));
        let p = self.velocities.iter().map(|x| V::from_fn(|k| 3.0 * x[k]));
        Swarm::new(q.collect(), p.collect())
    }

    /// The Lipschitz constants (L_g, L_a) of the pair term and of the adjacency.
    fn lipschitz(&self) -> (f64, f64) {
        let AlphaParams {
            r,
            epsilon,
            a,
            b,
            h,
            ..
        } = self.params;
        let r_alpha = SigmaNorm::new(epsilon).of_length(r);
        let bump_slope = core::f64::consts::PI / (2.0 * (1.0 - h) * r_alpha);
        let l_g = (0.5 * (a + b) + b * bump_slope) * (1.0 / epsilon).min(4.0 * r * r) + b;
        let l_a = bump_slope * (1.0 / epsilon.sqrt()).min(2.0 * r);
        (l_g, l_a)
    }

    /// Per agent: (degree, S_i = Σ_j s_ij, A_i = Σ_j a-priori size of t_ij), over the net of range
    /// `range`.
    fn sizes<V: Vector>(&self, swarm: &Swarm<V>, range: f64) -> Vec<(usize, f64, f64)> {
        let alpha =
            AlphaInteraction::new(self.params, self.c1, self.c2).expect("valid α-parameters");
        let sigma = SigmaNorm::new(self.params.epsilon);
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let net = ProximityNet::brute_force(q, range);
        (0..q.len())
            .map(|i| {
                let neighbours = net.graph().neighbours(i);
                let (mut exact, mut a_priori) = (0.0, 0.0);
                for &j in neighbours {
                    let j = j as usize;
                    let (dq, dp) = (q[j] - q[i], (p[j] - p[i]).length());
                    let (z, scale) = sigma.norm_and_gradient_scale(dq.length_squared());
                    let (phi, a_ij) = alpha.action().action_and_bump(z);
                    let sigma_length = dq.length() * scale;
                    exact += self.c1 * phi.abs() * sigma_length + self.c2 * a_ij * dp;
                    a_priori += self.c1 * self.params.b * sigma_length + self.c2 * dp;
                }
                (neighbours.len(), exact, a_priori)
            })
            .collect()
    }

    /// (the largest degree, Σ_i S_i) over the net of range r: what the round-off of Σ u_i grows
    /// with.
    fn degree_and_scale<V: Vector>(&self, swarm: &Swarm<V>) -> (usize, f64) {
        let sizes = self.sizes(swarm, self.params.r);
        let max_degree = sizes.iter().map(|s| s.0).max().unwrap_or(0);
        (max_degree, sizes.iter().map(|s| s.1).sum())
    }

    /// The bound on ‖u_i − u′_i‖ when u′ is computed from a state whose relative positions differ
    /// by at most `delta_q` and velocities by at most `delta_p` (see the module's notes).
    fn perturbation_bounds<V: Vector>(
        &self,
        swarm: &Swarm<V>,
        delta_q: f64,
        delta_p: f64,
    ) -> Vec<f64> {
        let (l_g, l_a) = self.lipschitz();
        let root_m = (V::DIM as f64).sqrt();
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let range = self.params.r + delta_q;
        let net = ProximityNet::brute_force(q, range);
        self.sizes(swarm, range)
            .into_iter()
            .enumerate()
            .map(|(i, (degree, _, a_priori))| {
                let round_off = 2.0 * (degree + 34) as f64 * U * root_m * a_priori;
                let moved: f64 = net
                    .graph()
                    .neighbours(i)
                    .iter()
                    .map(|&j| {
                        let dp = (p[j as usize] - p[i]).length();
                        self.c1 * l_g * delta_q + self.c2 * (l_a * dp * delta_q + 2.0 * delta_p)
                    })
                    .sum();
                round_off + moved
            })
            .collect()
    }
}

fn case() -> impl Strategy<Value = Case> {
    let params = (
        1.0..10.0f64,  // d
        1.05..2.0f64,  // r / d
        0.01..1.0f64,  // ε
        0.5..10.0f64,  // a
        0.0..10.0f64,  // b − a
        0.05..0.95f64, // h
    )
        .prop_map(|(d, ratio, epsilon, a, extra, h)| AlphaParams {
            d,
            r: ratio * d,
            epsilon,
            a,
            b: a + extra,
            h,
        });
    let agents = (2usize..=40).prop_flat_map(|n| {
        let point = || prop::array::uniform3(-1.0..1.0f64);
        (
            prop::collection::vec(point(), n),
            prop::collection::vec(point(), n),
        )
    });
    (params, 0.1..5.0f64, 0.0..5.0f64, 0.2..1.5f64, agents).prop_map(
        |(params, c1, c2, spread, (positions, velocities))| Case {
            params,
            c1,
            c2,
            spread,
            positions,
            velocities,
        },
    )
}

fn controls<V: Vector, P: Protocol<V>>(protocol: &P, swarm: &Swarm<V>) -> Vec<V> {
    let net = ProximityNet::brute_force(&swarm.positions, protocol.interaction_range());
    let mut u = vec![V::ZERO; swarm.len()];
    protocol.controls(0.0, swarm, &net, &mut u);
    u
}

fn total<V: Vector>(vectors: &[V]) -> V {
    vectors.iter().fold(V::ZERO, |acc, &v| acc + v)
}

/// Σ_i u_i = 0: the pair terms of i and j are exact negatives (the same operations on negated
/// differences), so only the summations err: ‖Σ u_i‖ ≤ (n + max degree + 2) u √m Σ_i S_i.
fn check_momentum<V: Vector>(case: &Case) -> Result<(), TestCaseError> {
    let swarm: Swarm<V> = case.swarm();
    let u = controls(&case.protocol(), &swarm);
    let (max_degree, scale) = case.degree_and_scale(&swarm);
    let k = (swarm.len() + max_degree + 2) as f64;
    let tolerance = k * U * (V::DIM as f64).sqrt() * scale;
    let sum = total(&u).length();
    prop_assert!(
        sum <= tolerance,
        "‖Σu‖ = {sum:e} > {tolerance:e} (Σ S_i = {scale:e})"
    );
    Ok(())
}

/// Σ_i p_i after k steps of symplectic Euler equals Σ_i p_i(0): each step adds h Σ u_i (bounded as
/// in [`check_momentum`]) and rounds p_i + h u_i (by u ‖p_i + h u_i‖ per agent and component);
/// measuring Σ p_i at both ends errs by n u √m Σ ‖p_i‖. So
/// ‖ΔP‖ ≤ Σ_steps (n + max degree + 3) u √m (h Σ_i S_i + Σ_i ‖p_i‖) + n u √m (Σ‖p_i(0)‖ + Σ‖p_i(T)‖).
fn check_momentum_along_a_run<V: Vector>(case: &Case, steps: usize) -> Result<(), TestCaseError> {
    let swarm: Swarm<V> = case.swarm();
    let n = swarm.len();
    let root_m = (V::DIM as f64).sqrt();
    let h = 0.01;
    let speeds = |s: &Swarm<V>| s.velocities.iter().map(|p| p.length()).sum::<f64>();
    let start = total(&swarm.velocities);
    let mut tolerance = n as f64 * U * root_m * speeds(&swarm);
    let mut sim = Simulation::new(case.protocol(), Integrator::SymplecticEuler, swarm, h)
        .expect("a valid simulation");
    for _ in 0..steps {
        let (max_degree, scale) = case.degree_and_scale(&sim.swarm());
        sim.step();
        let k = (n + max_degree + 3) as f64;
        tolerance += k * U * root_m * (h * scale + speeds(&sim.swarm()));
    }
    tolerance += n as f64 * U * root_m * speeds(&sim.swarm());
    let drift = (total(&sim.swarm().velocities) - start).length();
    prop_assert!(
        drift <= tolerance,
        "momentum drifted by {drift:e} > {tolerance:e} in {steps} steps"
    );
    Ok(())
}

/// u is unchanged when every q_i moves by `shift`: the relative positions move by at most
/// δq = 4u (max‖q_i‖ + ‖shift‖ + r) (rounding q_i + shift and the differences).
fn check_translation<V: Vector>(case: &Case, shift: V) -> Result<(), TestCaseError> {
    let swarm: Swarm<V> = case.swarm();
    let moved = Swarm::new(
        swarm.positions.iter().map(|&q| q + shift).collect(),
        swarm.velocities.clone(),
    );
    let protocol = case.protocol();
    let (u, u_moved) = (controls(&protocol, &swarm), controls(&protocol, &moved));
    let largest = swarm
        .positions
        .iter()
        .map(|q| q.length())
        .fold(0.0, f64::max);
    let delta_q = 4.0 * U * (largest + shift.length() + case.params.r);
    let bounds = case.perturbation_bounds(&swarm, delta_q, 0.0);
    for (i, ((a, b), bound)) in u.iter().zip(&u_moved).zip(bounds).enumerate() {
        let error = (*a - *b).length();
        prop_assert!(
            error <= bound,
            "agent {i}: ‖u − u_shifted‖ = {error:e} > {bound:e}"
        );
    }
    Ok(())
}

/// u turns with the swarm: u(Rq, Rp) = R u(q, p), for a rotation `rotate` accurate to 16u relative
/// (a few products and sums per coordinate, and a unit quaternion or angle rounded). The relative
/// positions move by δq = 2 · 16u max‖q_i‖ + 4u r, the velocities by δp = 16u max‖p_i‖, and R u_i
/// itself errs by 16u ‖u_i‖.
fn check_rotation<V: Vector>(case: &Case, rotate: impl Fn(V) -> V) -> Result<(), TestCaseError> {
    let swarm: Swarm<V> = case.swarm();
    let turned = Swarm::new(
        swarm.positions.iter().map(|&q| rotate(q)).collect(),
        swarm.velocities.iter().map(|&p| rotate(p)).collect(),
    );
    let protocol = case.protocol();
    let (u, u_turned) = (controls(&protocol, &swarm), controls(&protocol, &turned));
    let largest = |v: &[V]| v.iter().map(|x| x.length()).fold(0.0, f64::max);
    let delta_q = 32.0 * U * largest(&swarm.positions) + 4.0 * U * case.params.r;
    let delta_p = 16.0 * U * largest(&swarm.velocities);
    let bounds = case.perturbation_bounds(&swarm, delta_q, delta_p);
    for (i, ((a, b), bound)) in u.iter().zip(&u_turned).zip(bounds).enumerate() {
        let bound = bound + 16.0 * U * a.length();
        let error = (rotate(*a) - *b).length();
        prop_assert!(
            error <= bound,
            "agent {i}: ‖R u − u_R‖ = {error:e} > {bound:e}"
        );
    }
    Ok(())
}

/// Relabelling the agents relabels u: the pair terms are the same bits, only the order in which
/// each u_i sums them changes, so ‖u_{π(k)} − u′_k‖ ≤ 2 (degree + 2) u √m S_i.
fn check_permutation<V: Vector>(case: &Case, order: &[usize]) -> Result<(), TestCaseError> {
    let swarm: Swarm<V> = case.swarm();
    let shuffled = Swarm::new(
        order.iter().map(|&i| swarm.positions[i]).collect(),
        order.iter().map(|&i| swarm.velocities[i]).collect(),
    );
    let protocol = case.protocol();
    let (u, u_shuffled) = (controls(&protocol, &swarm), controls(&protocol, &shuffled));
    let sizes = case.sizes(&swarm, case.params.r);
    let root_m = (V::DIM as f64).sqrt();
    for (k, &i) in order.iter().enumerate() {
        let (degree, scale, _) = sizes[i];
        let bound = 2.0 * (degree + 2) as f64 * U * root_m * scale;
        let error = (u[i] - u_shuffled[k]).length();
        prop_assert!(
            error <= bound,
            "agent {i} (now {k}): ‖u_i − u′_k‖ = {error:e} > {bound:e}"
        );
    }
    Ok(())
}

/// A case with a random relabelling of its agents.
fn case_and_order() -> impl Strategy<Value = (Case, Vec<usize>)> {
    case().prop_flat_map(|case| {
        let order: Vec<usize> = (0..case.positions.len()).collect();
        (Just(case), Just(order).prop_shuffle())
    })
}

/// A uniformly distributed 3D rotation: a normalised quaternion from the unit 4-ball.
fn quaternion() -> impl Strategy<Value = DQuat> {
    prop::array::uniform4(-1.0..1.0f64)
        .prop_filter("a quaternion away from zero", |x| {
            let norm2: f64 = x.iter().map(|c| c * c).sum();
            (0.01..=1.0).contains(&norm2)
        })
        .prop_map(|[x, y, z, w]| DQuat::from_xyzw(x, y, z, w).normalize())
}

fn shift<V: Vector>(raw: [f64; 3], size: f64) -> V {
    V::from_fn(|k| raw[k] * size)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn algorithm1_inputs_sum_to_zero_2d(case in case()) {
        check_momentum::<DVec2>(&case)?;
    }

    #[test]
    fn algorithm1_inputs_sum_to_zero_3d(case in case()) {
        check_momentum::<DVec3>(&case)?;
    }

    #[test]
    fn algorithm1_preserves_momentum_along_a_run_2d(case in case(), steps in 1usize..20) {
        check_momentum_along_a_run::<DVec2>(&case, steps)?;
    }

    #[test]
    fn algorithm1_preserves_momentum_along_a_run_3d(case in case(), steps in 1usize..20) {
        check_momentum_along_a_run::<DVec3>(&case, steps)?;
    }

    #[test]
    fn algorithm1_is_translation_invariant_2d(
        case in case(),
        raw in prop::array::uniform3(-1.0..1.0f64),
        size in prop_oneof![Just(1.0), Just(1e3), Just(1e6)],
    ) {
        check_translation::<DVec2>(&case, shift(raw, size))?;
    }

    #[test]
    fn algorithm1_is_translation_invariant_3d(
        case in case(),
        raw in prop::array::uniform3(-1.0..1.0f64),
        size in prop_oneof![Just(1.0), Just(1e3), Just(1e6)],
    ) {
        check_translation::<DVec3>(&case, shift(raw, size))?;
    }

    #[test]
    fn algorithm1_is_rotation_equivariant_2d(
        case in case(),
        angle in -core::f64::consts::PI..core::f64::consts::PI,
    ) {
        let rotation = DMat2::from_angle(angle);
        check_rotation::<DVec2>(&case, |v| rotation * v)?;
    }

    #[test]
    fn algorithm1_is_rotation_equivariant_3d(case in case(), rotation in quaternion()) {
        check_rotation::<DVec3>(&case, |v| rotation * v)?;
    }

    #[test]
    fn algorithm1_is_permutation_equivariant_2d((case, order) in case_and_order()) {
        check_permutation::<DVec2>(&case, &order)?;
    }

    #[test]
    fn algorithm1_is_permutation_equivariant_3d((case, order) in case_and_order()) {
        check_permutation::<DVec3>(&case, &order)?;
    }
}

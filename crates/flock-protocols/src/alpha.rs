//! The α-α interaction of TAC 2006: gradient-based term and velocity consensus (eq. 23–24).

use flock_graph::ProximityNet;
use flock_math::{Bump, BumpedAction, Potential, SigmaNorm, UnevenSigmoid, Vector};

/// Agents per chunk of the sum in [`AlphaInteraction::potential`].
const POTENTIAL_CHUNK: usize = 4096;

/// Parameters of the α-interaction, with the papers' values as [`Default`]:
/// d = 7, r = 1.2 d, ε = 0.1, a = b = 5, h = 0.2 (TAC 2006, Section VIII).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaParams {
    /// Desired inter-agent distance d (the lattice scale).
    pub d: f64,
    /// Interaction range r > d.
    pub r: f64,
    /// σ-norm parameter ε > 0.
    pub epsilon: f64,
    /// Attraction bound a of the uneven sigmoid, 0 < a ≤ b.
    pub a: f64,
    /// Repulsion bound b of the uneven sigmoid.
    pub b: f64,
    /// Flat part h ∈ (0, 1) of the bump ρ_h in φ_α and in the adjacency.
    pub h: f64,
}

impl Default for AlphaParams {
    fn default() -> Self {
        Self {
            d: 7.0,
            r: 8.4,
            epsilon: 0.1,
            a: 5.0,
            b: 5.0,
            h: 0.2,
        }
    }
}

/// u_i^α = c₁ Σ_{j∈N_i} φ_α(‖q_j − q_i‖_σ) n_ij + c₂ Σ_{j∈N_i} a_ij(q)(p_j − p_i),
/// n_ij = σ_ε(q_j − q_i), a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) (TAC 2006 eq. 23; Algorithm 3's u^α with
/// gains c₁^α, c₂^α; c₁ = c₂ = 1 gives Algorithm 1 exactly).
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaInteraction {
    params: AlphaParams,
    sigma: SigmaNorm,
    action: BumpedAction,
    c1: f64,
    c2: f64,
}

impl AlphaInteraction {
    /// The interaction with gains c₁ (gradient) and c₂ (consensus).
    #[must_use]
    pub fn new(params: AlphaParams, c1: f64, c2: f64) -> Self {
        let sigma = SigmaNorm::new(params.epsilon);
        let action = BumpedAction::alpha(
            UnevenSigmoid::new(params.a, params.b),
            Bump::tac(params.h),
            sigma.of_length(params.d),
            sigma.of_length(params.r),
        );
        Self {
            params,
            sigma,
            action,
            c1,
            c2,
        }
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &AlphaParams {
        &self.params
    }

    /// The action function φ_α and its potential ψ_α.
    #[must_use]
    pub const fn action(&self) -> &BumpedAction {
        &self.action
    }

    /// The gradient gain c₁^α.
    #[must_use]
    pub const fn c1(&self) -> f64 {
        self.c1
    }

    /// u_i^α for agent `i`; the σ-norm, n_ij and a_ij of each pair share one square root and one cosine.
    #[must_use]
    pub fn input<V: Vector>(&self, i: usize, q: &[V], p: &[V], net: &ProximityNet) -> V {
        let (qi, pi) = (q[i], p[i]);
        let mut gradient = V::ZERO;
        let mut consensus = V::ZERO;
        for &j in net.graph().neighbours(i) {
            let j = j as usize;
            let dq = q[j] - qi;
            let (z, scale) = self.sigma.norm_and_gradient_scale(dq.length_squared());
            let (phi, a_ij) = self.action.action_and_bump(z);
            gradient += dq * (phi * scale);
            consensus += (p[j] - pi) * a_ij;
        }
        gradient * self.c1 + consensus * self.c2
    }

    /// The collective potential V(q) = ½ Σ_i Σ_{j≠i} ψ_α(‖q_j − q_i‖_σ) (TAC 2006 eq. 20), shifted by
    /// the constant of a fully dispersed group so that it is O(|E|): pairs out of range contribute
    /// ψ_α(r_α) each, and we sum ψ_α(z) − ψ_α(r_α) over the net's edges only. Gradients and Ḣ are
    /// unchanged; V = 0 when no two agents interact.
    #[must_use]
    pub fn potential<V: Vector>(&self, q: &[V], net: &ProximityNet) -> f64 {
        let far = self.action.potential(self.action.range());
        let graph = net.graph();
        // Running sums over chunks of POTENTIAL_CHUNK agents (in parallel with the `parallel`
        // feature), added in chunk order: the same value for any thread count, and the plain
        // running sum over the edges when there is a single chunk.
        let chunk_sum = |chunk: usize| {
            let agents = chunk * POTENTIAL_CHUNK..((chunk + 1) * POTENTIAL_CHUNK).min(graph.len());
            let mut total = 0.0;
            for i in agents {
                for &j in graph.neighbours(i) {
                    let j = j as usize;
                    if j > i {
                        let z = self.sigma.norm(q[j] - q[i]);
                        total += self.action.potential(z) - far;
                    }
                }
            }
            total
        };
        let chunks = graph.len().div_ceil(POTENTIAL_CHUNK);
        #[cfg(feature = "parallel")]
        let sums: Vec<f64> = {
            use rayon::prelude::*;
            (0..chunks).into_par_iter().map(chunk_sum).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let sums: Vec<f64> = (0..chunks).map(chunk_sum).collect();
        match sums.split_first() {
            Some((&first, rest)) => rest.iter().fold(first, |total, &s| total + s),
            None => 0.0,
        }
    }
}

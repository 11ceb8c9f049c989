//! The α-β interaction of TAC 2006 Algorithm 3: repulsion from β-agents on obstacles and damping
//! towards their velocities (eq. 67, u_i^β).

use flock_graph::Numbering;
use flock_math::{Bump, BumpedAction, Potential, SigmaNorm};
use flock_obstacles::{BetaAgent, ObstacleField, Space};

/// Parameters of the β-interaction, with the papers' values relative to the lattice distance d:
/// d′ = 0.6 d, r′ = 1.2 d′, h = 0.9 (TAC 2006, Section VIII).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BetaParams {
    /// Desired distance d′ > 0 to obstacles.
    pub d: f64,
    /// Range r′ > d′ within which an obstacle's β-agent is a neighbour.
    pub r: f64,
    /// Flat part h ∈ (0, 1) of the bump in φ_β and b_ik.
    pub h: f64,
}

impl BetaParams {
    /// The papers' choice for lattice distance `d`: d′ = 0.6 d, r′ = 1.2 d′, h = 0.9.
    #[must_use]
    pub fn papers(d: f64) -> Self {
        Self {
            d: 0.6 * d,
            r: 0.72 * d,
            h: 0.9,
        }
    }
}

/// u_i^β = c₁^β Σ_{k∈N_i^β} φ_β(‖q̂_ik − q_i‖_σ) n̂_ik + c₂^β Σ_{k∈N_i^β} b_ik(q)(p̂_ik − p_i),
/// n̂_ik = σ_ε(q̂_ik − q_i), b_ik = ρ_h(‖q̂_ik − q_i‖_σ / d_β), N_i^β = { k : ‖q̂_ik − q_i‖ < r′ }
/// (TAC 2006 eq. 67), over every convex obstacle of an [`ObstacleField`].
#[derive(Clone, Debug)]
pub struct BetaInteraction<V: Space> {
    field: ObstacleField<V>,
    params: BetaParams,
    sigma: SigmaNorm,
    action: BumpedAction,
    c1: f64,
    c2: f64,
}

impl<V: Space> BetaInteraction<V> {
    /// The interaction with the obstacles of `field`, σ-norm parameter `epsilon` and gains c₁^β, c₂^β.
    #[must_use]
    pub fn new(
        field: ObstacleField<V>,
        params: BetaParams,
        epsilon: f64,
        c1: f64,
        c2: f64,
    ) -> Self {
        let sigma = SigmaNorm::new(epsilon);
        let action = BumpedAction::beta(Bump::tac(params.h), sigma.of_length(params.d));
        Self {
            field,
            params,
            sigma,
            action,
            c1,
            c2,
        }
    }

    /// The obstacles.
    #[must_use]
    pub const fn field(&self) -> &ObstacleField<V> {
        &self.field
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &BetaParams {
        &self.params
    }

    /// The β-neighbours of an α-agent at (q, p): (obstacle index, β-agent), in obstacle order.
    #[must_use]
    pub fn neighbours(&self, q: V, p: V) -> Vec<(usize, BetaAgent<V>)> {
        let mut out = Vec::new();
        self.field.beta_agents(q, p, self.params.r, &mut out);
        out
    }

    /// u_i^β for an α-agent at (q, p).
    #[must_use]
    pub fn input(&self, q: V, p: V) -> V {
        let mut gradient = V::ZERO;
        let mut damping = V::ZERO;
        self.field
            .for_each_beta_agent(q, p, self.params.r, |_, beta| {
                let dq = beta.position - q;
                let (z, scale) = self.sigma.norm_and_gradient_scale(dq.length_squared());
                let (phi, b_ik) = self.action.action_and_bump(z);
                gradient += dq * (phi * scale);
                damping += (beta.velocity - p) * b_ik;
            });
        gradient * self.c1 + damping * self.c2
    }

    /// c₁^β V_β(q) with V_β = Σ_i Σ_{k∈N_i^β} ψ_β(‖q̂_ik − q_i‖_σ) (TAC 2006 eq. 70), the agents' sums
    /// added in ascending original index of `numbering` ([`Numbering::ordered_sum`]: in parallel
    /// with the `parallel` feature; the same bits for any thread count and any storage order).
    #[must_use]
    pub fn potential(&self, q: &[V], numbering: &Numbering) -> f64 {
        let total = numbering.ordered_sum(q.len(), |i| {
            let qi = q[i];
            let mut total = 0.0;
            self.field
                .for_each_beta_agent(qi, V::ZERO, self.params.r, |_, beta| {
                    total += self.action.potential(self.sigma.norm(beta.position - qi));
                });
            total
        });
        self.c1 * total
    }
}

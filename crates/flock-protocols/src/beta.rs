//! The α-β interaction of TAC 2006 Algorithm 3: repulsion from β-agents on obstacles and damping
//! towards their velocities (eq. 67, u_i^β).

use flock_graph::Numbering;
use flock_math::{Bump, BumpedAction, Potential, SigmaNorm};
use flock_obstacles::{BetaAgent, ObstacleField, Space};

use crate::critical_damping;
use crate::error::{ParamError, check};

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
    /// The papers' flat part h = 0.9 of the bump of φ_β.
    pub const PAPERS_H: f64 = 0.9;

    /// The papers' choice for lattice distance `d`: d′ = 0.6 d, r′ = 1.2 d′, h = 0.9.
    #[must_use]
    pub fn papers(d: f64) -> Self {
        let distance = Self::distance_for(d);
        Self {
            d: distance,
            r: Self::range_for(distance),
            h: Self::PAPERS_H,
        }
    }

    /// The papers' obstacle distance d′ = 0.6 d for lattice distance `d`.
    #[must_use]
    pub fn distance_for(d: f64) -> f64 {
        0.6 * d
    }

    /// The papers' β-range r′ = 1.2 d′ for obstacle distance `d_beta`.
    #[must_use]
    pub fn range_for(d_beta: f64) -> f64 {
        1.2 * d_beta
    }

    /// Checks 0 < d′ < r′ and h ∈ (0, 1).
    ///
    /// # Errors
    /// The first parameter outside its domain, named by its field (`d`, `r`, `h`).
    pub fn validate(&self) -> Result<(), ParamError> {
        check::positive("d", self.d)?;
        check::finite("r", self.r)?;
        check::require(
            self.r > self.d,
            "r",
            self.r,
            &format!(
                "must exceed the obstacle distance d′ = {} (0 < d′ < r′)",
                self.d
            ),
            "raise r (the papers use r′ = 1.2 d′) or lower d",
        )?;
        check::unit_interval("h", self.h)
    }
}

/// Algorithm 3's β-interaction as a scenario writes it: distances relative to the lattice
/// distance d by default (d′ = 0.6 d, r′ = 1.2 d′, [`BetaParams::papers`]), h = 0.9, and the gains
/// c₁^β (default 10) and c₂^β (default 2√c₁^β, [`critical_damping`]).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct BetaConfig {
    /// Desired distance d′ to obstacles; default 0.6 d.
    pub d: Option<f64>,
    /// β-neighbour range r′ > d′; default 1.2 d′.
    pub r: Option<f64>,
    /// Bump parameter h ∈ (0, 1) of φ_β and b_ik.
    pub h: f64,
    /// Repulsion gain c₁^β > 0.
    pub c1: f64,
    /// Damping gain c₂^β ≥ 0; default 2√c₁^β.
    pub c2: Option<f64>,
}

impl Default for BetaConfig {
    fn default() -> Self {
        Self {
            d: None,
            r: None,
            h: BetaParams::PAPERS_H,
            c1: 10.0,
            c2: None,
        }
    }
}

impl BetaConfig {
    /// d′ for lattice distance `d` (default 0.6 d).
    #[must_use]
    pub fn distance(&self, d: f64) -> f64 {
        self.d.unwrap_or_else(|| BetaParams::distance_for(d))
    }

    /// r′ for lattice distance `d` (default 1.2 d′).
    #[must_use]
    pub fn range(&self, d: f64) -> f64 {
        self.r
            .unwrap_or_else(|| BetaParams::range_for(self.distance(d)))
    }

    /// c₂^β (default 2√c₁^β).
    #[must_use]
    pub fn damping(&self) -> f64 {
        self.c2.unwrap_or_else(|| critical_damping(self.c1))
    }

    /// The parameters for lattice distance `d`.
    #[must_use]
    pub fn params(&self, d: f64) -> BetaParams {
        BetaParams {
            d: self.distance(d),
            r: self.range(d),
            h: self.h,
        }
    }

    /// The configuration with every default written out for lattice distance `d`.
    #[must_use]
    pub fn resolved(&self, d: f64) -> Self {
        Self {
            d: Some(self.distance(d)),
            r: Some(self.range(d)),
            c2: Some(self.damping()),
            ..*self
        }
    }

    /// Checks the parameters for lattice distance `d` ([`BetaParams::validate`]) and the gains
    /// c₁^β > 0, c₂^β ≥ 0.
    ///
    /// # Errors
    /// The first value outside its domain, named by its field.
    pub fn validate(&self, d: f64) -> Result<(), ParamError> {
        if let Some(d_beta) = self.d {
            check::positive("d", d_beta)?;
        }
        self.params(d).validate()?;
        check::positive("c1", self.c1)?;
        check::non_negative("c2", self.damping())
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
    ///
    /// # Errors
    /// Parameters outside their domain ([`BetaParams::validate`]), ε not positive, c₁^β ≤ 0 or
    /// c₂^β < 0.
    pub fn new(
        field: ObstacleField<V>,
        params: BetaParams,
        epsilon: f64,
        c1: f64,
        c2: f64,
    ) -> Result<Self, ParamError> {
        params.validate()?;
        check::positive("epsilon", epsilon)?;
        check::positive("c1", c1)?;
        check::non_negative("c2", c2)?;
        let sigma = SigmaNorm::new(epsilon);
        let action = BumpedAction::beta(Bump::tac(params.h), sigma.of_length(params.d));
        Ok(Self {
            field,
            params,
            sigma,
            action,
            c1,
            c2,
        })
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

//! The (α, α) protocols, the sink (translational) controller and the obstacle protocol of
//! Olfati-Saber, *Flocking with Obstacle Avoidance*, Caltech CDS technical report 03-006 (2003; seed
//! 004), as condensed in Olfati-Saber & Murray, CDC 2003 (seed 003) and Olfati-Saber, ACC 2004
//! (seed 000).
//!
//! Unlike TAC 2006, these protocols work with Euclidean distances: the pair potential is
//! ψ_α(‖q_j − q_i‖ − d_α) with the uneven sigmoid pair of eq. 29 ([`UnevenSigmoid`]), and the
//! smooth adjacency is a_ij = ρ(‖q_j − q_i‖ / r) with the influence map ρ of ACC 2004 eq. 4
//! ([`Bump::influence_map`]).
//!
//! - [`AlphaAlpha`]: the (α, α, 1) protocol (eq. 34), the (α, α, 2) protocol (eq. 35) and its
//!   approximation (eq. 36), one type with an [`AlphaAlphaForm`]; energy H_s = V + K_r (eq. 27–30).
//! - [`Flocking2003`]: an (α, α) protocol plus the translational PD controller of eq. 50 (seed 000
//!   eq. 40), the sink, reusing [`NavigationalFeedback`]; the flocking separation principle.
//! - [`ObstacleFlocking2003`]: eq. 58, the above plus β- and γ-agents on balls (eq. 53–57).
//! - [`influence_map_lipschitz`]: L_ρ = max |ρ′|, the constant of the error bound of eq. 37.

use core::f64::consts::PI;

use flock_graph::ProximityNet;
use flock_math::{Bump, Potential, UnevenSigmoid, Vector, mean};
use flock_metrics::DefectFactor;
#[cfg(feature = "obstacles")]
use flock_metrics::ObstacleMetrics;
#[cfg(feature = "obstacles")]
use flock_obstacles::{BetaAgent, Obstacle, ObstacleError, Space};

use crate::error::{ParamError, check};
use crate::{LocalForm, NavigationalFeedback, Perceived, Protocol, Swarm};
use flock_math::parallel::fill_interruptible;

/// Parameters of the 2003 (α, α) protocols.
///
/// [`Default`]: the simulations of seed 004 (§ 11, Fig. 7–9) and seed 000 (§ 5): d_α = 7,
/// r = 1.2 d_α; the action function of seed 004 Fig. 4 (a = 1, b = 5); and the influence map with
/// flat part k₀ = d_α / r (seed 004 § 3 sets k₀ = d_α / r for a structural net (d_α, r); its Fig. 2
/// example k₀ = 5/6, r = 12 is that ratio for d_α = 10) and power k = 1 (C¹, the least smoothness
/// that makes the force of eq. 35 continuous).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaAlphaParams {
    /// The desired inter-agent distance d_α, 0 < d_α < r.
    pub d_alpha: f64,
    /// The interaction range r: N_i = { j : ‖q_j − q_i‖ < r }.
    pub r: f64,
    /// The attraction bound a of φ_α (φ_α → a as z → ∞), 0 < a ≤ b.
    pub a: f64,
    /// The repulsion bound b of φ_α (φ_α → −b as z → −∞).
    pub b: f64,
    /// The influence map ρ of the smooth adjacency a_ij = ρ(‖q_j − q_i‖ / r) (seed 000 eq. 4).
    pub bump: Bump,
}

impl AlphaAlphaParams {
    /// d_α, r, a, b with the influence map of flat part k₀ = d_α / r and power 1.
    #[must_use]
    pub const fn new(d_alpha: f64, r: f64, a: f64, b: f64) -> Self {
        Self {
            d_alpha,
            r,
            a,
            b,
            bump: Bump::influence_map(d_alpha / r, 1),
        }
    }
}

impl Default for AlphaAlphaParams {
    fn default() -> Self {
        Self::new(7.0, 8.4, 1.0, 5.0)
    }
}

/// Which of the three 2003 (α, α) protocols: they differ only in the scalar g(‖q_j − q_i‖) that
/// multiplies n_ij = (q_j − q_i)/‖q_j − q_i‖ in the gradient term (z = ‖q_j − q_i‖ − d_α).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AlphaAlphaForm {
    /// (α, α, 1), seed 004 eq. 34: 0/1 adjacency, g = φ_α(z). Its energy (eq. 28/60) jumps by
    /// h₀ = ψ_α(r − d_α) when a link is made or lost (eq. 31); between switches it does not rise
    /// (Proposition 4).
    Nonsmooth,
    /// (α, α, 2), seed 004 eq. 35: g = a_ij φ_α(z) + (1/r) ρ′(‖q_j − q_i‖/r) ψ_α(z), the exact
    /// −∇V of the smooth potential of eq. 30 (seed 003 eq. 15, seed 000 eq. 23 write the same
    /// bracket as the derivative of ρ((z + d_α)/r) ψ_α(z)). H_s does not rise (Proposition 5).
    #[default]
    Smooth,
    /// The approximation of (α, α, 2), seed 004 eq. 36: g = a_ij φ_α(z), dropping the ρ′ term,
    /// within the bound of eq. 37 of it ([`AlphaAlpha::approximation_error_bound`]).
    Approximate,
}

/// The 2003 (α, α) protocol (seed 004 eq. 34–36; seed 003 eq. 14; seed 000 eq. 22):
///
/// u_i = Σ_{j∈N_i} g(‖q_j − q_i‖) n_ij + c₁ (p_j − p_i),  n_ij = (q_j − q_i)/‖q_j − q_i‖,
///
/// with g given by the [`AlphaAlphaForm`] and the consensus term unweighted over the net N_i, as
/// all three equations write it (seed 000 eq. 9: the ceiling Ā = ⌈A⌉ of the smooth adjacency).
/// Pair forces are antisymmetric, so Σ_i u_i = 0 (seed 004 § 10).
///
/// Its [`Protocol::energy`] is the structural energy H_s = V(q) + K_r(p̃) (eq. 27), K_r =
/// ½ Σ ‖p_i − p̄‖², V from [`AlphaAlpha::potential`].
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaAlpha {
    params: AlphaAlphaParams,
    form: AlphaAlphaForm,
    sigmoid: UnevenSigmoid,
    c1: f64,
}

impl AlphaAlpha {
    /// The protocol of the given form with consensus gain c₁ > 0 (c_d of seeds 000 and 003).
    #[must_use]
    pub fn new(params: AlphaAlphaParams, form: AlphaAlphaForm, c1: f64) -> Self {
        Self {
            params,
            form,
            sigmoid: UnevenSigmoid::new(params.a, params.b),
            c1,
        }
    }

    /// The parameters.
    #[must_use]
    pub const fn params(&self) -> &AlphaAlphaParams {
        &self.params
    }

    /// The form: (α, α, 1), (α, α, 2) or its approximation.
    #[must_use]
    pub const fn form(&self) -> AlphaAlphaForm {
        self.form
    }

    /// The consensus gain c₁.
    #[must_use]
    pub const fn consensus_gain(&self) -> f64 {
        self.c1
    }

    /// The pair (φ_α, ψ_α) of eq. 29.
    #[must_use]
    pub const fn sigmoid(&self) -> &UnevenSigmoid {
        &self.sigmoid
    }

    /// The adjacency a_ij of a pair at distance `distance`: 1 within r for (α, α, 1) (eq. 8),
    /// ρ(distance / r) for the smooth forms (eq. 17).
    #[must_use]
    pub fn adjacency(&self, distance: f64) -> f64 {
        match self.form {
            AlphaAlphaForm::Nonsmooth => {
                if distance < self.params.r {
                    1.0
                } else {
                    0.0
                }
            }
            AlphaAlphaForm::Smooth | AlphaAlphaForm::Approximate => {
                self.params.bump.value(distance / self.params.r)
            }
        }
    }

    /// The gradient coefficient g(‖q_j − q_i‖) of the form (see [`AlphaAlphaForm`]): the gradient
    /// term of u_i is Σ_j g n_ij. Divided by the distance it is the stress weight s_ij of seed 000
    /// eq. 26 / seed 003 eq. 16.
    #[must_use]
    pub fn pair_action(&self, distance: f64) -> f64 {
        let z = distance - self.params.d_alpha;
        let phi = self.sigmoid.action(z);
        match self.form {
            AlphaAlphaForm::Nonsmooth => phi,
            AlphaAlphaForm::Approximate => self.adjacency(distance) * phi,
            AlphaAlphaForm::Smooth => self.adjacency(distance) * phi + self.correction(distance),
        }
    }

    /// The term (1/r) ρ′(‖q_j − q_i‖/r) ψ_α(‖q_j − q_i‖ − d_α) by which eq. 35 differs from eq. 36.
    #[must_use]
    pub fn correction(&self, distance: f64) -> f64 {
        let r = self.params.r;
        self.params.bump.derivative(distance / r)
            * self.sigmoid.potential(distance - self.params.d_alpha)
            / r
    }

    /// The pair potential of the form: a_ij ψ_α(‖q_j − q_i‖ − d_α).
    #[must_use]
    pub fn pair_potential(&self, distance: f64) -> f64 {
        self.adjacency(distance) * self.sigmoid.potential(distance - self.params.d_alpha)
    }

    /// u_i for agent `i` (eq. 34, 35 or 36), from the net's edge lengths.
    #[must_use]
    pub fn input<V: Vector>(&self, i: usize, q: &[V], p: &[V], net: &ProximityNet) -> V {
        let graph = net.graph();
        let distances = &net.distances()[graph.edge_range(i)];
        let neighbours = graph.neighbours(i).iter().map(|&j| j as usize);
        let others = neighbours.zip(distances).map(|(j, &d)| (q[j], p[j], d));
        self.sum(q[i], p[i], others)
    }

    /// u_i (eq. 34, 35 or 36) of an agent perceiving itself at `own` = (q_i, p_i) and the states
    /// `others` = (q_j, p_j), in their order: those within r by their perceived distance
    /// √‖q_j − q_i‖² (the net's predicate and edge length, so with the exact states of its
    /// neighbours in list order, the bits of [`AlphaAlpha::input`]).
    #[must_use]
    pub fn local_input<V: Vector>(&self, own: &Perceived<V>, others: &[Perceived<V>]) -> V {
        let (qi, pi) = (own.position, own.velocity);
        self.sum(qi, pi, self.within_range(qi, others))
    }

    /// The perceived states (q_j, p_j, ‖q_j − q_i‖) of `others` within r of `qi`, in their order,
    /// by the net's predicate ‖q_j − q_i‖² < r² and its edge length √‖q_j − q_i‖².
    pub(crate) fn within_range<'a, V: Vector>(
        &self,
        qi: V,
        others: &'a [Perceived<V>],
    ) -> impl Iterator<Item = (V, V, f64)> + 'a {
        let r2 = self.params.r * self.params.r;
        others.iter().filter_map(move |o| {
            let d2 = (o.position - qi).length_squared();
            (d2 < r2).then(|| (o.position, o.velocity, d2.sqrt()))
        })
    }

    /// Σ_j g(‖q_j − q_i‖) n_ij + c₁ Σ_j (p_j − p_i) over `others` = (q_j, p_j, ‖q_j − q_i‖), in
    /// their order: the one sum of [`AlphaAlpha::input`] and [`AlphaAlpha::local_input`].
    #[inline]
    fn sum<V: Vector>(&self, qi: V, pi: V, others: impl Iterator<Item = (V, V, f64)>) -> V {
        let mut gradient = V::ZERO;
        let mut consensus = V::ZERO;
        for (qj, pj, distance) in others {
            // n(z) = z/‖z‖ for z ≠ 0 (seed 004 eq. 54); coincident agents exert no gradient force
            if distance > 0.0 {
                gradient += (qj - qi) * (self.pair_action(distance) / distance);
            }
            consensus += pj - pi;
        }
        gradient + consensus * self.c1
    }

    /// The potential V(q) of the form, from the net's edge lengths, each pair counted once:
    /// V = ½ Σ_i Σ_{j∈N_i} a_ij ψ_α(‖q_j − q_i‖ − d_α) = Σ_{i<j} a_ij ψ_α (seed 004 eq. 28 and 30).
    ///
    /// For (α, α, 1) a_ij = 1 on the net (eq. 28, 60); for the smooth forms a_ij = ρ(‖q_j − q_i‖/r)
    /// (eq. 30), whose exact negative gradient is the gradient term of eq. 35. Seed 000 eq. 6/19 and
    /// seed 003 eq. 8 write V without the ½ (each pair twice), which would make eq. 35 −½∇V; the
    /// 2003 report's ½ is the one for which eq. 35 is −∇V.
    #[must_use]
    pub fn potential(&self, net: &ProximityNet) -> f64 {
        half_edge_sum(net, |distance| self.pair_potential(distance))
    }

    /// The defect factor of this form's potential (seed 004 eq. 46–47): the smooth adjacency of
    /// eq. 30 for (α, α, 2) and its approximation, the 0/1 adjacency of eq. 28 for (α, α, 1).
    #[must_use]
    pub fn defect_factor(&self) -> DefectFactor {
        let AlphaAlphaParams {
            d_alpha, r, a, b, ..
        } = self.params;
        let adjacency = match self.form {
            AlphaAlphaForm::Nonsmooth => None,
            AlphaAlphaForm::Smooth | AlphaAlphaForm::Approximate => Some(self.params.bump),
        };
        DefectFactor::new(d_alpha, r, a, b, adjacency)
    }

    /// The potential of eq. 28 with the 0/1 adjacency of the net whatever the form:
    /// ½ Σ_i Σ_{j∈N_i} ψ_α(‖q_j − q_i‖ − d_α), the V(q) of the error bound of eq. 37.
    #[must_use]
    pub fn binary_potential(&self, net: &ProximityNet) -> f64 {
        half_edge_sum(net, |distance| {
            self.sigmoid.potential(distance - self.params.d_alpha)
        })
    }

    /// The bound of seed 004 eq. 37 on Σ_i ‖u_i^(α,α,2) − û_i^(α,α,2)‖: (2 L_ρ / r) V(q), with V
    /// the potential of eq. 28 ([`AlphaAlpha::binary_potential`]) and L_ρ = max |ρ′|
    /// ([`influence_map_lipschitz`]).
    ///
    /// It holds because each term of the difference is (1/r) |ρ′| ψ_α ≤ (L_ρ / r) ψ_α and
    /// Σ_i Σ_{j∈N_i} ψ_α = 2V. With the smooth V of eq. 30 instead it would fail near the edge of
    /// the range, where a_ij → 0 faster than ρ′.
    #[must_use]
    pub fn approximation_error_bound(&self, net: &ProximityNet) -> f64 {
        2.0 * influence_map_lipschitz(self.params.bump) / self.params.r * self.binary_potential(net)
    }

    /// The structural energy H_s = V(q) + K_r(p̃) = V + ½ Σ ‖p_i − p̄‖² (seed 004 eq. 27).
    #[must_use]
    pub fn structural_energy<V: Vector>(&self, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let p_bar = mean(&swarm.velocities);
        self.potential(net) + kinetic(&swarm.velocities, p_bar)
    }
}

impl<V: Vector> Protocol<V> for AlphaAlpha {
    fn interaction_range(&self) -> f64 {
        self.params.r
    }

    fn controls(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        fill_interruptible(inputs, |i| self.input(i, q, p, net));
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// H_s = V + K_r (seed 004 eq. 27): Ḣ_s = −(c₁/2) Σ_{(i,j)∈E} ‖p̃_j − p̃_i‖² ≤ 0 for (α, α, 2)
    /// (Proposition 5); for (α, α, 1) only between switches of the net (Proposition 4).
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.structural_energy(swarm, net)
    }
}

/// L_ρ = max_z |ρ′(z)| of the influence map ρ with flat part δ and power k (seed 000 eq. 4):
///
/// L_ρ = (kπ / (2(1 − δ))) · 2 sin x* cos^{2k−1} x*,  tan² x* = 1/(2k − 1),
///
/// from ρ′ = −(kπ/(2(1 − δ))) [½(1 + cos θ)]^{k−1} sin θ with θ = 2x; π / (2(1 − δ)) for k = 1.
/// The uniform bound |ρ′| ≤ L_ρ that seed 004 assumes for every bump (eq. 16) and uses in eq. 37.
#[must_use]
pub fn influence_map_lipschitz(bump: Bump) -> f64 {
    let k = f64::from(bump.power());
    let sin = (1.0 / (2.0 * k)).sqrt();
    let cos = ((2.0 * k - 1.0) / (2.0 * k)).sqrt();
    k * PI / (2.0 * (1.0 - bump.h())) * 2.0 * sin * cos.powf(2.0 * k - 1.0)
}

/// An (α, α) protocol plus an optional translational controller (seed 004 eq. 48–52; seed 000
/// eq. 40): u_i = u_i^α + f_i with the PD feedback f_i = −c₁(q_i − q_d) − c₂(p_i − p_d) to a
/// destination (q_d, p_d) — a *sink* when p_d = 0 (eq. 50 has c₁ = 1 and q_d = 0) — written as a
/// [`NavigationalFeedback`] to the γ-agent (q_d(t), p_d(t)) (linear form for the papers' PD).
///
/// Flocking separation principle (Proposition 6): Σ_i u_i^α = 0, so the centre of mass obeys
/// ˙q̄ = p̄, ˙p̄ = ū = −c₁(q̄ − q_d) − c₂(p̄ − p_d) whatever the (α, α) part, and
/// H_tr = (c₁/2)‖q̄ − q_d‖² + ½‖p̄ − p_d‖² ([`Flocking2003::translational_energy`]) decreases as
/// −c₂‖p̄ − p_d‖² for constant p_d. (Seed 004 eq. 49 writes V_tr = √(1 + ‖q̄ − q_d‖²) − 1, the
/// potential of its bounded centralised controller eq. 64; the quadratic V_tr is the one matching
/// the distributed PD of eq. 50.)
#[derive(Clone, Debug, PartialEq)]
pub struct Flocking2003<V> {
    /// The (α, α) part; (α, α, 2) ([`AlphaAlphaForm::Smooth`]) for the energy results.
    pub alpha: AlphaAlpha,
    /// The translational controller f_i, if any.
    pub translation: Option<NavigationalFeedback<V>>,
}

impl<V: Vector> Flocking2003<V> {
    /// u_i^α + f_i for agent `i`, given the destination state (q_d, p_d) at the current time.
    fn input(&self, i: usize, swarm: &Swarm<V>, net: &ProximityNet, destination: (V, V)) -> V {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        self.finish(self.alpha.input(i, q, p, net), q[i], p[i], destination)
    }

    /// u_i^α + f_i from agent i's perceived state and the states it heard.
    fn local(&self, own: &Perceived<V>, heard: &[Perceived<V>], destination: (V, V)) -> V {
        let alpha = self.alpha.local_input(own, heard);
        self.finish(alpha, own.position, own.velocity, destination)
    }

    /// u_i^α + f_i(q_i, p_i) (eq. 50), the one place the translational controller is added.
    #[inline]
    fn finish(&self, alpha: V, qi: V, pi: V, destination: (V, V)) -> V {
        match &self.translation {
            Some(feedback) => alpha + feedback.input(qi, pi, destination),
            None => alpha,
        }
    }

    /// The destination (q_d(t), p_d(t)); (0, 0) without a translational controller.
    fn destination(&self, t: f64) -> (V, V) {
        self.translation
            .as_ref()
            .map_or((V::ZERO, V::ZERO), |feedback| feedback.gamma.state(t))
    }

    /// The translational energy H_tr = V_tr(q̄) + ½ ‖p̄ − p_d‖² of the centre of mass (seed 004
    /// eq. 49), V_tr the potential of the feedback's position term at q̄ ((c₁/2)‖q̄ − q_d‖² for the
    /// PD); `None` without a translational controller.
    #[must_use]
    pub fn translational_energy(&self, t: f64, swarm: &Swarm<V>) -> Option<f64> {
        let feedback = self.translation.as_ref()?;
        let (q_d, p_d) = feedback.gamma.state(t);
        Some(
            feedback.potential(swarm.centre(), q_d)
                + 0.5 * (swarm.mean_velocity() - p_d).length_squared(),
        )
    }
}

impl<V: Vector> Protocol<V> for Flocking2003<V> {
    fn interaction_range(&self) -> f64 {
        self.alpha.params().r
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let destination = self.destination(t);
        fill_interruptible(inputs, |i| self.input(i, swarm, net, destination));
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// Without a translational controller, H_s = V + K_r (seed 004 eq. 27). With one,
    /// H = V + Σ_i V_f(q_i − q_d) + ½ Σ_i ‖p_i − p_d‖², V_f the feedback's potential
    /// ((c₁/2)‖·‖² for the PD): for constant p_d and (α, α, 2),
    /// Ḣ = −(c₁^α/2) Σ_{(i,j)∈E} ‖p_j − p_i‖² − c₂ Σ_i ‖p_i − p_d‖² ≤ 0. For the PD it splits as
    /// H = H_s + (c₁/2) Σ ‖q_i − q̄‖² + n H_tr (the separation of eq. 48–49).
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let Some(feedback) = &self.translation else {
            return self.alpha.structural_energy(swarm, net);
        };
        let (q_d, p_d) = feedback.gamma.state(t);
        let tether: f64 = swarm
            .positions
            .iter()
            .map(|&q| feedback.potential(q, q_d))
            .sum();
        self.alpha.potential(net) + tether + kinetic(&swarm.velocities, p_d)
    }

    /// `defect_factor` μ and `normalised_defect_factor` μ_n of the net (seed 004 eq. 46–47;
    /// ~0 on an α-lattice), with a translational controller `structural_energy` H_s and
    /// `translational_energy` H_tr (eq. 48–49): by the separation principle (Proposition 6) H_tr
    /// converges whatever the (α, α) part, and H_s does not rise under (α, α, 2), and the
    /// γ-tracking errors `gamma_position_error` ‖q̄ − q_d‖, `gamma_velocity_error` ‖p̄ − p_d‖
    /// ([`NavigationalFeedback::tracking_columns`]); then
    /// `stress_towards`, `stress_away`, `stress_neutral`, the agents whose local stress S_i is
    /// positive, negative or zero (seed 000 eq. 31–33, [`AlphaAlpha::stress_regimes`]).
    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        let defect = self.alpha.defect_factor().measure(&swarm.positions, net);
        let mut columns = vec![
            ("defect_factor", defect.factor),
            ("normalised_defect_factor", defect.normalised),
        ];
        if let Some(h_tr) = self.translational_energy(t, swarm) {
            columns.push((
                "structural_energy",
                self.alpha.structural_energy(swarm, net),
            ));
            columns.push(("translational_energy", h_tr));
        }
        if let Some(feedback) = &self.translation {
            let numbering = net.numbering();
            columns.extend(feedback.tracking_columns(
                t,
                &swarm.positions,
                &swarm.velocities,
                numbering,
            ));
        }
        columns.extend(self.alpha.stress_regimes(swarm, net).columns());
        columns
    }
}

/// A ball obstacle O_k = B(b_k, l_k) (seed 004 § 11): its centre and radius, which the γ-agent
/// needs, and the obstacle of the space ([`Space::Obstacle`], built by [`Obstacle::ball`]) that
/// projects on it.
#[cfg(feature = "obstacles")]
#[derive(Clone, Debug)]
pub struct BallObstacle<V: Space> {
    centre: V,
    radius: f64,
    shape: V::Obstacle,
}

#[cfg(feature = "obstacles")]
impl<V: Space> BallObstacle<V> {
    /// The closed ball B(centre, radius).
    ///
    /// # Errors
    /// As [`Obstacle::ball`]: a radius that is not finite and > 0, or a centre not finite.
    pub fn new(centre: V, radius: f64) -> Result<Self, ObstacleError> {
        Ok(Self {
            centre,
            radius,
            shape: V::Obstacle::ball(centre, radius)?,
        })
    }

    /// The centre b_k.
    #[must_use]
    pub const fn centre(&self) -> V {
        self.centre
    }

    /// The radius l_k.
    #[must_use]
    pub const fn radius(&self) -> f64 {
        self.radius
    }

    /// The β-agent (q̂, p̂) of the α-agent (q, p): q̂ = argmin_{x∈O_k} ‖x − q‖ (eq. 53) and
    /// p̂ = μ P p, μ = l_k / ‖q − b_k‖, which is eq. 55–57 for a ball.
    #[must_use]
    pub fn beta_agent(&self, q: V, p: V) -> BetaAgent<V> {
        self.shape.beta_agent(q, p)
    }
}

/// Gains and distances of the (α, β) and (α, γ) interactions of seed 004 eq. 54.
///
/// The seed leaves φ_β as "a repelling force"; here φ_β(z) = min(φ_α(z), 0), the repulsive branch of
/// the eq. 29 action function (same a, b), which vanishes for z ≥ 0, i.e. beyond d_β from the
/// obstacle. φ_γ = φ_α (eq. 54).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObstacleParams {
    /// The shell radius r₀: obstacle O_k is active for agent i when d(q_i, O_k) ≤ r₀ (the seed
    /// assumes r₀ = r/2).
    pub r0: f64,
    /// The gain c₃ of the β/γ position terms; the seed asks c₃ ≫ 1 so that avoidance has the
    /// highest priority.
    pub c3: f64,
    /// The gain c₄ of the velocity term c₄(p̂ − p_i).
    pub c4: f64,
    /// d_β: the distance to the obstacle below which φ_β repels.
    pub d_beta: f64,
    /// d_γ: the equilibrium distance of the (α, γ) pair.
    pub d_gamma: f64,
    /// λ_d: the γ-agent sits at x_k = b_k + λ_d n_d (the seed takes λ_d ∈ (0, 1]).
    pub lambda_d: f64,
    /// The bump ρ of the factor ρ(‖q̂ − q_i‖ / r₀).
    pub bump: Bump,
}

impl ObstacleParams {
    /// Our choice for an (α, α) protocol of range r (the seed gives no values): r₀ = r/2 (the
    /// seed's), d_β = r₀ (which is TAC 2006's d′ = 0.6 d_α when r = 1.2 d_α), d_γ = d_α, the
    /// (α, α) influence map as ρ, and the default [`AvoidanceGains`].
    #[must_use]
    pub fn for_alpha(alpha: &AlphaAlphaParams) -> Self {
        Self::new(alpha, AvoidanceGains::default())
    }

    /// The distances and bump of [`ObstacleParams::for_alpha`] with the gains `gains`.
    #[must_use]
    pub fn new(alpha: &AlphaAlphaParams, gains: AvoidanceGains) -> Self {
        let r0 = 0.5 * alpha.r;
        Self {
            r0,
            c3: gains.c3,
            c4: gains.c4,
            d_beta: r0,
            d_gamma: alpha.d_alpha,
            lambda_d: gains.lambda_d,
            bump: alpha.bump,
        }
    }
}

/// The gains of the 2003 obstacle protocol as a scenario writes them (seed 004 eq. 54), with our
/// defaults (the seed gives no values): c₃ = 10 (≫ 1, repulsion up to c₃ b), c₄ = 1, λ_d = 1.
///
/// c₄ matches the velocity of the β-agent, p̂ = μ P p with μ < 1 outside a ball, so it also
/// brakes motion along the obstacle: with c₄ = 2√c₃ ≈ 6.3 (TAC 2006's critical-damping rule) the
/// 9-agent flock of `tests/olfati_saber2003.rs` was still jammed in front of the ball after
/// 16 s; with c₄ = 1 it splits around the ball and passes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct AvoidanceGains {
    /// Gain c₃ > 0 of the β/γ position terms (the seed asks c₃ ≫ 1).
    pub c3: f64,
    /// Gain c₄ ≥ 0 of the velocity term c₄(p̂ − p_i).
    pub c4: f64,
    /// λ_d ∈ (0, 1]: the γ-agent of obstacle k sits at b_k + λ_d n_d.
    pub lambda_d: f64,
}

impl Default for AvoidanceGains {
    fn default() -> Self {
        Self {
            c3: 10.0,
            c4: 1.0,
            lambda_d: 1.0,
        }
    }
}

impl AvoidanceGains {
    /// Checks c₃ > 0, c₄ ≥ 0 and λ_d ∈ (0, 1].
    ///
    /// # Errors
    /// The first gain outside its domain, named by its field (`c3`, `c4`, `lambda_d`).
    pub fn validate(&self) -> Result<(), ParamError> {
        check::positive("c3", self.c3)?;
        check::non_negative("c4", self.c4)?;
        check::require(
            self.lambda_d > 0.0 && self.lambda_d <= 1.0,
            "lambda_d",
            self.lambda_d,
            "the γ-agent x_k = b_k + λ_d n_d needs λ_d in (0, 1]",
            "use lambda_d: 1.0",
        )
    }
}

/// The 2003 obstacle protocol (seed 004 eq. 58):
///
/// u_i = u_i^(α,α,2) + Σ_{O_k active for i} u_i^{O_k} + u^tr,
///
/// u_i^{O_k} = c₃ ρ(‖q̂ − q_i‖/r₀)[φ_β(‖q̂ − q_i‖ − d_β) n(q̂ − q_i) + φ_γ(‖x_k − q_i‖ − d_γ) n(x_k − q_i)]
/// + c₄(p̂ − p_i) (eq. 54),
///
/// with the β-agent (q̂, p̂) of agent i on the ball O_k (eq. 53, 55–57), active when
/// d(q_i, O_k) ≤ r₀; the γ-agent x_k = b_k + λ_d n_d, n_d = p_d/‖p_d‖ the desired direction of the
/// translational controller (x_k = b_k when p_d = 0 or there is none); n(z) = z/‖z‖ (0 for z = 0);
/// φ_β and the other choices in [`ObstacleParams`].
///
/// The seed states no energy result with obstacles; [`Protocol::energy`] is that of the
/// obstacle-free part ([`Flocking2003`]), which active obstacles may raise.
#[cfg(feature = "obstacles")]
#[derive(Clone, Debug)]
pub struct ObstacleFlocking2003<V: Space> {
    /// The (α, α) part (eq. 58 uses (α, α, 2)) and the translational controller u^tr.
    pub flocking: Flocking2003<V>,
    /// The balls O_k.
    pub obstacles: Vec<BallObstacle<V>>,
    /// The β/γ interaction parameters.
    pub params: ObstacleParams,
}

#[cfg(feature = "obstacles")]
impl<V: Space> ObstacleFlocking2003<V> {
    /// φ_β(z) = min(φ_α(z), 0): the repulsive branch of eq. 29.
    #[must_use]
    pub fn phi_beta(&self, z: f64) -> f64 {
        self.flocking.alpha.sigmoid().action(z).min(0.0)
    }

    /// The desired direction n_d = p_d/‖p_d‖ at time `t` (zero without a moving destination).
    #[must_use]
    pub fn direction(&self, t: f64) -> V {
        self.flocking.destination(t).1.normalize_or_zero()
    }

    /// The γ-agent x_k = b_k + λ_d n_d of obstacle `k`.
    #[must_use]
    pub fn gamma_agent(&self, k: usize, direction: V) -> V {
        self.obstacles[k].centre + direction * self.params.lambda_d
    }

    /// Σ_{O_k active} u^{O_k} (eq. 54) for an α-agent at (q, p), given n_d.
    #[must_use]
    pub fn obstacle_input(&self, q: V, p: V, direction: V) -> V {
        let params = &self.params;
        let phi_gamma = self.flocking.alpha.sigmoid();
        let mut total = V::ZERO;
        for (k, obstacle) in self.obstacles.iter().enumerate() {
            let beta = obstacle.beta_agent(q, p);
            if beta.distance > params.r0 {
                continue;
            }
            let to_beta = beta.position - q;
            let to_gamma = self.gamma_agent(k, direction) - q;
            let gamma_distance = to_gamma.length();
            let repulsion = self.phi_beta(beta.distance - params.d_beta);
            let attraction = phi_gamma.action(gamma_distance - params.d_gamma);
            let position =
                to_beta.normalize_or_zero() * repulsion + to_gamma.normalize_or_zero() * attraction;
            let weight = params.c3 * params.bump.value(beta.distance / params.r0);
            total += position * weight + (beta.velocity - p) * params.c4;
        }
        total
    }
}

#[cfg(feature = "obstacles")]
impl<V: Space> Protocol<V> for ObstacleFlocking2003<V> {
    fn interaction_range(&self) -> f64 {
        self.flocking.alpha.params().r
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let destination = self.flocking.destination(t);
        let direction = destination.1.normalize_or_zero();
        let (q, p) = (&swarm.positions, &swarm.velocities);
        fill_interruptible(inputs, |i| {
            self.flocking.input(i, swarm, net, destination)
                + self.obstacle_input(q[i], p[i], direction)
        });
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// The energy of the obstacle-free part, [`Flocking2003`]'s (no theorem covers obstacles).
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.flocking.energy(t, swarm, net)
    }

    /// [`Flocking2003`]'s columns, then `obstacle_clearance`, `inside_obstacles` (none without
    /// obstacles).
    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        let mut columns = self.flocking.diagnostics(t, swarm, net);
        if self.obstacles.is_empty() {
            return columns;
        }
        let clearance = |q: V| {
            self.obstacles
                .iter()
                .map(|ball| (q - ball.centre()).length() - ball.radius())
                .fold(f64::INFINITY, f64::min)
        };
        columns.extend(ObstacleMetrics::measure(&swarm.positions, clearance).columns());
        columns
    }
}

/// u_i of eq. 34–36 from agent i's perception: the agents heard within r by their perceived
/// distance.
impl<V: Vector> LocalForm<V> for AlphaAlpha {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        AlphaAlpha::local_input(self, own, heard)
    }
}

/// u_i = u_i^α + f_i (seed 004 eq. 50) from agent i's perception; the destination (q_d(t), p_d(t))
/// is known to every agent.
impl<V: Vector> LocalForm<V> for Flocking2003<V> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        self.local(own, heard, self.destination(t))
    }
}

/// u_i of eq. 58 from agent i's perception; the β- and γ-agents of the balls are computed from its
/// own perceived state (it senses the obstacles from where it believes it is).
#[cfg(feature = "obstacles")]
impl<V: Space> LocalForm<V> for ObstacleFlocking2003<V> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let destination = self.flocking.destination(t);
        let direction = destination.1.normalize_or_zero();
        self.flocking.local(own, heard, destination)
            + self.obstacle_input(own.position, own.velocity, direction)
    }
}

/// ½ Σ_i Σ_{j∈N_i} f(‖q_j − q_i‖) = Σ_{i<j} f over the net's edges, summed in edge order.
fn half_edge_sum(net: &ProximityNet, f: impl Fn(f64) -> f64) -> f64 {
    let graph = net.graph();
    let distances = net.distances();
    let mut total = 0.0;
    for i in 0..graph.len() {
        for (e, &j) in graph.edge_range(i).zip(graph.neighbours(i)) {
            if j as usize > i {
                total += f(distances[e]);
            }
        }
    }
    total
}

/// ½ Σ ‖p_i − p_ref‖².
fn kinetic<V: Vector>(velocities: &[V], reference: V) -> f64 {
    0.5 * velocities
        .iter()
        .map(|&p| (p - reference).length_squared())
        .sum::<f64>()
}

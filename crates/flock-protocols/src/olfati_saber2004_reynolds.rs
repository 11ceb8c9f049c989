//! The (α, α) protocol read as Reynolds's three rules: Olfati-Saber, *A unified analytical look at
//! Reynolds flocking rules*, ACC 2004 / Caltech CDS technical report (seed 000), § 4.
//!
//! The (α, α) protocol (seed 000 eq. 22) is the sum of two terms (eq. 25),
//!
//! - the motion-planning term u_i^mp = Σ_{j∈N_i} φ_α(‖q_j − q_i‖ − d_α) n_ij (eq. 24), written with
//!   the stress weights s_ij = φ_α(‖q_j − q_i‖ − d_α)/‖q_j − q_i‖ (eq. 26) as
//!   u_i^mp = Σ_j s_ij (q_j − q_i) (eq. 27) and, when the local stress S_i = Σ_j s_ij (eq. 31) is not
//!   zero, as u_i^mp = S_i (q_i^av − q_i) (eq. 33) with the centre of neighbours
//!   q_i^av = Σ_j s_ij q_j / S_i (eq. 32): towards q_i^av when S_i > 0 (flock centering, Reynolds's
//!   cohesion), away from it when S_i < 0 (collision avoidance, separation); when S_i = 0,
//!   u_i^mp = S_i⁺ (q_i^av+ − q_i^av−) (eq. 37), from the centre of negative friends to that of
//!   positive friends, or zero;
//! - the velocity-matching term u_i^vm = c_d Σ_{j∈N_i} (p_j − p_i) = c_d |N_i| (p_i^av − p_i)
//!   (eq. 17), Reynolds's alignment.
//!
//! Here g = [`AlphaAlpha::pair_action`] plays φ_α (the ACC 2004 action function for
//! [`AlphaAlphaForm::Smooth`](crate::AlphaAlphaForm::Smooth)) and c_d the consensus gain.
//!
//! - [`AlphaAlpha::reynolds_reading`]: per agent, [`AgentReading`]: both terms, the local stress,
//!   its [`StressRegime`] and the three rules of Reynolds ([`ReynoldsRules`]) for the same state.
//! - [`AlphaAlpha::stress_regimes`]: how many agents are in each regime ([`RegimeCounts`]), the
//!   `stress_towards`, `stress_away`, `stress_neutral` columns of the 2003 protocols' metrics.

use flock_graph::ProximityNet;
use flock_math::Vector;

use crate::{AlphaAlpha, Swarm};

/// An agent's local stress counts as zero (seed 000 case ii, eq. 37) when
/// |S_i| ≤ `NEUTRAL_STRESS` · |N_i| · b / d_α: round-off of the |N_i| stress weights, each of the
/// order of the stress scale b/d_α (the repulsion bound of φ_α over the desired distance). Seed 000
/// asks S_i = 0 exactly; this tolerance only absorbs round-off (at exactly d_α, φ_α(0) evaluates to
/// ~10⁻¹⁶, not 0). An agent without neighbours has S_i = 0 and is neutral.
pub const NEUTRAL_STRESS: f64 = 1e-9;

/// Where the motion-planning term moves an agent, by the sign of its local stress S_i (seed 000
/// eq. 31–33).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StressRegime {
    /// S_i > 0: u_i^mp = S_i (q_i^av − q_i) pulls i towards the centre of its neighbours
    /// (Reynolds's flock centering, cohesion).
    Towards,
    /// S_i < 0: u_i^mp pushes i away from the centre of its neighbours (Reynolds's collision
    /// avoidance, separation).
    Away,
    /// S_i = 0 (to [`NEUTRAL_STRESS`]): no centre of neighbours; u_i^mp = S_i⁺ (q_i^av+ − q_i^av−)
    /// (eq. 37), zero when every neighbour is a neutral friend (all at d_α) or there is none.
    Neutral,
}

/// Reynolds's three rules for one agent, unweighted over its neighbours N_i (j ≠ i, within r), as
/// the boids of the ABM frameworks ([`Boids`](crate::Boids)) form their cohere and separate
/// vectors, divided by |N_i| (all zero without neighbours):
///
/// - cohesion (flock centering) (1/|N_i|) Σ_j (q_j − q_i) = q̄_{N_i} − q_i, towards the plain
///   centre of the neighbours;
/// - separation (collision avoidance) −(1/|N_i|) Σ_{j: ‖q_j − q_i‖ < d_α} (q_j − q_i), with the
///   separation distance d_α, where the (α, α) pair force turns from repulsion to attraction;
/// - alignment (velocity matching) (1/|N_i|) Σ_j (p_j − p_i) = p_i^av − p_i, the mean neighbour
///   velocity minus one's own (seed 000 eq. 17; the boids add the mean heading to their own
///   instead, and use unit headings).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReynoldsRules<V> {
    /// q̄_{N_i} − q_i.
    pub cohesion: V,
    /// −(1/|N_i|) Σ_{‖q_j − q_i‖ < d_α} (q_j − q_i).
    pub separation: V,
    /// p̄_{N_i} − p_i.
    pub alignment: V,
}

/// Agent i of an (α, α) state read as seed 000 § 4 reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AgentReading<V> {
    /// The motion-planning term u_i^mp = Σ_j s_ij (q_j − q_i) (eq. 24, 27).
    pub motion_planning: V,
    /// The velocity-matching term u_i^vm = c_d Σ_j (p_j − p_i) (eq. 22, 17); u_i^mp + u_i^vm is the
    /// protocol's u_i ([`AlphaAlpha::input`]) bit for bit.
    pub velocity_matching: V,
    /// The local stress S_i = Σ_j s_ij (eq. 31).
    pub local_stress: f64,
    /// (S_i⁺, S_i⁻): the sums of s_ij over the positive and negative friends (eq. 28, 29, 31).
    pub signed_stress: (f64, f64),
    /// The regime of S_i's sign.
    pub regime: StressRegime,
    /// The centre of neighbours q_i^av = Σ_j s_ij q_j / S_i (eq. 32), `None` when neutral.
    pub centre_of_neighbours: Option<V>,
    /// |N_i|, the neighbours j ≠ i.
    pub neighbours: usize,
    /// Reynolds's rules for the same state.
    pub rules: ReynoldsRules<V>,
}

/// How many agents are in each [`StressRegime`]; they sum to n.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RegimeCounts {
    /// S_i > 0.
    pub towards: usize,
    /// S_i < 0.
    pub away: usize,
    /// S_i = 0.
    pub neutral: usize,
}

impl RegimeCounts {
    /// The counts as the metrics' columns `stress_towards`, `stress_away`, `stress_neutral`.
    #[must_use]
    pub fn columns(&self) -> [(&'static str, f64); 3] {
        [
            ("stress_towards", self.towards as f64),
            ("stress_away", self.away as f64),
            ("stress_neutral", self.neutral as f64),
        ]
    }

    /// n, the sum of the counts.
    #[must_use]
    pub const fn total(&self) -> usize {
        self.towards + self.away + self.neutral
    }
}

impl AlphaAlpha {
    /// Agent `i` of the state (`q`, `p`) with its net `net` (built at r, with distances), read
    /// as seed 000 § 4: its two terms, local stress, regime and Reynolds's rules.
    ///
    /// # Example
    /// ```
    /// use flock_graph::ProximityNet;
    /// use flock_protocols::{AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams, StressRegime};
    /// use glam::DVec2;
    ///
    /// let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), AlphaAlphaForm::Nonsmooth, 1.0);
    /// // d_α = 7: a neighbour at 8 attracts agent 0, towards the centre of its neighbours
    /// let q = [DVec2::ZERO, DVec2::new(8.0, 0.0)];
    /// let p = [DVec2::ZERO, DVec2::Y];
    /// let net = ProximityNet::brute_force(&q, 8.4);
    /// let reading = alpha.reynolds_reading(0, &q, &p, &net);
    /// assert_eq!(reading.regime, StressRegime::Towards);
    /// assert_eq!(reading.centre_of_neighbours, Some(q[1]));
    /// assert_eq!(reading.motion_planning + reading.velocity_matching, alpha.input(0, &q, &p, &net));
    /// assert_eq!(reading.rules.alignment, DVec2::Y);
    /// ```
    #[must_use]
    pub fn reynolds_reading<V: Vector>(
        &self,
        i: usize,
        q: &[V],
        p: &[V],
        net: &ProximityNet,
    ) -> AgentReading<V> {
        let graph = net.graph();
        let distances = &net.distances()[graph.edge_range(i)];
        let (qi, pi) = (q[i], p[i]);
        let d_alpha = self.params().d_alpha;
        let mut gradient = V::ZERO;
        let mut consensus = V::ZERO;
        let (mut positive, mut negative) = (0.0, 0.0);
        let mut weighted = V::ZERO;
        let mut offsets = V::ZERO;
        let mut too_close = V::ZERO;
        for (&j, &distance) in graph.neighbours(i).iter().zip(distances) {
            let (qj, pj) = (q[j as usize], p[j as usize]);
            // s_ij = 0 for a coincident neighbour (eq. 26), as in AlphaAlpha::input
            let s = if distance > 0.0 {
                self.pair_action(distance) / distance
            } else {
                0.0
            };
            if distance > 0.0 {
                gradient += (qj - qi) * s;
            }
            consensus += pj - pi;
            if s > 0.0 {
                positive += s;
            } else if s < 0.0 {
                negative += s;
            }
            weighted += qj * s;
            offsets += qj - qi;
            if distance < d_alpha {
                too_close += qj - qi;
            }
        }
        let neighbours = distances.len();
        let local_stress = positive + negative;
        let tolerance = NEUTRAL_STRESS * neighbours as f64 * self.params().b / d_alpha;
        let regime = if local_stress > tolerance {
            StressRegime::Towards
        } else if local_stress < -tolerance {
            StressRegime::Away
        } else {
            StressRegime::Neutral
        };
        let per = 1.0 / neighbours.max(1) as f64;
        AgentReading {
            motion_planning: gradient,
            velocity_matching: consensus * self.consensus_gain(),
            local_stress,
            signed_stress: (positive, negative),
            regime,
            centre_of_neighbours: (regime != StressRegime::Neutral)
                .then(|| weighted / local_stress),
            neighbours,
            rules: ReynoldsRules {
                cohesion: offsets * per,
                separation: -too_close * per,
                alignment: consensus * per,
            },
        }
    }

    /// [`AlphaAlpha::reynolds_reading`] of every agent of `swarm`, in order.
    #[must_use]
    pub fn reynolds_readings<V: Vector>(
        &self,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<AgentReading<V>> {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        (0..q.len())
            .map(|i| self.reynolds_reading(i, q, p, net))
            .collect()
    }

    /// How many agents of `swarm` are pulled towards the centre of their neighbours (S_i > 0),
    /// pushed away (S_i < 0) or neither (S_i = 0 to [`NEUTRAL_STRESS`]).
    #[must_use]
    pub fn stress_regimes<V: Vector>(&self, swarm: &Swarm<V>, net: &ProximityNet) -> RegimeCounts {
        let mut counts = RegimeCounts::default();
        for reading in self.reynolds_readings(swarm, net) {
            match reading.regime {
                StressRegime::Towards => counts.towards += 1,
                StressRegime::Away => counts.away += 1,
                StressRegime::Neutral => counts.neutral += 1,
            }
        }
        counts
    }
}

//! The bounded translational controllers of Olfati-Saber, *Flocking with Obstacle Avoidance*,
//! Caltech CDS 03-006 (2003; seed 004), § 10 and Appendix A.3: the *centralised* form of the
//! flocking separation principle.
//!
//! Each agent applies (eq. 48) u_i = u_i^α + ū with Σ_i u_i^α = 0, so the centre of mass obeys
//! ˙q̄ = p̄, ˙p̄ = ū whatever u^α, and ū is a feedback of (q̄, p̄) only:
//!
//! - sink at q_d (eq. 64): ū = k_tr^(1)(q̄, p̄) = −φ(q̄ − q_d) − c₂ φ(p̄), ‖ū‖ ≤ 1 + c₂,
//!   with V_tr(q̄) = √(1 + ‖q̄ − q_d‖²) − 1 (eq. 49) and Ḣ_tr = −c₂ p̄ᵀφ(p̄) ≤ 0 (eq. 63);
//! - desired group velocity p_d (eq. 66): ū = k_tr^(2)(p̄) = −c₂ φ(p̄ − p_d), ‖ū‖ ≤ c₂, with
//!   V_tr ≡ 0 and Ḣ_tr = −c₂ (p̄ − p_d)ᵀφ(p̄ − p_d) < 0 for p̄ ≠ p_d (eq. 65);
//!
//! φ(z) = z/√(1 + ‖z‖²) ([`sigma1_vec`]) and H_tr = V_tr(q̄) + ½‖p̄ − p_d‖² (eq. 49).
//!
//! These controllers are **centralised**: ū needs the centre of mass q̄ and the mean velocity p̄ of
//! all agents, which the report says must come from a coordinator or from average consensus
//! (§ 10, after Remark 6). The report's own distributed alternative is the PD of eq. 50, which
//! [`Flocking2003`] implements. [`CentralisedTracking2003`] computes q̄ and p̄ from the whole swarm
//! (the coordinator) and adds ū to the distributed part: the (α, α) protocol, optionally the
//! per-agent feedback of eq. 50 and the ball obstacles of eq. 54 — the protocol of eq. 58,
//! u_i = u_i^(α,α,2) + Σ_{O_k active} u_i^{O_k} + u^tr, whose u^tr carries no agent index.
//!
//! Proposition 6: with (α, α, 2) and no obstacle, Ḣ_s does not depend on ū (eq. 62) and Ḣ_tr does
//! not depend on u^α (eq. 63, 65), so H_s = V + K_r and H_tr are both non-increasing; with
//! obstacles Σ_i u_i^{O_k} ≠ 0 and neither statement holds.

use flock_graph::ProximityNet;
use flock_math::parallel::fill_interruptible;
use flock_math::{Vector, sigma1_vec};
use flock_obstacles::Space;

use crate::{
    AlphaAlpha, BallObstacle, Flocking2003, ObstacleFlocking2003, ObstacleParams, Protocol, Swarm,
};

/// A bounded translational controller ū = k_tr(q̄, p̄) of seed 004 (eq. 64 or 66).
///
/// # Example
/// ```
/// use flock_protocols::TranslationalController;
/// use glam::DVec2;
///
/// // eq. 66: ū = −c₂ φ(p̄ − p_d), at most c₂ in norm
/// let tracking = TranslationalController::group_velocity(DVec2::new(10.0, 0.0), 2.0);
/// let u = tracking.input(DVec2::ZERO, DVec2::ZERO);
/// assert!((u - DVec2::new(20.0 / 101f64.sqrt(), 0.0)).length() < 1e-15);
/// assert_eq!(tracking.energy(DVec2::ZERO, DVec2::ZERO), 50.0); // ½‖p̄ − p_d‖²
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TranslationalController<V> {
    /// k_tr^(1) of eq. 64 with a position gain: ū = −c₁ φ(q̄ − q_d) − c₂ φ(p̄) (the report's
    /// c₁ = 1, ū = −∇V_tr − c₂ φ(p̄)), H_tr = c₁ V_tr(q̄) + ½‖p̄‖².
    Sink {
        /// The sink q_d (p_d = 0).
        destination: V,
        /// Position gain c₁ > 0 (1 in eq. 64).
        c1: f64,
        /// Velocity gain c₂ > 0.
        c2: f64,
    },
    /// k_tr^(2) of eq. 66: ū = −c₂ φ(p̄ − p_d), H_tr = ½‖p̄ − p_d‖².
    GroupVelocity {
        /// The desired group velocity p_d.
        velocity: V,
        /// Velocity gain c₂ > 0.
        c2: f64,
    },
}

impl<V: Vector> TranslationalController<V> {
    /// The sink controller of eq. 64 (c₁ = 1).
    #[must_use]
    pub const fn sink(destination: V, c2: f64) -> Self {
        Self::Sink {
            destination,
            c1: 1.0,
            c2,
        }
    }

    /// The group-velocity controller of eq. 66.
    #[must_use]
    pub const fn group_velocity(velocity: V, c2: f64) -> Self {
        Self::GroupVelocity { velocity, c2 }
    }

    /// ū for the centre of mass q̄ and the mean velocity p̄.
    #[inline]
    #[must_use]
    pub fn input(&self, q_bar: V, p_bar: V) -> V {
        match *self {
            Self::Sink {
                destination,
                c1,
                c2,
            } => -(sigma1_vec(q_bar - destination) * c1) - sigma1_vec(p_bar) * c2,
            Self::GroupVelocity { velocity, c2 } => -(sigma1_vec(p_bar - velocity) * c2),
        }
    }

    /// The translational energy H_tr(q̄, p̄) = c₁ V_tr(q̄) + ½‖p̄ − p_d‖² (eq. 49), V_tr =
    /// √(1 + ‖q̄ − q_d‖²) − 1 for the sink and 0 for a group velocity.
    #[must_use]
    pub fn energy(&self, q_bar: V, p_bar: V) -> f64 {
        match *self {
            Self::Sink {
                destination, c1, ..
            } => {
                let d2 = (q_bar - destination).length_squared();
                // √(1 + x) − 1 without cancellation for small x
                c1 * d2 / ((1.0 + d2).sqrt() + 1.0) + 0.5 * p_bar.length_squared()
            }
            Self::GroupVelocity { velocity, .. } => 0.5 * (p_bar - velocity).length_squared(),
        }
    }

    /// The desired velocity p_d (zero for a sink).
    #[must_use]
    pub fn desired_velocity(&self) -> V {
        match *self {
            Self::Sink { .. } => V::ZERO,
            Self::GroupVelocity { velocity, .. } => velocity,
        }
    }

    /// The bound on ‖ū‖: 1 + c₂ for eq. 64 (c₁ + c₂ with a position gain), c₂ for eq. 66.
    #[must_use]
    pub fn bound(&self) -> f64 {
        match *self {
            Self::Sink { c1, c2, .. } => c1 + c2,
            Self::GroupVelocity { c2, .. } => c2,
        }
    }
}

/// A 2003 protocol plus the centralised translational controller: u_i = u_i^dist + ū(q̄, p̄)
/// (seed 004 eq. 48, 58, 64–66; see the [module](self)).
///
/// The distributed part is an [`ObstacleFlocking2003`]: its (α, α) protocol, its per-agent
/// translational feedback if any (eq. 50; `None` for the report's eq. 48 and 58) and its ball
/// obstacles (eq. 54; none for § 10). The γ-agents of the obstacles sit at b_k + λ_d n_d with
/// n_d = p_d/‖p_d‖ of the controller (of the per-agent feedback for a sink).
///
/// It has no [`LocalForm`](crate::LocalForm) ([`Protocol::local_form`]
/// is `None`): ū needs the centre of mass (q̄, p̄) of the whole flock, which no agent perceives
/// from its neighbours, so the conditions that make agents perceive different worlds
/// (communication, sensing, silent or removed agents) are refused for it.
#[derive(Clone, Debug)]
pub struct CentralisedTracking2003<V: Space> {
    /// The distributed part.
    pub distributed: ObstacleFlocking2003<V>,
    /// ū, the same for every agent.
    pub translation: TranslationalController<V>,
}

impl<V: Space> CentralisedTracking2003<V> {
    /// eq. 48 without obstacles: u_i = u_i^α + ū (Proposition 6).
    #[must_use]
    pub fn new(alpha: AlphaAlpha, translation: TranslationalController<V>) -> Self {
        let params = ObstacleParams::for_alpha(alpha.params());
        Self::with_obstacles(alpha, Vec::new(), params, translation)
    }

    /// eq. 58: u_i = u_i^(α,α) + Σ_{O_k active} u_i^{O_k} + ū.
    #[must_use]
    pub fn with_obstacles(
        alpha: AlphaAlpha,
        obstacles: Vec<BallObstacle<V>>,
        params: ObstacleParams,
        translation: TranslationalController<V>,
    ) -> Self {
        Self {
            distributed: ObstacleFlocking2003 {
                flocking: Flocking2003 {
                    alpha,
                    translation: None,
                },
                obstacles,
                params,
            },
            translation,
        }
    }

    /// The (α, α) part.
    #[must_use]
    pub const fn alpha(&self) -> &AlphaAlpha {
        &self.distributed.flocking.alpha
    }

    /// ū of the swarm: the controller at its centre of mass and mean velocity.
    #[must_use]
    pub fn common_input(&self, swarm: &Swarm<V>) -> V {
        self.translation
            .input(swarm.centre(), swarm.mean_velocity())
    }

    /// n_d = p_d/‖p_d‖ of the controller, or of the per-agent feedback when the controller has
    /// no desired velocity (a sink).
    #[must_use]
    pub fn direction(&self, t: f64) -> V {
        let p_d = self.translation.desired_velocity();
        if p_d == V::ZERO {
            self.distributed.direction(t)
        } else {
            p_d.normalize_or_zero()
        }
    }

    /// The structural energy H_s = V(q) + K_r(p̃) (eq. 27).
    #[must_use]
    pub fn structural_energy(&self, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.alpha().structural_energy(swarm, net)
    }

    /// The translational energy H_tr(q̄, p̄) (eq. 49).
    #[must_use]
    pub fn translational_energy(&self, swarm: &Swarm<V>) -> f64 {
        self.translation
            .energy(swarm.centre(), swarm.mean_velocity())
    }
}

impl<V: Space> Protocol<V> for CentralisedTracking2003<V> {
    fn interaction_range(&self) -> f64 {
        self.alpha().params().r
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let common = self.common_input(swarm);
        let direction = self.direction(t);
        let feedback = self.distributed.flocking.translation.as_ref();
        let destination = feedback.map(|f| f.gamma.state(t));
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let alpha = self.alpha();
        let obstacles = !self.distributed.obstacles.is_empty();
        fill_interruptible(inputs, |i| {
            let mut u = alpha.input(i, q, p, net);
            if let (Some(f), Some(state)) = (feedback, destination) {
                u += f.input(q[i], p[i], state);
            }
            if obstacles {
                u += self.distributed.obstacle_input(q[i], p[i], direction);
            }
            u + common
        });
    }

    /// H = H_s + H_tr, non-increasing for (α, α, 2) without obstacles or per-agent feedback
    /// (Proposition 6).
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.structural_energy(swarm, net) + self.translational_energy(swarm)
    }

    /// `structural_energy` H_s and `translational_energy` H_tr (eq. 48–49, the separation of
    /// Proposition 6), then those of the distributed part: its defect factor (eq. 46–47) and the
    /// obstacle columns of the ball obstacles, if any.
    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        let mut columns = vec![
            ("structural_energy", self.structural_energy(swarm, net)),
            ("translational_energy", self.translational_energy(swarm)),
        ];
        columns.extend(self.distributed.diagnostics(t, swarm, net));
        columns
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use glam::{DVec2, DVec3};

    #[test]
    fn sink_is_minus_the_gradient_of_v_tr_and_bounded() {
        let q_d = DVec3::new(1.0, -2.0, 0.5);
        let sink = TranslationalController::sink(q_d, 3.0);
        let q = DVec3::new(4.0, 2.0, -1.0);
        // with p̄ = 0 the input is −∇V_tr, V_tr = H_tr at rest
        let u = sink.input(q, DVec3::ZERO);
        let step = 1e-6;
        for e in [DVec3::X, DVec3::Y, DVec3::Z] {
            let fd = (sink.energy(q + e * step, DVec3::ZERO)
                - sink.energy(q - e * step, DVec3::ZERO))
                / (2.0 * step);
            assert_relative_eq!(-u.dot(e), fd, epsilon = 1e-8);
        }
        // ‖k_tr^(1)‖ ≤ 1 + c₂, approached far away and fast
        let far = sink.input(q_d + DVec3::X * 1e9, DVec3::X * 1e9);
        assert_relative_eq!(far.length(), 4.0, epsilon = 1e-12);
        assert_eq!(sink.bound(), 4.0);
        assert_eq!(sink.desired_velocity(), DVec3::ZERO);
        // eq. 64 has φ(p̄), not p̄: bounded in the velocity too
        let u = sink.input(q_d, DVec3::new(3.0, 4.0, 0.0));
        assert_relative_eq!(
            u,
            DVec3::new(-9.0, -12.0, 0.0) / 26f64.sqrt(),
            epsilon = 1e-15
        );
    }

    #[test]
    fn group_velocity_tracking_is_bounded_by_c2() {
        let p_d = DVec2::new(0.0, 10.0);
        let tracking = TranslationalController::group_velocity(p_d, 1.5);
        assert_eq!(tracking.input(DVec2::new(50.0, 3.0), p_d), DVec2::ZERO);
        let u = tracking.input(DVec2::ZERO, DVec2::new(1e8, 10.0));
        assert_relative_eq!(u, DVec2::new(-1.5, 0.0), epsilon = 1e-12);
        assert_eq!(tracking.bound(), 1.5);
        assert_eq!(
            tracking.energy(DVec2::new(7.0, 7.0), DVec2::new(0.0, 12.0)),
            2.0
        );
    }
}

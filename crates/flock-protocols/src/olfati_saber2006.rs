//! Algorithms 1, 2 and 3 of Olfati-Saber, *Flocking for multi-agent dynamic systems: algorithms and
//! theory*, IEEE TAC 51(3), 2006.

use flock_graph::ProximityNet;
use flock_math::{Vector, mean_of};
#[cfg(feature = "obstacles")]
use flock_metrics::ObstacleMetrics;
#[cfg(feature = "obstacles")]
use flock_obstacles::Space;

#[cfg(feature = "obstacles")]
use crate::BetaInteraction;
use crate::swarm::kinetic;
use crate::{
    AlphaInteraction, LocalForm, NavigationalFeedback, Perceived, Perceptions, Protocol, Swarm,
};

/// Algorithm 1 (eq. 24): u_i = u_i^α, the α-interaction alone. Total momentum is preserved
/// (Σ_i u_i = 0) and, in the frame of the centre of mass, H = V(q) + ½ Σ ‖p_i − p_c‖² is
/// non-increasing (Theorem 1). It rarely yields flocking: the typical outcome is regular
/// fragmentation (Fig. 12).
#[derive(Clone, Debug, PartialEq)]
pub struct Algorithm1 {
    /// The α-interaction.
    pub alpha: AlphaInteraction,
}

impl<V: Vector> Protocol<V> for Algorithm1 {
    fn uses_net_distances(&self) -> bool {
        false
    }

    fn follows_numbering(&self) -> bool {
        true
    }

    fn interaction_range(&self) -> f64 {
        self.alpha.params().r
    }

    fn controls(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        self.alpha.inputs(q, p, net, inputs, |_, u| u);
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// H = c₁^α V(q) + ½ Σ ‖p_i − p_c‖² (Theorem 1, moving frame).
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let numbering = net.numbering();
        let p_c = mean_of(numbering.ordered(&swarm.velocities));
        self.alpha.c1() * self.alpha.potential(&swarm.positions, net)
            + kinetic(&swarm.velocities, numbering, p_c)
    }
}

/// Algorithm 2 (eq. 25–26): u_i = u_i^α + f_i^γ with f_i^γ = −c₁(q_i − q_r) − c₂(p_i − p_r): the
/// α-interaction plus navigational feedback to a γ-agent. It yields flocking (Theorem 3, Fig. 10–11).
#[derive(Clone, Debug, PartialEq)]
pub struct Algorithm2<V> {
    /// The α-interaction.
    pub alpha: AlphaInteraction,
    /// The navigational feedback to the γ-agent.
    pub navigation: NavigationalFeedback<V>,
}

impl<V: Vector> Algorithm2<V> {
    /// u_i = u_i^α + f_i^γ for agent `i`, given the γ-agent's state `reference` = (q_r, p_r).
    #[must_use]
    pub fn input(&self, i: usize, reference: (V, V), q: &[V], p: &[V], net: &ProximityNet) -> V {
        self.alpha.input(i, q, p, net) + self.navigation.input(q[i], p[i], reference)
    }

    /// c₁^α V(q) + Σ_i V_γ(q_i): the potential part of the Hamiltonian, summed in original order.
    fn potential(&self, q_r: V, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let q = &swarm.positions;
        let tether = net
            .numbering()
            .ordered_sum(q.len(), |i| self.navigation.potential(q[i], q_r));
        self.alpha.c1() * self.alpha.potential(&swarm.positions, net) + tether
    }
}

impl<V: Vector> Protocol<V> for Algorithm2<V> {
    fn uses_net_distances(&self) -> bool {
        false
    }

    fn follows_numbering(&self) -> bool {
        true
    }

    fn interaction_range(&self) -> f64 {
        self.alpha.params().r
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let reference = self.navigation.gamma.state(t);
        self.alpha.inputs(q, p, net, inputs, |i, u| {
            u + self.navigation.input(q[i], p[i], reference)
        });
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// H = c₁^α V(q) + Σ V_γ(q_i) + ½ Σ ‖p_i − p_r‖² with V_γ the feedback potential ((c₁/2)‖q_i − q_r‖²
    /// for the linear form), the energy of the frame moving with
    /// the γ-agent; Ḣ = −c₂^α pᵀL̂p − c₂ Σ ‖p_i − p_r‖² ≤ 0 when p_r is constant (Theorem 3).
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let (q_r, p_r) = self.navigation.gamma.state(t);
        self.potential(q_r, swarm, net) + kinetic(&swarm.velocities, net.numbering(), p_r)
    }

    /// `gamma_position_error` ‖q̄ − q_r‖ and `gamma_velocity_error` ‖p̄ − p_r‖
    /// ([`NavigationalFeedback::tracking_columns`]).
    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        self.tracking_columns(t, swarm, net).to_vec()
    }
}

impl<V: Vector> Algorithm2<V> {
    /// The γ-tracking errors of the swarm at `t`, summed in original order.
    fn tracking_columns(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> [(&'static str, f64); 2] {
        self.navigation
            .tracking_columns(t, &swarm.positions, &swarm.velocities, net.numbering())
    }
}

/// Algorithm 3 (eq. 67): u_i = u_i^α + u_i^β + u_i^γ, flocking with obstacle avoidance. The α-part
/// and the navigational feedback are those of an [`Algorithm2`] (use
/// [`NavigationalFeedback::bounded`](crate::NavigationalFeedback::bounded) for the paper's
/// u_i^γ = −c₁^γ σ₁(q_i − q_r) − c₂^γ(p_i − p_r)); the β-part repels from the obstacles' β-agents.
/// With no obstacle within r′ of any agent it is exactly that Algorithm 2.
#[cfg(feature = "obstacles")]
#[derive(Clone, Debug)]
pub struct Algorithm3<V: Space> {
    /// The α-interaction and the navigational feedback.
    pub flock: Algorithm2<V>,
    /// The β-interaction with the obstacles.
    pub beta: BetaInteraction<V>,
}

#[cfg(feature = "obstacles")]
impl<V: Space> Protocol<V> for Algorithm3<V> {
    fn uses_net_distances(&self) -> bool {
        false
    }

    fn follows_numbering(&self) -> bool {
        true
    }

    fn interaction_range(&self) -> f64 {
        self.flock.alpha.params().r
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let reference = self.flock.navigation.gamma.state(t);
        // (u^α + u^γ) + u^β, as `self.flock.input(i, ..) + self.beta.input(..)`
        self.flock.alpha.inputs(q, p, net, inputs, |i, u| {
            u + self.flock.navigation.input(q[i], p[i], reference) + self.beta.input(q[i], p[i])
        });
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// H = c₁^α V_α + c₁^β V_β + c₁^γ V_γ + ½ Σ ‖p_i‖² (Theorem 6): non-increasing once
    /// (n/2)⟨p_c, p_d⟩ ≤ T (eq. 76), e.g. always for a static γ-agent.
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        let (q_r, _) = self.flock.navigation.gamma.state(t);
        self.flock.potential(q_r, swarm, net)
            + self.beta.potential(&swarm.positions, net.numbering())
            + kinetic(&swarm.velocities, net.numbering(), V::ZERO)
    }

    /// `obstacle_clearance`, `inside_obstacles` (none without obstacles), then the γ-tracking
    /// errors `gamma_position_error`, `gamma_velocity_error`.
    fn diagnostics(
        &self,
        t: f64,
        swarm: &Swarm<V>,
        net: &ProximityNet,
    ) -> Vec<(&'static str, f64)> {
        let field = self.beta.field();
        let mut columns = if field.is_empty() {
            Vec::new()
        } else {
            ObstacleMetrics::measure(&swarm.positions, |q| field.clearance(q)).columns()
        };
        columns.extend(self.flock.tracking_columns(t, swarm, net));
        columns
    }
}

/// u_i = u_i^α (eq. 24) from agent i's perception.
impl<V: Vector> LocalForm<V> for Algorithm1 {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        self.alpha.local_input(own, heard)
    }

    fn local_inputs(&self, _t: f64, block: Perceptions<'_, V>, out: &mut [V]) {
        self.alpha.local_inputs(block, out);
    }
}

/// u_i = u_i^α + f_i^γ (eq. 25–26) from agent i's perception; the γ-agent's state at t is known
/// to every agent.
impl<V: Vector> LocalForm<V> for Algorithm2<V> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let reference = self.navigation.gamma.state(t);
        self.alpha.local_input(own, heard)
            + self.navigation.input(own.position, own.velocity, reference)
    }

    fn local_inputs(&self, t: f64, block: Perceptions<'_, V>, out: &mut [V]) {
        let reference = self.navigation.gamma.state(t);
        self.alpha.local_inputs(block, out);
        for (u, own) in out.iter_mut().zip(block.owns) {
            *u += self.navigation.input(own.position, own.velocity, reference);
        }
    }

    fn reference(&self, t: f64) -> Option<(V, V)> {
        Some(self.navigation.gamma.state(t))
    }
}

/// u_i = u_i^α + u_i^γ + u_i^β (eq. 67) from agent i's perception; the β-agents are computed from
/// its own perceived state (it senses the obstacles from where it believes it is).
#[cfg(feature = "obstacles")]
impl<V: Space> LocalForm<V> for Algorithm3<V> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let (q, p) = (own.position, own.velocity);
        let reference = self.flock.navigation.gamma.state(t);
        self.flock.alpha.local_input(own, heard)
            + self.flock.navigation.input(q, p, reference)
            + self.beta.input(q, p)
    }

    fn local_inputs(&self, t: f64, block: Perceptions<'_, V>, out: &mut [V]) {
        let reference = self.flock.navigation.gamma.state(t);
        self.flock.alpha.local_inputs(block, out);
        for (u, own) in out.iter_mut().zip(block.owns) {
            let (q, p) = (own.position, own.velocity);
            *u = *u + self.flock.navigation.input(q, p, reference) + self.beta.input(q, p);
        }
    }

    fn reference(&self, t: f64) -> Option<(V, V)> {
        Some(self.flock.navigation.gamma.state(t))
    }

    fn beta_agents(&self, own: &Perceived<V>, out: &mut Vec<(V, V)>) {
        out.extend(
            self.beta
                .neighbours(own.position, own.velocity)
                .into_iter()
                .map(|(_, beta)| (beta.position, beta.velocity)),
        );
    }
}

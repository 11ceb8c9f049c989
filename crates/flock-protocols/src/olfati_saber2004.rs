//! The (α, α) protocol as a PD controller with Laplacian gains: Olfati-Saber, *A unified analytical
//! look at Reynolds flocking rules*, ACC 2004 (seed 000, Proposition 2), and Olfati-Saber & Murray,
//! CDC 2003 (seed 003, eq. 16–17).

use flock_graph::{ProximityNet, StressWeights, binary_weights, laplacian_apply, laplacian_row};
use flock_math::Vector;

use crate::{AlphaAlpha, LocalForm, Perceived, Protocol, Swarm};

/// The stress-weight (PD) form of an (α, α) protocol (seed 000 eq. 27 and 39, seed 003 eq. 17):
///
/// u = −L_s(q) q − c_d L(q) p,  i.e.  u_i = Σ_{j∈N_i} s_ij (q_j − q_i) + c_d (p_j − p_i),
///
/// with the stress weights s_ij = g(‖q_j − q_i‖)/‖q_j − q_i‖ (seed 000 eq. 26, seed 003 eq. 16;
/// s_ij = 0 for coincident agents), L_s the Laplacian of the stress matrix S(q) (sign-indefinite),
/// and L the Laplacian of the 0/1 adjacency Ā = ⌈A(q)⌉ of the net. Here g is the gradient
/// coefficient of the wrapped [`AlphaAlpha`] ([`AlphaAlpha::pair_action`]): with
/// [`AlphaAlphaForm::Smooth`](crate::AlphaAlphaForm::Smooth) it is the ACC-2004 action function
/// φ_α = d/dz[ρ((z + d_α)/r) ψ_α(z)] (seed 000 eq. 23) with the influence map of eq. 4, and
/// c_d = the consensus gain.
///
/// It computes the same inputs as the direct form up to round-off (the sums are grouped
/// differently: Σ s_ij (q_i − q_j) then negated, instead of Σ g n_ij), through two Laplacian
/// products; its energy is the wrapped protocol's. Its [`LocalForm`] is row i of both products
/// ([`laplacian_row`], the sum [`laplacian_apply`] runs per row), so it gives the bits of its own
/// [`Protocol::controls`].
#[derive(Clone, Debug, PartialEq)]
pub struct StressForm(pub AlphaAlpha);

impl StressForm {
    /// The stress weights s_ij of every directed edge of `net` (seed 000 eq. 26).
    #[must_use]
    pub fn stress_weights(&self, net: &ProximityNet) -> StressWeights {
        StressWeights::from_distances(net, |distance| self.stress_weight(distance))
    }

    /// s_ij = g(‖q_j − q_i‖)/‖q_j − q_i‖ of a pair at a positive distance (seed 000 eq. 26).
    #[inline]
    fn stress_weight(&self, distance: f64) -> f64 {
        self.0.pair_action(distance) / distance
    }

    /// u_i = −(L_s q)_i − c_d (L p)_i from the two rows (seed 000 eq. 39).
    #[inline]
    fn combine<V: Vector>(&self, stress_row: V, consensus_row: V) -> V {
        -stress_row - consensus_row * self.0.consensus_gain()
    }
}

impl<V: Vector> Protocol<V> for StressForm {
    fn interaction_range(&self) -> f64 {
        <AlphaAlpha as Protocol<V>>::interaction_range(&self.0)
    }

    /// u = −L_s(q) q − c_d L(q) p (seed 000 eq. 39); both products run in parallel row by row
    /// with the `parallel` feature, each row summed in neighbour order.
    fn controls(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let graph = net.graph();
        let stress = self.stress_weights(net);
        let mut consensus = vec![V::ZERO; swarm.len()];
        laplacian_apply(graph, stress.weights(), &swarm.positions, inputs);
        laplacian_apply(
            graph,
            &binary_weights(graph),
            &swarm.velocities,
            &mut consensus,
        );
        for (u, &lp) in inputs.iter_mut().zip(&consensus) {
            *u = self.combine(*u, lp);
        }
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }

    /// The wrapped protocol's structural energy H_s = V + K_r.
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.0.energy(t, swarm, net)
    }
}

/// Row i of u = −L_s(q) q − c_d L(q) p (seed 000 eq. 39) from agent i's perception: the agents
/// heard within r by their perceived distance, s_ij = 0 for a coincident one (as
/// [`StressWeights::from_distances`]), the 0/1 weights of Ā for the velocities.
impl<V: Vector> LocalForm<V> for StressForm {
    fn local_input(&self, _t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let near = || self.0.within_range(own.position, heard);
        let weight = |d: f64| if d > 0.0 { self.stress_weight(d) } else { 0.0 };
        let stress = laplacian_row(own.position, near().map(|(q, _, d)| (q, weight(d))));
        let consensus = laplacian_row(own.velocity, near().map(|(_, p, _)| (p, 1.0)));
        self.combine(stress, consensus)
    }
}

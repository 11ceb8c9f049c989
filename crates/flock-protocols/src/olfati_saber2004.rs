//! The (α, α) protocol as a PD controller with Laplacian gains: Olfati-Saber, *A unified analytical
//! look at Reynolds flocking rules*, ACC 2004 (seed 000, Proposition 2), and Olfati-Saber & Murray,
//! CDC 2003 (seed 003, eq. 16–17).

use flock_graph::{ProximityNet, StressWeights, binary_weights, laplacian_apply};
use flock_math::Vector;

use crate::{AlphaAlpha, Protocol, Swarm};

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
/// It computes the same inputs as the direct form, through two Laplacian products; its energy is
/// the wrapped protocol's.
#[derive(Clone, Debug, PartialEq)]
pub struct StressForm(pub AlphaAlpha);

impl StressForm {
    /// The stress weights s_ij of every directed edge of `net` (seed 000 eq. 26).
    #[must_use]
    pub fn stress_weights(&self, net: &ProximityNet) -> StressWeights {
        StressWeights::from_distances(net, |distance| self.0.pair_action(distance) / distance)
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
        let c_d = self.0.consensus_gain();
        for (u, lp) in inputs.iter_mut().zip(&consensus) {
            *u = -*u - *lp * c_d;
        }
    }

    /// The wrapped protocol's structural energy H_s = V + K_r.
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        self.0.energy(t, swarm, net)
    }
}

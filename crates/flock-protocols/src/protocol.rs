//! The [`Protocol`] trait: every flocking algorithm computes all agents' inputs from a read-only state.

use flock_graph::ProximityNet;
use flock_graph::parallel::map_chunks;
use flock_math::Vector;

use crate::Swarm;

/// A distributed flocking protocol: u_i as a function of the state of agent i and of its neighbours
/// in the proximity net, plus the energy function its stability theorem uses.
pub trait Protocol<V: Vector>: Sync {
    /// The interaction range r that defines N_i = { j : ‖q_j − q_i‖ < r }.
    #[must_use]
    fn interaction_range(&self) -> f64;

    /// Writes u_i for every agent into `inputs` (length n), from the state at time `t` and its net
    /// (built with [`Protocol::interaction_range`]). Bit-identical whatever the thread count.
    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]);

    /// The energy (Hamiltonian) of the closed-loop system whose non-increase the theory proves.
    #[must_use]
    fn energy(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64;

    /// Whether [`Protocol::controls`] and [`Protocol::energy`] read the net's stored distances
    /// ([`ProximityNet::distances`]); true unless a protocol says otherwise. When false, a
    /// [`Simulation`](crate::Simulation) keeps its nets without them
    /// ([`ProximityNet::without_distances`]): 8 bytes less per directed edge.
    #[must_use]
    fn uses_net_distances(&self) -> bool {
        true
    }
}

/// Indices per chunk of [`chunked_sum`].
const SUM_CHUNK: usize = 4096;

/// Σ over `0..len` as running sums `f(range)` over chunks of 4,096 indices (in parallel with the
/// `parallel` feature), added in chunk order: the same bits for any thread count, and the plain
/// running sum when there is a single chunk.
pub(crate) fn chunked_sum(len: usize, f: impl Fn(core::ops::Range<usize>) -> f64 + Sync) -> f64 {
    let sums = map_chunks(len, SUM_CHUNK, f);
    match sums.split_first() {
        Some((&first, rest)) => rest.iter().fold(first, |total, &s| total + s),
        None => 0.0,
    }
}

//! Adjacency weights a_ij of a net, one per directed edge (aligned with
//! [`Graph::neighbour_indices`]).
//!
//! - [`binary_weights`]: the 0/1 adjacency of the graph (ACC 2004 (seed 000) eq. 2; the fixed topology of
//!   Tanner, Jadbabaie & Pappas 2003).
//! - [`weights_from_distances`]: a smooth spatial adjacency a_ij = f(‖q_j − q_i‖), e.g.
//!   a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) (IEEE TAC 51(3) 2006) or ρ(‖q_j − q_i‖ / r) (seed 000 eq. 3),
//!   the function being supplied by the caller.

use crate::graph::Graph;
use crate::net::ProximityNet;
use flock_math::parallel::fill_indexed;

/// The 0/1 adjacency: a_ij = 1 for every edge of `graph`.
///
/// # Example
/// ```
/// use flock_graph::{Graph, binary_weights};
///
/// let g = Graph::from_edges(3, &[(0, 1), (1, 2)]).unwrap();
/// assert_eq!(binary_weights(&g), vec![1.0; 4]);
/// ```
#[must_use]
pub fn binary_weights(graph: &Graph) -> Vec<f64> {
    vec![1.0; graph.directed_edge_count()]
}

/// The spatial adjacency a_ij = f(‖q_j − q_i‖) of every directed edge of `net`.
///
/// The two directions of an edge carry bit-identical distances, so the weights are symmetric
/// (a_ij = a_ji) whatever `f`. Evaluated in parallel with the `parallel` feature (the result does
/// not depend on it).
///
/// # Example
/// ```
/// use flock_graph::{ProximityNet, weights_from_distances};
/// use glam::DVec2;
///
/// let net = ProximityNet::brute_force(&[DVec2::ZERO, DVec2::new(0.5, 0.0)], 1.0);
/// assert_eq!(weights_from_distances(&net, |d| 1.0 - d), vec![0.5, 0.5]);
/// ```
#[must_use]
pub fn weights_from_distances(net: &ProximityNet, f: impl Fn(f64) -> f64 + Sync) -> Vec<f64> {
    let distances = net.distances();
    let mut weights = vec![0.0; distances.len()];
    fill_indexed(&mut weights, |e| f(distances[e]));
    weights
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn smooth_weights_follow_the_distances() {
        let q = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(9.0, 9.0, 9.0),
        ];
        let net = ProximityNet::brute_force(&q, 2.5);
        let w = weights_from_distances(&net, |d| d * d);
        assert_eq!(w.len(), net.graph().directed_edge_count());
        for (wij, dij) in w.iter().zip(net.distances()) {
            assert_eq!(*wij, dij * dij);
        }
        assert_eq!(binary_weights(net.graph()).len(), w.len());
    }
}

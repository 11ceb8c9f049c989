//! Stress weights and signed friends of a net (Olfati-Saber, ACC 2004 (seed 000) eq. 26–37; the
//! TAC 2006 form of s_ij).
//!
//! The stress weights s_ij turn the gradient term of the (α, α) protocol into a weighted sum,
//! u_i^mp = Σ_{j∈N_i} s_ij (q_j − q_i) (eq. 27). Their signs split the neighbours into positive,
//! negative and neutral friends (eq. 28–30); the local stress S_i = Σ_j s_ij (eq. 31) and the
//! centres of neighbours and of friends (eq. 32, 34, 35) give Reynolds' rules a geometric reading:
//!
//! - S_i ≠ 0: u_i^mp = S_i (q_i^av − q_i) (eq. 33), towards or away from the centre of neighbours;
//! - S_i = 0: u_i^mp = S_i⁺ (q_i^av+ − q_i^av−) (eq. 37), from the centre of negative friends to that
//!   of positive friends.
//!
//! Entry points: [`StressWeights::from_distances`], [`StressWeights::motion_planning_term`],
//! [`StressWeights::friends`].

use flock_math::Vector;

use crate::adjacency::weights_from_distances;
use crate::graph::Graph;
use crate::net::ProximityNet;

/// The stress weights s_ij of a net, one per directed edge (aligned with
/// [`Graph::neighbour_indices`]); the graph is passed to each query.
///
/// # Example
/// ```
/// use flock_graph::{ProximityNet, StressWeights};
/// use glam::DVec2;
///
/// // Seed 000 eq. 26 with φ_α(z) = z and d_α = 1: s_ij = (‖q_j − q_i‖ − 1) / ‖q_j − q_i‖.
/// let q = [DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(0.0, 0.5)];
/// let net = ProximityNet::brute_force(&q, 2.5);
/// let s = StressWeights::from_distances(&net, |d| (d - 1.0) / d);
/// let g = net.graph();
/// assert_eq!(s.weights()[g.edge_range(0)], [0.5, -1.0]);
/// assert_eq!(s.local_stress(g, 0), -0.5);
/// let friends = s.friends(g, 0);
/// assert_eq!((friends.positive, friends.negative), (vec![1], vec![2]));
/// // u_0^mp = 0.5 (2, 0) − 1 (0, 0.5)
/// assert_eq!(s.motion_planning_term(g, 0, &q), DVec2::new(1.0, -0.5));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StressWeights {
    weights: Vec<f64>,
}

/// The signed friends of an agent i (eq. 28–30), each list ascending; together they partition N_i.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Friends {
    /// F_i⁺ = { j ∈ N_i : s_ij > 0 } (eq. 28).
    pub positive: Vec<u32>,
    /// F_i⁻ = { j ∈ N_i : s_ij < 0 } (eq. 29).
    pub negative: Vec<u32>,
    /// F_i⁰ = { j ∈ N_i : s_ij = 0 } (eq. 30) — unlike the paper, without i itself (i ∉ N_i here).
    /// Neighbours with a NaN weight are also put here, so the three lists always partition N_i.
    pub neutral: Vec<u32>,
}

impl StressWeights {
    /// s_ij = s(‖q_j − q_i‖) for every directed edge of `net`.
    ///
    /// The caller passes either φ_α(‖q‖ − d_α)/‖q‖ (seed 000 eq. 26) or φ_α(‖q‖_σ)/(1 + ε‖q‖_σ)
    /// (TAC 2006), as a function of the Euclidean distance ‖q‖. As eq. 26 prescribes, s_ij = 0 for
    /// coincident agents (distance 0) without calling `s`; this does not change u_i^mp, whose term
    /// s_ij (q_j − q_i) vanishes there anyway. Symmetric (s_ij = s_ji).
    #[must_use]
    pub fn from_distances(net: &ProximityNet, s: impl Fn(f64) -> f64 + Sync) -> Self {
        Self {
            weights: weights_from_distances(net, |d| if d > 0.0 { s(d) } else { 0.0 }),
        }
    }

    /// s_ij per directed edge.
    #[inline]
    #[must_use]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The neighbours j of `i` with their weights s_ij, ascending in j.
    fn edges<'a>(&'a self, graph: &'a Graph, i: usize) -> impl Iterator<Item = (usize, f64)> + 'a {
        graph
            .neighbours(i)
            .iter()
            .map(|&j| j as usize)
            .zip(self.weights[graph.edge_range(i)].iter().copied())
    }

    /// The local stress S_i = Σ_{j∈N_i} s_ij (eq. 31).
    #[must_use]
    pub fn local_stress(&self, graph: &Graph, i: usize) -> f64 {
        self.edges(graph, i).map(|(_, s)| s).sum()
    }

    /// The positive and negative parts (S_i⁺, S_i⁻) of the local stress: the sums of s_ij over
    /// F_i⁺ and F_i⁻ (eq. 31), S_i⁺ ≥ 0 ≥ S_i⁻.
    #[must_use]
    pub fn signed_local_stress(&self, graph: &Graph, i: usize) -> (f64, f64) {
        self.edges(graph, i).fold((0.0, 0.0), |(pos, neg), (_, s)| {
            if s > 0.0 {
                (pos + s, neg)
            } else if s < 0.0 {
                (pos, neg + s)
            } else {
                (pos, neg)
            }
        })
    }

    /// The positive, negative and neutral friends of `i` (eq. 28–30). The neutral friends exclude
    /// `i` itself, which the paper counts in F_i⁰.
    #[must_use]
    pub fn friends(&self, graph: &Graph, i: usize) -> Friends {
        let mut friends = Friends::default();
        for (j, s) in self.edges(graph, i) {
            let list = if s > 0.0 {
                &mut friends.positive
            } else if s < 0.0 {
                &mut friends.negative
            } else {
                &mut friends.neutral
            };
            list.push(j as u32);
        }
        friends
    }

    /// The centre of neighbours q_i^av = Σ_{j∈N_i} s_ij q_j / S_i (eq. 32), `None` when S_i = 0.
    #[must_use]
    pub fn centre_of_neighbours<V: Vector>(&self, graph: &Graph, i: usize, q: &[V]) -> Option<V> {
        let (sum, stress) = self.weighted_sum(graph, i, q, |_| true);
        (stress != 0.0).then(|| sum / stress)
    }

    /// The centres of positive and negative friends (q_i^av+, q_i^av−) =
    /// (Σ_{F_i⁺} s_ij q_j / S_i⁺, Σ_{F_i⁻} s_ij q_j / S_i⁻) (eq. 34, 35), each `None` when that set
    /// of friends is empty. Each lies in the convex hull of its friends.
    #[must_use]
    pub fn centres_of_friends<V: Vector>(
        &self,
        graph: &Graph,
        i: usize,
        q: &[V],
    ) -> (Option<V>, Option<V>) {
        let (positive, s_pos) = self.weighted_sum(graph, i, q, |s| s > 0.0);
        let (negative, s_neg) = self.weighted_sum(graph, i, q, |s| s < 0.0);
        (
            (s_pos != 0.0).then(|| positive / s_pos),
            (s_neg != 0.0).then(|| negative / s_neg),
        )
    }

    /// The motion-planning term u_i^mp = Σ_{j∈N_i} s_ij (q_j − q_i) (eq. 27).
    #[must_use]
    pub fn motion_planning_term<V: Vector>(&self, graph: &Graph, i: usize, q: &[V]) -> V {
        let qi = q[i];
        self.edges(graph, i)
            .fold(V::ZERO, |acc, (j, s)| acc + (q[j] - qi) * s)
    }

    /// (Σ s_ij q_j, Σ s_ij) over the neighbours j of `i` whose weight passes `keep`.
    fn weighted_sum<V: Vector>(
        &self,
        graph: &Graph,
        i: usize,
        q: &[V],
        keep: impl Fn(f64) -> bool,
    ) -> (V, f64) {
        self.edges(graph, i)
            .filter(|&(_, s)| keep(s))
            .fold((V::ZERO, 0.0), |(sum, stress), (j, s)| {
                (sum + q[j] * s, stress + s)
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn coincident_agents_have_zero_stress() {
        let q = [DVec2::ONE, DVec2::ONE];
        let net = ProximityNet::brute_force(&q, 1.0);
        assert_eq!(net.graph().undirected_edge_count(), 1);
        let s = StressWeights::from_distances(&net, |d| -1.0 / d);
        assert_eq!(s.weights(), &[0.0, 0.0]);
        let friends = s.friends(net.graph(), 0);
        assert_eq!(friends.neutral, vec![1]);
        assert_eq!(s.centre_of_neighbours(net.graph(), 0, &q), None);
        assert_eq!(s.motion_planning_term(net.graph(), 0, &q), DVec2::ZERO);
    }

    #[test]
    fn signed_local_stress_sums_to_local_stress() {
        let q = [
            DVec2::ZERO,
            DVec2::new(0.5, 0.0),
            DVec2::new(0.0, 1.5),
            DVec2::new(-2.0, 0.0),
        ];
        let net = ProximityNet::brute_force(&q, 3.0);
        let s = StressWeights::from_distances(&net, |d| d - 1.0);
        let (pos, neg) = s.signed_local_stress(net.graph(), 0);
        assert_eq!((pos, neg), (0.5 + 1.0, -0.5));
        assert_eq!(s.local_stress(net.graph(), 0), pos + neg);
    }
}

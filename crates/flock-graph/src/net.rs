//! [`ProximityNet`]: the proximity net G(q) of a configuration q (Olfati-Saber, IEEE TAC 51(3) 2006;
//! ACC 2004 (seed 000) eq. 2 with the 0/1 adjacency): the undirected graph with neighbour sets
//!
//! N_i = { j ≠ i : ‖q_j − q_i‖ < r },
//!
//! with the Euclidean distances of its edges. Build it in expected O(n) with
//! [`NeighbourSearch::build`](crate::NeighbourSearch::build); [`ProximityNet::brute_force`] is the
//! O(n²) reference it reproduces exactly.
//!
//! Both paths decide an edge with the same floating-point predicate, `(q_j − q_i).length_squared()
//! < r * r`, and take the distance as the square root of that same squared length, so the net
//! (neighbour order and distance bits) does not depend on the path that built it.
//! Agents with a NaN or infinite coordinate fail the predicate with every other agent: they have no
//! neighbours.

use flock_math::Vector;

use crate::graph::Graph;

/// A proximity net: the graph N_i = { j ≠ i : ‖q_j − q_i‖ < r } (strict) and the distance
/// ‖q_j − q_i‖ of every directed edge.
///
/// # Example
/// ```
/// use flock_graph::ProximityNet;
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(3.0, 0.0)];
/// let net = ProximityNet::brute_force(&q, 2.0);
/// assert_eq!(net.graph().neighbours(0), &[1]);
/// assert_eq!(net.graph().neighbours(1), &[0]); // ‖q_2 − q_1‖ = 2 is not < 2
/// assert_eq!(net.distances(), &[1.0, 1.0]);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ProximityNet {
    graph: Graph,
    /// ‖q_j − q_i‖ per directed edge, aligned with `graph.neighbour_indices()`.
    distances: Vec<f64>,
    /// The interaction range r.
    range: f64,
}

impl ProximityNet {
    /// The net of no agents, to be filled by
    /// [`NeighbourSearch::build`](crate::NeighbourSearch::build).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The graph of the net.
    #[inline]
    #[must_use]
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// ‖q_j − q_i‖ for every directed edge `i → j`, aligned with
    /// [`Graph::neighbour_indices`]; the two directions of an edge hold bit-identical values.
    #[inline]
    #[must_use]
    pub fn distances(&self) -> &[f64] {
        &self.distances
    }

    /// The range r the net was built with (0 for [`ProximityNet::new`]).
    #[inline]
    #[must_use]
    pub fn range(&self) -> f64 {
        self.range
    }

    /// The O(n²) reference: tests every ordered pair with the shared predicate.
    ///
    /// A range `r` that is not positive (or NaN) gives no edges.
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    #[must_use]
    pub fn brute_force<V: Vector>(positions: &[V], r: f64) -> Self {
        let mut net = Self::new();
        let r2 = range_squared(r);
        let (offsets, neighbours, distances) = net.clear_for_rebuild(positions.len(), r);
        for (i, &qi) in positions.iter().enumerate() {
            for (j, &qj) in positions.iter().enumerate() {
                let d2 = squared_distance(qi, qj);
                if j != i && in_range(d2, r2) {
                    neighbours.push(node_index(j));
                    distances.push(d2.sqrt());
                }
            }
            offsets.push(neighbours.len());
        }
        net
    }

    /// Empties the net for `n` agents and range `r`, keeping its allocations, and hands out the CSR
    /// arrays and the distances to be refilled (see `Graph::clear_for_rebuild`).
    ///
    /// # Panics
    /// When `n` exceeds `u32::MAX`.
    pub(crate) fn clear_for_rebuild(
        &mut self,
        n: usize,
        r: f64,
    ) -> (&mut Vec<usize>, &mut Vec<u32>, &mut Vec<f64>) {
        assert!(
            u32::try_from(n).is_ok(),
            "a proximity net holds at most {} agents, got {n}",
            u32::MAX
        );
        self.range = r;
        self.distances.clear();
        let (offsets, neighbours) = self.graph.clear_for_rebuild();
        offsets.reserve(n);
        (offsets, neighbours, &mut self.distances)
    }
}

/// r² as the predicate uses it: 0 (no edge passes) when `r` is not positive or is NaN.
#[inline]
#[must_use]
pub(crate) fn range_squared(r: f64) -> f64 {
    if r > 0.0 { r * r } else { 0.0 }
}

/// ‖q_j − q_i‖², bit-identical for (i, j) and (j, i) since IEEE subtraction is antisymmetric.
#[inline]
#[must_use]
pub(crate) fn squared_distance<V: Vector>(qi: V, qj: V) -> f64 {
    (qj - qi).length_squared()
}

/// The edge predicate ‖q_j − q_i‖² < r² (false for NaN).
#[inline]
#[must_use]
pub(crate) fn in_range(d2: f64, r2: f64) -> bool {
    d2 < r2
}

/// Agent index `j` as stored in the graph; lossless once the net checked `n ≤ u32::MAX`.
#[inline]
#[must_use]
pub(crate) fn node_index(j: usize) -> u32 {
    debug_assert!(u32::try_from(j).is_ok());
    j as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predicate_is_strict_and_rejects_nan() {
        assert!(in_range(0.0, 1.0));
        assert!(!in_range(1.0, 1.0));
        assert!(!in_range(f64::NAN, 1.0));
        assert!(!in_range(f64::INFINITY, f64::INFINITY));
        assert!(in_range(1e300, f64::INFINITY));
    }

    #[test]
    fn range_squared_of_non_positive_ranges_is_zero() {
        assert_eq!(range_squared(2.0), 4.0);
        assert_eq!(range_squared(0.0), 0.0);
        assert_eq!(range_squared(-3.0), 0.0);
        assert_eq!(range_squared(f64::NAN), 0.0);
        assert_eq!(range_squared(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn rebuild_resets_range_and_keeps_capacity() {
        let q = [glam::DVec2::ZERO, glam::DVec2::X, glam::DVec2::Y];
        let mut net = ProximityNet::brute_force(&q, 5.0);
        assert_eq!(net.graph().directed_edge_count(), 6);
        let capacity = net.distances.capacity();
        let (offsets, neighbours, distances) = net.clear_for_rebuild(0, 1.5);
        assert_eq!(offsets, &[0]);
        assert!(neighbours.is_empty());
        assert!(distances.is_empty());
        assert_eq!(distances.capacity(), capacity);
        assert_eq!(net.range(), 1.5);
        assert!(net.graph().is_empty());
    }
}

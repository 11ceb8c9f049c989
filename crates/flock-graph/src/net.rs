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
///
/// Two nets are equal when their graphs, distances, ranges and kinds are: the
/// [`ProximityNet::cell_layout`] is not compared.
#[derive(Clone, Debug, Default)]
pub struct ProximityNet {
    graph: Graph,
    /// ‖q_j − q_i‖ per directed edge, aligned with `graph.neighbour_indices()`; empty when
    /// `lean`.
    distances: Vec<f64>,
    /// The interaction range r.
    range: f64,
    /// True for a net that keeps no distances ([`ProximityNet::without_distances`]).
    lean: bool,
    /// The search's cell layout, when it laid the agents out (`laid_out`); its buffers are kept.
    layout: CellLayout,
    laid_out: bool,
}

/// The agents of a net in the order of the cells of the search that built it — each position in
/// that order a *slot* — with every agent's neighbours given as slots, still in ascending agent
/// index. Consecutive slots are near in space and share most of their neighbours, so a protocol
/// that copies the states into slot order and visits the slots reads its neighbours' states from
/// cache however the agents are numbered, and sums their terms in the net's order.
///
/// A [`NeighbourSearch`](crate::NeighbourSearch) lays a net out when the agents are numbered at
/// random (most neighbours of 256 sampled agents at least 4,096 indices away): agents numbered
/// along space are visited in index order with the same locality and no extra memory.
#[derive(Clone, Debug, Default)]
pub struct CellLayout {
    /// The agent in each slot: every agent with a finite position, once.
    order: Vec<u32>,
    /// The end of each slot's list in `neighbours`.
    ends: Vec<usize>,
    /// The neighbours of each slot, as slots, in ascending agent index.
    neighbours: Vec<u32>,
}

impl CellLayout {
    /// The agent in each slot.
    #[inline]
    #[must_use]
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// The neighbours of the agent in `slot`, as slots, in ascending agent index: the agents are
    /// `order[t]` for each slot t, the list of [`Graph::neighbours`]`(order[slot])`.
    #[inline]
    #[must_use]
    pub fn neighbours(&self, slot: usize) -> &[u32] {
        let start = if slot == 0 { 0 } else { self.ends[slot - 1] };
        &self.neighbours[start..self.ends[slot]]
    }

    /// Empties the layout for a rebuild, keeping its allocations.
    pub(crate) fn clear(&mut self) {
        self.order.clear();
        self.ends.clear();
        self.neighbours.clear();
    }

    /// Appends a slot-ordered run of lists: the agents `order`, the list ends `ends` (relative to
    /// `lists`) and the lists themselves.
    pub(crate) fn extend(&mut self, order: &[u32], ends: &[usize], lists: &[u32]) {
        let base = self.neighbours.len();
        self.order.extend_from_slice(order);
        self.ends.extend(ends.iter().map(|&end| base + end));
        self.neighbours
            .extend_from_slice(&lists[..ends.last().copied().unwrap_or(0)]);
    }
}

impl PartialEq for ProximityNet {
    fn eq(&self, other: &Self) -> bool {
        self.graph == other.graph
            && self.distances == other.distances
            && self.range == other.range
            && self.lean == other.lean
    }
}

impl ProximityNet {
    /// The net of no agents, to be filled by
    /// [`NeighbourSearch::build`](crate::NeighbourSearch::build).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The net of no agents, to be filled by
    /// [`NeighbourSearch::build`](crate::NeighbourSearch::build) with its graph only: it keeps no
    /// distances (8 bytes less per directed edge), [`ProximityNet::distances`] is empty and
    /// [`ProximityNet::edge_lengths`] recomputes them, bit-identically, from the positions.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use glam::DVec2;
    ///
    /// let q = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(3.0, 0.0)];
    /// let mut net = ProximityNet::without_distances();
    /// NeighbourSearch::new().build(&q, 2.0, &mut net);
    /// assert_eq!(net.graph().neighbours(0), &[1]);
    /// assert!(!net.has_distances() && net.distances().is_empty());
    /// assert_eq!(net.edge_lengths(&q).collect::<Vec<_>>(), [1.0, 1.0]);
    /// ```
    #[must_use]
    pub fn without_distances() -> Self {
        Self {
            lean: true,
            ..Self::default()
        }
    }

    /// False for a net made by [`ProximityNet::without_distances`], whose
    /// [`ProximityNet::distances`] is empty.
    #[inline]
    #[must_use]
    pub fn has_distances(&self) -> bool {
        !self.lean
    }

    /// ‖q_j − q_i‖ for every directed edge `i → j`, in the order of
    /// [`Graph::neighbour_indices`]: the stored [`ProximityNet::distances`], or, for a net without
    /// them, the same bits recomputed from `positions` (which must be the positions the net was
    /// built from; they are not read when the distances are stored).
    ///
    /// # Panics
    /// When the net has no distances and `positions` has fewer agents than the net.
    pub fn edge_lengths<'a, V: Vector>(
        &'a self,
        positions: &'a [V],
    ) -> impl Iterator<Item = f64> + 'a {
        let computed = self.lean.then(|| {
            assert!(
                positions.len() >= self.graph.len(),
                "{} positions for a net of {} agents",
                positions.len(),
                self.graph.len()
            );
            (0..self.graph.len()).flat_map(move |i| {
                let qi = positions[i];
                self.graph
                    .neighbours(i)
                    .iter()
                    .map(move |&j| squared_distance(qi, positions[j as usize]).sqrt())
            })
        });
        let stored = (!self.lean).then(|| self.distances.iter().copied());
        computed
            .into_iter()
            .flatten()
            .chain(stored.into_iter().flatten())
    }

    /// The graph of the net.
    #[inline]
    #[must_use]
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// ‖q_j − q_i‖ for every directed edge `i → j`, aligned with
    /// [`Graph::neighbour_indices`]; the two directions of an edge hold bit-identical values.
    /// Empty for a net made by [`ProximityNet::without_distances`] (see
    /// [`ProximityNet::edge_lengths`]).
    #[inline]
    #[must_use]
    pub fn distances(&self) -> &[f64] {
        &self.distances
    }

    /// The [`CellLayout`] of the search that built the net, when it laid the agents out (agents
    /// numbered at random); `None` otherwise, and for [`ProximityNet::brute_force`].
    #[inline]
    #[must_use]
    pub fn cell_layout(&self) -> Option<&CellLayout> {
        self.laid_out.then_some(&self.layout)
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
        let distances = distances.unwrap_or_else(|| unreachable!("a new net keeps distances"));
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
    /// arrays and, unless the net keeps none, the distances to be refilled (see
    /// `Graph::clear_for_rebuild`).
    ///
    /// # Panics
    /// When `n` exceeds `u32::MAX`.
    pub(crate) fn clear_for_rebuild(
        &mut self,
        n: usize,
        r: f64,
    ) -> (&mut Vec<usize>, &mut Vec<u32>, Option<&mut Vec<f64>>) {
        self.distances.clear();
        self.graph.clear_for_rebuild();
        let (offsets, neighbours, distances) = self.arrays_for_rebuild(n, r);
        offsets.reserve(n);
        (offsets, neighbours, distances)
    }
}

impl ProximityNet {
    /// The emptied [`CellLayout`] of a net just rebuilt, to be filled; the net then has it.
    pub(crate) fn layout_for_rebuild(&mut self) -> &mut CellLayout {
        self.laid_out = true;
        self.layout.clear();
        &mut self.layout
    }

    /// Sets the range of a net to be rebuilt for `n` agents and hands out its arrays as they are,
    /// to be resized and entirely overwritten: the CSR arrays and, unless the net keeps none, the
    /// distances (see `Graph::arrays_for_rebuild`).
    ///
    /// # Panics
    /// When `n` exceeds `u32::MAX`.
    pub(crate) fn arrays_for_rebuild(
        &mut self,
        n: usize,
        r: f64,
    ) -> (&mut Vec<usize>, &mut Vec<u32>, Option<&mut Vec<f64>>) {
        assert!(
            u32::try_from(n).is_ok(),
            "a proximity net holds at most {} agents, got {n}",
            u32::MAX
        );
        self.range = r;
        self.laid_out = false;
        let (offsets, neighbours) = self.graph.arrays_for_rebuild();
        (
            offsets,
            neighbours,
            (!self.lean).then_some(&mut self.distances),
        )
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
        let distances = distances.unwrap();
        assert!(distances.is_empty());
        assert_eq!(distances.capacity(), capacity);
        assert_eq!(net.range(), 1.5);
        assert!(net.graph().is_empty());
    }

    #[test]
    fn edge_lengths_of_both_kinds_of_nets_agree() {
        let q = [
            glam::DVec3::ZERO,
            glam::DVec3::new(0.3, -0.2, 0.1),
            glam::DVec3::new(1.0, 0.7, -0.4),
            glam::DVec3::new(0.3, -0.2, 0.1),
        ];
        let full = ProximityNet::brute_force(&q, 1.5);
        let mut lean = ProximityNet::without_distances();
        crate::NeighbourSearch::new().build(&q, 1.5, &mut lean);
        assert_eq!(lean.graph(), full.graph());
        assert!(lean.distances().is_empty() && !lean.has_distances());
        let bits =
            |net: &ProximityNet| -> Vec<u64> { net.edge_lengths(&q).map(f64::to_bits).collect() };
        assert_eq!(bits(&lean), bits(&full));
        assert_eq!(
            bits(&full),
            full.distances()
                .iter()
                .map(|d| d.to_bits())
                .collect::<Vec<_>>()
        );
    }
}

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
//!
//! A net may carry a [`Numbering`] of agents stored out of their original order (a simulation
//! that keeps them sorted in space): its lists are then storage indices in ascending *original*
//! index, so that sums over an agent's neighbours, added in original order
//! ([`Numbering::ordered_sum`]), have the bits of the same net in original order.

use flock_math::{Domain, Vector};

use crate::graph::Graph;
use crate::numbering::Numbering;

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
/// Two nets are equal when their graphs, distances, ranges, kinds and numberings are.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ProximityNet {
    graph: Graph,
    /// ‖q_j − q_i‖ per directed edge, aligned with `graph.neighbour_indices()`; empty when
    /// `lean`.
    distances: Vec<f64>,
    /// The interaction range r.
    range: f64,
    /// True for a net that keeps no distances ([`ProximityNet::without_distances`]).
    lean: bool,
    /// How the positions it is built from are stored; kept across rebuilds.
    numbering: Numbering,
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
    /// built from; they are not read when the distances are stored). For a net built in a
    /// periodic box, [`ProximityNet::edge_lengths_in`].
    ///
    /// # Panics
    /// When the net has no distances and `positions` has fewer agents than the net.
    pub fn edge_lengths<'a, V: Vector>(
        &'a self,
        positions: &'a [V],
    ) -> impl Iterator<Item = f64> + 'a {
        self.edge_lengths_in(&Domain::Open, positions)
    }

    /// The lengths ‖q_j − q_i‖ of agent `i`'s edges, in list order: stored or recomputed, as by
    /// [`ProximityNet::edge_lengths`].
    ///
    /// # Panics
    /// When `i` is not an agent of the net, or the net has no distances and `positions` has no
    /// agent `i` or one of its neighbours.
    pub fn lengths_of<'a, V: Vector>(
        &'a self,
        i: usize,
        positions: &'a [V],
    ) -> impl Iterator<Item = f64> + 'a {
        self.lengths_of_in(&Domain::Open, i, positions)
    }

    /// The edge lengths of a net built in `domain` (minimum-image distances on a torus, as
    /// [`NeighbourSearch::build_in`](crate::NeighbourSearch::build_in) stores them): the stored
    /// distances, or, for a net without them, the same bits recomputed from `positions`.
    /// [`Domain::Open`] is [`ProximityNet::edge_lengths`].
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(4.0, 4.0) };
    /// let q = [DVec2::new(0.5, 1.0), DVec2::new(3.5, 1.0)];
    /// let mut lean = ProximityNet::without_distances();
    /// NeighbourSearch::new().build_in(&torus, &q, 1.5, &mut lean);
    /// assert_eq!(lean.edge_lengths_in(&torus, &q).collect::<Vec<_>>(), [1.0, 1.0]);
    /// ```
    ///
    /// # Panics
    /// When the net has no distances and `positions` has fewer agents than the net.
    pub fn edge_lengths_in<'a, V: Vector>(
        &'a self,
        domain: &'a Domain<V>,
        positions: &'a [V],
    ) -> impl Iterator<Item = f64> + 'a {
        if self.lean {
            assert!(
                positions.len() >= self.graph.len(),
                "{} positions for a net of {} agents",
                positions.len(),
                self.graph.len()
            );
        }
        (0..self.graph.len()).flat_map(move |i| self.lengths_of_in(domain, i, positions))
    }

    /// The lengths of agent `i`'s edges in `domain`, in list order: stored or recomputed by
    /// minimum image, as by [`ProximityNet::edge_lengths_in`].
    ///
    /// # Panics
    /// As [`ProximityNet::lengths_of`].
    pub fn lengths_of_in<'a, V: Vector>(
        &'a self,
        domain: &'a Domain<V>,
        i: usize,
        positions: &'a [V],
    ) -> impl Iterator<Item = f64> + 'a {
        let graph = &self.graph;
        graph.edge_range(i).map(move |e| {
            if self.lean {
                let j = graph.neighbour_indices()[e] as usize;
                squared_distance_in(domain, positions[i], positions[j]).sqrt()
            } else {
                self.distances[e]
            }
        })
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

    /// How the agents of the positions the net is built from are stored: its lists hold storage
    /// indices in ascending original index. The identity unless set with
    /// [`ProximityNet::permute`].
    #[inline]
    #[must_use]
    pub fn numbering(&self) -> &Numbering {
        &self.numbering
    }

    /// Moves the agents as [`Numbering::permute`]`(order)` (the agent at storage index `order[s]`
    /// goes to s), for the positions the net will next be built from; the net is emptied until
    /// that rebuild, keeping its allocations.
    ///
    /// # Panics
    /// As [`Numbering::permute`].
    pub fn permute(&mut self, order: &[u32]) {
        self.numbering.permute(order);
        self.distances.clear();
        self.graph.clear_for_rebuild();
    }

    /// Gives the net the numbering of `other` (as [`Clone::clone_from`], reusing allocations, and
    /// only when the two differ: equal stamps are equal numberings); the net is emptied until its
    /// next rebuild.
    pub fn share_numbering(&mut self, other: &Self) {
        if self.numbering.stamp() != other.numbering.stamp() {
            self.numbering.clone_from(&other.numbering);
        }
        self.distances.clear();
        self.graph.clear_for_rebuild();
    }

    /// Whether most neighbours of 256 agents spread evenly over the storage indices are at least
    /// 4,096 indices away from them: the agents are not stored along space, so
    /// that reading their neighbours' states misses the caches (a simulation then sorts them by
    /// cell). Deterministic.
    #[must_use]
    pub fn is_scattered(&self) -> bool {
        let graph = &self.graph;
        let n = graph.len();
        let sampled = SAMPLED.min(n);
        let (mut near, mut far) = (0_usize, 0_usize);
        for s in 0..sampled {
            let i = s * n / sampled;
            for &j in graph.neighbours(i) {
                if (j as usize).abs_diff(i) >= SCATTERED {
                    far += 1;
                } else {
                    near += 1;
                }
            }
        }
        far > near
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

    /// The O(n²) reference in `domain`: tests every ordered pair with the shared predicate on the
    /// displacement [`Domain::displacement`] (the minimum image on a torus), and stores the square
    /// root of that same squared length. [`Domain::Open`] is [`ProximityNet::brute_force`].
    ///
    /// # Example
    /// ```
    /// use flock_graph::ProximityNet;
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let q = [DVec2::new(0.5, 0.5), DVec2::new(9.5, 9.5)];
    /// let net = ProximityNet::brute_force_in(&torus, &q, 2.0);
    /// assert_eq!(net.graph().neighbours(0), &[1]); // through the corner
    /// assert_eq!(net.distances()[0], 2.0_f64.sqrt());
    /// ```
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    #[must_use]
    pub fn brute_force_in<V: Vector>(domain: &Domain<V>, positions: &[V], r: f64) -> Self {
        if !domain.is_periodic() {
            return Self::brute_force(positions, r);
        }
        let mut net = Self::new();
        let r2 = range_squared(r);
        let (offsets, neighbours, distances) = net.clear_for_rebuild(positions.len(), r);
        let distances = distances.unwrap_or_else(|| unreachable!("a new net keeps distances"));
        for (i, &qi) in positions.iter().enumerate() {
            for (j, &qj) in positions.iter().enumerate() {
                let d2 = squared_distance_in(domain, qi, qj);
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
        let (offsets, neighbours, distances, _) = self.arrays_for_rebuild(n, r);
        offsets.reserve(n);
        (offsets, neighbours, distances)
    }
}

impl ProximityNet {
    /// Sets the range of a net to be rebuilt for `n` agents and hands out its arrays as they are,
    /// to be resized and entirely overwritten: the CSR arrays and, unless the net keeps none, the
    /// distances (see `Graph::arrays_for_rebuild`); and its numbering, which the lists follow.
    ///
    /// # Panics
    /// When `n` exceeds `u32::MAX`, or differs from the number of agents of a numbering other
    /// than the identity.
    #[allow(clippy::type_complexity)]
    pub(crate) fn arrays_for_rebuild(
        &mut self,
        n: usize,
        r: f64,
    ) -> (
        &mut Vec<usize>,
        &mut Vec<u32>,
        Option<&mut Vec<f64>>,
        &Numbering,
    ) {
        assert!(
            u32::try_from(n).is_ok(),
            "a proximity net holds at most {} agents, got {n}",
            u32::MAX
        );
        assert!(
            self.numbering.numbers(n),
            "{n} positions for a net whose numbering has another number of agents"
        );
        self.range = r;
        let (offsets, neighbours) = self.graph.arrays_for_rebuild();
        (
            offsets,
            neighbours,
            (!self.lean).then_some(&mut self.distances),
            &self.numbering,
        )
    }
}

/// Index distance beyond which a neighbour counts as scattered in memory (a quarter of a megabyte
/// of 2D positions and velocities away).
const SCATTERED: usize = 4096;

#[cfg(test)]
impl ProximityNet {
    /// The neighbours of the agent stored at `s`, by original index, in list order.
    pub(crate) fn named_neighbours(&self, s: usize) -> Vec<u32> {
        self.graph
            .neighbours(s)
            .iter()
            .map(|&t| self.numbering.original(t as usize) as u32)
            .collect()
    }
}

/// Agents sampled by [`ProximityNet::is_scattered`].
const SAMPLED: usize = 256;

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

/// ‖displacement(q_i, q_j)‖² in `domain`: the minimum image on a torus, bit-identical for (i, j)
/// and (j, i) (the minimum image is odd: rounding and `round` are symmetric), and
/// [`squared_distance`] bit for bit in open space.
#[inline]
#[must_use]
pub(crate) fn squared_distance_in<V: Vector>(domain: &Domain<V>, qi: V, qj: V) -> f64 {
    match domain {
        Domain::Open => squared_distance(qi, qj),
        Domain::Periodic { .. } => domain.displacement(qi, qj).length_squared(),
    }
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

    /// A shared numbering follows every permutation of its source, and stays equal to it when
    /// shared again without one.
    #[test]
    fn a_shared_numbering_follows_its_source() {
        let (mut source, mut copy) = (ProximityNet::new(), ProximityNet::new());
        for order in [[2, 0, 1, 3], [3, 2, 1, 0], [1, 0, 3, 2]] {
            source.permute(&order);
            copy.share_numbering(&source);
            assert_eq!(copy.numbering(), source.numbering());
            let kept = copy.numbering().clone();
            copy.share_numbering(&source);
            assert_eq!(copy.numbering(), &kept);
            assert_eq!(copy.numbering().stamp(), source.numbering().stamp());
        }
    }
}

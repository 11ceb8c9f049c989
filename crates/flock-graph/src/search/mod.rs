//! Fixed-radius neighbour search on a uniform cell grid, in open space and on a periodic box:
//! [`NeighbourSearch`] rebuilds a [`ProximityNet`] every step in expected O(n), and
//! [`nearest_pair_distance`] finds the closest pair of agents.
//!
//! The agents are bucketed by a counting sort into cells of side at least the range r, so every
//! neighbour of an agent lies in its own cell or one of the 3^m − 1 adjacent ones (across the
//! wrap on a torus). The lists are built agent by agent in cell order (so that consecutive agents
//! scan the same memory), each as agents sorted by neighbour index (original index, for a net with
//! a [`Numbering`](crate::Numbering)), into per-block buffers; they are then gathered in agent
//! order into the net as agent indices, each distance recomputed there with the predicate's own
//! squared length. The net is canonical: equal to [`ProximityNet::brute_force`] (on a torus
//! [`ProximityNet::brute_force_in`]) edge for edge and bit for bit (for a numbering, to the
//! brute-force net of the agents in original order, relabelled). With the `parallel` feature the
//! blocks are filled, and the net gathered, on the rayon pool; since the blocks and gather ranges
//! only partition the work, the net is identical with or without it, for any pool size.
//! [`NeighbourSearch::cell_order`] gives the cell order itself, for callers that store their
//! agents in it.
//!
//! One concept a file, each importing only those above it:
//! - `cells`: the agents of a grid sorted by cell, shared by both grids;
//! - `lists`: the lists in blocks of slots, their order, and the net assembled from them;
//! - `open_grid`, `open`: the grid over the agents' bounding box, and the search on it, whose
//!   lists are kept between builds while the agents stay within a skin (`skin`);
//! - `torus_grid`, `torus`: the grid of a periodic box with its cells across the wrap, and the
//!   search on it;
//! - this file: [`NeighbourSearch`], which holds both searches and dispatches on the domain.

mod cells;
mod lists;
mod open;
mod open_grid;
mod skin;
#[cfg(test)]
mod tests;
mod torus;
mod torus_grid;

use flock_math::{Domain, Vector};

use crate::net::{ProximityNet, node_index};
use open::OpenSearch;
use torus::TorusSearch;

/// Reusable fixed-radius neighbour search. Its buffers (and those of the nets it fills) are kept
/// between calls, so a warm search allocates nothing while the number of agents does not grow.
///
/// # Example
/// ```
/// use flock_graph::{NeighbourSearch, ProximityNet};
/// use glam::DVec3;
///
/// let q: Vec<DVec3> = (0..10).map(|k| DVec3::new(k as f64, 0.0, 0.0)).collect();
/// let mut search = NeighbourSearch::new();
/// let mut net = ProximityNet::new();
/// search.build(&q, 1.5, &mut net);
/// assert_eq!(net.graph().neighbours(4), &[3, 5]);
/// assert_eq!(net, ProximityNet::brute_force(&q, 1.5));
/// ```
#[derive(Clone, Debug, Default)]
pub struct NeighbourSearch {
    /// The search in open space.
    open: OpenSearch,
    /// The search on a periodic box.
    torus: TorusSearch,
}

impl NeighbourSearch {
    /// A search with empty buffers.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Rebuilds `net`, reusing its allocations, as the proximity net of `positions` with range `r`:
    /// N_i = { j ≠ i : ‖q_j − q_i‖ < r }.
    ///
    /// The result is identical to [`ProximityNet::brute_force`]`(positions, r)`: same neighbour
    /// order (ascending), bit-identical distances. A net with a [`Numbering`](crate::Numbering)
    /// keeps it, and lists each agent's neighbours in ascending original index. A range that is not positive (or NaN) gives no
    /// edges; an infinite range joins every pair of finite agents. Agents with a NaN or infinite
    /// coordinate have no neighbours (and do not panic). A net made by
    /// [`ProximityNet::without_distances`] gets the same graph and no distances.
    ///
    /// The search keeps the lists of its last full build, out to 1.1 r, and serves the next
    /// builds of the same number of agents, range and numbering from them while no agent has
    /// moved more than 0.05 r since (a simulation's agents, step after step): the same net, in
    /// about 0.6 of the time of a full build (10⁶ agents on a lattice).
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    pub fn build<V: Vector>(&mut self, positions: &[V], r: f64, net: &mut ProximityNet) {
        self.open.build(positions, r, net);
    }

    /// The agents with a finite position, in the order of the cells of side at least `r` of a
    /// grid over them (ascending index within a cell): agents near in that order are near in
    /// space. The order [`NeighbourSearch::build`] visits them in; its buffer is reused.
    pub fn cell_order<V: Vector>(&mut self, positions: &[V], r: f64) -> &[u32] {
        self.open.cell_order(positions, r)
    }

    /// The exact minimum distance over all pairs of finite agents, `None` when there are fewer
    /// than two: [`nearest_pair_distance`] reusing this search's buffers.
    #[must_use]
    pub fn nearest_pair_distance<V: Vector>(&mut self, positions: &[V]) -> Option<f64> {
        self.open.nearest_pair_distance(positions)
    }

    /// Rebuilds `net` as the proximity net of `positions` in `domain` with range `r`:
    /// N_i = { j ≠ i : ‖displacement(q_i, q_j)‖ < r }, the distance of a periodic box being the
    /// minimum image.
    ///
    /// [`Domain::Open`] is [`NeighbourSearch::build`], bit for bit. On a torus the positions must
    /// lie in the box [0, L) (wrapped with [`Domain::wrap`]); the net equals
    /// [`ProximityNet::brute_force_in`]`(domain, positions, r)`: same neighbour order (ascending
    /// index), the stored distances the bit-identical minimum-image distances, whatever the rayon
    /// pool size. The numbering is kept as by [`NeighbourSearch::build`] (lists in ascending
    /// original index). No side is required to exceed 2r: with sides below that, each pair is
    /// still joined once, by its minimum image. A range that is not positive gives no edges;
    /// agents with a non-finite coordinate have none.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let q = [DVec2::new(0.2, 5.0), DVec2::new(9.7, 5.0), DVec2::new(5.0, 5.0)];
    /// let mut net = ProximityNet::new();
    /// NeighbourSearch::new().build_in(&torus, &q, 1.0, &mut net);
    /// assert_eq!(net.graph().neighbours(0), &[1]); // across the wrap
    /// assert!((net.distances()[0] - 0.5).abs() < 1e-12);
    /// assert_eq!(net, ProximityNet::brute_force_in(&torus, &q, 1.0));
    /// ```
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    pub fn build_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        r: f64,
        net: &mut ProximityNet,
    ) {
        match domain {
            Domain::Open => self.build(positions, r, net),
            Domain::Periodic { size } => self.torus.build(domain, *size, positions, r, net),
        }
    }

    /// The number of edges {i, j} (i < j, agent indices) of the net that
    /// [`NeighbourSearch::build_in`]`(domain, positions, r, …)` builds for which `accept(i, j)`
    /// holds, counted pair by pair without building the net: memory O(n) whatever the agents'
    /// degree, where the net holds every list. For counts over dense nets, such as the crossings
    /// of a net's edges, whose midpoints can have thousands of neighbours each. The count is the
    /// same for any rayon pool size.
    ///
    /// `None`, before any pair is tested, when the grid's candidate pairs exceed `most_tests`:
    /// Σ over its cells c of n_c times the agents of c and of its adjacent cells (ordered pairs,
    /// each agent with itself included; about twice the pairs the count tests, and n² when every
    /// agent is within r of every other). A bound on the work for callers that must not hang on
    /// a crowd.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let q: Vec<DVec2> = (0..10).map(|k| DVec2::new(k as f64, 0.0)).collect();
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let mut search = NeighbourSearch::new();
    /// let all = usize::MAX;
    /// // the ring's 10 links
    /// assert_eq!(search.count_pairs_in(&torus, &q, 1.5, all, |_, _| true), Some(10));
    /// // in open space the line has 9 links, 5 of them from an even agent up
    /// let even = |i: usize, _| i % 2 == 0;
    /// assert_eq!(search.count_pairs_in(&Domain::Open, &q, 1.5, all, even), Some(5));
    /// // with a range of 20 every pair of the 10 agents is a candidate: 100 tests
    /// assert_eq!(search.count_pairs_in(&Domain::Open, &q, 20.0, 99, even), None);
    /// assert_eq!(search.count_pairs_in(&Domain::Open, &q, 20.0, 100, even), Some(25));
    /// ```
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    pub fn count_pairs_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        r: f64,
        most_tests: usize,
        accept: impl Fn(usize, usize) -> bool + Sync,
    ) -> Option<usize> {
        match domain {
            Domain::Open => self.open.count_pairs(positions, r, most_tests, &accept),
            Domain::Periodic { size } => self
                .torus
                .count_pairs(*size, positions, r, most_tests, &accept),
        }
    }

    /// The agents with a finite position in the order of the cells of `domain`'s grid for range
    /// `r` (ascending index within a cell): [`NeighbourSearch::cell_order`] in open space, and on
    /// a torus the order [`NeighbourSearch::build_in`] visits them in. Its buffer is reused.
    pub fn cell_order_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        r: f64,
    ) -> &[u32] {
        match domain {
            Domain::Open => self.open.cell_order(positions, r),
            Domain::Periodic { size } => self.torus.cell_order(*size, positions, r),
        }
    }

    /// Fills `out` (resized to `positions.len()`) with the distance from each agent to its nearest
    /// other agent in `domain` (minimum image on a torus): out_i = min_{j≠i} ‖displacement(q_i,
    /// q_j)‖ over the finite agents j, +∞ for an agent with no other finite agent (fewer than two,
    /// or a non-finite position).
    ///
    /// Exact, bit-identical to the minimum of the brute-force distances, whatever the thread count:
    /// a cell grid with a growing reach, starting at the mean spacing of the agents, each pass
    /// searching only the agents not yet settled (expected O(n) for agents of bounded density;
    /// isolated agents cost more passes, never a wrong answer).
    ///
    /// # Example
    /// ```
    /// use flock_graph::NeighbourSearch;
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let q = [DVec2::new(0.5, 5.0), DVec2::new(9.5, 5.0), DVec2::new(3.5, 1.0)];
    /// let mut d = Vec::new();
    /// NeighbourSearch::new().nearest_distances_in(&torus, &q, &mut d);
    /// assert_eq!(d[..2], [1.0, 1.0]);
    /// NeighbourSearch::new().nearest_distances_in(&Domain::Open, &q, &mut d);
    /// assert_eq!(d[0], 5.0);
    /// ```
    pub fn nearest_distances_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        out: &mut Vec<f64>,
    ) {
        let n = positions.len();
        out.clear();
        out.resize(n, f64::INFINITY);
        let finite = positions.iter().filter(|q| q.is_finite()).count();
        if finite < 2 {
            return;
        }
        // The largest squared distance between finite agents (bounded by the box's half
        // diagonal on a torus, by the bounding box's diagonal in open space), and a first reach.
        let (lo, hi) = positions.iter().filter(|q| q.is_finite()).fold(
            (None::<V>, None::<V>),
            |(lo, hi), &q| {
                (
                    Some(lo.map_or(q, |l| l.min(q))),
                    Some(hi.map_or(q, |h| h.max(q))),
                )
            },
        );
        let (lo, hi) = (lo.unwrap_or(V::ZERO), hi.unwrap_or(V::ZERO));
        let extent = match domain {
            Domain::Open => hi - lo,
            Domain::Periodic { size } => V::from_fn(|k| {
                (hi.coord(k) - lo.coord(k))
                    .min(size.coord(k) / 2.0)
                    .max(0.0)
            }),
        };
        let diameter = extent.length();
        let volume = (0..V::DIM)
            .map(|k| extent.coord(k))
            .filter(|&e| e > 0.0)
            .fold(1.0, |v, e| v * e);
        let mut reach = (volume / finite as f64).powf(1.0 / V::DIM as f64);
        if !(reach > 0.0 && reach.is_finite()) || reach > diameter {
            reach = diameter;
        }
        let mut pending: Vec<u32> = (0..n)
            .filter(|&i| positions[i].is_finite())
            .map(node_index)
            .collect();
        loop {
            // the last pass: every pair is a candidate, any distance is accepted
            let last = reach >= diameter || !reach.is_finite();
            let threshold = if last { f64::INFINITY } else { reach * reach };
            let grid_reach = if last { f64::INFINITY } else { reach };
            let mut found = vec![f64::INFINITY; pending.len()];
            match domain {
                Domain::Open => {
                    self.open
                        .nearest(positions, grid_reach, threshold, &pending, &mut found);
                }
                Domain::Periodic { size } => {
                    self.torus.nearest(
                        *size, positions, grid_reach, threshold, &pending, &mut found,
                    );
                }
            }
            let mut still = Vec::new();
            for (&i, &d2) in pending.iter().zip(&found) {
                if d2.is_finite() {
                    out[i as usize] = d2.sqrt();
                } else {
                    still.push(i);
                }
            }
            pending = still;
            if pending.is_empty() || last {
                return;
            }
            reach = (2.0 * reach).min(diameter);
        }
    }
}

/// The exact minimum distance min_{i≠j} ‖q_j − q_i‖ over all pairs of finite agents (agents with
/// a NaN or infinite coordinate are ignored), `None` when there are fewer than two.
///
/// Grid search with a growing radius: expected O(n) for agents spread with a bounded density
/// (degenerate clusters may cost more, never a wrong answer). The value is bit-identical to the
/// minimum of `(q_j − q_i).length()` over all pairs. Used for the minimum-distance metric when the
/// proximity net has no edges.
///
/// # Example
/// ```
/// use flock_graph::nearest_pair_distance;
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(10.0, 0.0), DVec2::new(10.0, 3.0)];
/// assert_eq!(nearest_pair_distance(&q), Some(3.0));
/// assert_eq!(nearest_pair_distance(&q[..1]), None);
/// ```
#[must_use]
pub fn nearest_pair_distance<V: Vector>(positions: &[V]) -> Option<f64> {
    NeighbourSearch::new().nearest_pair_distance(positions)
}

//! [`Graph`]: an undirected graph on agents `0..n` in compressed sparse row (CSR) form.
//!
//! Every undirected edge `{i, j}` is stored twice, as the directed edges `i → j` and `j → i`, and
//! each agent's neighbour list is sorted ascending. The directed edges are numbered
//! `0..directed_edge_count()` in the order of [`Graph::neighbour_indices`]; per-edge arrays
//! (adjacency weights, stress weights, distances) are aligned with that numbering, and
//! [`Graph::edge_range`] gives the slice of agent `i`.

use core::fmt;
use core::ops::Range;

/// An undirected graph on the nodes `0..n`, in CSR form, each edge stored in both directions.
///
/// Node `i`'s neighbours are `neighbour_indices()[offsets()[i]..offsets()[i + 1]]`, sorted ascending,
/// never containing `i` itself.
///
/// # Example
/// ```
/// use flock_graph::Graph;
///
/// let g = Graph::from_edges(4, &[(0, 1), (2, 1), (1, 0)]).unwrap();
/// assert_eq!(g.len(), 4);
/// assert_eq!(g.neighbours(1), &[0, 2]);
/// assert_eq!(g.neighbours(3), &[] as &[u32]);
/// assert_eq!(g.undirected_edge_count(), 2);
/// assert_eq!(g.edge_range(1), 1..3);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Graph {
    /// `offsets[i]..offsets[i + 1]` are the directed edges of node `i`; `len() + 1` entries.
    offsets: Vec<usize>,
    /// Heads of the directed edges, grouped by tail, ascending within a group.
    neighbours: Vec<u32>,
}

impl Default for Graph {
    /// The graph with no nodes.
    fn default() -> Self {
        Self::empty(0)
    }
}

impl Graph {
    /// The graph on `n` nodes without edges.
    #[must_use]
    pub fn empty(n: usize) -> Self {
        Self {
            offsets: vec![0; n + 1],
            neighbours: Vec::new(),
        }
    }

    /// A fixed graph on `n` nodes from a list of undirected edges (e.g. the user-given topology of
    /// the Tanner–Jadbabaie–Pappas law).
    ///
    /// Duplicated edges, in either orientation, are merged.
    ///
    /// # Errors
    /// [`GraphError::SelfLoop`] for an edge `(i, i)`, [`GraphError::OutOfRange`] for an endpoint
    /// `≥ n`, [`GraphError::TooManyNodes`] when `n` does not fit the `u32` node indices. The first
    /// offending edge of the list is reported.
    pub fn from_edges(n: usize, edges: &[(usize, usize)]) -> Result<Self, GraphError> {
        if u32::try_from(n).is_err() {
            return Err(GraphError::TooManyNodes { n });
        }
        let mut directed = Vec::with_capacity(2 * edges.len());
        for (index, &(i, j)) in edges.iter().enumerate() {
            if i >= n || j >= n {
                return Err(GraphError::OutOfRange {
                    index,
                    edge: (i, j),
                    n,
                });
            }
            if i == j {
                return Err(GraphError::SelfLoop { index, node: i });
            }
            // Both endpoints are < n ≤ u32::MAX, so the casts are lossless.
            directed.push((i as u32, j as u32));
            directed.push((j as u32, i as u32));
        }
        directed.sort_unstable();
        directed.dedup();
        let mut offsets = vec![0; n + 1];
        for &(i, _) in &directed {
            offsets[i as usize + 1] += 1;
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let neighbours = directed.into_iter().map(|(_, j)| j).collect();
        Ok(Self {
            offsets,
            neighbours,
        })
    }

    /// The graph of agents stored as `numbering` says (node s is agent `numbering.original(s)`,
    /// each list in ascending original index, as a [`ProximityNet`](crate::ProximityNet) built
    /// with a numbering lists them) relabelled by original index: node k is agent k. The graph
    /// itself (a copy) for the identity.
    #[must_use]
    pub fn in_original_order(&self, numbering: &crate::Numbering) -> Self {
        if numbering.is_identity() {
            return self.clone();
        }
        let mut offsets = Vec::with_capacity(self.offsets.len());
        let mut neighbours = Vec::with_capacity(self.neighbours.len());
        offsets.push(0);
        for s in numbering.stored_of(0..self.len()) {
            neighbours.extend(
                self.neighbours(s)
                    .iter()
                    .map(|&j| numbering.original(j as usize) as u32),
            );
            offsets.push(neighbours.len());
        }
        Self {
            offsets,
            neighbours,
        }
    }

    /// Number of nodes n.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// True when the graph has no nodes.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The neighbours N_i of node `i`, ascending. Panics when `i >= len()`.
    #[inline]
    #[must_use]
    pub fn neighbours(&self, i: usize) -> &[u32] {
        &self.neighbours[self.edge_range(i)]
    }

    /// The degree |N_i| of node `i`. Panics when `i >= len()`.
    #[inline]
    #[must_use]
    pub fn degree(&self, i: usize) -> usize {
        self.offsets[i + 1] - self.offsets[i]
    }

    /// The indices of the directed edges `i → j`, `j ∈ N_i`, into the per-edge arrays.
    /// Panics when `i >= len()`.
    #[inline]
    #[must_use]
    pub fn edge_range(&self, i: usize) -> Range<usize> {
        self.offsets[i]..self.offsets[i + 1]
    }

    /// The CSR offsets: `len() + 1` non-decreasing entries, from 0 to `directed_edge_count()`.
    #[inline]
    #[must_use]
    pub fn offsets(&self) -> &[usize] {
        &self.offsets
    }

    /// The heads of all directed edges, grouped by tail node, ascending within each group.
    #[inline]
    #[must_use]
    pub fn neighbour_indices(&self) -> &[u32] {
        &self.neighbours
    }

    /// Number of directed edges, Σ_i |N_i| (twice the number of undirected edges).
    #[inline]
    #[must_use]
    pub fn directed_edge_count(&self) -> usize {
        self.neighbours.len()
    }

    /// Number of undirected edges |E|.
    #[inline]
    #[must_use]
    pub fn undirected_edge_count(&self) -> usize {
        self.neighbours.len() / 2
    }

    /// Empties the graph and sets its node count to `n` through the returned CSR arrays, keeping
    /// their allocations: `offsets` is `[0]` and `neighbours` is empty. The caller pushes one
    /// offset per node; the result must satisfy the invariants of [`Graph`].
    pub(crate) fn clear_for_rebuild(&mut self) -> (&mut Vec<usize>, &mut Vec<u32>) {
        self.offsets.clear();
        self.offsets.push(0);
        self.neighbours.clear();
        (&mut self.offsets, &mut self.neighbours)
    }

    /// The CSR arrays as they are, to be resized and entirely overwritten (resizing keeps the old
    /// entries, so only growth is initialised); the caller restores the invariants of [`Graph`].
    pub(crate) fn arrays_for_rebuild(&mut self) -> (&mut Vec<usize>, &mut Vec<u32>) {
        (&mut self.offsets, &mut self.neighbours)
    }
}

/// Why [`Graph::from_edges`] rejected an edge list.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GraphError {
    /// The edge `(node, node)` joins a node to itself.
    SelfLoop {
        /// Position of the edge in the list.
        index: usize,
        /// The node.
        node: usize,
    },
    /// An endpoint of the edge is not a node of the graph.
    OutOfRange {
        /// Position of the edge in the list.
        index: usize,
        /// The edge as given.
        edge: (usize, usize),
        /// Number of nodes of the graph.
        n: usize,
    },
    /// The node count exceeds the `u32` node indices.
    TooManyNodes {
        /// The requested node count.
        n: usize,
    },
}

impl fmt::Display for GraphError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::SelfLoop { index, node } => {
                write!(
                    f,
                    "edge #{index} ({node}, {node}) is a self-loop on node {node}"
                )
            }
            Self::OutOfRange {
                index,
                edge: (i, j),
                n,
            } => {
                let bad = if i >= n { i } else { j };
                write!(
                    f,
                    "edge #{index} ({i}, {j}) has endpoint {bad} out of range for a graph of {n} nodes \
                     (valid nodes are 0..{n})"
                )
            }
            Self::TooManyNodes { n } => {
                write!(
                    f,
                    "{n} nodes exceed the maximum of {} (node indices are u32)",
                    u32::MAX
                )
            }
        }
    }
}

impl std::error::Error for GraphError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_empty_with_valid_offsets() {
        let g = Graph::default();
        assert!(g.is_empty());
        assert_eq!(g.offsets(), &[0]);
        assert_eq!(g.directed_edge_count(), 0);
    }

    #[test]
    fn clear_for_rebuild_keeps_capacity() {
        let mut g = Graph::from_edges(5, &[(0, 1), (1, 2), (3, 4)]).unwrap();
        let capacity = g.neighbours.capacity();
        let (offsets, neighbours) = g.clear_for_rebuild();
        assert_eq!(offsets, &[0]);
        assert!(neighbours.is_empty());
        assert_eq!(neighbours.capacity(), capacity);
        assert!(g.is_empty());
    }

    #[test]
    fn empty_has_isolated_nodes() {
        let g = Graph::empty(3);
        assert_eq!(g.len(), 3);
        for i in 0..3 {
            assert!(g.neighbours(i).is_empty());
            assert_eq!(g.degree(i), 0);
        }
    }
}

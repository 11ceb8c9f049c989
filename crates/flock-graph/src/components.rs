//! Connected components of a net: the flocks F_1, …, F_k of a configuration, and the density
//! δ₀ = max_k |F_k| / n of the net (Olfati-Saber, Flocking with Obstacle Avoidance (seed 004),
//! eq. 7). A flock is a connected net (ACC 2004 (seed 000)).
//!
//! [`Components::of`] runs union-find (path compression, union by rank) over the edges: O(|E| α(n)).

use crate::graph::Graph;

/// The connected components of a graph, labelled canonically: component 0 contains node 0, and
/// components are numbered in the order of their smallest node.
///
/// # Example
/// ```
/// use flock_graph::{Components, Graph};
///
/// let g = Graph::from_edges(5, &[(3, 1), (0, 4)]).unwrap();
/// let c = Components::of(&g);
/// assert_eq!(c.count(), 3);
/// assert_eq!(c.labels(), &[0, 1, 2, 1, 0]);
/// assert_eq!(c.sizes(), &[2, 2, 1]);
/// assert_eq!(c.giant_share(), 0.4);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Components {
    labels: Vec<u32>,
    sizes: Vec<usize>,
}

impl Components {
    /// The components of `graph`.
    #[must_use]
    pub fn of(graph: &Graph) -> Self {
        let n = graph.len();
        let mut sets = DisjointSets::new(n);
        for i in 0..n {
            for &j in graph.neighbours(i) {
                if j as usize > i {
                    sets.union(i, j as usize);
                }
            }
        }
        // Label the roots in order of first appearance, i.e. of their component's smallest node.
        // A root's label is kept at its own place until the root itself is labelled (with the
        // same label), so that no second array of n labels is needed.
        let mut labels = vec![u32::MAX; n];
        let mut sizes = Vec::new();
        for i in 0..n {
            let root = sets.find(i);
            if labels[root] == u32::MAX {
                labels[root] = sizes.len() as u32;
                sizes.push(0);
            }
            let label = labels[root];
            sizes[label as usize] += 1;
            labels[i] = label;
        }
        Self { labels, sizes }
    }

    /// The number k of components (0 for the empty graph).
    #[inline]
    #[must_use]
    pub fn count(&self) -> usize {
        self.sizes.len()
    }

    /// The component of each node, in `0..count()`, numbered in order of their smallest node.
    #[inline]
    #[must_use]
    pub fn labels(&self) -> &[u32] {
        &self.labels
    }

    /// The population |F_k| of each component, indexed by label.
    #[inline]
    #[must_use]
    pub fn sizes(&self) -> &[usize] {
        &self.sizes
    }

    /// True when the graph is one flock: exactly one component (false for the empty graph).
    #[inline]
    #[must_use]
    pub fn is_connected(&self) -> bool {
        self.count() == 1
    }

    /// The population max_k |F_k| of the largest component (0 for the empty graph).
    #[inline]
    #[must_use]
    pub fn giant_size(&self) -> usize {
        self.sizes.iter().copied().max().unwrap_or(0)
    }

    /// The density δ₀ = max_k |F_k| / Σ_k |F_k| of the net (seed 004 eq. 7): 1 for a flock, close
    /// to 1 for a quasi-flock. Defined as 0 for the empty graph (no agents, no flock).
    #[inline]
    #[must_use]
    pub fn giant_share(&self) -> f64 {
        if self.labels.is_empty() {
            0.0
        } else {
            self.giant_size() as f64 / self.labels.len() as f64
        }
    }
}

/// Union-find over `0..n` (n ≤ 2³², node indices being `u32`) with path compression and union by
/// rank: 5 bytes per node.
struct DisjointSets {
    parent: Vec<u32>,
    /// An upper bound on the height of each root's tree (≤ log₂ n).
    rank: Vec<u8>,
}

impl DisjointSets {
    fn new(n: usize) -> Self {
        assert!(
            n <= 1 << 32,
            "{n} nodes exceed the u32 node indices of a graph"
        );
        Self {
            // i < n ≤ 2³²
            parent: (0..n).map(|i| i as u32).collect(),
            rank: vec![0; n],
        }
    }

    /// The root of `x`'s set; every node on the path is re-attached to the root.
    fn find(&mut self, x: usize) -> usize {
        let mut root = x;
        while self.parent[root] as usize != root {
            root = self.parent[root] as usize;
        }
        let mut node = x;
        while self.parent[node] as usize != root {
            let next = self.parent[node] as usize;
            // root < n ≤ 2³²
            self.parent[node] = root as u32;
            node = next;
        }
        root
    }

    /// Merges the sets of `a` and `b`, the lower tree under the higher.
    fn union(&mut self, a: usize, b: usize) {
        let (mut a, mut b) = (self.find(a), self.find(b));
        if a == b {
            return;
        }
        if self.rank[a] < self.rank[b] {
            core::mem::swap(&mut a, &mut b);
        }
        // a < n ≤ 2³²
        self.parent[b] = a as u32;
        if self.rank[a] == self.rank[b] {
            self.rank[a] += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn find_compresses_paths() {
        let mut sets = DisjointSets::new(4);
        // Build the chain 3 → 2 → 1 → 0 by hand, then find from its tail.
        sets.parent = vec![0, 0, 1, 2];
        assert_eq!(sets.find(3), 0);
        assert_eq!(sets.parent, vec![0, 0, 0, 0]);
    }

    #[test]
    fn union_hangs_the_lower_tree_under_the_higher() {
        let mut sets = DisjointSets::new(5);
        sets.union(3, 4);
        let pair = sets.find(4);
        assert_eq!(sets.rank[pair], 1);
        sets.union(2, 3);
        assert_eq!(sets.find(2), pair, "a single node goes under the pair");
        assert_eq!(sets.rank[pair], 1);
        sets.union(0, 2);
        let root = sets.find(4);
        assert_eq!(root, pair);
        assert_eq!(sets.find(0), root);
        assert_ne!(sets.find(1), root);
    }

    #[test]
    fn empty_graph_has_no_components() {
        let c = Components::of(&Graph::empty(0));
        assert_eq!(c.count(), 0);
        assert_eq!(c.giant_size(), 0);
        assert_eq!(c.giant_share(), 0.0);
        assert!(!c.is_connected());
    }
}

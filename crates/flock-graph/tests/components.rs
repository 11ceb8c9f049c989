//! Connected components: known graphs, canonical labels, densities, and a BFS reference.

use std::collections::VecDeque;

use flock_graph::{Components, Graph};
use rand::RngExt;

use crate::common::rng;

/// A graph made of paths with the given populations, nodes numbered path after path.
fn paths(populations: &[usize]) -> Graph {
    let mut edges = Vec::new();
    let mut first = 0;
    for &size in populations {
        edges.extend((first..first + size - 1).map(|i| (i, i + 1)));
        first += size;
    }
    Graph::from_edges(first, &edges).unwrap()
}

/// Canonical labels by breadth-first search from the smallest unlabelled node.
fn bfs_labels(g: &Graph) -> Vec<u32> {
    let mut labels = vec![u32::MAX; g.len()];
    let mut next = 0;
    for start in 0..g.len() {
        if labels[start] != u32::MAX {
            continue;
        }
        labels[start] = next;
        let mut queue = VecDeque::from([start]);
        while let Some(i) = queue.pop_front() {
            for &j in g.neighbours(i) {
                if labels[j as usize] == u32::MAX {
                    labels[j as usize] = next;
                    queue.push_back(j as usize);
                }
            }
        }
        next += 1;
    }
    labels
}

#[test]
fn known_small_graphs() {
    let c = Components::of(&Graph::empty(4));
    assert_eq!(
        (c.count(), c.labels(), c.sizes()),
        (4, &[0, 1, 2, 3][..], &[1, 1, 1, 1][..])
    );
    assert_eq!(c.giant_share(), 0.25);

    // A cycle is one flock.
    let cycle = Graph::from_edges(5, &[(0, 1), (1, 2), (2, 3), (3, 4), (4, 0)]).unwrap();
    let c = Components::of(&cycle);
    assert!(c.is_connected());
    assert_eq!((c.count(), c.giant_size(), c.giant_share()), (1, 5, 1.0));

    // Two triangles interleaved: {0, 2, 4} and {1, 3, 5}; label 0 is the component of node 0.
    let g = Graph::from_edges(7, &[(4, 2), (2, 0), (0, 4), (5, 3), (3, 1), (1, 5)]).unwrap();
    let c = Components::of(&g);
    assert_eq!(c.labels(), &[0, 1, 0, 1, 0, 1, 2]);
    assert_eq!(c.sizes(), &[3, 3, 1]);
    assert!(!c.is_connected());

    // Labels follow the smallest node, whatever the edge order.
    let g = Graph::from_edges(4, &[(3, 2), (1, 3)]).unwrap();
    assert_eq!(Components::of(&g).labels(), &[0, 1, 1, 1]);
}

#[test]
fn densities_of_the_tac_slides() {
    // "5 components with population 1, 1, 1, 1, 96": density 0.96.
    let c = Components::of(&paths(&[1, 1, 96, 1, 1]));
    assert_eq!(c.count(), 5);
    assert_eq!(c.giant_size(), 96);
    assert_eq!(c.sizes(), &[1, 1, 96, 1, 1]);
    assert_eq!(c.giant_share(), 0.96);
    // "5 components with population 20, 20, 20, 20, 20": density 0.2.
    let c = Components::of(&paths(&[20; 5]));
    assert_eq!(c.count(), 5);
    assert_eq!(c.giant_share(), 0.2);
    // No agents: no flock.
    assert_eq!(Components::of(&Graph::empty(0)).giant_share(), 0.0);
}

#[test]
fn union_find_agrees_with_breadth_first_search() {
    let mut rng = rng(5);
    for _ in 0..100 {
        let n = rng.random_range(0..200usize);
        let m = rng.random_range(0..=n);
        let edges: Vec<(usize, usize)> = (0..m)
            .map(|_| (rng.random_range(0..n), rng.random_range(0..n)))
            .filter(|(i, j)| i != j)
            .collect();
        let g = Graph::from_edges(n, &edges).unwrap();
        let c = Components::of(&g);
        let labels = bfs_labels(&g);
        assert_eq!(c.labels(), labels.as_slice());
        assert_eq!(c.sizes().iter().sum::<usize>(), n);
        for (label, &size) in c.sizes().iter().enumerate() {
            assert_eq!(
                labels.iter().filter(|&&l| l as usize == label).count(),
                size
            );
        }
    }
}

//! `Graph`: construction from edge lists, CSR invariants and error messages.

use flock_graph::{Graph, GraphError};
use rand::RngExt;

use crate::common::rng;

#[test]
fn duplicates_in_either_orientation_are_merged() {
    let g = Graph::from_edges(4, &[(0, 1), (1, 0), (0, 1), (3, 0), (2, 3), (0, 3)]).unwrap();
    assert_eq!(g.undirected_edge_count(), 3);
    assert_eq!(g.directed_edge_count(), 6);
    assert_eq!(g.neighbours(0), &[1, 3]);
    assert_eq!(g.neighbours(3), &[0, 2]);
    assert_eq!(g.offsets(), &[0, 2, 3, 4, 6]);
    assert_eq!(g.neighbour_indices(), &[1, 3, 0, 3, 0, 2]);
    assert_eq!(g.edge_range(3), 4..6);
    assert_eq!(g.degree(0), 2);
}

#[test]
fn empty_graphs() {
    let g = Graph::from_edges(0, &[]).unwrap();
    assert!(g.is_empty());
    assert_eq!(g, Graph::empty(0));
    let g = Graph::from_edges(3, &[]).unwrap();
    assert_eq!((g.len(), g.directed_edge_count()), (3, 0));
    assert_eq!(g, Graph::empty(3));
}

#[test]
fn self_loop_is_rejected_with_the_edge_named() {
    let err = Graph::from_edges(5, &[(0, 1), (2, 2)]).unwrap_err();
    assert_eq!(err, GraphError::SelfLoop { index: 1, node: 2 });
    let message = err.to_string();
    assert!(
        message.contains("edge #1") && message.contains("(2, 2)") && message.contains("self-loop"),
        "{message}"
    );
}

#[test]
fn out_of_range_endpoint_is_rejected_with_the_edge_named() {
    let err = Graph::from_edges(3, &[(0, 1), (1, 2), (2, 7)]).unwrap_err();
    assert_eq!(
        err,
        GraphError::OutOfRange {
            index: 2,
            edge: (2, 7),
            n: 3
        }
    );
    let message = err.to_string();
    assert!(
        message.contains("edge #2") && message.contains("(2, 7)"),
        "{message}"
    );
    assert!(
        message.contains("endpoint 7") && message.contains("3 nodes"),
        "{message}"
    );
    // The first endpoint is named when it is the offending one; range is checked before loops.
    let message = Graph::from_edges(2, &[(9, 9)]).unwrap_err().to_string();
    assert!(
        message.contains("endpoint 9") && message.contains("edge #0"),
        "{message}"
    );
    // It is a std error.
    let boxed: Box<dyn std::error::Error> = Box::new(err);
    assert!(boxed.to_string().contains("out of range"));
}

#[test]
fn random_edge_lists_give_symmetric_sorted_csr() {
    let mut rng = rng(9);
    for _ in 0..50 {
        let n = rng.random_range(1..60usize);
        let edges: Vec<(usize, usize)> = (0..3 * n)
            .map(|_| (rng.random_range(0..n), rng.random_range(0..n)))
            .filter(|(i, j)| i != j)
            .collect();
        let g = Graph::from_edges(n, &edges).unwrap();
        assert_eq!(g.offsets().len(), n + 1);
        assert_eq!(*g.offsets().last().unwrap(), g.directed_edge_count());
        assert_eq!(g.directed_edge_count(), 2 * g.undirected_edge_count());
        for i in 0..n {
            let list = g.neighbours(i);
            assert!(
                list.windows(2).all(|w| w[0] < w[1]),
                "sorted, no duplicates"
            );
            assert!(!list.contains(&(i as u32)));
            for &j in list {
                assert!(
                    g.neighbours(j as usize).binary_search(&(i as u32)).is_ok(),
                    "symmetric"
                );
                assert!(edges.contains(&(i, j as usize)) || edges.contains(&(j as usize, i)));
            }
        }
        for &(i, j) in &edges {
            assert!(g.neighbours(i).contains(&(j as u32)));
        }
    }
}

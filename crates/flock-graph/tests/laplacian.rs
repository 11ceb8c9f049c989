//! The Laplacian L̂ = L ⊗ I_m: sum-of-squares identity, kernel, and rank(L) = n − #components.

use approx::assert_relative_eq;
use flock_graph::{
    Components, Graph, ProximityNet, binary_weights, laplacian_apply, laplacian_quadratic_form,
    weights_from_distances,
};
use flock_math::Vector;
use glam::{DVec2, DVec3};
use rand::RngExt;

use crate::common::{cloud, rng, searched};

/// A smooth bump: 1 on [0, h r), cosine down to 0 at r (TAC 2006's ρ_h on ‖·‖ / r).
fn bump(d: f64, r: f64) -> f64 {
    let (h, z) = (0.2, d / r);
    if z < h {
        1.0
    } else {
        0.5 * (1.0 + (core::f64::consts::PI * (z - h) / (1.0 - h)).cos())
    }
}

fn check_quadratic_form<V: Vector>() {
    let r = 0.4;
    let q: Vec<V> = cloud(1, 400, 1.0, 0.0);
    let net = searched(&q, r);
    let g = net.graph();
    let z: Vec<V> = cloud(2, 400, 3.0, 1.0);
    for weights in [
        binary_weights(g),
        weights_from_distances(&net, |d| bump(d, r)),
    ] {
        let mut lz = vec![V::ZERO; q.len()];
        laplacian_apply(g, &weights, &z, &mut lz);
        let dot: f64 = z.iter().zip(&lz).map(|(&a, &b)| a.dot(b)).sum();
        let sos = laplacian_quadratic_form(g, &weights, &z);
        // ½ Σ_i Σ_j a_ij ‖z_j − z_i‖² written out independently.
        let mut expected = 0.0;
        for i in 0..g.len() {
            for (e, &j) in g.edge_range(i).zip(g.neighbours(i)) {
                expected += 0.5 * weights[e] * (z[j as usize] - z[i]).length_squared();
            }
        }
        assert!(sos > 0.0);
        assert_relative_eq!(sos, expected, max_relative = 1e-12);
        assert_relative_eq!(dot, sos, max_relative = 1e-10);

        // The constant field is in the kernel, exactly.
        let constant = vec![V::from_fn(|k| 1.5 - k as f64); q.len()];
        laplacian_apply(g, &weights, &constant, &mut lz);
        assert!(lz.iter().all(|&v| v == V::ZERO));
        assert_eq!(laplacian_quadratic_form(g, &weights, &constant), 0.0);
    }
}

#[test]
fn quadratic_form_is_a_sum_of_squares_2d() {
    check_quadratic_form::<DVec2>();
}

#[test]
fn quadratic_form_is_a_sum_of_squares_3d() {
    check_quadratic_form::<DVec3>();
}

#[test]
fn laplacian_of_an_empty_net_is_zero() {
    let net = ProximityNet::brute_force(&[DVec2::ZERO, DVec2::new(5.0, 0.0)], 1.0);
    let mut out = [DVec2::NAN; 2];
    laplacian_apply(net.graph(), &[], &[DVec2::X, DVec2::Y], &mut out);
    assert_eq!(out, [DVec2::ZERO; 2]);
}

/// Rank of a dense matrix by Gaussian elimination with partial pivoting.
fn rank(mut m: Vec<Vec<f64>>) -> usize {
    let (rows, cols) = (m.len(), m.first().map_or(0, Vec::len));
    let mut rank = 0;
    for col in 0..cols {
        if rank == rows {
            break;
        }
        let pivot = (rank..rows)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .unwrap();
        if m[pivot][col].abs() < 1e-9 {
            continue;
        }
        m.swap(rank, pivot);
        let (above, below) = m.split_at_mut(rank + 1);
        let pivot_row = &above[rank];
        for row in below {
            let factor = row[col] / pivot_row[col];
            for (x, &p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= factor * p;
            }
        }
        rank += 1;
    }
    rank
}

/// The dense 0/1 Laplacian L = Δ(A) − A of a graph.
fn dense_laplacian(g: &Graph) -> Vec<Vec<f64>> {
    let n = g.len();
    let mut l = vec![vec![0.0; n]; n];
    for (i, row) in l.iter_mut().enumerate() {
        row[i] = g.degree(i) as f64;
        for &j in g.neighbours(i) {
            row[j as usize] -= 1.0;
        }
    }
    l
}

#[test]
fn rank_of_laplacian_is_n_minus_components() {
    let mut rng = rng(3);
    let mut seen_disconnected = false;
    for trial in 0..200 {
        let n = rng.random_range(1..=30);
        let p = rng.random::<f64>() * 0.25;
        let mut edges = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                if rng.random::<f64>() < p {
                    edges.push((i, j));
                }
            }
        }
        let g = Graph::from_edges(n, &edges).unwrap();
        let components = Components::of(&g);
        seen_disconnected |= components.count() > 1;
        assert_eq!(
            rank(dense_laplacian(&g)),
            n - components.count(),
            "trial {trial}, n = {n}"
        );
        // L applied through the CSR equals the dense product.
        let z: Vec<DVec2> = (0..n)
            .map(|_| DVec2::new(rng.random(), rng.random()))
            .collect();
        let mut lz = vec![DVec2::ZERO; n];
        laplacian_apply(&g, &binary_weights(&g), &z, &mut lz);
        let l = dense_laplacian(&g);
        for i in 0..n {
            let dense = (0..n).fold(DVec2::ZERO, |acc, j| acc + z[j] * l[i][j]);
            assert_relative_eq!(lz[i], dense, epsilon = 1e-12);
        }
    }
    assert!(seen_disconnected);
}

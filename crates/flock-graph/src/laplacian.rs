//! The graph Laplacian L = Δ(A) − A of a weighted net and its m-dimensional form L̂ = L ⊗ I_m,
//! applied without forming n × n matrices (IEEE TAC 51(3) 2006; ACC 2004 (seed 000) eq. 16):
//!
//! - [`laplacian_apply`]: (L̂z)_i = Σ_{j∈N_i} a_ij (z_i − z_j);
//! - [`laplacian_quadratic_form`]: zᵀL̂z = ½ Σ_i Σ_{j∈N_i} a_ij ‖z_j − z_i‖², the sum-of-squares
//!   property that makes L̂ positive semidefinite for non-negative symmetric weights.
//!
//! The weights are per directed edge, aligned with [`Graph::neighbour_indices`] (see
//! [`crate::adjacency`]); for symmetric weights L is symmetric.

use flock_math::Vector;

use crate::adjacency::binary_weights;
use crate::graph::Graph;
use flock_math::parallel::fill_indexed;

/// `out_i = (L̂z)_i = Σ_{j∈N_i} a_ij (z_i − z_j)` for every agent, in parallel with the `parallel`
/// feature (each row summed in neighbour order: the result does not depend on it).
///
/// The velocity-consensus term of the flocking protocols is `−(L̂p)_i`.
///
/// # Panics
/// When `weights` is not one per directed edge or `z`, `out` are not one per node.
///
/// # Example
/// ```
/// use flock_graph::{Graph, binary_weights, laplacian_apply};
/// use glam::DVec2;
///
/// let g = Graph::from_edges(3, &[(0, 1), (1, 2)]).unwrap();
/// let z = [DVec2::new(1.0, 0.0), DVec2::new(0.0, 0.0), DVec2::new(0.0, 2.0)];
/// let mut out = [DVec2::ZERO; 3];
/// laplacian_apply(&g, &binary_weights(&g), &z, &mut out);
/// assert_eq!(out, [DVec2::new(1.0, 0.0), DVec2::new(-1.0, -2.0), DVec2::new(0.0, 2.0)]);
/// ```
pub fn laplacian_apply<V: Vector>(graph: &Graph, weights: &[f64], z: &[V], out: &mut [V]) {
    check_lengths(graph, weights, z);
    assert_eq!(out.len(), graph.len(), "one output per node");
    fill_indexed(out, |i| {
        let row = graph.neighbours(i).iter().map(|&j| z[j as usize]);
        laplacian_row(z[i], row.zip(weights[graph.edge_range(i)].iter().copied()))
    });
}

/// Row i of L̂z from node i's value and its neighbours' (z_j, a_ij) in their order:
/// Σ_j a_ij (z_i − z_j), summed left to right. The one sum of [`laplacian_apply`], for a node
/// that knows only its own row (a distributed controller).
///
/// # Example
/// ```
/// use flock_graph::laplacian_row;
/// use glam::DVec2;
///
/// let row = [(DVec2::new(1.0, 0.0), 2.0), (DVec2::new(0.0, 1.0), 1.0)];
/// assert_eq!(laplacian_row(DVec2::ZERO, row.into_iter()), DVec2::new(-2.0, -1.0));
/// ```
#[inline]
#[must_use]
pub fn laplacian_row<V: Vector>(zi: V, neighbours: impl Iterator<Item = (V, f64)>) -> V {
    neighbours.fold(V::ZERO, |acc, (zj, a)| acc + (zi - zj) * a)
}

/// The quadratic form zᵀL̂z = ½ Σ_i Σ_{j∈N_i} a_ij ‖z_j − z_i‖² (each undirected edge counted once
/// per direction, hence the ½). Non-negative for non-negative weights. Summed serially in edge
/// order (deterministic).
///
/// # Panics
/// When `weights` is not one per directed edge or `z` not one per node.
///
/// # Example
/// ```
/// use flock_graph::{Graph, binary_weights, laplacian_quadratic_form};
/// use glam::DVec2;
///
/// let g = Graph::from_edges(2, &[(0, 1)]).unwrap();
/// let z = [DVec2::new(0.0, 0.0), DVec2::new(3.0, 4.0)];
/// assert_eq!(laplacian_quadratic_form(&g, &binary_weights(&g), &z), 25.0);
/// ```
#[must_use]
pub fn laplacian_quadratic_form<V: Vector>(graph: &Graph, weights: &[f64], z: &[V]) -> f64 {
    check_lengths(graph, weights, z);
    let sum: f64 = (0..graph.len())
        .map(|i| {
            graph
                .neighbours(i)
                .iter()
                .zip(&weights[graph.edge_range(i)])
                .map(|(&j, &a)| a * (z[j as usize] - z[i]).length_squared())
                .sum::<f64>()
        })
        .sum();
    0.5 * sum
}

/// Panics unless there is one weight per directed edge and one vector per node.
fn check_lengths<V>(graph: &Graph, weights: &[f64], z: &[V]) {
    assert_eq!(
        weights.len(),
        graph.directed_edge_count(),
        "one weight per directed edge"
    );
    assert_eq!(z.len(), graph.len(), "one vector per node");
}

/// The eigenvalues 0 = λ₁ ≤ λ₂ ≤ … ≤ λ_n of the 0/1 Laplacian L = Δ − A of `graph`, ascending,
/// by the cyclic Jacobi method on the dense n × n matrix (O(n³) per sweep: meant for graphs of a
/// few hundred nodes, such as the fixed graphs of the consensus theorems, where λ_max bounds
/// the delay τ < π/(2cλ_max) and the sampled period cTλ_max < 2, and the λ_k give the stationary
/// disagreement under noise).
///
/// # Example
/// ```
/// use flock_graph::{Graph, laplacian_eigenvalues};
///
/// // the cycle C₄: 2 − 2 cos(2πk/4) = 0, 2, 2, 4
/// let c4 = Graph::from_edges(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]).unwrap();
/// let lambda = laplacian_eigenvalues(&c4);
/// for (got, want) in lambda.iter().zip([0.0, 2.0, 2.0, 4.0]) {
///     assert!((got - want).abs() < 1e-12);
/// }
/// ```
#[must_use]
pub fn laplacian_eigenvalues(graph: &Graph) -> Vec<f64> {
    weighted_laplacian_eigenvalues(graph, &binary_weights(graph))
}

/// The eigenvalues of the weighted Laplacian L = Δ(A) − A, ascending, for symmetric weights a_ij
/// per directed edge (aligned with [`Graph::neighbour_indices`]), by the same Jacobi method as
/// [`laplacian_eigenvalues`]. With the bump adjacency a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) (TAC 2006
/// eq. 11) its λ_max bounds the delay of the flock's linearised velocity consensus.
///
/// # Panics
/// When `weights` is not one per directed edge.
///
/// # Example
/// ```
/// use flock_graph::{Graph, weighted_laplacian_eigenvalues};
///
/// // one edge of weight a: L = [[a, −a], [−a, a]], eigenvalues 0 and 2a
/// let g = Graph::from_edges(2, &[(0, 1)]).unwrap();
/// let lambda = weighted_laplacian_eigenvalues(&g, &[0.25, 0.25]);
/// assert!(lambda[0].abs() < 1e-15 && (lambda[1] - 0.5).abs() < 1e-15);
/// ```
#[must_use]
pub fn weighted_laplacian_eigenvalues(graph: &Graph, weights: &[f64]) -> Vec<f64> {
    assert_eq!(
        weights.len(),
        graph.directed_edge_count(),
        "one weight per directed edge"
    );
    let n = graph.len();
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        let row = graph
            .neighbours(i)
            .iter()
            .zip(&weights[graph.edge_range(i)]);
        for (&j, &w) in row {
            a[i * n + i] += w;
            a[i * n + j as usize] -= w;
        }
    }
    let scale: f64 = a.iter().map(|x| x * x).sum::<f64>().max(1.0);
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i * n + j] * a[i * n + j])
            .sum();
        if off <= 1e-30 * scale {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                // the rotation that zeroes a_pq (Golub & Van Loan, Algorithm 8.5.2)
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + theta.hypot(1.0));
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / t.hypot(1.0);
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k * n + p], a[k * n + q]);
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p * n + k], a[q * n + k]);
                    a[p * n + k] = c * apk - s * aqk;
                    a[q * n + k] = s * apk + c * aqk;
                }
            }
        }
    }
    let mut lambda: Vec<f64> = (0..n).map(|i| a[i * n + i]).collect();
    lambda.sort_by(f64::total_cmp);
    lambda
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn row_sums_are_zero_on_a_weighted_triangle() {
        let g = Graph::from_edges(3, &[(0, 1), (1, 2), (2, 0)]).unwrap();
        // Edges in CSR order: 0→1, 0→2, 1→0, 1→2, 2→0, 2→1; symmetric weights.
        let w = [2.0, 0.5, 2.0, 3.0, 0.5, 3.0];
        let ones = [DVec3::ONE; 3];
        let mut out = [DVec3::NAN; 3];
        laplacian_apply(&g, &w, &ones, &mut out);
        assert_eq!(out, [DVec3::ZERO; 3]);
        let e0 = [DVec3::X, DVec3::ZERO, DVec3::ZERO];
        laplacian_apply(&g, &w, &e0, &mut out);
        // First column of L: (a01 + a02, −a10, −a20).
        assert_eq!(out, [DVec3::X * 2.5, DVec3::X * -2.0, DVec3::X * -0.5]);
    }

    #[test]
    fn weighted_eigenvalues_scale_with_uniform_weights_and_sum_to_the_trace() {
        let c4 = Graph::from_edges(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]).unwrap();
        let doubled = weighted_laplacian_eigenvalues(&c4, &[2.0; 8]);
        for (got, want) in doubled.iter().zip(laplacian_eigenvalues(&c4)) {
            assert!((got - 2.0 * want).abs() < 1e-12);
        }
        // the triangle above: trace L = 2 Σ_edges a = 2 (2 + 0.5 + 3)
        let g = Graph::from_edges(3, &[(0, 1), (1, 2), (2, 0)]).unwrap();
        let lambda = weighted_laplacian_eigenvalues(&g, &[2.0, 0.5, 2.0, 3.0, 0.5, 3.0]);
        assert!(lambda[0].abs() < 1e-12);
        assert!((lambda.iter().sum::<f64>() - 11.0).abs() < 1e-12);
    }

    #[test]
    #[should_panic(expected = "one weight per directed edge")]
    fn rejects_misaligned_weights() {
        let g = Graph::from_edges(2, &[(0, 1)]).unwrap();
        let _ = laplacian_quadratic_form(&g, &[1.0], &[DVec3::ZERO; 2]);
    }
}

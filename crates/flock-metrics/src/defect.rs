//! The defect factor of a net (CDS 03-006, seed 004 § 9, eq. 46–47; CDC 2003, seed 003 eq. 19): how
//! far a configuration is from a realization of the structural net (d_α, r), i.e. from an
//! α-lattice, for the 2003 (α, α) protocols.
//!
//! μ = V(q) + w ‖∇V(q)‖² ≥ 0 (eq. 46),  μ_n = μ / (|E| h₀),  h₀ = ψ_α(r − d_α) (eq. 47),
//!
//! with V the structural potential of eq. 28/30 (the potential of the 2003 protocols,
//! [`DefectFactor::measure`]), |E| the number of (undirected) edges of the net and h₀ the energy
//! jump of one link at the edge of the range (eq. 31). Any realization of (d_α, r) — every neighbour
//! exactly d_α away — has V = 0 and ∇V = 0, hence μ = 0; a stressed equilibrium (∇V = 0, V > 0) or
//! a configuration still in motion has μ > 0.
//!
//! # The weight w
//! The seeds leave w > 0 free (eq. 46: "a constant weight"; seed 003: λ > 0). V has the units of
//! φ_α × length and ‖∇V‖² those of φ_α², so w is a length over a force. [`DefectFactor::new`] takes
//! w = 1/(4k), k = φ_α′(0) = ((a + b)/2)(1 + c²)^(−3/2) the stiffness of the pair potential at
//! d_α: for an isolated pair a small z away from d_α, V ≈ ½ k z² and ‖∇V‖² ≈ 2 (k z)² (both
//! agents), so the two terms of μ are then equal and neither dominates by a choice of units.
//! [`DefectFactor::with_weight`] sets another w.

use flock_graph::ProximityNet;
use flock_math::{Bump, Potential, UnevenSigmoid, Vector};

/// The defect factor of seed 004 eq. 46–47 for the 2003 pair potential ψ_α of eq. 29.
///
/// # Example
/// ```
/// use flock_graph::ProximityNet;
/// use flock_math::Bump;
/// use flock_metrics::DefectFactor;
/// use glam::DVec2;
///
/// // d_α = 7, r = 1.2 d_α, a = 1, b = 5 (seed 004 § 11), the smooth adjacency of eq. 17
/// let defect = DefectFactor::new(7.0, 8.4, 1.0, 5.0, Some(Bump::influence_map(7.0 / 8.4, 1)));
/// let triangle = [DVec2::ZERO, DVec2::new(7.0, 0.0), DVec2::new(3.5, 7.0 * 0.75f64.sqrt())];
/// let exact = defect.measure(&triangle, &ProximityNet::brute_force(&triangle, 8.4));
/// assert_eq!(exact.edges, 3);
/// assert!(exact.normalised < 1e-20);
/// let bent = [DVec2::ZERO, DVec2::new(7.0, 0.0), DVec2::new(3.5, 5.0)];
/// assert!(defect.measure(&bent, &ProximityNet::brute_force(&bent, 8.4)).normalised > 1e-3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DefectFactor {
    d_alpha: f64,
    r: f64,
    sigmoid: UnevenSigmoid,
    adjacency: Option<Bump>,
    weight: f64,
}

/// One evaluation of the defect factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Defect {
    /// The structural potential V(q).
    pub potential: f64,
    /// ‖∇V(q)‖² = Σ_i ‖∇_{q_i} V‖².
    pub gradient_squared: f64,
    /// The undirected edges |E| of the net.
    pub edges: usize,
    /// μ = V + w ‖∇V‖² (eq. 46).
    pub factor: f64,
    /// μ_n = μ / (|E| h₀) (eq. 47); 0 for a net without edges.
    pub normalised: f64,
}

impl DefectFactor {
    /// The defect factor of the 2003 potential with desired distance d_α, range r, action function
    /// of eq. 29 with 0 < a < b, and adjacency `Some(ρ)` (smooth, a_ij = ρ(‖q_j − q_i‖/r), eq. 17 and
    /// 30, the potential of (α, α, 2)) or `None` (0/1 on the net, eq. 8 and 28, that of (α, α, 1));
    /// weight w = 1/(4 φ_α′(0)) (see the [module](self)).
    #[must_use]
    pub fn new(d_alpha: f64, r: f64, a: f64, b: f64, adjacency: Option<Bump>) -> Self {
        let sigmoid = UnevenSigmoid::new(a, b);
        let mut defect = Self {
            d_alpha,
            r,
            sigmoid,
            adjacency,
            weight: 0.0,
        };
        defect.weight = 0.25 / defect.stiffness();
        defect
    }

    /// The same with weight `w` > 0.
    #[must_use]
    pub const fn with_weight(mut self, w: f64) -> Self {
        self.weight = w;
        self
    }

    /// The weight w of ‖∇V‖².
    #[must_use]
    pub const fn weight(&self) -> f64 {
        self.weight
    }

    /// k = φ_α′(0) = ((a + b)/2) σ₁′(c) = ((a + b)/2)(1 + c²)^(−3/2): the stiffness of ψ_α at
    /// the desired distance (ψ_α(z) ≈ ½ k z²).
    #[must_use]
    pub fn stiffness(&self) -> f64 {
        let (a, b, c) = (self.sigmoid.a(), self.sigmoid.b(), self.sigmoid.c());
        0.5 * (a + b) * (1.0 + c * c).powf(-1.5)
    }

    /// h₀ = ψ_α(r − d_α): the energy of one link at the edge of the range, the jump of eq. 31.
    #[must_use]
    pub fn h0(&self) -> f64 {
        self.sigmoid.potential(self.r - self.d_alpha)
    }

    /// The pair potential a_ij ψ_α(‖q_j − q_i‖ − d_α) at distance `distance` < r.
    #[must_use]
    pub fn pair_potential(&self, distance: f64) -> f64 {
        self.adjacency(distance) * self.sigmoid.potential(distance - self.d_alpha)
    }

    /// Its derivative with respect to the distance: a_ij φ_α + (1/r) ρ′(‖q_j − q_i‖/r) ψ_α for the
    /// smooth adjacency (the bracket of eq. 35), φ_α for the 0/1 adjacency (eq. 34, between
    /// switches of the net).
    #[must_use]
    pub fn pair_action(&self, distance: f64) -> f64 {
        let z = distance - self.d_alpha;
        let phi = self.sigmoid.action(z);
        match self.adjacency {
            None => phi,
            Some(rho) => {
                rho.value(distance / self.r) * phi
                    + rho.derivative(distance / self.r) / self.r * self.sigmoid.potential(z)
            }
        }
    }

    fn adjacency(&self, distance: f64) -> f64 {
        self.adjacency
            .map_or(1.0, |rho| rho.value(distance / self.r))
    }

    /// μ and μ_n of positions `q` with their proximity net of range r (with or without stored
    /// distances; agents stored in any order with its numbering: every sum runs in original order).
    ///
    /// V = ½ Σ_i Σ_{j∈N_i} a_ij ψ_α(‖q_j − q_i‖ − d_α) (eq. 28/30) and
    /// ∇_{q_i} V = −Σ_{j∈N_i} g(‖q_j − q_i‖) n_ij, g = [`DefectFactor::pair_action`],
    /// n_ij = (q_j − q_i)/‖q_j − q_i‖ (coincident agents contribute no direction), the negative of
    /// the gradient term of the (α, α) protocols.
    #[must_use]
    pub fn measure<V: Vector>(&self, q: &[V], net: &ProximityNet) -> Defect {
        let graph = net.graph();
        let n = graph.len();
        let numbering = net.numbering();
        let potential = 0.5
            * numbering.ordered_sum(n, |i| {
                net.lengths_of(i, q)
                    .fold(0.0, |sum, l| sum + self.pair_potential(l))
            });
        let gradient_squared = numbering.ordered_sum(n, |i| {
            let mut gradient = V::ZERO;
            for (&j, l) in graph.neighbours(i).iter().zip(net.lengths_of(i, q)) {
                if l > 0.0 {
                    gradient += (q[i] - q[j as usize]) * (self.pair_action(l) / l);
                }
            }
            gradient.length_squared()
        });
        let edges = graph.undirected_edge_count();
        let factor = potential + self.weight * gradient_squared;
        let normalised = if edges == 0 {
            0.0
        } else {
            factor / (edges as f64 * self.h0())
        };
        Defect {
            potential,
            gradient_squared,
            edges,
            factor,
            normalised,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use glam::{DVec2, DVec3};

    const D: f64 = 7.0;
    const R: f64 = 8.4;

    fn smooth() -> DefectFactor {
        DefectFactor::new(D, R, 1.0, 5.0, Some(Bump::influence_map(D / R, 1)))
    }

    fn triangular_lattice<V: Vector>(rows: usize, cols: usize, d: f64) -> Vec<V> {
        let mut points = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                let x = d * (c as f64 + 0.5 * (r % 2) as f64);
                let y = d * r as f64 * 3f64.sqrt() / 2.0;
                points.push(V::from_fn(|k| [x, y, 0.0][k]));
            }
        }
        points
    }

    /// A wobble of amplitude `amplitude` on every agent (deterministic).
    fn perturbed<V: Vector>(q: &[V], amplitude: f64) -> Vec<V> {
        q.iter()
            .enumerate()
            .map(|(k, &x)| {
                let t = k as f64;
                x + V::from_fn(|axis| (1.3 * t + 2.1 * axis as f64).sin()) * amplitude
            })
            .collect()
    }

    fn measure<V: Vector>(defect: &DefectFactor, q: &[V]) -> Defect {
        defect.measure(q, &ProximityNet::brute_force(q, R))
    }

    /// ~0 on an exact α-lattice, and growing with the size of a perturbation.
    fn zero_on_a_lattice_and_growing<V: Vector>() {
        let q: Vec<V> = triangular_lattice(6, 7, D);
        for defect in [smooth(), DefectFactor::new(D, R, 1.0, 5.0, None)] {
            let exact = measure(&defect, &q);
            assert_eq!(exact.edges, 6 * 6 + 5 * 13);
            assert!(exact.normalised < 1e-25, "{exact:?}");
            let mut previous = exact.normalised;
            for amplitude in [0.05, 0.1, 0.2, 0.35] {
                let m = measure(&defect, &perturbed(&q, amplitude));
                assert_eq!(m.edges, exact.edges, "the perturbation keeps the net");
                assert!(m.normalised > 2.0 * previous, "{amplitude}: {m:?}");
                previous = m.normalised;
            }
            assert!(previous > 1e-3, "{previous}");
        }
    }

    #[test]
    fn zero_on_a_lattice_and_growing_2d() {
        zero_on_a_lattice_and_growing::<DVec2>();
    }

    #[test]
    fn zero_on_a_lattice_and_growing_3d() {
        zero_on_a_lattice_and_growing::<DVec3>();
    }

    /// The gradient of the measure is that of the potential: central differences of V.
    #[test]
    fn gradient_matches_finite_differences_of_the_potential() {
        let q = perturbed(&triangular_lattice::<DVec2>(3, 3, D), 0.6);
        let defect = smooth();
        let v = |q: &[DVec2]| measure(&defect, q).potential;
        let step = 1e-6;
        let mut squared = 0.0;
        for i in 0..q.len() {
            for axis in [DVec2::X, DVec2::Y] {
                let (mut plus, mut minus) = (q.clone(), q.clone());
                plus[i] += axis * step;
                minus[i] -= axis * step;
                let g = (v(&plus) - v(&minus)) / (2.0 * step);
                squared += g * g;
            }
        }
        assert_relative_eq!(
            measure(&defect, &q).gradient_squared,
            squared,
            max_relative = 1e-6
        );
    }

    /// With w = 1/(4k) both terms of μ agree for a pair slightly off d_α (inside the flat part of ρ,
    /// where a_ij = 1): V ≈ ½ k z², w ‖∇V‖² ≈ w · 2 (k z)².
    #[test]
    fn default_weight_balances_the_two_terms_for_a_pair() {
        let defect = smooth();
        let q = [DVec2::ZERO, DVec2::new(D - 0.01, 0.0)];
        let m = measure(&defect, &q);
        let gradient_term = defect.weight() * m.gradient_squared;
        assert_relative_eq!(gradient_term, m.potential, max_relative = 0.02);
        // a = 1, b = 5: c² = 0.8, k = 3 / 1.8^1.5
        assert_relative_eq!(defect.stiffness(), 3.0 / 1.8f64.powf(1.5), epsilon = 1e-15);
        assert_relative_eq!(defect.weight(), 1.8f64.powf(1.5) / 12.0, epsilon = 1e-15);
    }

    /// μ_n of a single link: V / h₀ + w ‖∇V‖² / h₀ with h₀ = ψ_α(r − d_α) (eq. 31, 47).
    #[test]
    fn normalisation_by_edges_and_h0() {
        let defect = smooth().with_weight(0.5);
        let q = [DVec2::ZERO, DVec2::new(8.0, 0.0), DVec2::new(40.0, 0.0)];
        let m = measure(&defect, &q);
        let pair = defect.pair_potential(8.0);
        let force = defect.pair_action(8.0);
        assert_eq!(m.edges, 1);
        assert_relative_eq!(m.potential, pair, epsilon = 1e-15);
        assert_relative_eq!(m.gradient_squared, 2.0 * force * force, epsilon = 1e-15);
        assert_relative_eq!(
            m.normalised,
            (pair + force * force) / defect.h0(),
            epsilon = 1e-15
        );
        // h₀ = ψ_α(1.4) of eq. 29 with a = 1, b = 5, c = 2/√5
        let c = 2.0 / 5f64.sqrt();
        let h0 = 3.0 * ((1.0 + (1.4 + c) * (1.4 + c)).sqrt() - (1.0 + c * c).sqrt()) - 2.0 * 1.4;
        assert_relative_eq!(defect.h0(), h0, epsilon = 1e-14);
    }
}

//! The σ-norm of Olfati-Saber (TAC 2006, eq. 8–9) and the scalar sigmoid σ₁.

use crate::Vector;

/// The σ-norm ‖z‖_σ = (1/ε)(√(1 + ε‖z‖²) − 1), ε > 0 (TAC 2006 eq. 8), a smooth replacement of
/// the Euclidean norm, and its gradient σ_ε(z) = z / √(1 + ε‖z‖²) = z / (1 + ε‖z‖_σ) (eq. 9).
///
/// The methods taking a Euclidean length `d = ‖z‖` let callers that already hold a distance share
/// the square root between the norm and the gradient.
///
/// # Example
/// ```
/// use flock_math::SigmaNorm;
/// use glam::DVec2;
/// let sigma = SigmaNorm::new(0.1);
/// let z = DVec2::new(3.0, 4.0);
/// assert!((sigma.norm(z) - 10.0 * ((1.0f64 + 2.5).sqrt() - 1.0)).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SigmaNorm {
    epsilon: f64,
}

impl SigmaNorm {
    /// The σ-norm with parameter `epsilon > 0` (the papers use ε = 0.1).
    #[inline]
    #[must_use]
    pub const fn new(epsilon: f64) -> Self {
        Self { epsilon }
    }

    /// The parameter ε.
    #[inline]
    #[must_use]
    pub const fn epsilon(&self) -> f64 {
        self.epsilon
    }

    /// ‖z‖_σ for a vector z.
    #[inline]
    #[must_use]
    pub fn norm<V: Vector>(&self, z: V) -> f64 {
        self.of_length_squared(z.length_squared())
    }

    /// ‖z‖_σ for a vector of Euclidean length `d`.
    #[inline]
    #[must_use]
    pub fn of_length(&self, d: f64) -> f64 {
        self.of_length_squared(d * d)
    }

    /// ‖z‖_σ for a vector with ‖z‖² = `d2`, written d² / (√(1 + εd²) + 1), which equals
    /// (√(1 + εd²) − 1)/ε without its cancellation at small d.
    #[inline]
    #[must_use]
    pub fn of_length_squared(&self, d2: f64) -> f64 {
        d2 / ((1.0 + self.epsilon * d2).sqrt() + 1.0)
    }

    /// The Euclidean length whose σ-norm is `s ≥ 0`: the inverse of [`SigmaNorm::of_length`].
    #[inline]
    #[must_use]
    pub fn length_of(&self, s: f64) -> f64 {
        (s * (2.0 + self.epsilon * s)).sqrt()
    }

    /// The gradient σ_ε(z) = ∇‖z‖_σ = z / √(1 + ε‖z‖²) (eq. 9).
    #[inline]
    #[must_use]
    pub fn gradient<V: Vector>(&self, z: V) -> V {
        z * self.gradient_scale(z.length_squared())
    }

    /// (‖z‖_σ, 1/√(1 + εd²)) for ‖z‖² = `d2`: the norm and the gradient factor sharing one square
    /// root, for the inner loop of the α-interaction.
    #[inline]
    #[must_use]
    pub fn norm_and_gradient_scale(&self, d2: f64) -> (f64, f64) {
        let root = (1.0 + self.epsilon * d2).sqrt();
        (d2 / (root + 1.0), 1.0 / root)
    }

    /// The factor 1/√(1 + εd²) = 1/(1 + ε‖z‖_σ) with σ_ε(z) = z · factor, for ‖z‖² = `d2`.
    #[inline]
    #[must_use]
    pub fn gradient_scale(&self, d2: f64) -> f64 {
        1.0 / (1.0 + self.epsilon * d2).sqrt()
    }
}

/// σ₁(z) = z / √(1 + z²) (TAC 2006, below eq. 15): a smooth sigmoid with values in (−1, 1).
#[inline]
#[must_use]
pub fn sigma1(z: f64) -> f64 {
    z / (1.0 + z * z).sqrt()
}

/// σ₁ applied to a vector: z / √(1 + ‖z‖²), the bounded navigational feedback of Algorithm 3.
#[inline]
#[must_use]
pub fn sigma1_vec<V: Vector>(z: V) -> V {
    z / (1.0 + z.length_squared()).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use glam::{DVec2, DVec3};

    fn gradient_matches_finite_differences<V: Vector>() {
        let sigma = SigmaNorm::new(0.1);
        let z = V::from_fn(|k| 1.5 - 2.0 * k as f64);
        let g = sigma.gradient(z);
        let step = 1e-6;
        for axis in 0..V::DIM {
            let e = V::from_fn(|k| if k == axis { step } else { 0.0 });
            let fd = (sigma.norm(z + e) - sigma.norm(z - e)) / (2.0 * step);
            assert_relative_eq!(g.coord(axis), fd, epsilon = 1e-8);
        }
        let s = sigma.norm(z);
        assert_relative_eq!(g.coord(0), z.coord(0) / (1.0 + 0.1 * s), epsilon = 1e-15);
        let (norm, scale) = sigma.norm_and_gradient_scale(z.length_squared());
        assert_eq!(norm, s);
        assert_eq!(scale, sigma.gradient_scale(z.length_squared()));
    }

    #[test]
    fn gradient_check_2d() {
        gradient_matches_finite_differences::<DVec2>();
    }

    #[test]
    fn gradient_check_3d() {
        gradient_matches_finite_differences::<DVec3>();
    }

    #[test]
    fn sigma_norm_of_papers_distances() {
        let sigma = SigmaNorm::new(0.1);
        // d = 7, r = 8.4 (TAC 2006 simulations): d_α = 10(√5.9 − 1), r_α = 10(√8.056 − 1)
        assert_relative_eq!(
            sigma.of_length(7.0),
            10.0 * (5.9f64.sqrt() - 1.0),
            epsilon = 1e-12
        );
        assert_relative_eq!(
            sigma.of_length(8.4),
            10.0 * (8.056f64.sqrt() - 1.0),
            epsilon = 1e-12
        );
        assert_eq!(sigma.of_length(0.0), 0.0);
        // small lengths: ‖z‖_σ ≈ ‖z‖²/2 without cancellation
        assert_relative_eq!(sigma.of_length(1e-9), 0.5e-18, max_relative = 1e-12);
        for d in [0.0, 0.3, 7.0, 1e3] {
            assert_relative_eq!(sigma.length_of(sigma.of_length(d)), d, max_relative = 1e-12);
        }
    }

    #[test]
    fn sigma1_is_an_odd_bounded_sigmoid() {
        assert_eq!(sigma1(0.0), 0.0);
        assert_relative_eq!(sigma1(1.0), 1.0 / 2f64.sqrt());
        assert_relative_eq!(sigma1(-3.0), -sigma1(3.0));
        assert!(sigma1(1e6) < 1.0 && sigma1(1e6) > 0.999_999);
        let v = sigma1_vec(DVec2::new(3.0, 4.0));
        assert_relative_eq!(v.length(), 5.0 / 26f64.sqrt(), epsilon = 1e-15);
    }
}

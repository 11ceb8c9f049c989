//! The uneven sigmoid φ of TAC 2006 (eq. 15), which is also the 2003 action function (seed 004
//! eq. 29), together with its closed-form potential.

use crate::{Potential, sigma1};

/// The uneven sigmoid φ(z) = ½[(a + b) σ₁(z + c) + (a − b)], 0 < a ≤ b, c = |a − b| / √(4ab),
/// so that φ(0) = 0 (TAC 2006 eq. 15).
///
/// As a [`Potential`] it is the 2003 pair (seed 004 eq. 29):
/// ψ(z) = ((a + b)/2)(√(1 + (z + c)²) − √(1 + c²)) + ((a − b)/2) z, φ = dψ/dz, ψ(0) = 0, with
/// z = ‖q_j − q_i‖ − d_α a Euclidean distance error.
///
/// # Example
/// ```
/// use flock_math::{Potential, UnevenSigmoid};
/// let phi = UnevenSigmoid::new(5.0, 5.0);
/// assert_eq!(phi.action(0.0), 0.0);
/// assert!((phi.action(1e9) - 5.0).abs() < 1e-6); // tends to a
/// assert!((phi.action(-1e9) + 5.0).abs() < 1e-6); // tends to −b
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnevenSigmoid {
    a: f64,
    b: f64,
    c: f64,
}

impl UnevenSigmoid {
    /// φ with 0 < a ≤ b (the caller validates; TAC uses a = b = 5).
    #[must_use]
    pub fn new(a: f64, b: f64) -> Self {
        let c = (a - b).abs() / (4.0 * a * b).sqrt();
        Self { a, b, c }
    }

    /// The attraction bound a (φ → a as z → ∞).
    #[inline]
    #[must_use]
    pub const fn a(&self) -> f64 {
        self.a
    }

    /// The repulsion bound b (φ → −b as z → −∞).
    #[inline]
    #[must_use]
    pub const fn b(&self) -> f64 {
        self.b
    }

    /// The shift c = |a − b| / √(4ab).
    #[inline]
    #[must_use]
    pub const fn c(&self) -> f64 {
        self.c
    }
}

impl Potential for UnevenSigmoid {
    #[inline]
    fn action(&self, z: f64) -> f64 {
        0.5 * ((self.a + self.b) * sigma1(z + self.c) + (self.a - self.b))
    }

    #[inline]
    fn potential(&self, z: f64) -> f64 {
        let (s, c) = (0.5 * (self.a + self.b), self.c);
        s * ((1.0 + (z + c) * (z + c)).sqrt() - (1.0 + c * c).sqrt()) + 0.5 * (self.a - self.b) * z
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn vanishes_at_zero_for_uneven_gains() {
        for (a, b) in [(5.0, 5.0), (1.0, 4.0), (0.3, 10.0)] {
            let phi = UnevenSigmoid::new(a, b);
            assert_relative_eq!(phi.action(0.0), 0.0, epsilon = 1e-15);
            assert_eq!(phi.potential(0.0), 0.0);
            assert!(phi.potential(-2.0) > 0.0 && phi.potential(2.0) > 0.0);
        }
    }

    #[test]
    fn known_values() {
        // a = 1, b = 4: c = 3/4, φ(z) = ½[5 σ₁(z + 3/4) − 3]
        let phi = UnevenSigmoid::new(1.0, 4.0);
        assert_relative_eq!(phi.c(), 0.75);
        let z: f64 = 1.25;
        assert_relative_eq!(
            phi.action(z),
            0.5 * (5.0 * 2.0 / 5f64.sqrt() - 3.0),
            epsilon = 1e-15
        );
        assert_relative_eq!(
            phi.potential(z),
            2.5 * (5f64.sqrt() - 1.25) - 1.5 * z,
            epsilon = 1e-14
        );
    }

    #[test]
    fn action_is_the_derivative_of_the_potential() {
        let phi = UnevenSigmoid::new(2.0, 7.0);
        for i in -40..=40 {
            let z = f64::from(i) * 0.25;
            let step = 1e-6;
            let fd = (phi.potential(z + step) - phi.potential(z - step)) / (2.0 * step);
            assert_relative_eq!(phi.action(z), fd, epsilon = 1e-7);
        }
    }
}

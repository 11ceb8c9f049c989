//! A Tanner–Jadbabaie–Pappas pair potential (seed 001, Definition IV.3).

use crate::Potential;

/// V(z) = d²/z² + ln(z²/d²) − 1 of the distance z = ‖r_ij‖: nonnegative, → ∞ as z → 0, with its
/// unique minimum V(d) = 0 at the desired distance d (Tanner, Jadbabaie & Pappas 2003, Definition
/// IV.3, which gives these conditions and no formula: 1/‖r‖² + ln ‖r‖², the usual example, is ours,
/// scaled to distance d and shifted to vanish at d).
///
/// # Example
/// ```
/// use flock_math::{Potential, TannerPotential};
/// let v = TannerPotential::new(2.0);
/// assert_eq!(v.potential(2.0), 0.0);
/// assert_eq!(v.action(2.0), 0.0);
/// assert!(v.potential(1e-3) > 1e5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TannerPotential {
    distance: f64,
}

impl TannerPotential {
    /// The potential with its minimum at the desired distance `distance > 0`.
    #[must_use]
    pub const fn new(distance: f64) -> Self {
        Self { distance }
    }

    /// The desired distance d.
    #[must_use]
    pub const fn distance(&self) -> f64 {
        self.distance
    }
}

impl Potential for TannerPotential {
    /// dV/dz = 2/z − 2d²/z³.
    #[inline]
    fn action(&self, z: f64) -> f64 {
        let d2 = self.distance * self.distance;
        2.0 / z - 2.0 * d2 / (z * z * z)
    }

    #[inline]
    fn potential(&self, z: f64) -> f64 {
        let x = z * z / (self.distance * self.distance);
        1.0 / x + x.ln() - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn unique_minimum_at_the_desired_distance() {
        let v = TannerPotential::new(1.5);
        assert_eq!(v.potential(1.5), 0.0);
        for i in 1..300 {
            let z = f64::from(i) * 0.02;
            assert!(v.potential(z) >= 0.0);
            assert_eq!(v.action(z) < 0.0, z < 1.5, "z = {z}");
        }
        assert!(v.potential(1e-4) > 1e7);
    }

    #[test]
    fn action_is_the_derivative_of_the_potential() {
        let v = TannerPotential::new(1.5);
        for i in 1..100 {
            let z = f64::from(i) * 0.07;
            let step = 1e-7;
            let fd = (v.potential(z + step) - v.potential(z - step)) / (2.0 * step);
            assert_relative_eq!(v.action(z), fd, max_relative = 1e-6);
        }
    }
}

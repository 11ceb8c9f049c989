//! Bump functions: smooth cut-offs that turn 0/1 adjacency into smooth adjacency.

use core::f64::consts::PI;

/// The bump function ρ with flat part [0, h) and power k:
///
/// ρ(z) = 1 on [0, h); (1/2^k)[1 + cos(π (z − h)/(1 − h))]^k on [h, 1]; 0 otherwise.
///
/// With k = 1 this is the bump ρ_h of TAC 2006 (eq. 10), used for the smooth adjacency
/// a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) and inside φ_α and φ_β; with general k it is the C^k influence
/// map of ACC 2004 (seed 000 eq. 4, where h is written δ).
///
/// # Example
/// ```
/// use flock_math::Bump;
/// let rho = Bump::tac(0.2);
/// assert_eq!(rho.value(0.1), 1.0);
/// assert!((rho.value(0.6) - 0.5).abs() < 1e-15);
/// assert_eq!(rho.value(1.5), 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bump {
    h: f64,
    power: i32,
}

impl Bump {
    /// The TAC 2006 bump ρ_h, h ∈ (0, 1) (eq. 10).
    #[inline]
    #[must_use]
    pub const fn tac(h: f64) -> Self {
        Self { h, power: 1 }
    }

    /// The ACC 2004 influence map with flat part [0, δ] and power k ≥ 1 (seed 000 eq. 4).
    #[inline]
    #[must_use]
    pub const fn influence_map(delta: f64, k: i32) -> Self {
        Self { h: delta, power: k }
    }

    /// The end h of the flat part.
    #[inline]
    #[must_use]
    pub const fn h(&self) -> f64 {
        self.h
    }

    /// The power k (1 for ρ_h).
    #[inline]
    #[must_use]
    pub const fn power(&self) -> i32 {
        self.power
    }

    /// The phase θ = π (z − h)/(1 − h) of the cosine part.
    #[inline]
    fn phase(&self, z: f64) -> f64 {
        PI * (z - self.h) / (1.0 - self.h)
    }

    /// ρ(z).
    #[inline]
    #[must_use]
    pub fn value(&self, z: f64) -> f64 {
        if (0.0..self.h).contains(&z) {
            1.0
        } else if (self.h..=1.0).contains(&z) {
            let half = 0.5 * (1.0 + self.phase(z).cos());
            // powi(1) is exact; skipping the call keeps ρ_h to one cosine
            if self.power == 1 {
                half
            } else {
                half.powi(self.power)
            }
        } else {
            0.0
        }
    }

    /// ρ′(z) = −(kπ / (2(1 − h))) [½(1 + cos θ)]^(k−1) sin θ on [h, 1], 0 elsewhere.
    #[inline]
    #[must_use]
    pub fn derivative(&self, z: f64) -> f64 {
        if (self.h..=1.0).contains(&z) {
            let theta = self.phase(z);
            let k = f64::from(self.power);
            -k * PI / (2.0 * (1.0 - self.h))
                * (0.5 * (1.0 + theta.cos())).powi(self.power - 1)
                * theta.sin()
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn tac_bump_known_values() {
        let rho = Bump::tac(0.2);
        assert_eq!(rho.value(0.0), 1.0);
        assert_eq!(rho.value(0.199), 1.0);
        assert_eq!(rho.value(0.2), 1.0);
        assert_relative_eq!(rho.value(0.6), 0.5, epsilon = 1e-15);
        assert_relative_eq!(rho.value(1.0), 0.0, epsilon = 1e-15);
        assert_eq!(rho.value(1.0 + 1e-12), 0.0);
        assert_eq!(rho.value(-0.1), 0.0);
        // z = h + (1 − h)/3: ½(1 + cos(π/3)) = 3/4
        assert_relative_eq!(rho.value(0.2 + 0.8 / 3.0), 0.75, epsilon = 1e-15);
    }

    #[test]
    fn continuous_and_c1_at_h_and_one() {
        for bump in [Bump::tac(0.2), Bump::tac(0.9), Bump::influence_map(0.3, 3)] {
            let h = bump.h();
            let tiny = 1e-9;
            for knot in [h, 1.0] {
                assert_relative_eq!(
                    bump.value(knot - tiny),
                    bump.value(knot + tiny),
                    epsilon = 1e-6
                );
                assert_relative_eq!(
                    bump.derivative(knot - tiny),
                    bump.derivative(knot + tiny),
                    epsilon = 1e-6
                );
                assert_relative_eq!(bump.derivative(knot), 0.0, epsilon = 1e-12);
            }
        }
    }

    #[test]
    fn derivative_matches_finite_differences() {
        for bump in [
            Bump::tac(0.2),
            Bump::influence_map(0.1, 2),
            Bump::influence_map(0.5, 4),
        ] {
            for i in 1..40 {
                let z = f64::from(i) / 40.0 * 1.1;
                let step = 1e-6;
                let fd = (bump.value(z + step) - bump.value(z - step)) / (2.0 * step);
                assert_relative_eq!(bump.derivative(z), fd, epsilon = 1e-6);
            }
        }
    }

    #[test]
    fn influence_map_with_power_one_is_the_tac_bump() {
        let (tac, acc) = (Bump::tac(0.35), Bump::influence_map(0.35, 1));
        for i in 0..=120 {
            let z = f64::from(i) / 100.0;
            assert_eq!(tac.value(z), acc.value(z));
        }
    }

    #[test]
    fn influence_map_is_the_kth_power_of_the_cosine_part() {
        let (one, three) = (Bump::influence_map(0.25, 1), Bump::influence_map(0.25, 3));
        for z in [0.3, 0.5, 0.8, 0.99] {
            assert_relative_eq!(three.value(z), one.value(z).powi(3), max_relative = 1e-14);
        }
    }
}

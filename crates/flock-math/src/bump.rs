//! Bump functions: smooth cut-offs that turn 0/1 adjacency into smooth adjacency.

use core::f64::consts::PI;
use wide::f64x4;

/// The bump function ρ with flat part [0, h) and power k:
///
/// ρ(z) = 1 on [0, h); (1/2^k)[1 + cos(π (z − h)/(1 − h))]^k on [h, 1]; 0 otherwise.
///
/// With k = 1 this is the bump ρ_h of TAC 2006 (eq. 10), used for the smooth adjacency
/// a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) and inside φ_α and φ_β; with general k it is the C^k influence
/// map of ACC 2004 (seed 000 eq. 4, where h is written δ).
///
/// The cosine is `wide`'s `f64x4::sin_cos` (after Agner Fog's vector class library: a
/// three-part reduction by π/2, then degree-11/12 polynomials), four lanes at a time and without
/// a branch, so that the pair loops evaluate ρ for four pairs at once ([`Bump::values`]). A lane
/// is a function of its own argument alone: [`Bump::value`] is lane 0 of the same call with the
/// argument in every lane, so ρ(z) has the same bits wherever it is computed, alone or in any
/// lane of a batch. Over θ ∈ [0, π] (2·10⁷ points) it differs from glibc's `cos` in 26 % of the
/// points, by at most 2 ULP (1.1e-16 absolute), and ρ_h by at most 1.1e-16; against the exact
/// cosine (200-bit `mpmath`, 2·10⁵ points) it is within 1.44 ULP (glibc 0.51), ρ_h within
/// 1.2e-16 (glibc 8.3e-17). Its bits depend on whether the build enables FMA (`wide` fuses its
/// multiply–adds only when the target has it; the default x86-64 target has not, aarch64 has),
/// and not on the C library.
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

    /// ρ(z): lane 0 of [`Bump::values`] with `z` in every lane.
    #[inline]
    #[must_use]
    pub fn value(&self, z: f64) -> f64 {
        self.values([z; 4])[0]
    }

    /// ρ(z_k) for four arguments at once, one vector cosine for the four: lane k is
    /// [`Bump::value`]`(z[k])` bit for bit, whatever the other lanes hold.
    #[inline]
    #[must_use]
    pub fn values(&self, z: [f64; 4]) -> [f64; 4] {
        let cos = f64x4::new(z.map(|z| self.phase(z))).cos().to_array();
        core::array::from_fn(|k| self.given_cos(z[k], cos[k]))
    }

    /// ρ(z) given cos θ(z): 1 on [0, h), [½(1 + cos θ)]^k on [h, 1], 0 otherwise (and for NaN).
    #[inline]
    fn given_cos(&self, z: f64, cos: f64) -> f64 {
        if (0.0..self.h).contains(&z) {
            1.0
        } else if (self.h..=1.0).contains(&z) {
            let half = 0.5 * (1.0 + cos);
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

    /// ρ′(z) = −(kπ / (2(1 − h))) [½(1 + cos θ)]^(k−1) sin θ on [h, 1], 0 elsewhere; sin θ and
    /// cos θ from the vector `sin_cos` of [`Bump::value`].
    #[inline]
    #[must_use]
    pub fn derivative(&self, z: f64) -> f64 {
        if (self.h..=1.0).contains(&z) {
            let (sin, cos) = f64x4::splat(self.phase(z)).sin_cos();
            let (sin, cos) = (sin.to_array()[0], cos.to_array()[0]);
            let k = f64::from(self.power);
            -k * PI / (2.0 * (1.0 - self.h)) * (0.5 * (1.0 + cos)).powi(self.power - 1) * sin
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::{assert_abs_diff_eq, assert_relative_eq, assert_ulps_eq};

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

    /// The vector cosine against the platform's `cos` over θ ∈ [0, π] (the phase of ρ on [h, 1]):
    /// within 2 ULP, and ρ_h = ½(1 + cos θ) within 1.2e-16 (both measured at 2·10⁷ points).
    #[test]
    fn the_vector_cosine_is_within_two_ulp_of_cos_on_the_bumps_phase() {
        let rho = Bump::tac(0.0);
        let n = 1_000_000;
        for k in 0..=n {
            let z = f64::from(k) / f64::from(n);
            let theta = PI * z;
            let (sin, cos) = f64x4::splat(theta).sin_cos();
            assert_ulps_eq!(cos.to_array()[0], theta.cos(), max_ulps = 2);
            assert_ulps_eq!(
                sin.to_array()[0],
                theta.sin(),
                epsilon = 1e-16,
                max_ulps = 2
            );
            assert_abs_diff_eq!(rho.value(z), 0.5 * (1.0 + theta.cos()), epsilon = 1.2e-16);
        }
    }

    proptest::proptest! {
        /// Lane k of `values` is `value` of its own argument, bit for bit, whatever the other
        /// lanes hold (in the flat part, the cosine part, beyond it, or NaN) and wherever the
        /// argument sits among the four.
        #[test]
        fn a_lane_is_the_value_of_its_own_argument(
            z in proptest::array::uniform4(-0.5..1.5f64),
            nan in 0..5usize,
            h in 0.05..0.95f64,
            power in 1..4i32,
        ) {
            let mut z = z;
            if let Some(lane) = z.get_mut(nan) {
                *lane = f64::NAN;
            }
            let bump = Bump::influence_map(h, power);
            for shift in 0..4 {
                let mut rotated = z;
                rotated.rotate_left(shift);
                let lanes = bump.values(rotated);
                for (lane, &arg) in lanes.iter().zip(&rotated) {
                    proptest::prop_assert_eq!(lane.to_bits(), bump.value(arg).to_bits());
                }
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

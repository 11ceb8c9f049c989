//! Action functions cut off by a bump, φ(z) = ρ_h(z / R) · g(z), and their potentials: φ_α and φ_β
//! of TAC 2006 (eq. 16 and 56).

use std::sync::OnceLock;

use crate::{Bump, CumulativeIntegral, Potential, UnevenSigmoid, sigma1};

/// An action function φ(z) = ρ_h(z / R) (s σ₁(z − z₀) + o) and its potential ψ(z) = ∫_{z*}^z φ(s) ds.
///
/// Two instances carry the theory of TAC 2006:
/// - [`BumpedAction::alpha`]: φ_α(z) = ρ_h(z / r_α) φ(z − d_α) (eq. 16), ψ_α(z) = ∫_{d_α}^z φ_α
///   (eq. 17), the attractive/repulsive pair potential between α-agents in σ-norm coordinates;
/// - [`BumpedAction::beta`]: φ_β(z) = ρ_h(z / d_β)(σ₁(z − d_β) − 1) (eq. 56), ψ_β(z) = ∫_{d_β}^z φ_β ≥ 0,
///   the repulsive potential between an α-agent and a β-agent.
///
/// ψ is exact to rounding: on the flat part [0, h R) of the bump the integral has a closed form;
/// across the cosine part [h R, R] a [`CumulativeIntegral`] joins exact knots of ψ, φ and φ′ every
/// 1/128 (σ₁ bends on a unit scale, so the quintic between them is off by less than
/// 1e-16 (a + b)); beyond R, φ = 0 and ψ is constant. An evaluation calls no transcendental
/// function on the cosine part and one square root on the flat part.
///
/// # Example
/// ```
/// use flock_math::{Bump, BumpedAction, Potential, SigmaNorm, UnevenSigmoid};
/// let sigma = SigmaNorm::new(0.1);
/// let (d_alpha, r_alpha) = (sigma.of_length(7.0), sigma.of_length(8.4));
/// let phi_alpha = BumpedAction::alpha(UnevenSigmoid::new(5.0, 5.0), Bump::tac(0.2), d_alpha, r_alpha);
/// assert!(phi_alpha.action(d_alpha).abs() < 1e-12); // equilibrium at the lattice distance
/// assert_eq!(phi_alpha.potential(d_alpha), 0.0);
/// assert!(phi_alpha.action(0.5 * d_alpha) < 0.0); // repulsive below d_α
/// ```
#[derive(Clone, Debug)]
pub struct BumpedAction {
    scale: f64,
    shift: f64,
    offset: f64,
    bump: Bump,
    range: f64,
    zero: f64,
    /// ∫_0^{hR} φ, the whole flat part.
    flat: f64,
    /// ψ's table, built at the first ψ asked for ([`Potential::potential`]: a run's energy): a
    /// step needs φ alone, and the table is most of the cost of building a protocol (an
    /// environment's reset builds one).
    psi: OnceLock<PsiTable>,
}

/// What ψ reads beyond φ: ∫ φ on the cosine part, and where ψ is zero.
#[derive(Clone, Debug)]
struct PsiTable {
    /// ∫_{hR}^z φ on the cosine part.
    table: CumulativeIntegral,
    /// ∫_0^{z*} φ, so that ψ(z) = ∫_0^z φ − this.
    anchor: f64,
}

/// Two actions are equal when their parameters are: ψ's table is a function of them.
impl PartialEq for BumpedAction {
    fn eq(&self, other: &Self) -> bool {
        (
            self.scale,
            self.shift,
            self.offset,
            self.bump,
            self.range,
            self.zero,
        ) == (
            other.scale,
            other.shift,
            other.offset,
            other.bump,
            other.range,
            other.zero,
        )
    }
}

impl BumpedAction {
    /// φ_α(z) = ρ_h(z / r_α) φ(z − d_α) with the uneven sigmoid φ (TAC 2006 eq. 16), ψ_α(d_α) = 0.
    /// `d_alpha = ‖d‖_σ` and `r_alpha = ‖r‖_σ` with 0 < d_α < r_α.
    #[must_use]
    pub fn alpha(sigmoid: UnevenSigmoid, bump: Bump, d_alpha: f64, r_alpha: f64) -> Self {
        let (a, b) = (sigmoid.a(), sigmoid.b());
        Self::new(
            0.5 * (a + b),
            d_alpha - sigmoid.c(),
            0.5 * (a - b),
            bump,
            r_alpha,
            d_alpha,
        )
    }

    /// φ_β(z) = ρ_h(z / d_β)(σ₁(z − d_β) − 1) (TAC 2006 eq. 56), ψ_β(d_β) = 0, with
    /// `d_beta = ‖d′‖_σ > 0`; the papers use h = 0.9 here.
    #[must_use]
    pub fn beta(bump: Bump, d_beta: f64) -> Self {
        Self::new(1.0, d_beta, -1.0, bump, d_beta, d_beta)
    }

    /// Cells of the ψ table: σ₁ bends on a unit scale, and |σ₁⁽⁵⁾| ≤ 45.
    const TABLE_SPACING: f64 = 1.0 / 128.0;

    fn new(scale: f64, shift: f64, offset: f64, bump: Bump, range: f64, zero: f64) -> Self {
        let mut this = Self {
            scale,
            shift,
            offset,
            bump,
            range,
            zero,
            flat: 0.0,
            psi: OnceLock::new(),
        };
        let flat_end = bump.h() * range;
        this.flat = this.profile_integral(flat_end) - this.profile_integral(0.0);
        this
    }

    /// ψ's table, built the first time.
    fn psi(&self) -> &PsiTable {
        self.psi.get_or_init(|| {
            let table = CumulativeIntegral::new(
                |z| self.action(z),
                |z| self.action_derivative(z),
                self.bump.h() * self.range,
                self.range,
                Self::TABLE_SPACING,
            );
            let anchor = self.integral_from_origin(&table, self.zero);
            PsiTable { table, anchor }
        })
    }

    /// The cut-off R: φ(z) = 0 for z ≥ R (r_α for φ_α, d_β for φ_β).
    #[inline]
    #[must_use]
    pub const fn range(&self) -> f64 {
        self.range
    }

    /// The zero z* of ψ (d_α for φ_α, d_β for φ_β).
    #[inline]
    #[must_use]
    pub const fn zero(&self) -> f64 {
        self.zero
    }

    /// The bump ρ_h that cuts φ off.
    #[inline]
    #[must_use]
    pub const fn bump(&self) -> Bump {
        self.bump
    }

    /// (φ(z), ρ_h(z / R)): the action and the bump at once, sharing the cosine. For α-agents the
    /// second value is the smooth adjacency a_ij = ρ_h(‖q_j − q_i‖_σ / r_α) (TAC 2006 eq. 11).
    #[inline]
    #[must_use]
    pub fn action_and_bump(&self, z: f64) -> (f64, f64) {
        let rho = self.bump.value(z / self.range);
        (rho * self.profile(z), rho)
    }

    /// [`BumpedAction::action_and_bump`] of four arguments at once, one vector cosine for the
    /// four ([`Bump::values`]): lane k is `action_and_bump(z[k])` bit for bit, whatever the other
    /// lanes hold.
    #[inline]
    #[must_use]
    pub fn actions_and_bumps(&self, z: [f64; 4]) -> ([f64; 4], [f64; 4]) {
        let rho = self.bump.values(z.map(|z| z / self.range));
        (core::array::from_fn(|k| rho[k] * self.profile(z[k])), rho)
    }

    /// φ′(z) = ρ_h′(z / R) g(z) / R + ρ_h(z / R) s σ₁′(z − z₀), with σ₁′(x) = (1 + x²)^(−3/2).
    #[must_use]
    pub fn action_derivative(&self, z: f64) -> f64 {
        let x = z - self.shift;
        let sigma1_slope = 1.0 / ((1.0 + x * x) * (1.0 + x * x).sqrt());
        self.bump.derivative(z / self.range) / self.range * self.profile(z)
            + self.bump.value(z / self.range) * self.scale * sigma1_slope
    }

    /// The uncut profile g(z) = s σ₁(z − z₀) + o.
    #[inline]
    fn profile(&self, z: f64) -> f64 {
        self.scale * sigma1(z - self.shift) + self.offset
    }

    /// A closed-form antiderivative of the profile: s √(1 + (z − z₀)²) + o z.
    #[inline]
    fn profile_integral(&self, z: f64) -> f64 {
        let x = z - self.shift;
        self.scale * (1.0 + x * x).sqrt() + self.offset * z
    }

    /// ∫_0^z φ (φ = 0 for z < 0, where ρ_h vanishes), `table` the cosine part's.
    fn integral_from_origin(&self, table: &CumulativeIntegral, z: f64) -> f64 {
        let flat_end = self.bump.h() * self.range;
        if z <= 0.0 {
            return 0.0;
        }
        if z <= flat_end {
            self.profile_integral(z) - self.profile_integral(0.0)
        } else {
            self.flat + table.integral_to(z)
        }
    }
}

impl Potential for BumpedAction {
    #[inline]
    fn action(&self, z: f64) -> f64 {
        self.action_and_bump(z).0
    }

    fn potential(&self, z: f64) -> f64 {
        let psi = self.psi();
        self.integral_from_origin(&psi.table, z) - psi.anchor
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{GaussLegendre, SigmaNorm};
    use approx::assert_relative_eq;

    fn papers_alpha() -> BumpedAction {
        let sigma = SigmaNorm::new(0.1);
        BumpedAction::alpha(
            UnevenSigmoid::new(5.0, 5.0),
            Bump::tac(0.2),
            sigma.of_length(7.0),
            sigma.of_length(8.4),
        )
    }

    fn papers_beta() -> BumpedAction {
        BumpedAction::beta(Bump::tac(0.9), SigmaNorm::new(0.1).of_length(0.6 * 7.0))
    }

    /// Adaptive Simpson quadrature: an independent check of the tabulated potential.
    fn adaptive_simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
        let simpson = |a: f64, b: f64| (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b));
        let m = 0.5 * (a + b);
        let (whole, halves) = (simpson(a, b), simpson(a, m) + simpson(m, b));
        if depth == 0 || (halves - whole).abs() <= 15.0 * tol {
            halves + (halves - whole) / 15.0
        } else {
            adaptive_simpson(f, a, m, 0.5 * tol, depth - 1)
                + adaptive_simpson(f, m, b, 0.5 * tol, depth - 1)
        }
    }

    #[test]
    fn psi_alpha_matches_adaptive_quadrature() {
        let phi = papers_alpha();
        let f = |s: f64| phi.action(s);
        for i in 0..=50 {
            let z = f64::from(i) * 0.45;
            let reference = adaptive_simpson(&f, phi.zero(), z, 1e-12, 40);
            assert_relative_eq!(phi.potential(z), reference, epsilon = 1e-9);
        }
    }

    /// The table against a direct composite 20-point Gauss–Legendre integral from the end of the
    /// flat part: both exact to rounding, so they agree to a few ulps of ψ.
    #[test]
    fn psi_is_exact_to_rounding_on_the_cosine_part() {
        let rule = GaussLegendre::new(20);
        for phi in [papers_alpha(), papers_beta()] {
            let flat_end = phi.bump().h() * phi.range();
            let at_flat_end = phi.potential(flat_end);
            let mut worst = 0.0_f64;
            for i in 0..=997 {
                let z = flat_end + (phi.range() - flat_end) * f64::from(i) / 997.0;
                let direct = at_flat_end + rule.integrate(|s| phi.action(s), flat_end, z, 16);
                worst = worst.max((phi.potential(z) - direct).abs());
            }
            let scale = phi.potential(0.0).abs();
            assert!(
                worst <= 1e-14 * scale,
                "largest error {worst:e} (ψ(0) = {scale})"
            );
        }
    }

    /// ψ_α(0) for the papers' parameters, from a 40-digit mpmath quadrature of eq. 17.
    #[test]
    fn psi_alpha_at_zero_matches_a_high_precision_reference() {
        assert_relative_eq!(
            papers_alpha().potential(0.0),
            52.383_811_786_644_86,
            max_relative = 1e-15
        );
    }

    /// `derivative` against central differences of `f` at 300 points of (0, 1.1 R), for φ_α and
    /// φ_β.
    fn check_derivative(
        f: impl Fn(&BumpedAction, f64) -> f64,
        derivative: impl Fn(&BumpedAction, f64) -> f64,
        tolerance: f64,
    ) {
        for phi in [papers_alpha(), papers_beta()] {
            for i in 1..300 {
                let z = f64::from(i) / 300.0 * 1.1 * phi.range();
                let step = 1e-6;
                let fd = (f(&phi, z + step) - f(&phi, z - step)) / (2.0 * step);
                assert_relative_eq!(derivative(&phi, z), fd, epsilon = tolerance);
            }
        }
    }

    #[test]
    fn phi_prime_matches_finite_differences() {
        check_derivative(BumpedAction::action, BumpedAction::action_derivative, 1e-6);
    }

    #[test]
    fn psi_alpha_is_zero_at_d_alpha_and_nonnegative() {
        let phi = papers_alpha();
        assert_eq!(phi.potential(phi.zero()), 0.0);
        for i in 0..=400 {
            let z = f64::from(i) * 0.06;
            assert!(
                phi.potential(z) >= -1e-12,
                "ψ_α({z}) = {}",
                phi.potential(z)
            );
        }
        // constant beyond r_α, where φ_α vanishes
        assert_eq!(phi.action(phi.range() + 0.1), 0.0);
        assert_eq!(phi.potential(phi.range()), phi.potential(phi.range() + 5.0));
    }

    #[test]
    fn phi_is_the_derivative_of_psi() {
        check_derivative(BumpedAction::potential, BumpedAction::action, 1e-7);
    }

    #[test]
    fn phi_alpha_known_values() {
        let phi = papers_alpha();
        let (d_alpha, r_alpha) = (phi.zero(), phi.range());
        // flat part: φ_α(z) = 5 σ₁(z − d_α) (a = b, c = 0)
        let z: f64 = 2.0;
        assert_relative_eq!(phi.action(z), 5.0 * sigma1(z - d_alpha), epsilon = 1e-15);
        // midpoint of the cosine part: ρ_h = ½
        let z = 0.6 * r_alpha;
        assert_relative_eq!(phi.action(z), 2.5 * sigma1(z - d_alpha), epsilon = 1e-14);
        assert_relative_eq!(phi.action_and_bump(z).1, 0.5, epsilon = 1e-14);
        assert_eq!(phi.action(r_alpha), 0.0);
    }

    #[test]
    fn phi_beta_is_repulsive_and_psi_beta_nonnegative() {
        let phi = papers_beta();
        let d_beta = phi.zero();
        assert_eq!(phi.action(d_beta), 0.0);
        assert_eq!(phi.potential(d_beta), 0.0);
        assert_eq!(phi.potential(2.0 * d_beta), 0.0);
        for i in 0..100 {
            let z = f64::from(i) / 100.0 * d_beta;
            assert!(phi.action(z) < 0.0);
            assert!(phi.potential(z) > 0.0);
        }
        // ψ_β(0) = ∫_0^{d_β} (1 − σ₁(s − d_β)) ρ_h(s/d_β) ds, checked with a plain Gauss rule
        let reference = -GaussLegendre::new(20).integrate(|s| phi.action(s), 0.0, d_beta, 400);
        assert_relative_eq!(phi.potential(0.0), reference, epsilon = 1e-10);
    }

    proptest::proptest! {
        /// ψ_α ≥ 0 with its minimum at d_α, ψ_β ≥ 0, and φ = dψ/dz, for every argument.
        #[test]
        fn potentials_are_nonnegative_with_phi_their_derivative(fraction in 0.0f64..1.3) {
            for phi in [papers_alpha(), papers_beta()] {
                let z = fraction * phi.range();
                proptest::prop_assert!(phi.potential(z) >= -1e-12);
                let step = 1e-6 * phi.range();
                if z > step {
                    let fd = (phi.potential(z + step) - phi.potential(z - step)) / (2.0 * step);
                    proptest::prop_assert!((phi.action(z) - fd).abs() <= 1e-6);
                }
            }
        }
    }
}

//! Gauss–Legendre quadrature, used to integrate action functions across the cosine part of a bump
//! (ψ_α and ψ_β have no closed form there).

/// An n-point Gauss–Legendre rule on [−1, 1], with nodes found by Newton's method on P_n.
///
/// A composite rule with `panels` sub-intervals integrates a smooth (analytic) integrand to machine
/// precision with few nodes: the error of one panel decays like (width)^(2n).
///
/// # Example
/// ```
/// use flock_math::GaussLegendre;
/// let rule = GaussLegendre::new(5);
/// // exact for polynomials of degree ≤ 2n − 1 = 9
/// let integral = rule.integrate(|x| x.powi(9) + 3.0 * x * x, 0.0, 2.0, 1);
/// assert!((integral - (1024.0 / 10.0 + 8.0)).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The rule with `n ≥ 1` nodes.
    #[must_use]
    pub fn new(n: usize) -> Self {
        assert!(n >= 1, "a Gauss–Legendre rule needs at least one node");
        let mut nodes = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        for k in 0..n {
            // Tricomi's initial guess for the k-th root, then Newton on P_n.
            let mut x = (core::f64::consts::PI * (k as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp) = legendre_with_derivative(n, x);
                let step = p / dp;
                x -= step;
                if step.abs() <= 1e-16 {
                    break;
                }
            }
            let (_, dp) = legendre_with_derivative(n, x);
            nodes.push(x);
            weights.push(2.0 / ((1.0 - x * x) * dp * dp));
        }
        Self { nodes, weights }
    }

    /// ∫_a^b f(x) dx by the composite rule over `panels ≥ 1` equal sub-intervals.
    #[must_use]
    pub fn integrate(&self, f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
        let panels = panels.max(1);
        let width = (b - a) / panels as f64;
        let mut total = 0.0;
        for panel in 0..panels {
            let lo = a + width * panel as f64;
            let mid = lo + 0.5 * width;
            let sum: f64 = self
                .nodes
                .iter()
                .zip(&self.weights)
                .map(|(&x, &w)| w * f(mid + 0.5 * width * x))
                .sum();
            total += 0.5 * width * sum;
        }
        total
    }
}

/// Cumulative integrals F(x) = ∫_lo^x f on [lo, hi], exact to rounding and cheap to evaluate.
///
/// At equally spaced knots the table holds F (each cell integrated by an 8-point Gauss–Legendre
/// rule and summed with compensation), f and f′ exactly; between knots F is the quintic Hermite
/// interpolant of (F, F′ = f, F″ = f′), whose error is at most |f⁽⁵⁾| w⁶ / 46 080 on a cell of
/// width w. The caller chooses the largest cell width for which that is below rounding: for ψ_α
/// and ψ_β, whose σ₁ bends on a unit scale (|σ₁⁽⁵⁾| ≤ 45), cells of 1/128 leave an error below
/// 1e-16 × (a + b). An evaluation costs a polynomial of degree five and no call to f.
#[derive(Clone, Debug, PartialEq)]
pub struct CumulativeIntegral {
    lo: f64,
    hi: f64,
    spacing: f64,
    knots: Vec<Knot>,
}

/// F, f and f′ at one knot of a [`CumulativeIntegral`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Knot {
    integral: f64,
    value: f64,
    slope: f64,
}

impl CumulativeIntegral {
    /// The most cells a table holds (1.5 MB); wider cells are used beyond that.
    pub const MAX_CELLS: usize = 1 << 16;

    /// Tabulates ∫_lo^x f, f and f′ = `derivative` on [lo, hi] with cells of width at most
    /// `max_spacing` (at least one cell, at most [`Self::MAX_CELLS`]).
    #[must_use]
    pub fn new(
        f: impl Fn(f64) -> f64,
        derivative: impl Fn(f64) -> f64,
        lo: f64,
        hi: f64,
        max_spacing: f64,
    ) -> Self {
        let rule = GaussLegendre::new(8);
        let length = (hi - lo).max(0.0);
        let cells = ((length / max_spacing).ceil() as usize).clamp(1, Self::MAX_CELLS);
        let spacing = length / cells as f64;
        // the cells tile [lo, hi] exactly: each one ends where the next begins
        let at = |k: usize| {
            if k == cells {
                hi
            } else {
                lo + spacing * k as f64
            }
        };
        let knot = |k: usize, integral: f64| {
            let x = at(k);
            Knot {
                integral,
                value: f(x),
                slope: derivative(x),
            }
        };
        let mut knots = Vec::with_capacity(cells + 1);
        // Neumaier's compensated sum of the cell integrals
        let (mut total, mut carry) = (0.0_f64, 0.0_f64);
        knots.push(knot(0, 0.0));
        for k in 0..cells {
            let cell = rule.integrate(&f, at(k), at(k + 1), 1);
            let sum = total + cell;
            carry += if total.abs() >= cell.abs() {
                (total - sum) + cell
            } else {
                (cell - sum) + total
            };
            total = sum;
            knots.push(knot(k + 1, total + carry));
        }
        Self {
            lo,
            hi,
            spacing,
            knots,
        }
    }

    /// ∫_lo^x f for x clamped to [lo, hi].
    #[inline]
    #[must_use]
    pub fn integral_to(&self, x: f64) -> f64 {
        let x = x.clamp(self.lo, self.hi);
        if self.spacing <= 0.0 {
            return 0.0;
        }
        let u = (x - self.lo) / self.spacing;
        let k = (u as usize).min(self.knots.len() - 2);
        let t = u - k as f64;
        let (a, b) = (self.knots[k], self.knots[k + 1]);
        // the quintic Hermite basis on [0, 1], in Horner form
        let (t2, t3) = (t * t, t * t * t);
        let h1 = t3 * (10.0 + t * (-15.0 + 6.0 * t));
        let g0 = t + t3 * (-6.0 + t * (8.0 - 3.0 * t));
        let g1 = t3 * (-4.0 + t * (7.0 - 3.0 * t));
        let k0 = 0.5 * t2 * (1.0 + t * (-3.0 + t * (3.0 - t)));
        let k1 = 0.5 * t3 * (1.0 + t * (-2.0 + t));
        let w = self.spacing;
        a.integral
            + (b.integral - a.integral) * h1
            + w * (a.value * g0 + b.value * g1)
            + w * w * (a.slope * k0 + b.slope * k1)
    }
}

/// P_n(x) and P_n′(x) by the three-term recurrence.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p_prev, mut p) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let next = ((2.0 * k - 1.0) * x * p - (k - 1.0) * p_prev) / k;
        p_prev = p;
        p = next;
    }
    let dp = n as f64 * (x * p - p_prev) / (x * x - 1.0);
    (p, dp)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn weights_sum_to_two_and_nodes_are_symmetric() {
        for n in 1..=20 {
            let rule = GaussLegendre::new(n);
            assert_relative_eq!(rule.weights.iter().sum::<f64>(), 2.0, epsilon = 1e-13);
            let mut sorted = rule.nodes.clone();
            sorted.sort_by(f64::total_cmp);
            for (lo, hi) in sorted.iter().zip(sorted.iter().rev()) {
                assert_relative_eq!(*lo, -*hi, epsilon = 1e-14);
            }
        }
    }

    #[test]
    fn exact_for_polynomials_up_to_degree_2n_minus_1() {
        let rule = GaussLegendre::new(6);
        for degree in 0..12 {
            let exact = (3f64.powi(degree + 1) - (-1f64).powi(degree + 1)) / f64::from(degree + 1);
            let got = rule.integrate(|x| x.powi(degree), -1.0, 3.0, 1);
            assert_relative_eq!(got, exact, max_relative = 1e-13);
        }
    }

    #[test]
    fn cumulative_integral_of_a_cosine() {
        // cells of 1/64: the Hermite error bound is w⁶/46 080 ≈ 3e-16
        let table = CumulativeIntegral::new(f64::cos, |x| -x.sin(), 0.5, 4.0, 1.0 / 64.0);
        let mut worst = 0.0_f64;
        for i in 0..=7000 {
            let x = 0.5 + f64::from(i) * 5e-4;
            worst = worst.max((table.integral_to(x) - (x.sin() - 0.5f64.sin())).abs());
        }
        assert!(worst <= 2e-15, "largest error {worst:e}");
        assert_relative_eq!(
            table.integral_to(9.0),
            4f64.sin() - 0.5f64.sin(),
            epsilon = 1e-15
        );
        assert_eq!(table.integral_to(0.0), 0.0);
    }

    #[test]
    fn cumulative_integral_error_follows_the_sixth_power_of_the_cell() {
        // halving the cells divides the interpolation error by ≈ 2⁶ = 64 while it is above rounding
        let error = |spacing: f64| {
            let table = CumulativeIntegral::new(f64::exp, f64::exp, 0.0, 2.0, spacing);
            (0..=400)
                .map(|i| {
                    let x = f64::from(i) * 5e-3 + 1e-3;
                    (table.integral_to(x.min(2.0)) - (x.min(2.0).exp() - 1.0)).abs()
                })
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (error(0.5), error(0.25));
        assert!(coarse > 1e-9, "coarse error {coarse:e}");
        assert!(
            (40.0..90.0).contains(&(coarse / fine)),
            "ratio {}",
            coarse / fine
        );
    }

    #[test]
    fn cumulative_integral_caps_its_cells() {
        let table = CumulativeIntegral::new(|_| 1.0, |_| 0.0, 0.0, 1e9, 1e-3);
        assert_eq!(table.knots.len(), CumulativeIntegral::MAX_CELLS + 1);
        assert_relative_eq!(table.integral_to(3.7e8), 3.7e8, max_relative = 1e-15);
    }

    #[test]
    fn composite_rule_integrates_a_cosine_to_machine_precision() {
        let rule = GaussLegendre::new(10);
        let got = rule.integrate(f64::cos, 0.3, 2.9, 4);
        assert_relative_eq!(got, 2.9f64.sin() - 0.3f64.sin(), epsilon = 1e-15);
    }
}

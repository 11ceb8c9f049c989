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

/// Cumulative integrals F(x) = ∫_lo^x f on [lo, hi], tabulated exactly at equally spaced knots and
/// completed by one Gauss–Legendre panel from the knot below x: nothing is interpolated, so no
/// accuracy is lost, and an evaluation costs one short panel.
#[derive(Clone, Debug, PartialEq)]
pub struct CumulativeIntegral {
    lo: f64,
    hi: f64,
    spacing: f64,
    knots: Vec<f64>,
    rule: GaussLegendre,
}

impl CumulativeIntegral {
    /// Knots per table; with an analytic integrand the panels between knots are short enough for an
    /// 8-point rule to reach machine precision.
    const KNOTS: usize = 32;

    /// Tabulates ∫_lo^x f at `lo + k (hi − lo)/32`, k = 0..=32.
    #[must_use]
    pub fn new(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Self {
        let rule = GaussLegendre::new(8);
        let spacing = (hi - lo) / Self::KNOTS as f64;
        let mut knots = Vec::with_capacity(Self::KNOTS + 1);
        let mut total = 0.0;
        knots.push(total);
        for k in 0..Self::KNOTS {
            let a = lo + spacing * k as f64;
            total += rule.integrate(&f, a, a + spacing, 2);
            knots.push(total);
        }
        Self {
            lo,
            hi,
            spacing,
            knots,
            rule,
        }
    }

    /// ∫_lo^x f for x clamped to [lo, hi]; `f` must be the integrand given to [`Self::new`].
    #[must_use]
    pub fn integral_to(&self, f: impl Fn(f64) -> f64, x: f64) -> f64 {
        let x = x.clamp(self.lo, self.hi);
        let k = (((x - self.lo) / self.spacing) as usize).min(Self::KNOTS);
        let knot = self.lo + self.spacing * k as f64;
        self.knots[k] + self.rule.integrate(f, knot, x, 1)
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
        let table = CumulativeIntegral::new(f64::cos, 0.5, 4.0);
        for i in 0..=70 {
            let x = 0.5 + f64::from(i) * 0.05;
            assert_relative_eq!(
                table.integral_to(f64::cos, x),
                x.sin() - 0.5f64.sin(),
                epsilon = 1e-14
            );
        }
        assert_relative_eq!(
            table.integral_to(f64::cos, 9.0),
            4f64.sin() - 0.5f64.sin(),
            epsilon = 1e-14
        );
        assert_eq!(table.integral_to(f64::cos, 0.0), 0.0);
    }

    #[test]
    fn composite_rule_integrates_a_cosine_to_machine_precision() {
        let rule = GaussLegendre::new(10);
        let got = rule.integrate(f64::cos, 0.3, 2.9, 4);
        assert_relative_eq!(got, 2.9f64.sin() - 0.3f64.sin(), epsilon = 1e-15);
    }
}

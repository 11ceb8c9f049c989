//! The plots of the report's functions (Olfati-Saber, CDS 03-006, seed 004), drawn from the very
//! functions the simulations call, two panels each as the report has them:
//!
//! - Fig. 2: the bump function ρ(z/r) with k₀ = 5/6 and r = 12 (§ 3, after eq. 16), and its
//!   derivative; ours: the bump itself, the cosine influence map of seed 003 eq. 5, whose slope
//!   is bounded by π/(2(1 − k₀)) (its minimum, at the middle of the transition, divided by r).
//! - Fig. 4: ψ_α(z) and φ_α(z) of eq. 29 with a = 1 and b = 5.
//! - Fig. 5: the pair potential of two α-agents against their distance ‖q‖: (a) non-smooth,
//!   ψ_α(‖q‖ − d_α) inside r and 0 beyond (eq. 28), with the jump h₀ = ψ_α(r − d_α) at r of
//!   eq. 31; (b) smooth, ρ(‖q‖/r) ψ_α(‖q‖ − d_α) (eq. 30), with the parameters of the report's
//!   Example 2 (d_α = 10, r = 1.2 d_α = 12, a = 1, b = 5).
//!
//! [`function_svg`], [`function_png`]: a figure; [`ReportFunction::curves`] its sampled data.

use flock_math::{Bump, Potential, UnevenSigmoid};
use flocking::protocols::{AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams};
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};

use crate::curves::metric_curves::{Curves, fitted_range};
use crate::draw::render::{self, Figure};
use crate::error::VizError;
use crate::snapshots::snapshot::{below_title, grid_size};

/// d_α of Figs. 2 and 5 (k₀ = d_α / r = 5/6).
const D_ALPHA: f64 = 10.0;
/// r of Figs. 2 and 5.
const R: f64 = 12.0;
/// a and b of Figs. 4 and 5.
const A: f64 = 1.0;
const B: f64 = 5.0;
/// Points per curve: 1400 intervals, so that every grid below holds d_α, r and z = 0 exactly.
const SAMPLES: usize = 1401;

/// One of the report's function plots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportFunction {
    /// Fig. 2: ρ(z/r) and its derivative.
    Bump,
    /// Fig. 4: ψ_α and φ_α.
    Action,
    /// Fig. 5: the non-smooth and the smooth pair potential.
    PairPotential,
}

/// One panel's curve: x and y values, a NaN where the curve jumps.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The panel's title.
    pub title: &'static str,
    /// The horizontal axis' label.
    pub x_desc: &'static str,
    /// The vertical axis' label.
    pub y_desc: &'static str,
    /// The abscissae.
    pub x: Vec<f64>,
    /// The values (NaN breaks the line).
    pub y: Vec<f64>,
}

impl ReportFunction {
    /// Every plot, in the report's order.
    pub const ALL: [Self; 3] = [Self::Bump, Self::Action, Self::PairPotential];

    /// The file stem of its figure, e.g. `tr2003_fig4_action`.
    #[must_use]
    pub const fn stem(self) -> &'static str {
        match self {
            Self::Bump => "tr2003_fig2_bump",
            Self::Action => "tr2003_fig4_action",
            Self::PairPotential => "tr2003_fig5_pair_potential",
        }
    }

    /// The report's caption, as seed 004 prints it.
    #[must_use]
    pub const fn caption(self) -> &'static str {
        match self {
            Self::Bump => "Figure 2: (a) A bump function ρ(z) and (b) ρ′(z).",
            Self::Action => {
                "Figure 4: The potential and action functions with parameters a = 1 and b = 5: \
                 (a) ψα(z) and (b) φα(z)."
            }
            Self::PairPotential => {
                "Figure 5: The pair-wise potential function between two α-agents: (a) the \
                 nonsmooth potential and (b) the smooth potential."
            }
        }
    }

    /// The two panels' curves.
    #[must_use]
    pub fn curves(self) -> [Curve; 2] {
        match self {
            Self::Bump => {
                let bump = Bump::influence_map(D_ALPHA / R, 1);
                let x = grid(0.0, 14.0);
                [
                    curve("(a) ρ(z/r), k₀ = 5/6, r = 12", "ρ", &x, |z| {
                        bump.value(z / R)
                    }),
                    curve("(b) d/dz ρ(z/r) = ρ′(z/r)/r", "dρ/dz", &x, |z| {
                        bump.derivative(z / R) / R
                    }),
                ]
            }
            Self::Action => {
                let sigmoid = UnevenSigmoid::new(A, B);
                let x = grid(-10.0, 10.0);
                [
                    curve("(a) ψα(z), a = 1, b = 5", "ψα", &x, |z| {
                        sigmoid.potential(z)
                    }),
                    curve("(b) φα(z) = ψα′(z)", "φα", &x, |z| {
                        sigmoid.action(z)
                    }),
                ]
            }
            Self::PairPotential => {
                let params = AlphaAlphaParams::new(D_ALPHA, R, A, B);
                let pair = |form| AlphaAlpha::new(params, form, 1.0);
                let (nonsmooth, smooth) = (
                    pair(AlphaAlphaForm::Nonsmooth),
                    pair(AlphaAlphaForm::Smooth),
                );
                let x = grid(8.0, 15.0);
                // a NaN at r breaks the non-smooth curve at its jump
                let mut jumping = x.clone();
                let at = jumping.partition_point(|&d| d < R);
                jumping.insert(at, R);
                let mut a = curve("(a) non-smooth, d = 10, r = 12", "ψ", &jumping, |d| {
                    nonsmooth.pair_potential(d)
                });
                a.y[at] = f64::NAN;
                let mut b = curve("(b) smooth", "ψ", &x, |d| smooth.pair_potential(d));
                (a.x_desc, b.x_desc) = ("‖q‖", "‖q‖");
                [a, b]
            }
        }
    }
}

/// `SAMPLES` evenly spaced points of [from, to].
fn grid(from: f64, to: f64) -> Vec<f64> {
    (0..SAMPLES)
        .map(|k| from + (to - from) * k as f64 / (SAMPLES - 1) as f64)
        .collect()
}

/// The curve of `f` over `x`, against z.
fn curve(title: &'static str, y_desc: &'static str, x: &[f64], f: impl Fn(f64) -> f64) -> Curve {
    Curve {
        title,
        x_desc: "z",
        y_desc,
        x: x.to_vec(),
        y: x.iter().map(|&z| f(z)).collect(),
    }
}

/// The SVG figure of `function`: the report's caption over its two panels.
///
/// # Errors
/// [`VizError::Draw`] if plotters fails.
pub fn function_svg(function: ReportFunction) -> Result<String, VizError> {
    render::svg(&FunctionFigure::new(function))
}

/// The figure of [`function_svg`] as a PNG image.
///
/// # Errors
/// As [`function_svg`]; [`VizError::Encode`] if PNG encoding fails.
pub fn function_png(function: ReportFunction) -> Result<Vec<u8>, VizError> {
    render::png(&FunctionFigure::new(function))
}

/// A function figure, sampled and ready to draw.
struct FunctionFigure {
    title: &'static str,
    curves: [Curve; 2],
}

impl FunctionFigure {
    fn new(function: ReportFunction) -> Self {
        Self {
            title: function.caption(),
            curves: function.curves(),
        }
    }
}

/// The size of one panel in pixels.
const PANEL: (u32, u32) = (560, 340);

impl Figure for FunctionFigure {
    fn size(&self) -> (u32, u32) {
        let (w, h) = grid_size(PANEL, 2, 1, self.title);
        // the captions are long: room for them in the title band
        (w.max(1100), h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body = below_title(root, self.title)?;
        for (area, c) in body.split_evenly((1, 2)).iter().zip(&self.curves) {
            let curves = Curves {
                title: c.title,
                x_desc: c.x_desc,
                y_desc: c.y_desc,
                t: &c.x,
                values: &c.y,
                secondary: None,
                primary_label: None,
                log: false,
            };
            let x_range = fitted_range(c.x.iter().copied(), false);
            let y_range = fitted_range(c.y.iter().copied(), false);
            curves.draw(area, x_range, y_range)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// The value at the sample nearest `x`.
    fn at(c: &Curve, x: f64) -> f64 {
        let k =
            c.x.iter()
                .enumerate()
                .min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs()))
                .map(|(k, _)| k)
                .unwrap_or_default();
        c.y[k]
    }

    #[test]
    fn the_bump_is_flat_to_k0_r_and_its_slope_bounded_by_pi_over_2_1_minus_k0() {
        let [rho, slope] = ReportFunction::Bump.curves();
        assert_eq!(at(&rho, 10.0), 1.0);
        assert_eq!(at(&rho, 12.0), 0.0);
        assert_relative_eq!(at(&rho, 11.0), 0.5, epsilon = 1e-12);
        let bound = core::f64::consts::PI / (2.0 * (1.0 - 5.0 / 6.0)) / R;
        let least = slope.y.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            least >= -bound && least < -0.999 * bound,
            "{least} vs −{bound}"
        );
        assert!(slope.y.iter().all(|&v| v <= 0.0));
    }

    #[test]
    fn psi_alpha_is_zero_at_its_minimum_and_phi_alpha_is_bounded_by_a_and_b() {
        let [psi, phi] = ReportFunction::Action.curves();
        assert_relative_eq!(at(&psi, 0.0), 0.0, epsilon = 1e-12);
        assert!(psi.y.iter().all(|&v| v >= -1e-12));
        assert_relative_eq!(at(&phi, 0.0), 0.0, epsilon = 1e-12);
        assert!(phi.y.iter().all(|&v| (-B..=A).contains(&v)));
        // bounded sigmoid: steeper repulsion (b) than attraction (a)
        assert!(at(&phi, -10.0) < -4.5 && at(&phi, 10.0) > 0.9);
    }

    #[test]
    fn the_nonsmooth_pair_potential_jumps_by_h0_at_r_and_the_smooth_one_does_not() {
        let [nonsmooth, smooth] = ReportFunction::PairPotential.curves();
        let h0 = UnevenSigmoid::new(A, B).potential(R - D_ALPHA);
        let gap = nonsmooth
            .y
            .iter()
            .position(|v| v.is_nan())
            .expect("a break at r");
        assert_eq!(nonsmooth.x[gap], R);
        assert_relative_eq!(nonsmooth.y[gap - 1], h0, max_relative = 1e-2);
        assert_eq!(nonsmooth.y[gap + 1], 0.0);
        // the smooth one reaches 0 at r continuously: small steps on either side of it
        assert_eq!(at(&smooth, R), 0.0);
        for (x, w) in smooth.x.iter().zip(smooth.y.windows(2)) {
            if (x - R).abs() < 0.5 {
                assert!((w[1] - w[0]).abs() < 1e-2 * h0, "a jump at ‖q‖ = {x}");
            }
        }
        assert_eq!(at(&smooth, D_ALPHA), 0.0);
    }

    #[test]
    fn each_figure_is_drawn_with_the_reports_caption() {
        for function in ReportFunction::ALL {
            let svg = function_svg(function).expect("drawn");
            assert!(svg.contains(&function.caption()[..9]), "{function:?}");
            assert!(
                function_png(function)
                    .expect("drawn")
                    .starts_with(b"\x89PNG")
            );
        }
    }
}

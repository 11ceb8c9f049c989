//! The metric curves of a run, as what matters for its model ([`MetricsOptions::kind`]). For
//! Olfati-Saber's and Tanner's protocols, as TAC 2006 Fig. 18 plots them: connectivity C(t),
//! cohesion radius R(t), deviation energy Ẽ(t) and velocity mismatch K̃(t), one panel each,
//! followed by panels for the energy H, the minimum distance between agents and, when the run has
//! them, the clearance to the nearest obstacle and the distance ‖q̄ − q_r‖ of the flock's centre
//! from its γ-agent. For the models that set velocities (Vicsek, boids, Couzin) the order
//! parameters (polarisation and milling), the groups (C, C*), the cohesion radius and the mean
//! nearest-neighbour distance, with no lattice, energy or collision panel, which mean nothing for
//! them; Cucker–Smale adds its velocity mismatch, Vásárhelyi's model its own order parameters.
//! Every panel has a title, axes and units; Ẽ and K̃ are on a log scale (their non-positive
//! values, e.g. K̃ = 0 at rest, are left out of the curve).
//!
//! - [`metrics_svg`], [`metrics_png`]: the figure.
//! - [`MetricsOptions`]: panel size, columns, title, units.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::prelude::{
    ChartBuilder, DrawingArea, DrawingBackend, IntoLogRange, LineSeries, PathElement,
};
use plotters::style::Color;

use flocking::VerdictKind;

use crate::data::metric_series::Metrics;
use crate::draw::format;
use crate::draw::render::{self, Figure};
use crate::draw::style::{self, CURVE, CURVE_SECONDARY, GRID, INK};
use crate::error::VizError;
use crate::snapshots::snapshot::{below_title, grid_size, text_style};

/// How the metric figure is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct MetricsOptions {
    /// The size of one panel in pixels (width, height).
    pub panel_size: (u32, u32),
    /// Panels per row.
    pub columns: usize,
    /// The figure's title (may be empty).
    pub title: String,
    /// The scenario's unit of length.
    pub length_unit: String,
    /// The unit of time.
    pub time_unit: String,
    /// Whose panels: the verdict kind of the run's model ([`VerdictKind::of`]).
    pub kind: VerdictKind,
}

impl Default for MetricsOptions {
    fn default() -> Self {
        Self {
            panel_size: (560, 320),
            columns: 2,
            title: String::new(),
            length_unit: "m".to_owned(),
            time_unit: "s".to_owned(),
            kind: VerdictKind::Definition5,
        }
    }
}

/// How a metric's values are placed on the vertical axis.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Scale {
    /// From 0 to 1 (fractions: C, C*).
    Unit,
    /// Linear, fitted to the values.
    Linear,
    /// Logarithmic, fitted to the positive values.
    Log,
}

/// One panel of the figure.
struct Panel {
    /// The column plotted.
    column: &'static str,
    /// A second column drawn in grey, its legend text, and the legend text of the first.
    secondary: Option<(&'static str, &'static str, &'static str)>,
    /// The panel's title, e.g. `connectivity C`.
    title: &'static str,
    /// The vertical axis' label, `{L}` standing for the length unit and `{T}` for the time unit.
    y_desc: &'static str,
    scale: Scale,
}

/// C (and C*) against t.
const CONNECTIVITY: Panel = Panel {
    column: "connectivity",
    secondary: Some((
        "giant_component",
        "C* (giant component)",
        "C (connectivity)",
    )),
    title: "connectivity C",
    y_desc: "C (dimensionless)",
    scale: Scale::Unit,
};

/// R against t.
const COHESION: Panel = Panel {
    column: "cohesion_radius",
    secondary: None,
    title: "cohesion radius R",
    y_desc: "R ({L})",
    scale: Scale::Linear,
};

/// K̃ against t.
const MISMATCH: Panel = Panel {
    column: "velocity_mismatch",
    secondary: None,
    title: "velocity mismatch K̃",
    y_desc: "K̃ ({L}²/{T}², log scale)",
    scale: Scale::Log,
};

/// The least distance against t.
const MIN_DISTANCE: Panel = Panel {
    column: "min_distance",
    secondary: None,
    title: "min distance between agents",
    y_desc: "min ‖q_j − q_i‖ ({L})",
    scale: Scale::Linear,
};

/// The polarisation and the milling against t.
const ORDER: Panel = Panel {
    column: "polarisation",
    secondary: Some(("milling", "milling O_r", "polarisation O_p")),
    title: "order: polarisation and milling",
    y_desc: "O_p, O_r (dimensionless)",
    scale: Scale::Unit,
};

/// The mean nearest-neighbour distance against t.
const SPACING: Panel = Panel {
    column: "nearest_neighbour_mean",
    secondary: None,
    title: "mean nearest-neighbour distance",
    y_desc: "mean min_j ‖q_j − q_i‖ ({L})",
    scale: Scale::Linear,
};

/// The panels of Definition 5's models (TAC 2006 Fig. 18 and more), in order; a panel whose
/// column is missing is left out.
const LATTICE_PANELS: [Panel; 8] = [
    CONNECTIVITY,
    COHESION,
    Panel {
        column: "deviation_energy",
        secondary: None,
        title: "deviation energy Ẽ",
        y_desc: "Ẽ (dimensionless, log scale)",
        scale: Scale::Log,
    },
    MISMATCH,
    Panel {
        column: "energy",
        secondary: None,
        title: "energy H",
        y_desc: "H ({L}²/{T}², unit mass)",
        scale: Scale::Linear,
    },
    MIN_DISTANCE,
    Panel {
        column: "obstacle_clearance",
        secondary: None,
        title: "obstacle clearance",
        y_desc: "clearance ({L})",
        scale: Scale::Linear,
    },
    Panel {
        column: "gamma_position_error",
        secondary: None,
        title: "distance from the γ-agent ‖q̄ − q_r‖",
        y_desc: "‖q̄ − q_r‖ ({L})",
        scale: Scale::Linear,
    },
];

/// The panels of the models that set velocities (Vicsek, boids, Couzin).
const ORDER_PANELS: [Panel; 4] = [ORDER, CONNECTIVITY, COHESION, SPACING];

/// The panels of Cucker–Smale: the convergence of the velocities first.
const CUCKER_SMALE_PANELS: [Panel; 4] = [MISMATCH, COHESION, ORDER, CONNECTIVITY];

/// The panels of Vásárhelyi et al.: their order parameters φ^corr, φ^vel/v^flock, and the
/// least distance (their collisions at r^coll).
const VASARHELYI_PANELS: [Panel; 6] = [
    ORDER,
    Panel {
        column: "velocity_correlation",
        secondary: None,
        title: "velocity correlation φ^corr",
        y_desc: "φ^corr (dimensionless)",
        scale: Scale::Unit,
    },
    Panel {
        column: "speed_ratio",
        secondary: None,
        title: "mean speed / flocking speed φ^vel / v^flock",
        y_desc: "φ^vel / v^flock (dimensionless)",
        scale: Scale::Linear,
    },
    CONNECTIVITY,
    MIN_DISTANCE,
    Panel {
        column: "wall_violation",
        secondary: None,
        title: "distance outside the arena φ^wall",
        y_desc: "φ^wall ({L})",
        scale: Scale::Linear,
    },
];

/// The panels of a model of verdict kind `kind`.
fn panels_of(kind: VerdictKind) -> &'static [Panel] {
    match kind {
        VerdictKind::Definition5 => &LATTICE_PANELS,
        VerdictKind::CuckerSmale => &CUCKER_SMALE_PANELS,
        VerdictKind::Order(_) | VerdictKind::Couzin => &ORDER_PANELS,
        VerdictKind::Vasarhelyi => &VASARHELYI_PANELS,
    }
}

/// The SVG figure of a run's metrics (TAC 2006 Fig. 18 and more; see the module documentation).
///
/// # Errors
/// [`VizError::Invalid`] when the metrics have no rows or none of the plotted columns, or the
/// panel size is out of bounds.
///
/// # Example
/// ```
/// use flock_viz::{Metrics, MetricsOptions, metrics_svg};
///
/// let t = vec![0.0, 1.0, 2.0];
/// let m = Metrics::from_columns(vec![
///     ("t".into(), t),
///     ("connectivity".into(), vec![0.2, 0.8, 1.0]),
///     ("cohesion_radius".into(), vec![50.0, 30.0, 20.0]),
/// ])
/// .unwrap();
/// let svg = metrics_svg(&m, &MetricsOptions::default()).unwrap();
/// assert!(svg.contains("connectivity C") && svg.contains("R (m)") && svg.contains("t (s)"));
/// ```
pub fn metrics_svg(metrics: &Metrics, options: &MetricsOptions) -> Result<String, VizError> {
    render::svg(&MetricsFigure::new(metrics, options)?)
}

/// The figure of [`metrics_svg`] as a PNG image.
///
/// # Errors
/// As [`metrics_svg`]; [`VizError::Encode`] if PNG encoding fails.
pub fn metrics_png(metrics: &Metrics, options: &MetricsOptions) -> Result<Vec<u8>, VizError> {
    render::png(&MetricsFigure::new(metrics, options)?)
}

/// The metric figure, checked and ready to draw.
struct MetricsFigure<'a> {
    metrics: &'a Metrics,
    options: &'a MetricsOptions,
    panels: Vec<&'static Panel>,
    columns: usize,
    rows: usize,
}

impl<'a> MetricsFigure<'a> {
    fn new(metrics: &'a Metrics, options: &'a MetricsOptions) -> Result<Self, VizError> {
        if metrics.is_empty() {
            return Err(VizError::invalid("the metrics have no rows"));
        }
        let panels: Vec<&'static Panel> = panels_of(options.kind)
            .iter()
            .filter(|p| metrics.column(p.column).is_some())
            .collect();
        if panels.is_empty() {
            return Err(VizError::invalid(format!(
                "the metrics have none of the plotted columns ({}); they have {:?}",
                panels_of(options.kind)
                    .iter()
                    .map(|p| p.column)
                    .collect::<Vec<_>>()
                    .join(", "),
                metrics.names()
            )));
        }
        let columns = options.columns.clamp(1, panels.len());
        let rows = panels.len().div_ceil(columns);
        Ok(Self {
            metrics,
            options,
            panels,
            columns,
            rows,
        })
    }
}

impl Figure for MetricsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        grid_size(
            self.options.panel_size,
            self.columns,
            self.rows,
            &self.options.title,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body = below_title(root, &self.options.title)?;
        let areas = body.split_evenly((self.rows, self.columns));
        for (area, panel) in areas.iter().zip(&self.panels) {
            self.draw_panel(area, panel)?;
        }
        Ok(())
    }
}

impl MetricsFigure<'_> {
    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: &Panel,
    ) -> Result<(), VizError> {
        let t = self.metrics.time();
        let values = self.metrics.column(panel.column).unwrap_or_default();
        let secondary = panel.secondary.and_then(|(column, label, primary)| {
            Some((self.metrics.column(column)?, label, primary))
        });
        let t_range = fitted_range(t.iter().copied(), false);
        let y_desc = panel
            .y_desc
            .replace("{L}", &self.options.length_unit)
            .replace("{T}", &self.options.time_unit);
        let x_desc = format!("t ({})", self.options.time_unit);
        let primary_label = secondary.map(|(_, _, primary)| primary);
        let secondary = secondary.map(|(values, label, _)| (values, label));
        let curves = Curves {
            title: panel.title,
            x_desc: &x_desc,
            y_desc: &y_desc,
            t,
            values,
            secondary,
            primary_label,
            log: panel.scale == Scale::Log,
        };
        match panel.scale {
            Scale::Unit => curves.draw(area, t_range, 0.0..1.05),
            Scale::Linear => {
                let y_range = fitted_range(values.iter().copied(), false);
                curves.draw(area, t_range, y_range)
            }
            Scale::Log => {
                let y_range = fitted_range(values.iter().copied(), true);
                if y_range.start > 0.0 {
                    curves.draw(area, t_range, y_range.log_scale())
                } else {
                    // No positive value: an empty log axis would mean nothing.
                    curves.draw(area, t_range, fitted_range(values.iter().copied(), false))
                }
            }
        }
    }
}

/// The data and labels of one panel: values against t (or any abscissa).
pub(crate) struct Curves<'a> {
    pub(crate) title: &'a str,
    pub(crate) x_desc: &'a str,
    pub(crate) y_desc: &'a str,
    pub(crate) t: &'a [f64],
    pub(crate) values: &'a [f64],
    pub(crate) secondary: Option<(&'a [f64], &'a str)>,
    /// The legend of the first column, when there is a second.
    pub(crate) primary_label: Option<&'a str>,
    pub(crate) log: bool,
}

impl Curves<'_> {
    pub(crate) fn draw<DB, Y>(
        &self,
        area: &DrawingArea<DB, Shift>,
        t_range: Range<f64>,
        y: Y,
    ) -> Result<(), VizError>
    where
        DB: DrawingBackend,
        Y: AsRangedCoord<Value = f64>,
        Y::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(area)
            .caption(self.title, text_style(16))
            .margin_top(6)
            .margin_bottom(4)
            .margin_left(6)
            .margin_right(18)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(t_range, y)
            .map_err(VizError::draw)?;
        chart
            .configure_mesh()
            .light_line_style(style::rgb(GRID).mix(0.0))
            .bold_line_style(style::rgb(GRID))
            .x_desc(self.x_desc)
            .y_desc(self.y_desc)
            .x_labels(7)
            .y_labels(6)
            .x_label_formatter(&|v| format::tick(*v))
            .y_label_formatter(&|v| format::tick(*v))
            .label_style(text_style(12))
            .axis_desc_style(text_style(13))
            .axis_style(style::rgb(INK))
            .draw()
            .map_err(VizError::draw)?;

        if let Some((values, label)) = &self.secondary {
            let colour = style::rgb(CURVE_SECONDARY);
            let mut first = true;
            for run in self.runs(values) {
                let series = chart
                    .draw_series(LineSeries::new(run, colour.stroke_width(2)))
                    .map_err(VizError::draw)?;
                if first {
                    series.label(*label).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                    });
                    first = false;
                }
            }
        }
        let colour = style::rgb(CURVE);
        for (k, run) in self.runs(self.values).into_iter().enumerate() {
            let series = chart
                .draw_series(LineSeries::new(run, colour.stroke_width(2)))
                .map_err(VizError::draw)?;
            if let (0, Some(label)) = (k, &self.primary_label) {
                series.label(*label).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
        }
        if self.secondary.is_some() {
            chart
                .configure_series_labels()
                .label_font(text_style(12))
                .background_style(style::rgb(style::BACKGROUND).mix(0.85))
                .border_style(style::rgb(GRID))
                .position(plotters::chart::SeriesLabelPosition::LowerRight)
                .draw()
                .map_err(VizError::draw)?;
        }
        Ok(())
    }

    /// The curve as runs of consecutive plottable points: finite, and positive on a log axis.
    fn runs(&self, values: &[f64]) -> Vec<Vec<(f64, f64)>> {
        let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut current = Vec::new();
        for (&t, &v) in self.t.iter().zip(values) {
            if t.is_finite() && v.is_finite() && (!self.log || v > 0.0) {
                current.push((t, v));
            } else if !current.is_empty() {
                runs.push(std::mem::take(&mut current));
            }
        }
        if !current.is_empty() {
            runs.push(current);
        }
        runs
    }
}

/// An axis range holding the finite values (positive ones for a log axis), with a 5 % margin on
/// a linear axis and whole decades on a log axis; a sensible range when there is no spread.
pub(crate) fn fitted_range(values: impl Iterator<Item = f64>, log: bool) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return if log { 0.0..0.0 } else { 0.0..1.0 };
    }
    if log {
        let (a, b) = (lo.log10().floor(), hi.log10().ceil());
        let b = if a == b { b + 1.0 } else { b };
        // a hair beyond the decades, so that plotters' ticks, found as powers of ten from the
        // rounded logarithm of the ends, include both ends (1e-13..1e-12 had one tick)
        return 10f64.powf(a) * (1.0 - 1e-9)..10f64.powf(b) * (1.0 + 1e-9);
    }
    if lo == hi {
        let pad = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return lo - pad..hi + pad;
    }
    let pad = 0.05 * (hi - lo);
    lo - pad..hi + pad
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A log panel whose values span less than a decade is widened to whole decades, and gets a
    /// labelled tick at each end (issue 53 item 8): at least two, whatever the decade.
    #[test]
    fn a_log_panel_of_less_than_a_decade_has_two_ticks() {
        use plotters::coord::combinators::LogCoord;
        use plotters::coord::ranged1d::Ranged;
        for a in -14..=6 {
            let lo = 2.0 * 10f64.powi(a);
            let range = fitted_range([lo, 1.5 * lo].into_iter(), true);
            let coord: LogCoord<f64> = range.clone().log_scale().into();
            let ticks = coord.key_points(4usize);
            assert!(ticks.len() >= 2, "10^{a}: {range:?} has ticks {ticks:?}");
        }
    }

    #[test]
    fn ranges_fit_the_values() {
        assert_eq!(fitted_range([1.0, 3.0].into_iter(), false), 0.9..3.1);
        assert_eq!(fitted_range([2.0, 2.0].into_iter(), false), 1.8..2.2);
        assert_eq!(fitted_range([f64::NAN].into_iter(), false), 0.0..1.0);
        let r = fitted_range([0.0, 2e-9, 3e-2].into_iter(), true);
        assert!((r.start - 1e-9).abs() < 1e-17 && (r.end - 0.1).abs() < 1e-9);
    }
}

//! Phase diagrams of parameter sweeps (`flocking sweep plot`): a metric over one or two swept
//! parameters, each point of the grid summarised over its seeds.
//!
//! - Two axes: a heatmap, one cell per (x, y) grid value — the cells in the order of the sorted
//!   values, labelled with them (so a logarithmic grid is evenly spaced) — coloured by the mean
//!   over the seeds (viridis), with a colour bar; a cell without a finite value is grey.
//! - One axis: the mean against x (log x on request) inside a band — min to max, or the 25–75 %
//!   quantiles — with a dot for every run.
//!
//! NaN values (failed runs, empty fields) are left out of means, bands and dots.

use plotters::coord::Shift;
use plotters::prelude::{
    ChartBuilder, Circle, DrawingArea, DrawingBackend, IntoLogRange, IntoSegmentedCoord,
    LineSeries, Polygon, Rectangle, SegmentValue,
};
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use plotters::style::{Color, RGBColor};

use crate::error::VizError;
use crate::format;
use crate::render::{self, Figure, TextMode};
use crate::snapshot::{below_title, text_style};
use crate::style::{self, CURVE, INK};

/// One run of a sweep as the phase diagram sees it: its axis values and the metric (NaN when the
/// run failed or has no value).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhasePoint {
    /// The value of the x axis.
    pub x: f64,
    /// The value of the y axis, for a heatmap.
    pub y: Option<f64>,
    /// The metric.
    pub value: f64,
}

/// The band of a one-axis diagram.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Band {
    /// From the least to the largest value over the seeds.
    #[default]
    MinMax,
    /// From the 25 % to the 75 % quantile (linear interpolation between order statistics).
    Quantiles,
}

/// How a phase diagram is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseOptions {
    /// The title (may be empty).
    pub title: String,
    /// The x axis' label (the parameter path).
    pub x_label: String,
    /// The y axis' label: `Some` for a heatmap.
    pub y_label: Option<String>,
    /// The metric's name (the colour bar's or the y axis' label).
    pub metric: String,
    /// Logarithmic x axis (one-axis diagrams; a heatmap's cells are evenly spaced anyway).
    pub log_x: bool,
    /// Logarithmic metric axis (one-axis diagrams).
    pub log_y: bool,
    /// The band of a one-axis diagram.
    pub band: Band,
    /// The figure's size in pixels.
    pub size: (u32, u32),
}

impl Default for PhaseOptions {
    fn default() -> Self {
        Self {
            title: String::new(),
            x_label: String::new(),
            y_label: None,
            metric: String::new(),
            log_x: false,
            log_y: false,
            band: Band::MinMax,
            size: (800, 600),
        }
    }
}

/// The grey of a heatmap cell without a finite value.
pub const EMPTY_CELL: [u8; 3] = [0xC8, 0xC8, 0xC8];
/// The band of a one-axis diagram.
pub const BAND: [u8; 3] = [0xC6, 0xD4, 0xEA];

/// The phase diagram as SVG.
///
/// # Errors
/// [`VizError::Invalid`] for no point, no finite value, or points with and without y.
///
/// # Example
/// ```
/// use flock_viz::phase::{PhaseOptions, PhasePoint, phase_svg};
///
/// let points: Vec<PhasePoint> = [(0.1, 1.0, 0.2), (0.1, 2.0, 0.9), (0.2, 1.0, 0.4), (0.2, 2.0, 1.0)]
///     .map(|(x, y, value)| PhasePoint { x, y: Some(y), value })
///     .to_vec();
/// let options = PhaseOptions {
///     x_label: "algorithm.c1".into(),
///     y_label: Some("agents".into()),
///     metric: "alpha_flock".into(),
///     ..PhaseOptions::default()
/// };
/// let svg = phase_svg(&points, &options).unwrap();
/// assert!(svg.contains("algorithm.c1") && svg.contains("alpha_flock"));
/// ```
pub fn phase_svg(points: &[PhasePoint], options: &PhaseOptions) -> Result<String, VizError> {
    render::svg(&Diagram::new(points, options)?)
}

/// The phase diagram as PNG.
///
/// # Errors
/// As [`phase_svg`].
pub fn phase_png(points: &[PhasePoint], options: &PhaseOptions) -> Result<Vec<u8>, VizError> {
    render::png(&Diagram::new(points, options)?)
}

/// The values of each grid point: the sorted distinct x (and y) and the finite values there.
struct Diagram<'a> {
    options: &'a PhaseOptions,
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// `cells[i][j]`: the finite values at (xs[i], ys[j]) (j = 0 without y).
    cells: Vec<Vec<Vec<f64>>>,
    range: (f64, f64),
}

fn distinct(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}

fn index(values: &[f64], x: f64) -> usize {
    values
        .binary_search_by(|v| v.total_cmp(&x))
        .expect("a value of the grid")
}

/// The q-quantile of sorted values (linear between order statistics).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    let position = q * (sorted.len() - 1) as f64;
    let (below, above) = (position.floor() as usize, position.ceil() as usize);
    sorted[below] + (sorted[above] - sorted[below]) * (position - below as f64)
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

impl<'a> Diagram<'a> {
    fn new(points: &[PhasePoint], options: &'a PhaseOptions) -> Result<Self, VizError> {
        let metric = &options.metric;
        if points.is_empty() {
            return Err(VizError::invalid(format!("no run to draw {metric} of")));
        }
        let heatmap = options.y_label.is_some();
        if points.iter().any(|p| p.y.is_some() != heatmap) {
            return Err(VizError::invalid(
                "a heatmap needs a y value for every run and a y label; a line needs neither",
            ));
        }
        if points
            .iter()
            .any(|p| !p.x.is_finite() || p.y.is_some_and(|y| !y.is_finite()))
        {
            return Err(VizError::invalid(
                "an axis value that is not a finite number",
            ));
        }
        let xs = distinct(points.iter().map(|p| p.x));
        let ys = distinct(points.iter().map(|p| p.y.unwrap_or(0.0)));
        let mut cells = vec![vec![Vec::new(); ys.len()]; xs.len()];
        for p in points.iter().filter(|p| p.value.is_finite()) {
            cells[index(&xs, p.x)][index(&ys, p.y.unwrap_or(0.0))].push(p.value);
        }
        for column in &mut cells {
            for cell in column {
                cell.sort_by(f64::total_cmp);
            }
        }
        let finite = || cells.iter().flatten().flatten().copied();
        let (lo, hi) = (
            finite().fold(f64::INFINITY, f64::min),
            finite().fold(f64::NEG_INFINITY, f64::max),
        );
        if lo > hi {
            return Err(VizError::invalid(format!("no run has a value of {metric}")));
        }
        Ok(Self {
            options,
            xs,
            ys,
            cells,
            range: (lo, hi),
        })
    }

    /// The colour of `value` on the map from the least to the largest mean.
    fn colour(&self, value: f64, (lo, hi): (f64, f64)) -> RGBColor {
        let h = if hi > lo {
            (value - lo) / (hi - lo)
        } else {
            0.5
        };
        ViridisRGB.get_color_normalized(h.clamp(0.0, 1.0), 0.0, 1.0)
    }

    fn heatmap<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError> {
        let o = self.options;
        let means: Vec<Vec<Option<f64>>> = self
            .cells
            .iter()
            .map(|column| column.iter().map(|cell| mean(cell)).collect())
            .collect();
        let range = means
            .iter()
            .flatten()
            .flatten()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &m| {
                (lo.min(m), hi.max(m))
            });
        let (plot, bar) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(130));
        let (nx, ny) = (self.xs.len() as i32, self.ys.len() as i32);
        let label = |values: &[f64], v: &SegmentValue<i32>| match v {
            SegmentValue::CenterOf(k) => values
                .get(*k as usize)
                .map_or_else(String::new, |&x| format::tick(x)),
            _ => String::new(),
        };
        let mut chart = ChartBuilder::on(&plot)
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((0..nx - 1).into_segmented(), (0..ny - 1).into_segmented())
            .map_err(VizError::draw)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(text.text(&o.x_label))
            .y_desc(text.text(o.y_label.as_deref().unwrap_or_default()))
            .x_labels(self.xs.len())
            .y_labels(self.ys.len())
            .x_label_formatter(&|v| label(&self.xs, v))
            .y_label_formatter(&|v| label(&self.ys, v))
            .label_style(text_style(13))
            .axis_desc_style(text_style(14))
            .axis_style(style::rgb(INK))
            .draw()
            .map_err(VizError::draw)?;
        let small = self.xs.len() <= 12 && self.ys.len() <= 12;
        for (i, column) in means.iter().enumerate() {
            for (j, m) in column.iter().enumerate() {
                let (i, j) = (i as i32, j as i32);
                let corners = [
                    (SegmentValue::Exact(i), SegmentValue::Exact(j)),
                    (SegmentValue::Exact(i + 1), SegmentValue::Exact(j + 1)),
                ];
                let fill = m.map_or(style::rgb(EMPTY_CELL), |m| self.colour(m, range));
                chart
                    .draw_series([Rectangle::new(corners, fill.filled())])
                    .map_err(VizError::draw)?;
                if let (Some(m), true) = (m, small) {
                    let ink = if self.colour(*m, range).0 < 120 {
                        style::rgb([0xFF, 0xFF, 0xFF])
                    } else {
                        style::rgb(INK)
                    };
                    let position = (SegmentValue::CenterOf(i), SegmentValue::CenterOf(j));
                    chart
                        .draw_series([plotters::element::Text::new(
                            format::significant(*m, 3),
                            position,
                            text_style(12).color(&ink),
                        )])
                        .map_err(VizError::draw)?;
                }
            }
        }
        self.colour_bar(&bar, range, text)
    }

    /// A vertical colour bar of the map from `lo` to `hi`, labelled with the metric.
    fn colour_bar<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (lo, hi): (f64, f64),
        text: TextMode,
    ) -> Result<(), VizError> {
        let (lo_axis, hi_axis) = if hi > lo {
            (lo, hi)
        } else {
            (lo - 0.5, lo + 0.5)
        };
        let mut chart = ChartBuilder::on(area)
            .margin_top(12)
            .margin_bottom(60)
            .margin_right(8)
            .y_label_area_size(56)
            .build_cartesian_2d(0.0..1.0, lo_axis..hi_axis)
            .map_err(VizError::draw)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(text.text(&format!("{} (mean)", self.options.metric)))
            .y_labels(6)
            .y_label_formatter(&|v| {
                // a tick at round-off from 0 is 0
                let v = if v.abs() <= 1e-9 * (hi_axis - lo_axis) {
                    0.0
                } else {
                    *v
                };
                format::tick(v)
            })
            .label_style(text_style(12))
            .axis_desc_style(text_style(13))
            .axis_style(style::rgb(INK))
            .draw()
            .map_err(VizError::draw)?;
        const STEPS: usize = 64;
        let step = (hi_axis - lo_axis) / STEPS as f64;
        chart
            .draw_series((0..STEPS).map(|k| {
                let y0 = lo_axis + step * k as f64;
                let colour = self.colour(y0 + 0.5 * step, (lo, hi));
                Rectangle::new([(0.0, y0), (1.0, y0 + step)], colour.filled())
            }))
            .map_err(VizError::draw)?;
        Ok(())
    }

    fn line<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError> {
        let o = self.options;
        let rows: Vec<(f64, &Vec<f64>)> = self
            .xs
            .iter()
            .zip(&self.cells)
            .map(|(&x, column)| (x, &column[0]))
            .filter(|(_, cell)| !cell.is_empty())
            .collect();
        let band: Vec<(f64, f64, f64)> = rows
            .iter()
            .map(|&(x, cell)| match o.band {
                Band::MinMax => (x, cell[0], cell[cell.len() - 1]),
                Band::Quantiles => (x, quantile(cell, 0.25), quantile(cell, 0.75)),
            })
            .collect();
        let (x0, x1) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let (x0, x1) = if x1 > x0 {
            (x0, x1)
        } else {
            (x0 - 0.5, x0 + 0.5)
        };
        let (y0, y1) = self.range;
        let pad = if y1 > y0 { 0.05 * (y1 - y0) } else { 0.5 };
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72);
        let points: Vec<(f64, f64)> = self
            .xs
            .iter()
            .zip(&self.cells)
            .flat_map(|(&x, column)| column[0].iter().map(move |&v| (x, v)))
            .collect();
        let means: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|&(x, cell)| mean(cell).map(|m| (x, m)))
            .collect();
        let mut outline: Vec<(f64, f64)> = band.iter().map(|&(x, lo, _)| (x, lo)).collect();
        outline.extend(band.iter().rev().map(|&(x, _, hi)| (x, hi)));
        macro_rules! draw {
            ($x:expr, $y:expr) => {{
                let mut chart = builder.build_cartesian_2d($x, $y).map_err(VizError::draw)?;
                chart
                    .configure_mesh()
                    .x_desc(text.text(&o.x_label))
                    .y_desc(text.text(&o.metric))
                    .x_labels(8)
                    .y_labels(8)
                    .label_style(text_style(13))
                    .axis_desc_style(text_style(14))
                    .axis_style(style::rgb(INK))
                    .light_line_style(style::rgb([0xEE, 0xEE, 0xEE]))
                    .bold_line_style(style::rgb([0xE0, 0xE0, 0xE0]))
                    .draw()
                    .map_err(VizError::draw)?;
                chart
                    .draw_series([Polygon::new(outline.clone(), style::rgb(BAND).filled())])
                    .map_err(VizError::draw)?;
                chart
                    .draw_series(LineSeries::new(
                        means.clone(),
                        style::rgb(CURVE).stroke_width(2),
                    ))
                    .map_err(VizError::draw)?;
                chart
                    .draw_series(
                        points
                            .iter()
                            .map(|&p| Circle::new(p, 3, style::rgb(CURVE).filled())),
                    )
                    .map_err(VizError::draw)?;
            }};
        }
        let positive = y0 > 0.0;
        match (o.log_x && x0 > 0.0, o.log_y && positive) {
            (false, false) => draw!(x0..x1, (y0 - pad)..(y1 + pad)),
            (true, false) => draw!((x0..x1).log_scale(), (y0 - pad)..(y1 + pad)),
            (false, true) => draw!(x0..x1, (y0..y1 * 1.05).log_scale()),
            (true, true) => draw!((x0..x1).log_scale(), (y0..y1 * 1.05).log_scale()),
        }
        Ok(())
    }
}

impl Figure for Diagram<'_> {
    fn size(&self) -> (u32, u32) {
        self.options.size
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError> {
        let body = below_title(root, &self.options.title, text)?;
        if self.options.y_label.is_some() {
            self.heatmap(&body, text)
        } else {
            self.line(&body, text)
        }
    }
}

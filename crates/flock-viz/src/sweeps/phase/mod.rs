//! Phase diagrams of parameter sweeps (`flocking sweep plot`): a metric over one or two swept
//! parameters, each point of the grid summarised over its seeds.
//!
//! - Two axes: a heatmap, one cell per (x, y) grid value, coloured by the mean over the seeds
//!   (viridis, linear or in ln value), with a colour bar; a cell without a finite value is grey.
//!   A numeric axis is the value axis (ln value with a log scale): each cell is centred on its
//!   value and spans halfway to its neighbours, so unevenly spaced values (0, 0.01, 0.1, 0.5)
//!   have cells of uneven widths, and a logarithmic grid on a log axis even ones.
//! - One axis: the mean against x (log x on request) inside a band — min to max, or the 25–75 %
//!   quantiles — with a dot for every run, and a legend that says which band it is.
//! - Categories ([`PhaseOptions::x_categories`], [`PhaseOptions::y_categories`]): an axis of
//!   names (an algorithm, a vehicle, a loss model) in the sweep's order; along x each category
//!   is a bar of its band with its mean, nothing joining two of them.
//!
//! - Panels (small multiples): one diagram per value of a third parameter, on a grid, with the
//!   same axes and the same colour map in every panel, each titled ("n = 50").
//!
//! - Series: the panels drawn instead on one set of axes, a colour and a marker per panel (square,
//!   plus, cross, triangle, diamond, as Vicsek et al. 1995 Fig. 2(a) marks its N), with a legend —
//!   for comparisons across the panels' parameter (a finite-size comparison); log axes as a
//!   line's.
//!
//! - [`Bound`]: a theoretical value of x (a stability bound) drawn as a labelled vertical line.
//!
//! - [`Reference`]: values from a source drawn beside the sweep's — a paper's points over a line
//!   diagram (black markers), or a paper's borders over a heatmap (labelled red lines).
//!
//! - [`phase_table`]: the numbers drawn, as CSV.
//!
//! NaN values (failed runs, empty fields) are left out of means, bands and dots.

mod cells;
mod figure;
mod grid;
mod heatmap;
mod line;
mod table;
#[cfg(test)]
mod tests;

use crate::draw::render;
use crate::error::VizError;
use grid::Diagram;

pub use table::phase_table;

/// One run of a sweep as the phase diagram sees it: its axis values, the metric (NaN when the
/// run failed or has no value) and its panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhasePoint {
    /// The value of the x axis.
    pub x: f64,
    /// The value of the y axis, for a heatmap.
    pub y: Option<f64>,
    /// The metric.
    pub value: f64,
    /// The panel it is drawn in: an index into [`PhaseOptions::panels`] (0 without panels).
    pub panel: usize,
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

impl Band {
    /// What the band shows, for the legend.
    #[must_use]
    pub fn meaning(self) -> &'static str {
        match self {
            Self::MinMax => "min–max over the seeds",
            Self::Quantiles => "25–75 % of the seeds",
        }
    }
}

/// How a phase diagram is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseOptions {
    /// The title (may be empty).
    pub title: String,
    /// The x axis' label.
    pub x_label: String,
    /// The y axis' label: `Some` for a heatmap.
    pub y_label: Option<String>,
    /// The metric's name (the colour bar's or the y axis' label).
    pub metric: String,
    /// The titles of the panels, in order; empty for a single untitled diagram.
    pub panels: Vec<String>,
    /// Logarithmic x axis (when every x is positive).
    pub log_x: bool,
    /// Logarithmic y axis: the metric of a one-axis diagram, a heatmap's y (when every y is
    /// positive).
    pub log_y: bool,
    /// The band of a one-axis diagram.
    pub band: Band,
    /// The size of a panel in pixels (the figure is the grid of its panels).
    pub size: (u32, u32),
    /// A theoretical bound on x, drawn as a labelled vertical line in every panel.
    pub bound: Option<Bound>,
    /// Draw the panels of a one-axis diagram as series on one set of axes (a colour and a
    /// marker each, the panels' titles in the legend) rather than side by side.
    pub series: bool,
    /// Values from sources drawn beside the sweep's.
    pub references: Vec<Reference>,
    /// The names of x's categories, in the sweep's order: when not empty, x is categorical (an
    /// `algorithm`, a `vehicle`, a loss model), each point's x is the index of its category, and
    /// the axis is labelled with the names (no log scale, no bound).
    pub x_categories: Vec<String>,
    /// The names of y's categories (a heatmap), as [`PhaseOptions::x_categories`].
    pub y_categories: Vec<String>,
    /// A logarithmic colour scale (a heatmap whose means are all positive): for a metric that
    /// spans decades, such as a velocity mismatch.
    pub log_colour: bool,
    /// A heatmap's numeric axes in equal cells, in the order of their values, rather than each
    /// cell at its value: for values that crowd at one end and include 0 (delays 0, 0.01, …,
    /// 0.8), which a log axis cannot spread.
    pub even_cells: bool,
}

/// Values from a source drawn beside a sweep's: over a line diagram, its points as black markers
/// (the marker of its series); over a heatmap, a line through its points in the axes' values
/// (a border between states), labelled at the mean of its vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// What it is, for the legend or the line's label ("N = 40, Vicsek et al. 1995").
    pub label: String,
    /// The panel (series) it belongs to: its marker, and the only panel it is drawn in when the
    /// panels are side by side; `None` for every panel, with the marker after the panels' last.
    pub series: Option<usize>,
    /// Its points: (x, metric) over a line diagram, (x, y) over a heatmap.
    pub points: Vec<(f64, f64)>,
}

/// A labelled value of x, such as a stability bound τ* of the swept delay, drawn as a vertical
/// line at its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Bound {
    /// The value of x, within the grid's x values.
    pub x: f64,
    /// Its label ("τ* (linearised)").
    pub label: String,
}

impl Default for PhaseOptions {
    fn default() -> Self {
        Self {
            title: String::new(),
            x_label: String::new(),
            y_label: None,
            metric: String::new(),
            panels: Vec::new(),
            log_x: false,
            log_y: false,
            band: Band::MinMax,
            size: (800, 600),
            bound: None,
            series: false,
            references: Vec::new(),
            x_categories: Vec::new(),
            y_categories: Vec::new(),
            log_colour: false,
            even_cells: false,
        }
    }
}

/// The grey of a heatmap cell without a finite value.
pub const EMPTY_CELL: [u8; 3] = [0xC8, 0xC8, 0xC8];
/// The band of a one-axis diagram.
pub const BAND: [u8; 3] = [0xC6, 0xD4, 0xEA];
/// The line of a [`Bound`], and a [`Reference`] over a heatmap.
pub const BOUND: [u8; 3] = [0xD6, 0x27, 0x28];
/// The colours of the series, in order (then again).
pub const SERIES: [[u8; 3]; 5] = [
    [0x1F, 0x4E, 0x9C],
    [0xD6, 0x27, 0x28],
    [0x2C, 0xA0, 0x2C],
    [0xE0, 0x82, 0x14],
    [0x7B, 0x32, 0x94],
];

/// The phase diagram as SVG.
///
/// # Errors
/// [`VizError::Invalid`] for no point, no finite value, points with and without y, or a point
/// in a panel that is not there.
///
/// # Example
/// ```
/// use flock_viz::phase::{PhaseOptions, PhasePoint, phase_svg};
///
/// let points: Vec<PhasePoint> = [(0.1, 1.0, 0.2), (0.1, 2.0, 0.9), (0.2, 1.0, 0.4), (0.2, 2.0, 1.0)]
///     .map(|(x, y, value)| PhasePoint { x, y: Some(y), value, panel: 0 })
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

//! Phase diagrams of parameter sweeps (`flocking sweep plot`): a metric over one or two swept
//! parameters, each point of the grid summarised over its seeds.
//!
//! - Two axes: a heatmap, one cell per (x, y) grid value — the cells in the order of the sorted
//!   values, labelled with them (so a logarithmic grid is evenly spaced) — coloured by the mean
//!   over the seeds (viridis), with a colour bar; a cell without a finite value is grey.
//! - One axis: the mean against x (log x on request) inside a band — min to max, or the 25–75 %
//!   quantiles — with a dot for every run.
//!
//! - Panels (small multiples): one diagram per value of a third parameter, on a grid, with the
//!   same axes and the same colour map in every panel, each titled ("n = 50").
//!
//! - Series: the panels drawn instead on one set of axes, a colour and a marker per panel (square,
//!   plus, cross, triangle, diamond, as Vicsek et al. 1995 Fig. 2(a) marks its N), with a legend —
//!   for comparisons across the panels' parameter (a finite-size comparison).
//!
//! - [`Bound`]: a theoretical value of x (a stability bound) drawn as a labelled vertical line.
//!
//! - [`Reference`]: values from a source drawn beside the sweep's — a paper's points over a line
//!   diagram (black markers), or a paper's borders over a heatmap (labelled red lines).
//!
//! - [`phase_table`]: the numbers drawn, as CSV.
//!
//! NaN values (failed runs, empty fields) are left out of means, bands and dots.

use plotters::chart::MeshStyle;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::element::{EmptyElement, PathElement, Text};
use plotters::prelude::{
    ChartBuilder, Circle, DrawingArea, DrawingBackend, IntoLogRange, IntoSegmentedCoord,
    LineSeries, Polygon, Rectangle, SegmentValue,
};
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use plotters::style::{Color, RGBColor};

use crate::draw::format;
use crate::draw::render::{self, Figure, TextMode};
use crate::draw::style::{self, CURVE, INK};
use crate::error::VizError;
use crate::snapshots::snapshot::{below_title, text_style};

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
    /// Logarithmic x axis (one-axis diagrams; a heatmap's cells are evenly spaced anyway).
    pub log_x: bool,
    /// Logarithmic metric axis (one-axis diagrams).
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
/// line. In a heatmap, whose cells are evenly spaced, it is placed between the centres of the two
/// cells around it, linearly in x (logarithmically with [`PhaseOptions::log_x`] and x > 0).
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
/// The half size of a marker, in pixels.
const MARKER: i32 = 5;

/// The outline of marker `k` (square, plus, cross, triangle, diamond, then again) as a path of
/// pixel offsets from its centre.
fn marker(k: usize) -> Vec<(i32, i32)> {
    let r = MARKER;
    match k % 5 {
        0 => vec![(-r, -r), (r, -r), (r, r), (-r, r), (-r, -r)],
        1 => vec![(-r, 0), (r, 0), (0, 0), (0, -r), (0, r)],
        2 => vec![(-r, -r), (r, r), (0, 0), (r, -r), (-r, r)],
        3 => vec![(0, -r), (r, r), (-r, r), (0, -r)],
        _ => vec![(0, -r), (r, 0), (0, r), (-r, 0), (0, -r)],
    }
}

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

/// The numbers a phase diagram draws, as CSV: `panel,x,y,runs,mean,low,high`, one line per
/// grid point of each panel (panels in order, then x, then y, ascending) — the panel's title, the
/// point, how many finite values it has, their mean and the band ([`PhaseOptions::band`]), empty
/// where it has none. Numbers are written as Rust prints them (shortest round trip).
///
/// # Errors
/// As [`phase_svg`].
///
/// # Example
/// ```
/// use flock_viz::phase::{PhaseOptions, PhasePoint, phase_table};
///
/// let points: Vec<PhasePoint> = [(0.1, 1.0), (0.1, 3.0), (0.2, f64::NAN)]
///     .map(|(x, value)| PhasePoint { x, y: None, value, panel: 0 })
///     .to_vec();
/// let table = phase_table(&points, &PhaseOptions::default()).unwrap();
/// assert_eq!(table, "panel,x,y,runs,mean,low,high\n,0.1,,2,2,1,3\n,0.2,,0,,,\n");
/// ```
pub fn phase_table(points: &[PhasePoint], options: &PhaseOptions) -> Result<String, VizError> {
    let diagram = Diagram::new(points, options)?;
    let mut table = String::from("panel,x,y,runs,mean,low,high\n");
    for (k, cells) in diagram.panels.iter().enumerate() {
        let title = options.panels.get(k).map_or("", String::as_str);
        let title = if title.contains([',', '"']) {
            format!("\"{}\"", title.replace('"', "\"\""))
        } else {
            title.to_owned()
        };
        for (&x, column) in diagram.xs.iter().zip(cells) {
            for (&y, cell) in diagram.ys.iter().zip(column) {
                let y = if options.y_label.is_some() {
                    y.to_string()
                } else {
                    String::new()
                };
                let (mean, low, high) = match mean(cell) {
                    Some(mean) => {
                        let (low, high) = options.band.of(cell);
                        (mean.to_string(), low.to_string(), high.to_string())
                    }
                    None => Default::default(),
                };
                table += &format!("{title},{x},{y},{},{mean},{low},{high}\n", cell.len());
            }
        }
    }
    Ok(table)
}

impl Band {
    /// The band of sorted, non-empty values.
    fn of(self, sorted: &[f64]) -> (f64, f64) {
        match self {
            Self::MinMax => (sorted[0], sorted[sorted.len() - 1]),
            Self::Quantiles => (quantile(sorted, 0.25), quantile(sorted, 0.75)),
        }
    }
}

/// The finite values of one panel: `cells[i][j]` at (xs[i], ys[j]) (j = 0 without y), sorted.
type Cells = Vec<Vec<Vec<f64>>>;

/// The values of each grid point of each panel: the sorted distinct x (and y) of every panel and
/// the finite values there.
struct Diagram<'a> {
    options: &'a PhaseOptions,
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// One per panel.
    panels: Vec<Cells>,
    /// The least and largest finite value of every panel.
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

/// Where `x` falls among the cells of the sorted grid values `values`, in cells from the first
/// cell's centre: between the two values around it (or beyond the first or last two, extended),
/// linearly in x, or in ln x with `log` and positive values.
fn cell_position(values: &[f64], x: f64, log: bool) -> f64 {
    if values.len() == 1 {
        return 0.0;
    }
    let above = values
        .partition_point(|&v| v < x)
        .clamp(1, values.len() - 1);
    let (a, b) = (values[above - 1], values[above]);
    let t = if log && a > 0.0 {
        (x / a).ln() / (b / a).ln()
    } else {
        (x - a) / (b - a)
    };
    (above - 1) as f64 + t
}

/// Draws the mesh of a line diagram: x labelled with the swept parameter, y with the metric,
/// `labels` values along each, a light grid.
fn line_mesh<X, Y, XT, YT, DB>(
    mut mesh: MeshStyle<'_, '_, X, Y, DB>,
    o: &PhaseOptions,
    text: TextMode,
    labels: usize,
) -> Result<(), VizError>
where
    X: Ranged<ValueType = XT> + ValueFormatter<XT>,
    Y: Ranged<ValueType = YT> + ValueFormatter<YT>,
    DB: DrawingBackend,
{
    mesh.x_desc(text.text(&o.x_label))
        .y_desc(text.text(&o.metric))
        .x_labels(labels)
        .y_labels(labels)
        .label_style(text_style(13))
        .axis_desc_style(text_style(14))
        .axis_style(style::rgb(INK))
        .light_line_style(style::rgb([0xEE, 0xEE, 0xEE]))
        .bold_line_style(style::rgb([0xE0, 0xE0, 0xE0]))
        .draw()
        .map_err(VizError::draw)
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
        let count = options.panels.len().max(1);
        if let Some(p) = points.iter().find(|p| p.panel >= count) {
            return Err(VizError::invalid(format!(
                "a run in panel {} of {count}",
                p.panel
            )));
        }
        let xs = distinct(points.iter().map(|p| p.x));
        let ys = distinct(points.iter().map(|p| p.y.unwrap_or(0.0)));
        let mut panels = vec![vec![vec![Vec::new(); ys.len()]; xs.len()]; count];
        for p in points.iter().filter(|p| p.value.is_finite()) {
            panels[p.panel][index(&xs, p.x)][index(&ys, p.y.unwrap_or(0.0))].push(p.value);
        }
        for cell in panels.iter_mut().flatten().flatten() {
            cell.sort_by(f64::total_cmp);
        }
        let finite = || panels.iter().flatten().flatten().flatten().copied();
        let (lo, hi) = (
            finite().fold(f64::INFINITY, f64::min),
            finite().fold(f64::NEG_INFINITY, f64::max),
        );
        if lo > hi {
            return Err(VizError::invalid(format!("no run has a value of {metric}")));
        }
        if options.series && heatmap {
            return Err(VizError::invalid(
                "series are drawn on a line diagram; a heatmap has panels",
            ));
        }
        if let Some(r) = options.references.iter().find(|r| {
            r.series.is_some_and(|k| k >= count)
                || r.points
                    .iter()
                    .any(|&(x, y)| !x.is_finite() || !y.is_finite())
        }) {
            return Err(VizError::invalid(format!(
                "the reference {:?} has a point that is not finite or a series that is not drawn",
                r.label
            )));
        }
        if let Some(bound) = &options.bound {
            let (first, last) = (xs[0], xs[xs.len() - 1]);
            if !(first..=last).contains(&bound.x) {
                return Err(VizError::invalid(format!(
                    "the bound {} is outside the x values drawn, {} to {}",
                    bound.x,
                    format::tick(first),
                    format::tick(last)
                )));
            }
        }
        Ok(Self {
            options,
            xs,
            ys,
            panels,
            range: (lo, hi),
        })
    }

    /// The means of a panel's cells.
    fn means(cells: &Cells) -> Vec<Vec<Option<f64>>> {
        cells
            .iter()
            .map(|column| column.iter().map(|cell| mean(cell)).collect())
            .collect()
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

    /// The heatmap of the panel `cells` on the colour map of `range` (the colour bar is drawn
    /// once for every panel).
    fn heatmap<DB: DrawingBackend>(
        &self,
        plot: &DrawingArea<DB, Shift>,
        cells: &Cells,
        range: (f64, f64),
        text: TextMode,
    ) -> Result<(), VizError> {
        let o = self.options;
        let means = Self::means(cells);
        let (nx, ny) = (self.xs.len() as i32, self.ys.len() as i32);
        let label = |values: &[f64], v: &SegmentValue<i32>| match v {
            SegmentValue::CenterOf(k) => values
                .get(*k as usize)
                .map_or_else(String::new, |&x| format::tick(x)),
            _ => String::new(),
        };
        let mut chart = ChartBuilder::on(plot)
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
                        .draw_series([Text::new(
                            format::significant(*m, 3),
                            position,
                            text_style(12).color(&ink),
                        )])
                        .map_err(VizError::draw)?;
                }
            }
        }
        let pixel =
            |i: i32, j: i32| chart.backend_coord(&(SegmentValue::Exact(i), SegmentValue::Exact(j)));
        let (left, width) = (pixel(0, 0).0, pixel(1, 0).0 - pixel(0, 0).0);
        let (bottom, height) = (pixel(0, 0).1, pixel(0, 1).1 - pixel(0, 0).1);
        // within the grid's outer cell edges: a line beyond them runs along the edge
        let within = |at: f64, count: usize| at.clamp(-0.5, count as f64 - 0.5) + 0.5;
        let column = |x: f64| {
            let at = within(cell_position(&self.xs, x, o.log_x), self.xs.len());
            left + (at * f64::from(width)).round() as i32
        };
        let row = |y: f64| {
            let at = within(cell_position(&self.ys, y, false), self.ys.len());
            bottom + (at * f64::from(height)).round() as i32
        };
        let plot = chart.plotting_area().strip_coord_spec();
        let (x0, y0) = plot.get_base_pixel();
        let ink = style::rgb(BOUND);
        for reference in &o.references {
            let path: Vec<(i32, i32)> = reference
                .points
                .iter()
                .map(|&(x, y)| (column(x) - x0, row(y) - y0))
                .collect();
            plot.draw(&PathElement::new(path.clone(), ink.stroke_width(3)))
                .map_err(VizError::draw)?;
            // labelled at the mean of its vertices (a closed line's first one counted once)
            let closed = path.len() > 2 && path.first() == path.last();
            let vertices = &path[..path.len() - usize::from(closed)];
            if !vertices.is_empty() {
                let count = vertices.len() as i32;
                let x = vertices.iter().map(|p| p.0).sum::<i32>() / count;
                let y = vertices.iter().map(|p| p.1).sum::<i32>() / count;
                let label = text.text(&reference.label);
                plot.draw(&Text::new(
                    label,
                    (x - 20, y - 6),
                    text_style(12).color(&ink),
                ))
                .map_err(VizError::draw)?;
            }
        }
        self.bound(&plot, column, text)
    }

    /// The bound, if any, as a vertical line at the backend pixel column `column` across `plot`
    /// (a chart's plotting area), labelled at its top.
    fn bound<DB: DrawingBackend>(
        &self,
        plot: &DrawingArea<DB, Shift>,
        column: impl FnOnce(f64) -> i32,
        text: TextMode,
    ) -> Result<(), VizError> {
        let Some(bound) = &self.options.bound else {
            return Ok(());
        };
        let x = column(bound.x) - plot.get_base_pixel().0;
        let (width, height) = plot.dim_in_pixel();
        let ink = style::rgb(BOUND);
        plot.draw(&PathElement::new(
            vec![(x, 0), (x, height as i32)],
            ink.stroke_width(2),
        ))
        .map_err(VizError::draw)?;
        let (label, font) = (text.text(&bound.label), text_style(13).color(&ink));
        let wide = plot
            .estimate_text_size(&label, &font)
            .map_err(VizError::draw)?
            .0 as i32;
        // right of the line, or left of it where the plot ends first
        let left = if x + 5 + wide > width as i32 {
            x - 5 - wide
        } else {
            x + 5
        };
        plot.draw(&Text::new(label, (left, 5), font))
            .map_err(VizError::draw)
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
            .y_desc(text.text(&self.options.metric))
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

    /// The references of panel `k` (or of every panel) as black markers: (marker, points).
    fn references(&self, k: Option<usize>) -> Vec<(usize, Vec<(f64, f64)>)> {
        self.options
            .references
            .iter()
            .filter(|r| k.is_none() || r.series.is_none() || r.series == k)
            .map(|r| (r.series.unwrap_or(self.panels.len()), r.points.clone()))
            .collect()
    }

    /// The means of every panel on one set of axes, a colour and a marker each, with the
    /// references beside them and a legend.
    fn series<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError> {
        let o = self.options;
        let (x0, x1) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let references = self.references(None);
        let reference_values = || {
            references
                .iter()
                .flat_map(|(_, p)| p.iter().map(|&(_, v)| v))
        };
        let y0 = reference_values().fold(self.range.0, f64::min);
        let y1 = reference_values().fold(self.range.1, f64::max);
        let pad = if y1 > y0 { 0.05 * (y1 - y0) } else { 0.5 };
        let x_pad = if x1 > x0 { 0.02 * (x1 - x0) } else { 0.5 };
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((x0 - x_pad)..(x1 + x_pad), (y0 - pad)..(y1 + pad))
            .map_err(VizError::draw)?;
        line_mesh(chart.configure_mesh(), o, text, 11)?;
        for (k, cells) in self.panels.iter().enumerate() {
            let colour = style::rgb(SERIES[k % SERIES.len()]);
            let means: Vec<(f64, f64)> = self
                .xs
                .iter()
                .zip(cells)
                .filter_map(|(&x, column)| mean(&column[0]).map(|m| (x, m)))
                .collect();
            chart
                .draw_series(LineSeries::new(means.clone(), colour.stroke_width(1)))
                .map_err(VizError::draw)?;
            let shape = marker(k);
            let series = chart
                .draw_series(means.iter().map(|&p| {
                    EmptyElement::at(p) + PathElement::new(shape.clone(), colour.stroke_width(2))
                }))
                .map_err(VizError::draw)?;
            let label = o.panels.get(k).cloned().unwrap_or_default();
            series.label(text.text(&label)).legend(move |(x, y)| {
                EmptyElement::at((x + 8, y)) + PathElement::new(marker(k), colour.stroke_width(2))
            });
        }
        let ink = style::rgb(INK);
        for (reference, (k, points)) in o.references.iter().zip(&references) {
            let shape = marker(*k);
            let k = *k;
            chart
                .draw_series(points.iter().map(|&p| {
                    EmptyElement::at(p) + PathElement::new(shape.clone(), ink.stroke_width(1))
                }))
                .map_err(VizError::draw)?
                .label(text.text(&reference.label))
                .legend(move |(x, y)| {
                    EmptyElement::at((x + 8, y)) + PathElement::new(marker(k), ink.stroke_width(1))
                });
        }
        chart
            .configure_series_labels()
            .label_font(text_style(12))
            .background_style(style::rgb(style::BACKGROUND).mix(0.9))
            .border_style(style::rgb([0xE0, 0xE0, 0xE0]))
            .position(plotters::chart::SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(VizError::draw)?;
        let plot = chart.plotting_area().strip_coord_spec();
        self.bound(&plot, |x| chart.backend_coord(&(x, y0)).0, text)
    }

    /// The line and band of panel `k`, whose cells are `cells`, with its references.
    fn line<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        k: usize,
        cells: &Cells,
        text: TextMode,
    ) -> Result<(), VizError> {
        let o = self.options;
        let rows: Vec<(f64, &Vec<f64>)> = self
            .xs
            .iter()
            .zip(cells)
            .map(|(&x, column)| (x, &column[0]))
            .filter(|(_, cell)| !cell.is_empty())
            .collect();
        let band: Vec<(f64, f64, f64)> = rows
            .iter()
            .map(|&(x, cell)| {
                let (low, high) = o.band.of(cell);
                (x, low, high)
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
            .zip(cells)
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
                line_mesh(chart.configure_mesh(), o, text, 8)?;
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
                for (shape, reference) in self.references(Some(k)) {
                    let shape = marker(shape);
                    chart
                        .draw_series(reference.into_iter().map(|p| {
                            EmptyElement::at(p)
                                + PathElement::new(shape.clone(), style::rgb(INK).stroke_width(1))
                        }))
                        .map_err(VizError::draw)?;
                }
                let plot = chart.plotting_area().strip_coord_spec();
                self.bound(
                    &plot,
                    |x| chart.backend_coord(&(x, y0.max(f64::MIN_POSITIVE))).0,
                    text,
                )?;
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

impl Diagram<'_> {
    /// The panels' grid: (rows, columns), as near square as the panels allow (one cell for
    /// series).
    fn grid(&self) -> (usize, usize) {
        let count = if self.options.series {
            1
        } else {
            self.panels.len()
        };
        let columns = (1..=count).find(|c| c * c >= count).unwrap_or(1);
        (count.div_ceil(columns), columns)
    }
}

/// The width of a heatmap's colour bar.
const COLOUR_BAR: u32 = 130;

impl Figure for Diagram<'_> {
    fn size(&self) -> (u32, u32) {
        let (rows, columns) = self.grid();
        let (width, height) = self.options.size;
        let bar = if self.options.y_label.is_some() {
            COLOUR_BAR
        } else {
            0
        };
        (width * columns as u32 + bar, height * rows as u32)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError> {
        let body = below_title(root, &self.options.title, text)?;
        let heatmap = self.options.y_label.is_some();
        let range = self
            .panels
            .iter()
            .flat_map(Self::means)
            .flatten()
            .flatten()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), m| {
                (lo.min(m), hi.max(m))
            });
        let grid = if heatmap {
            let (grid, bar) =
                body.split_horizontally(body.dim_in_pixel().0.saturating_sub(COLOUR_BAR));
            self.colour_bar(&bar, range, text)?;
            grid
        } else {
            body
        };
        if self.options.series {
            return self.series(&grid, text);
        }
        let areas = grid.split_evenly(self.grid());
        for (k, (cells, area)) in self.panels.iter().zip(&areas).enumerate() {
            let area = match self.options.panels.get(k) {
                Some(title) => area
                    .titled(&text.text(title), text_style(16))
                    .map_err(VizError::draw)?,
                None => area.clone(),
            };
            if heatmap {
                self.heatmap(&area, cells, range, text)?;
            } else {
                self.line(&area, k, cells, text)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two panels of a line: N = 40 and N = 400, two x each.
    fn two_series() -> Vec<PhasePoint> {
        [(0, 1.0, 0.9), (0, 2.0, 0.6), (1, 1.0, 0.8), (1, 2.0, 0.3)]
            .map(|(panel, x, value)| PhasePoint {
                x,
                y: None,
                value,
                panel,
            })
            .to_vec()
    }

    fn series_options(references: Vec<Reference>) -> PhaseOptions {
        PhaseOptions {
            panels: vec!["N = 40".into(), "N = 400".into()],
            series: true,
            references,
            ..PhaseOptions::default()
        }
    }

    /// Series share one set of axes: one legend entry per panel and per reference, each
    /// series in its colour and the references in black, drawn within the points' range even
    /// where they lie outside the sweep's values.
    #[test]
    fn series_and_references_share_one_set_of_axes() {
        let reference = Reference {
            label: "N = 40, paper".into(),
            series: Some(0),
            points: vec![(1.5, 0.05)],
        };
        let svg = phase_svg(&two_series(), &series_options(vec![reference])).unwrap();
        for label in ["N = 40", "N = 400", "N = 40, paper"] {
            assert!(
                svg.contains(&format!("\n{label}\n</text>")),
                "no legend entry {label}"
            );
        }
        for colour in [SERIES[0], SERIES[1], style::INK] {
            assert!(svg.contains(&style::hex(colour)), "no {colour:?}");
        }
        // one set of axes: the x label once
        let without = phase_svg(&two_series(), &series_options(Vec::new())).unwrap();
        assert!(!without.contains("paper"));
        assert_ne!(svg, without);
    }

    /// A heatmap has no series, and a reference must belong to a drawn panel and be finite.
    #[test]
    fn series_and_references_are_refused_where_they_cannot_be_drawn() {
        let heatmap: Vec<PhasePoint> = [(1.0, 1.0, 0.1), (2.0, 1.0, 0.2)]
            .map(|(x, y, value)| PhasePoint {
                x,
                y: Some(y),
                value,
                panel: 0,
            })
            .to_vec();
        let options = PhaseOptions {
            y_label: Some("y".into()),
            series: true,
            ..PhaseOptions::default()
        };
        assert!(phase_svg(&heatmap, &options).is_err());
        let stray = Reference {
            label: "stray".into(),
            series: Some(2),
            points: vec![(1.0, 0.5)],
        };
        assert!(phase_svg(&two_series(), &series_options(vec![stray])).is_err());
        let infinite = Reference {
            label: "infinite".into(),
            series: None,
            points: vec![(1.0, f64::INFINITY)],
        };
        assert!(phase_svg(&two_series(), &series_options(vec![infinite])).is_err());
    }

    /// Over a heatmap a reference is a red line through its points, placed between the cells
    /// of the values around it, and changes the drawing.
    #[test]
    fn a_reference_over_a_heatmap_is_a_labelled_red_line() {
        let points: Vec<PhasePoint> = [(0.0, 1.0), (0.0, 2.0), (1.0, 1.0), (1.0, 2.0)]
            .map(|(x, y)| PhasePoint {
                x,
                y: Some(y),
                value: x + y,
                panel: 0,
            })
            .to_vec();
        let options = |references| PhaseOptions {
            y_label: Some("y".into()),
            references,
            ..PhaseOptions::default()
        };
        let border = Reference {
            label: "border".into(),
            series: None,
            points: vec![(0.5, 1.0), (0.5, 2.0)],
        };
        let svg = phase_svg(&points, &options(vec![border])).unwrap();
        assert!(svg.contains("\nborder\n</text>"));
        assert!(svg.contains(&style::hex(BOUND)));
        assert!(
            !phase_svg(&points, &options(Vec::new()))
                .unwrap()
                .contains(&style::hex(BOUND))
        );
        assert_eq!(cell_position(&[0.0, 1.0, 3.0], 2.0, false), 1.5);
        assert_eq!(cell_position(&[0.0, 1.0, 3.0], 4.0, false), 2.5);
    }
}

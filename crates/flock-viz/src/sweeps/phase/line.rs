//! A one-axis phase diagram: the mean and band of a panel, or every panel as a series on one set
//! of axes, with the references and the bound.

use plotters::chart::{ChartContext, MeshStyle, SeriesLabelPosition};
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::{CoordTranslate, Shift};
use plotters::element::{EmptyElement, PathElement, Text};
use plotters::prelude::{
    ChartBuilder, Circle, DrawingArea, DrawingBackend, IntoLogRange, LineSeries, Polygon, Rectangle,
};
use plotters::style::Color;

use super::grid::{Cells, Diagram, mean};
use super::{BAND, BOUND, PhaseOptions, SERIES};
use crate::draw::format;
use crate::draw::style::{self, CURVE, INK};
use crate::error::VizError;
use crate::snapshots::snapshot::text_style;

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

/// Draws the mesh of a line diagram: x labelled with the swept parameter (a categorical x with
/// its categories' names at 0, 1, …), y with the metric, `labels` values along each, a light
/// grid.
fn line_mesh<'b, X, Y, DB>(
    mut mesh: MeshStyle<'_, 'b, X, Y, DB>,
    o: &PhaseOptions,
    (labels, category): (usize, &'b dyn Fn(&f64) -> String),
) -> Result<(), VizError>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    DB: DrawingBackend,
{
    let names = &o.x_categories;
    if !names.is_empty() {
        mesh.x_label_formatter(category);
    }
    mesh.x_desc(&o.x_label)
        .y_desc(&o.metric)
        .x_labels(if names.is_empty() {
            labels
        } else {
            names.len()
        })
        .y_labels(labels)
        .y_label_formatter(&|v| format::tick(*v))
        .label_style(text_style(13))
        .axis_desc_style(text_style(14))
        .axis_style(style::rgb(INK))
        .light_line_style(style::rgb([0xEE, 0xEE, 0xEE]))
        .bold_line_style(style::rgb([0xE0, 0xE0, 0xE0]))
        .draw()
        .map_err(VizError::draw)
}

/// Draws the legend of `chart`'s labelled series at `corner`, over a light background.
fn legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    corner: SeriesLabelPosition,
) -> Result<(), VizError>
where
    DB: DrawingBackend + 'a,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .label_font(text_style(12))
        .background_style(style::rgb(style::BACKGROUND).mix(0.9))
        .border_style(style::rgb([0xE0, 0xE0, 0xE0]))
        .position(corner)
        .draw()
        .map_err(VizError::draw)
}

impl Diagram<'_> {
    /// Where a line diagram's legend goes: at the lower right when the last mean `last` lies in
    /// the upper half of the metric axis (in ln value on a log axis), else at the upper right.
    fn corner(&self, last: Option<f64>) -> SeriesLabelPosition {
        let (lo, hi) = self.range;
        let log = self.options.log_y && lo > 0.0;
        let high = last.is_some_and(|m| {
            if log {
                m * m > lo * hi
            } else {
                m > 0.5 * (lo + hi)
            }
        });
        if high {
            SeriesLabelPosition::LowerRight
        } else {
            SeriesLabelPosition::UpperRight
        }
    }
}

/// The name of the category at `x` (0, 1, …), nothing between them.
fn category(names: &[String], x: f64) -> String {
    let k = x.round();
    if (x - k).abs() < 1e-9 && k >= 0.0 {
        names.get(k as usize).cloned().unwrap_or_default()
    } else {
        String::new()
    }
}

impl Diagram<'_> {
    /// The bound, if any, as a vertical line at the backend pixel column `column` across `plot`
    /// (a chart's plotting area), labelled at its top.
    pub(super) fn bound<DB: DrawingBackend>(
        &self,
        plot: &DrawingArea<DB, Shift>,
        column: impl FnOnce(f64) -> i32,
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
        let (label, font) = (bound.label.as_str(), text_style(13).color(&ink));
        let wide = plot
            .estimate_text_size(label, &font)
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
    pub(super) fn series<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
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
        let categorical = !o.x_categories.is_empty();
        // the means at the last x, the legend placed where they leave room
        let last = self.panels.iter().filter_map(|cells| {
            let column = &cells[cells.len() - 1];
            mean(&column[0])
        });
        let corner = self.corner(last.reduce(f64::max));
        let x_pad = match (categorical, x1 > x0) {
            (true, _) | (false, false) => 0.5,
            (false, true) => 0.02 * (x1 - x0),
        };
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72);
        macro_rules! draw {
            ($x:expr, $y:expr) => {{
                let mut chart = builder.build_cartesian_2d($x, $y).map_err(VizError::draw)?;
                line_mesh(
                    chart.configure_mesh(),
                    o,
                    (11, &|v| category(&o.x_categories, *v)),
                )?;
                for (k, cells) in self.panels.iter().enumerate() {
                    let colour = style::rgb(SERIES[k % SERIES.len()]);
                    let means: Vec<(f64, f64)> = self
                        .xs
                        .iter()
                        .zip(cells)
                        .filter_map(|(&x, column)| mean(&column[0]).map(|m| (x, m)))
                        .collect();
                    // categories are not joined: there is nothing between them
                    if !categorical {
                        chart
                            .draw_series(LineSeries::new(means.clone(), colour.stroke_width(1)))
                            .map_err(VizError::draw)?;
                    }
                    let shape = marker(k);
                    let series = chart
                        .draw_series(means.iter().map(|&p| {
                            EmptyElement::at(p)
                                + PathElement::new(shape.clone(), colour.stroke_width(2))
                        }))
                        .map_err(VizError::draw)?;
                    let label = o.panels.get(k).cloned().unwrap_or_default();
                    series.label(&label).legend(move |(x, y)| {
                        EmptyElement::at((x + 8, y))
                            + PathElement::new(marker(k), colour.stroke_width(2))
                    });
                }
                let ink = style::rgb(INK);
                for (reference, (k, points)) in o.references.iter().zip(&references) {
                    let shape = marker(*k);
                    let k = *k;
                    chart
                        .draw_series(points.iter().map(|&p| {
                            EmptyElement::at(p)
                                + PathElement::new(shape.clone(), ink.stroke_width(1))
                        }))
                        .map_err(VizError::draw)?
                        .label(&reference.label)
                        .legend(move |(x, y)| {
                            EmptyElement::at((x + 8, y))
                                + PathElement::new(marker(k), ink.stroke_width(1))
                        });
                }
                legend(&mut chart, corner)?;
                let plot = chart.plotting_area().strip_coord_spec();
                self.bound(&plot, |x| chart.backend_coord(&(x, y0)).0)
            }};
        }
        // log axes where asked and every value drawn is positive (as a line diagram's)
        match (o.log_x && x0 > 0.0 && !categorical, o.log_y && y0 > 0.0) {
            (false, false) => draw!((x0 - x_pad)..(x1 + x_pad), (y0 - pad)..(y1 + pad)),
            (true, false) => draw!((x0..x1).log_scale(), (y0 - pad)..(y1 + pad)),
            (false, true) => draw!((x0 - x_pad)..(x1 + x_pad), (y0..y1 * 1.05).log_scale()),
            (true, true) => draw!((x0..x1).log_scale(), (y0..y1 * 1.05).log_scale()),
        }
    }

    /// The line and band of panel `k`, whose cells are `cells`, with its references.
    pub(super) fn line<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        k: usize,
        cells: &Cells,
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
        let categorical = !o.x_categories.is_empty();
        let (x0, x1) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let (x0, x1) = if x1 > x0 && !categorical {
            (x0, x1)
        } else {
            (x0 - 0.5, x1 + 0.5)
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
        // one band along the line, or a bar per category (nothing lies between them)
        let outlines: Vec<Vec<(f64, f64)>> = if categorical {
            let half = 0.2;
            band.iter()
                .map(|&(x, lo, hi)| {
                    vec![
                        (x - half, lo),
                        (x + half, lo),
                        (x + half, hi),
                        (x - half, hi),
                    ]
                })
                .collect()
        } else {
            let mut outline: Vec<(f64, f64)> = band.iter().map(|&(x, lo, _)| (x, lo)).collect();
            outline.extend(band.iter().rev().map(|&(x, _, hi)| (x, hi)));
            vec![outline]
        };
        let mean_lines: Vec<Vec<(f64, f64)>> = if categorical {
            means
                .iter()
                .map(|&(x, m)| vec![(x - 0.3, m), (x + 0.3, m)])
                .collect()
        } else {
            vec![means.clone()]
        };
        let corner = self.corner(means.last().map(|&(_, m)| m));

        macro_rules! draw {
            ($x:expr, $y:expr) => {{
                let mut chart = builder.build_cartesian_2d($x, $y).map_err(VizError::draw)?;
                line_mesh(
                    chart.configure_mesh(),
                    o,
                    (8, &|v| category(&o.x_categories, *v)),
                )?;
                let band = style::rgb(BAND);
                chart
                    .draw_series(
                        outlines
                            .iter()
                            .map(|outline| Polygon::new(outline.clone(), band.filled())),
                    )
                    .map_err(VizError::draw)?
                    .label(o.band.meaning())
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 5), (x + 16, y + 5)], band.filled())
                    });
                let curve = style::rgb(CURVE);
                chart
                    .draw_series(
                        mean_lines
                            .iter()
                            .map(|line| PathElement::new(line.clone(), curve.stroke_width(2))),
                    )
                    .map_err(VizError::draw)?
                    .label("mean over the seeds")
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 16, y)], curve.stroke_width(2))
                    });
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, curve.filled())))
                    .map_err(VizError::draw)?
                    .label("a run")
                    .legend(move |(x, y)| Circle::new((x + 8, y), 3, curve.filled()));
                legend(&mut chart, corner)?;
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
                self.bound(&plot, |x| {
                    chart.backend_coord(&(x, y0.max(f64::MIN_POSITIVE))).0
                })?;
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

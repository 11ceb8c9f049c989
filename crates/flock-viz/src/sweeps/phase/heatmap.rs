//! A two-axis phase diagram: the heatmap of a panel, its colour bar, and the references and
//! bound drawn over it.

use plotters::coord::Shift;
use plotters::element::{PathElement, Text};
use plotters::prelude::{
    ChartBuilder, DrawingArea, DrawingBackend, IntoLogRange, IntoSegmentedCoord, Rectangle,
    SegmentValue,
};
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use plotters::style::{Color, RGBColor};

use super::grid::{Cells, Diagram, cell_position};
use super::{BOUND, EMPTY_CELL};
use crate::draw::format;
use crate::draw::style::{self, INK};
use crate::error::VizError;
use crate::snapshots::snapshot::text_style;

impl Diagram<'_> {
    /// The colour of `value` on the map from the least to the largest mean, linear or
    /// ([`super::PhaseOptions::log_colour`]) in ln value.
    pub(super) fn colour(&self, value: f64, (lo, hi): (f64, f64)) -> RGBColor {
        let h = if hi <= lo {
            0.5
        } else if self.options.log_colour {
            (value / lo).ln() / (hi / lo).ln()
        } else {
            (value - lo) / (hi - lo)
        };
        ViridisRGB.get_color_normalized(h.clamp(0.0, 1.0), 0.0, 1.0)
    }

    /// The heatmap of the panel `cells` on the colour map of `range` (the colour bar is drawn
    /// once for every panel).
    pub(super) fn heatmap<DB: DrawingBackend>(
        &self,
        plot: &DrawingArea<DB, Shift>,
        cells: &Cells,
        range: (f64, f64),
    ) -> Result<(), VizError> {
        let o = self.options;
        let means = Self::means(cells);
        let (nx, ny) = (self.xs.len() as i32, self.ys.len() as i32);
        // a category by its name, a number as a tick
        let label = |values: &[f64], names: &[String], v: &SegmentValue<i32>| match v {
            SegmentValue::CenterOf(k) => values.get(*k as usize).map_or_else(String::new, |&x| {
                names
                    .get(x as usize)
                    .filter(|_| !names.is_empty())
                    .cloned()
                    .unwrap_or_else(|| format::tick(x))
            }),
            _ => String::new(),
        };
        let mut chart = ChartBuilder::on(plot)
            .margin(12)
            .x_label_area_size(48)
            // room for the longest category's name (about 7 pixels a character at 13 px)
            .y_label_area_size(
                o.y_categories
                    .iter()
                    .map(|name| 24 + 7 * name.chars().count() as u32)
                    .fold(72, u32::max),
            )
            .build_cartesian_2d((0..nx - 1).into_segmented(), (0..ny - 1).into_segmented())
            .map_err(VizError::draw)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&o.x_label)
            .y_desc(o.y_label.as_deref().unwrap_or_default())
            .x_labels(self.xs.len())
            .y_labels(self.ys.len())
            .x_label_formatter(&|v| label(&self.xs, &o.x_categories, v))
            .y_label_formatter(&|v| label(&self.ys, &o.y_categories, v))
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
                plot.draw(&Text::new(
                    reference.label.as_str(),
                    (x - 20, y - 6),
                    text_style(12).color(&ink),
                ))
                .map_err(VizError::draw)?;
            }
        }
        self.bound(&plot, column)
    }

    /// A vertical colour bar of the map from `lo` to `hi`, labelled with the metric.
    pub(super) fn colour_bar<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (lo, hi): (f64, f64),
    ) -> Result<(), VizError> {
        let (lo_axis, hi_axis) = if hi > lo {
            (lo, hi)
        } else {
            (lo - 0.5, lo + 0.5)
        };
        let mut builder = ChartBuilder::on(area);
        builder
            .margin_top(12)
            .margin_bottom(60)
            .margin_right(8)
            .y_label_area_size(56);
        const STEPS: usize = 64;
        let log = self.options.log_colour && hi > lo;
        let step = (hi_axis - lo_axis) / STEPS as f64;
        // the bar's steps (from, to, the colour at their middle): geometric on a log scale
        let steps: Vec<(f64, f64, RGBColor)> = (0..STEPS)
            .map(|k| {
                let k = k as f64;
                let (y0, y1, middle) = if log {
                    let at = |t: f64| lo * (hi / lo).powf(t / STEPS as f64);
                    (at(k), at(k + 1.0), at(k + 0.5))
                } else {
                    let y0 = lo_axis + step * k;
                    (y0, y0 + step, y0 + 0.5 * step)
                };
                (y0, y1, self.colour(middle, (lo, hi)))
            })
            .collect();
        // a tick at round-off from 0 is 0
        let tick = |v: &f64| {
            let v = if v.abs() <= 1e-9 * (hi_axis - lo_axis) {
                0.0
            } else {
                *v
            };
            format::tick(v)
        };
        macro_rules! bar {
            ($y:expr) => {{
                let mut chart = builder
                    .build_cartesian_2d(0.0..1.0, $y)
                    .map_err(VizError::draw)?;
                chart
                    .configure_mesh()
                    .disable_mesh()
                    .disable_x_axis()
                    .y_desc(&self.options.metric)
                    .y_labels(6)
                    .y_label_formatter(&tick)
                    .label_style(text_style(12))
                    .axis_desc_style(text_style(13))
                    .axis_style(style::rgb(INK))
                    .draw()
                    .map_err(VizError::draw)?;
                chart
                    .draw_series(steps.iter().map(|&(y0, y1, colour)| {
                        Rectangle::new([(0.0, y0), (1.0, y1)], colour.filled())
                    }))
                    .map_err(VizError::draw)?;
            }};
        }
        if log {
            bar!((lo..hi).log_scale());
        } else {
            bar!(lo_axis..hi_axis);
        }
        Ok(())
    }
}

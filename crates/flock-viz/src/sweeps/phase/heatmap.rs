//! A two-axis phase diagram: the heatmap of a panel, its colour bar, and the references and
//! bound drawn over it.

use plotters::coord::Shift;
use plotters::coord::ranged1d::Ranged;
use plotters::element::{PathElement, Text};
use plotters::prelude::{ChartBuilder, DrawingArea, DrawingBackend, IntoLogRange, Rectangle};
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, RGBColor, TextStyle};

use super::cells::{CellAxis, Layout};
use super::grid::{Cells, Diagram};
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
        let layout = |categories: &[String], log: bool| match () {
            _ if !categories.is_empty() => Layout::Categories,
            _ if o.even_cells => Layout::Even,
            _ => Layout::Values { log },
        };
        let xa = CellAxis::new(&self.xs, layout(&o.x_categories, o.log_x));
        let ya = CellAxis::new(&self.ys, layout(&o.y_categories, o.log_y));
        // a category by its name, a number as a tick
        let name = |values: &[f64], names: &[String], k: usize| {
            let x = values[k];
            names
                .get(x as usize)
                .filter(|_| !names.is_empty())
                .cloned()
                .unwrap_or_else(|| format::tick(x))
        };
        let x_names: Vec<String> = (0..self.xs.len())
            .map(|k| name(&self.xs, &o.x_categories, k))
            .collect();
        let y_names: Vec<String> = (0..self.ys.len())
            .map(|k| name(&self.ys, &o.y_categories, k))
            .collect();
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
            .build_cartesian_2d(xa.clone(), ya.clone())
            .map_err(VizError::draw)?;
        // the labels that fit where the values crowd (the dense end of an uneven axis): each at
        // its cell's centre, shown when clear of the last one shown
        let size = |text: &str, font: &TextStyle| plot.estimate_text_size(text, font);
        let label_font = text_style(13);
        let (y_start, x_start) = (ya.range().start, xa.range().start);
        let mut x_shown = Vec::with_capacity(x_names.len());
        for (name, &u) in x_names.iter().zip(&xa.centres) {
            let width = size(name, &label_font).map_err(VizError::draw)?.0;
            x_shown.push((chart.backend_coord(&(u, y_start)).0, width));
        }
        let mut y_shown = Vec::with_capacity(y_names.len());
        for (name, &u) in y_names.iter().zip(&ya.centres) {
            let height = size(name, &label_font).map_err(VizError::draw)?.1;
            y_shown.push((chart.backend_coord(&(x_start, u)).1, height));
        }
        let (x_shown, y_shown) = (clear_of_each_other(&x_shown), clear_of_each_other(&y_shown));
        let label = |axis: &CellAxis, names: &[String], shown: &[bool], u: &f64| {
            axis.cell_at(*u)
                .filter(|&k| shown[k])
                .map_or_else(String::new, |k| names[k].clone())
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&o.x_label)
            .y_desc(o.y_label.as_deref().unwrap_or_default())
            .x_labels(self.xs.len())
            .y_labels(self.ys.len())
            .x_label_formatter(&|u| label(&xa, &x_names, &x_shown, u))
            .y_label_formatter(&|u| label(&ya, &y_names, &y_shown, u))
            .label_style(label_font.clone())
            .axis_desc_style(text_style(14))
            .axis_style(style::rgb(INK))
            .draw()
            .map_err(VizError::draw)?;
        let small = self.xs.len() <= 12 && self.ys.len() <= 12;
        // centred in its cell
        let value_font = text_style(12).pos(Pos::new(HPos::Center, VPos::Center));
        for (i, column) in means.iter().enumerate() {
            for (j, m) in column.iter().enumerate() {
                let corners = [
                    (xa.edges[i], ya.edges[j]),
                    (xa.edges[i + 1], ya.edges[j + 1]),
                ];
                let fill = m.map_or(style::rgb(EMPTY_CELL), |m| self.colour(m, range));
                chart
                    .draw_series([Rectangle::new(corners, fill.filled())])
                    .map_err(VizError::draw)?;
                let Some(m) = m.filter(|_| small) else {
                    continue;
                };
                // the mean written in its cell, where it fits
                let text = format::significant(m, 3);
                let (w, h) = size(&text, &value_font).map_err(VizError::draw)?;
                let (a, b) = (
                    chart.backend_coord(&corners[0]),
                    chart.backend_coord(&corners[1]),
                );
                if (b.0 - a.0).unsigned_abs() < w + 4 || (b.1 - a.1).unsigned_abs() < h + 2 {
                    continue;
                }
                let ink = if self.colour(m, range).0 < 120 {
                    style::rgb([0xFF, 0xFF, 0xFF])
                } else {
                    style::rgb(INK)
                };
                chart
                    .draw_series([Text::new(
                        text,
                        (xa.centres[i], ya.centres[j]),
                        value_font.color(&ink),
                    )])
                    .map_err(VizError::draw)?;
            }
        }
        // the pixel of a value on each axis (a line beyond the outer cell edges runs along them)
        let column = |x: f64| chart.backend_coord(&(xa.at(x), ya.range().start)).0;
        let row = |y: f64| chart.backend_coord(&(xa.range().start, ya.at(y))).1;
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

/// Which of the labels at `(pixel, size)` along an axis, in order, to show: the first, then each
/// whose half size and the last shown's, plus 4 pixels, fit between them.
pub(super) fn clear_of_each_other(labels: &[(i32, u32)]) -> Vec<bool> {
    let mut last: Option<(i32, u32)> = None;
    labels
        .iter()
        .map(|&(at, size)| {
            let clear = last.is_none_or(|(before, before_size)| {
                at.abs_diff(before) >= (size + before_size) / 2 + 4
            });
            if clear {
                last = Some((at, size));
            }
            clear
        })
        .collect()
}

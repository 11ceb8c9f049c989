//! The numbers of a phase diagram: its points gathered into the cells of the grid of each panel,
//! checked, and summarised (mean, band).

use super::{Band, PhaseOptions, PhasePoint};
use crate::draw::format;
use crate::error::VizError;

impl Band {
    /// The band of sorted, non-empty values.
    pub(super) fn of(self, sorted: &[f64]) -> (f64, f64) {
        match self {
            Self::MinMax => (sorted[0], sorted[sorted.len() - 1]),
            Self::Quantiles => (quantile(sorted, 0.25), quantile(sorted, 0.75)),
        }
    }
}

/// The finite values of one panel: `cells[i][j]` at (xs[i], ys[j]) (j = 0 without y), sorted.
pub(super) type Cells = Vec<Vec<Vec<f64>>>;

/// The values of each grid point of each panel: the sorted distinct x (and y) of every panel and
/// the finite values there.
pub(super) struct Diagram<'a> {
    pub(super) options: &'a PhaseOptions,
    pub(super) xs: Vec<f64>,
    pub(super) ys: Vec<f64>,
    /// One per panel.
    pub(super) panels: Vec<Cells>,
    /// The least and largest finite value of every panel.
    pub(super) range: (f64, f64),
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

pub(super) fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

impl<'a> Diagram<'a> {
    pub(super) fn new(points: &[PhasePoint], options: &'a PhaseOptions) -> Result<Self, VizError> {
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
        let categories = [
            ("x", &options.x_categories, &xs),
            ("y", &options.y_categories, &ys),
        ];
        for (axis, names, values) in categories {
            if !names.is_empty()
                && values
                    .iter()
                    .any(|&v| v.fract() != 0.0 || v < 0.0 || v >= names.len() as f64)
            {
                return Err(VizError::invalid(format!(
                    "a categorical {axis} is the index of a category, 0 to {}",
                    names.len() - 1
                )));
            }
        }
        if heatmap && !options.y_categories.is_empty() && options.log_y {
            return Err(VizError::invalid("a categorical y has no log scale"));
        }
        if !options.x_categories.is_empty() && (options.log_x || options.bound.is_some()) {
            return Err(VizError::invalid(
                "a categorical x has neither a log scale nor a bound",
            ));
        }
        if options.even_cells && !heatmap {
            return Err(VizError::invalid(
                "even cells are for a heatmap (give y); a line diagram draws x at its values",
            ));
        }
        if options.even_cells && (options.log_x || options.log_y) {
            return Err(VizError::invalid(
                "even cells space the values evenly already: give either even cells or a log axis",
            ));
        }
        let categorical = !options.x_categories.is_empty() || !options.y_categories.is_empty();
        if categorical && !options.references.is_empty() {
            return Err(VizError::invalid(
                "references are drawn in the values of numeric axes, not beside categories",
            ));
        }
        if options.log_colour && !(heatmap && lo > 0.0) {
            return Err(VizError::invalid(format!(
                "a log colour scale is for a heatmap of positive values; the least value of {metric} is {}",
                format::tick(lo)
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
    pub(super) fn means(cells: &Cells) -> Vec<Vec<Option<f64>>> {
        cells
            .iter()
            .map(|column| column.iter().map(|cell| mean(cell)).collect())
            .collect()
    }
}

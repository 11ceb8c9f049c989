//! [`CellAxis`]: where the cells of a heatmap axis lie, on the axis' coordinate.
//!
//! A numeric axis is the value axis (ln value with a log scale and positive values): each value's
//! cell is centred on it and spans halfway to its neighbours, the first and last as far beyond
//! their value as towards their neighbour; unevenly spaced values (0, 0.01, 0.1, 0.5) give cells of uneven widths, as a reader of a
//! paper expects. A categorical axis has one equal cell per category, centred on its index, and
//! so has a numeric axis drawn with even cells (values that crowd at one end, such as delays 0,
//! 0.01, 0.02, …, 0.8, which no log scale can spread because of the 0): a value between two of
//! the grid's is then placed between their cells in proportion. As plotters' coordinate, the axis
//! is linear over its cells, its ticks at their centres.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::types::RangedCoordf64;

/// The cells of one axis of a heatmap, in the coordinate the chart is drawn in.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct CellAxis {
    /// The centre of each value's cell.
    pub(super) centres: Vec<f64>,
    /// The cells' edges: cell k spans `edges[k]..edges[k + 1]`.
    pub(super) edges: Vec<f64>,
    /// The axis is ln value.
    log: bool,
    /// The grid's values when the cells are even (the centres are then their indices).
    even: Option<Vec<f64>>,
}

/// How the cells of an axis are laid out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Layout {
    /// Categories: equal cells at their indices.
    Categories,
    /// Values, in ln value with `log` when every value is positive.
    Values { log: bool },
    /// Values in equal cells, in order.
    Even,
}

impl CellAxis {
    /// The cells of the sorted distinct `values`, laid out as `layout` says.
    pub(super) fn new(values: &[f64], layout: Layout) -> Self {
        let log = layout == Layout::Values { log: true } && values[0] > 0.0;
        let centres: Vec<f64> = match layout {
            Layout::Categories | Layout::Even => (0..values.len()).map(|k| k as f64).collect(),
            Layout::Values { .. } if log => values.iter().map(|v| v.ln()).collect(),
            Layout::Values { .. } => values.to_vec(),
        };
        let n = centres.len();
        let edges = if n == 1 {
            vec![centres[0] - 0.5, centres[0] + 0.5]
        } else {
            let first = centres[0] - (centres[1] - centres[0]) / 2.0;
            let last = centres[n - 1] + (centres[n - 1] - centres[n - 2]) / 2.0;
            std::iter::once(first)
                .chain(centres.windows(2).map(|w| (w[0] + w[1]) / 2.0))
                .chain(std::iter::once(last))
                .collect()
        };
        Self {
            centres,
            edges,
            log,
            even: (layout == Layout::Even).then(|| values.to_vec()),
        }
    }

    /// Where the value `x` (of a numeric axis) is on the axis, within its extent (a value beyond
    /// it, or not positive on a log axis, is at its edge).
    pub(super) fn at(&self, x: f64) -> f64 {
        let range = Ranged::range(self);
        let u = if let Some(values) = &self.even {
            even_position(values, x)
        } else if self.log {
            if x > 0.0 { x.ln() } else { range.start }
        } else {
            x
        };
        u.clamp(range.start, range.end)
    }

    /// The index of the cell centred at `u` (a key point of the axis), if any.
    pub(super) fn cell_at(&self, u: f64) -> Option<usize> {
        self.centres.iter().position(|&c| c == u)
    }
}

/// Where `x` lies among the sorted `values` drawn in even cells: the index of a value it equals,
/// in proportion between the indices of the two it lies between, beyond the ends at the outer
/// cell edges (±0.5).
fn even_position(values: &[f64], x: f64) -> f64 {
    let n = values.len();
    if x < values[0] {
        return -0.5;
    }
    if x > values[n - 1] {
        return n as f64 - 0.5;
    }
    let k = values.partition_point(|&v| v <= x).saturating_sub(1);
    if k == n - 1 {
        k as f64
    } else {
        k as f64 + (x - values[k]) / (values[k + 1] - values[k])
    }
}

impl Ranged for CellAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        RangedCoordf64::from(self.range()).map(value, limit)
    }

    /// The cells' centres, where the axis is labelled.
    fn key_points<Hint: KeyPointHint>(&self, _hint: Hint) -> Vec<f64> {
        self.centres.clone()
    }

    /// The first cell's lower edge to the last cell's upper edge.
    fn range(&self) -> Range<f64> {
        self.edges[0]..self.edges[self.edges.len() - 1]
    }
}

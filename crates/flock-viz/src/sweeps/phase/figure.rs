//! A phase diagram as a figure: its title, its panels on a grid (or one set of axes for
//! series) and a heatmap's colour bar.

use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};

use super::grid::Diagram;
use crate::draw::render::Figure;
use crate::error::VizError;
use crate::snapshots::snapshot::{below_title, text_style};

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

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body = below_title(root, &self.options.title)?;
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
            self.colour_bar(&bar, range)?;
            grid
        } else {
            body
        };
        if self.options.series {
            return self.series(&grid);
        }
        let areas = grid.split_evenly(self.grid());
        for (k, (cells, area)) in self.panels.iter().zip(&areas).enumerate() {
            let area = match self.options.panels.get(k) {
                Some(title) => area.titled(title, text_style(16)).map_err(VizError::draw)?,
                None => area.clone(),
            };
            if heatmap {
                self.heatmap(&area, cells, range)?;
            } else {
                self.line(&area, k, cells)?;
            }
        }
        Ok(())
    }
}

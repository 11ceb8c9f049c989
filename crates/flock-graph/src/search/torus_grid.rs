//! The grid of a periodic box (a torus): [`TorusGrid`], its finite agents sorted by cell, and
//! each cell's candidates across the wrap with the periods that take them to their images
//! ([`CandidateCells`]).
//!
//! The box [0, L₁) × … × [0, L_m) is cut into c_k = ⌊L_k / s⌋ cells per axis (at least one),
//! s the range padded against rounding as in the open grid, so every cell is at least s wide and
//! two agents whose minimum-image distance is below r lie in the same cell or in cells adjacent
//! across the wrap. The adjacent cells of cell c along an axis are c − 1, c, c + 1 modulo c_k,
//! taken once each: with two cells per axis c − 1 and c + 1 are the same cell, with one cell there
//! is only c, so no pair is visited twice. When the agents are few the cells are merged (halving
//! the axis with the most cells) until there are at most 4n.

use core::ops::Range;

use flock_math::Vector;

use crate::search::cells::{
    CELLS_PER_AGENT, CellSort, MAX_CELLS, NO_SLOT, SlotCells, cell_coords, padded_side,
};

/// A grid of the periodic box, its finite agents sorted by cell ([`CellSort`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct TorusGrid {
    /// Cells per axis (1 on the unused axis of 2D).
    dims: [usize; 3],
    /// Cell width L_k / c_k per axis.
    width: [f64; 3],
    /// The agents sorted by cell.
    pub(crate) sorted: CellSort,
}

/// The slot ranges of up to 27 cells: a cell and its neighbours across the wrap, each once, with
/// the whole periods that take each one's agents to their images next to the cell.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CandidateCells {
    ranges: [(usize, usize); 27],
    /// Per range, per axis, the periods the displacement to its agents loses across the wrap: 1
    /// for the cell before the first (the last cell), −1 for the one after the last (the first
    /// cell), 0 otherwise.
    shifts: [[f64; 3]; 27],
    count: usize,
}

impl CandidateCells {
    #[inline]
    pub(crate) fn iter(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.ranges[..self.count].iter().map(|&(a, b)| a..b)
    }

    /// The ranges with their shifts.
    #[inline]
    pub(crate) fn shifted(&self) -> impl Iterator<Item = (Range<usize>, [f64; 3])> + '_ {
        self.iter().zip(self.shifts.iter().copied())
    }

    /// The number of agents in the cells.
    pub(crate) fn len(&self) -> usize {
        self.iter().map(|range| range.len()).sum()
    }
}

/// The distinct cells c − 1, c, c + 1 modulo `cells`, and how many there are.
#[inline]
fn around(c: usize, cells: usize) -> ([usize; 3], usize) {
    match cells {
        1 => ([0; 3], 1),
        2 => ([0, 1, 0], 2),
        _ => ([(c + cells - 1) % cells, c, (c + 1) % cells], 3),
    }
}

impl TorusGrid {
    /// Rebuilds the grid of the box of sides `size` for `positions`, with cells wide enough that
    /// a minimum-image squared distance below `reach²` (as the predicate computes it) joins agents
    /// of the same or adjacent cells.
    pub(crate) fn rebuild<V: Vector>(&mut self, size: V, positions: &[V], reach: f64) {
        let finite = positions.iter().filter(|q| q.is_finite()).count();
        let longest = (0..V::DIM).fold(0.0_f64, |m, k| m.max(size.coord(k)));
        let side = padded_side(reach, longest);
        let max_cells = (CELLS_PER_AGENT * finite.max(1)).min(MAX_CELLS);
        let mut dims = [1_usize; 3];
        for (k, dim) in dims.iter_mut().enumerate().take(V::DIM) {
            let c = (size.coord(k) / side).floor();
            // NaN (an infinite side) and fewer than one cell give one cell
            *dim = if c >= 1.0 {
                c.min(max_cells as f64) as usize
            } else {
                1
            };
        }
        while dims.iter().map(|&c| c as f64).product::<f64>() > max_cells as f64 {
            let k = (0..3).max_by_key(|&k| dims[k]).unwrap_or(0);
            dims[k] = dims[k].div_ceil(2);
        }
        self.dims = dims;
        self.width = core::array::from_fn(|k| {
            if k < V::DIM {
                size.coord(k) / dims[k] as f64
            } else {
                1.0
            }
        });
        let cells: usize = dims.iter().product();
        let (width, dims_) = (self.width, self.dims);
        let cell_of = |q: V| -> u32 {
            if !q.is_finite() {
                return NO_SLOT;
            }
            let c: [usize; 3] = core::array::from_fn(|k| {
                if k >= V::DIM || dims_[k] == 1 {
                    return 0;
                }
                // positions are in the box; an agent a few ulps off it lands in the cell it wraps
                // to (or one adjacent, which the padding covers)
                let t = (q.coord(k) / width[k]).floor().rem_euclid(dims_[k] as f64);
                (t as usize).min(dims_[k] - 1)
            });
            (c[0] + dims_[0] * (c[1] + dims_[1] * c[2])) as u32
        };
        self.sorted.sort(cells, positions, cell_of);
    }

    /// The coordinates of `cell`.
    pub(crate) fn cell_coords(&self, cell: usize) -> [usize; 3] {
        cell_coords(cell, self.dims)
    }

    /// The slot ranges of the cell `[cx, cy, cz]` and of its neighbours across the wrap, with
    /// their shifts (meaningful on the axes of at least three cells: see
    /// [`TorusGrid::shifts_are_exact`]).
    pub(crate) fn candidates(&self, [cx, cy, cz]: [usize; 3]) -> CandidateCells {
        let [dx, dy, dz] = self.dims;
        let ((xs, nx), (ys, ny), (zs, nz)) = (around(cx, dx), around(cy, dy), around(cz, dz));
        // with three cells or more on axis k: the last cell seen from the first, and the first
        // seen from the last
        let shift = |k: usize, c: usize, neighbour: usize| match (c, neighbour) {
            (0, n) if n + 1 == self.dims[k] && n > 1 => 1.0,
            (c, 0) if c + 1 == self.dims[k] && c > 1 => -1.0,
            _ => 0.0,
        };
        let mut out = CandidateCells::default();
        for &z in &zs[..nz] {
            for &y in &ys[..ny] {
                for &x in &xs[..nx] {
                    let cell = x + dx * (y + dy * z);
                    let (a, b) = (self.sorted.start(cell), self.sorted.start(cell + 1));
                    if a < b {
                        out.ranges[out.count] = (a, b);
                        out.shifts[out.count] = [shift(0, cx, x), shift(1, cy, y), shift(2, cz, z)];
                        out.count += 1;
                    }
                }
            }
        }
        out
    }

    /// The candidate cells of ascending slots from `slot` on: each cell's computed once, when
    /// its first slot is reached (consecutive slots share their cell).
    pub(crate) fn candidates_from(&self, slot: usize) -> SlotCandidates<'_> {
        SlotCandidates {
            grid: self,
            cells: self.sorted.cells_from(slot, self.dims),
            cell: usize::MAX,
            candidates: CandidateCells::default(),
        }
    }

    /// Whether every axis of an m-dimensional box has at least three cells. Then the agents of a
    /// candidate cell within range r of an agent of cell c are at their minimum image once the
    /// cell's shift is taken off their difference, and every other candidate stays beyond r:
    ///
    /// - along an axis, a candidate in c or in a neighbour not across the wrap is less than two
    ///   cells away: |d| < 2w ≤ L − w (w = L/c_k ≤ L/3, and w > r). Its minimum image is d when
    ///   |d| < L/2; otherwise it is L − |d| > w > r, and d itself is at least L/2 > r: out of range
    ///   both ways;
    /// - across the wrap, d ∈ (L − 2w, L) (or its negative): the minimum image is d − L when
    ///   d ≥ L/2; otherwise it is d, with |d| > L − 2w ≥ w > r, and |d − L| > L/2 > r: out of range
    ///   both ways.
    ///
    /// Where the shift is the minimum image's, `d − k·L` is `minimum_image`'s bit for bit (k·L is
    /// exact), up to the sign of a zero, which the squared length drops. An in-range pair is far
    /// from the threshold L/2 (|d| < r or |d − L| < r), so rounding cannot tell the two apart.
    pub(crate) fn shifts_are_exact(&self, dim: usize) -> bool {
        self.dims[..dim].iter().all(|&c| c >= 3)
    }
}

/// The candidate cells of the slots of a [`TorusGrid`] visited in ascending order
/// ([`TorusGrid::candidates_from`]).
pub(crate) struct SlotCandidates<'a> {
    grid: &'a TorusGrid,
    cells: SlotCells<'a>,
    /// The cell whose candidates `candidates` holds (`usize::MAX`: none yet).
    cell: usize,
    candidates: CandidateCells,
}

impl SlotCandidates<'_> {
    /// The candidate cells of `slot`'s cell; `slot` must not decrease between calls.
    #[inline]
    pub(crate) fn of(&mut self, slot: usize) -> &CandidateCells {
        let cell = self.cells.cell_of(slot);
        if cell != self.cell {
            self.cell = cell;
            self.candidates = self.grid.candidates(self.cells.coords());
        }
        &self.candidates
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn two_cells_per_axis_give_each_cell_once() {
        assert_eq!(around(0, 2), ([0, 1, 0], 2));
        assert_eq!(around(1, 2), ([0, 1, 0], 2));
        assert_eq!(around(0, 1), ([0; 3], 1));
        assert_eq!(around(0, 5), ([4, 0, 1], 3));
        assert_eq!(around(4, 5), ([3, 4, 0], 3));
        let mut grid = TorusGrid::default();
        let q = [
            DVec2::new(0.5, 0.5),
            DVec2::new(1.5, 1.5),
            DVec2::new(1.9, 0.1),
        ];
        grid.rebuild(DVec2::new(2.0, 2.0), &q, 0.99);
        assert_eq!(grid.dims, [2, 2, 1]);
        let cells = grid.candidates(grid.cell_coords(0));
        assert_eq!(cells.count, 3, "the three non-empty cells, each once");
    }

    #[test]
    fn few_agents_merge_cells() {
        let mut grid = TorusGrid::default();
        let q = [DVec2::new(1.0, 1.0), DVec2::new(50.0, 50.0)];
        grid.rebuild(DVec2::new(100.0, 100.0), &q, 1.0);
        assert!(grid.dims.iter().product::<usize>() <= 8, "{:?}", grid.dims);
        assert!(grid.width[0] >= 1.0);
    }
}

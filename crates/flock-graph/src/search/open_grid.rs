//! The open-space grid: uniform cubic cells over the bounding box of the finite agents
//! ([`CellGrid`]), each agent's candidates the slots of its cell's 3^m block ([`CandidateRows`]).
//!
//! The cell side is the reach padded by a few ulps of it and of the largest coordinate
//! ([`padded_side`]), so rounding at cell boundaries cannot hide a pair that the predicate
//! accepts, even far from the origin. When the agents are spread thin the cell is enlarged until
//! there are at most [`CELLS_PER_AGENT`] · n cells ([`fit_side`]): memory stays O(n) whatever
//! the configuration.

use core::ops::Range;

use flock_math::Vector;

use crate::net::{in_range, squared_distance};
use crate::search::cells::{
    CELLS_PER_AGENT, CellSort, MAX_CELLS, NO_SLOT, SlotCells, cell_coords, padded_side,
};
use flock_math::parallel::map_chunks;

/// Agents per chunk of the parallel displacement check ([`CellGrid::moved_within`]).
const MOVED_CHUNK: usize = 1 << 14;

/// Agents per chunk of the parallel bounds.
const BOUNDS_CHUNK: usize = 1 << 16;

/// Axis-aligned bounds of the finite agents.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounds {
    lo: [f64; 3],
    hi: [f64; 3],
    /// Largest coordinate magnitude.
    max_abs: f64,
    /// Number of finite agents.
    finite: usize,
}

impl Bounds {
    /// The bounds of the finite agents of `positions` (all zero when there are none).
    pub(crate) fn of<V: Vector>(positions: &[V]) -> Self {
        debug_assert!(V::DIM <= 3);
        let mut bounds = Self {
            lo: [0.0; 3],
            hi: [0.0; 3],
            max_abs: 0.0,
            finite: 0,
        };
        // (lo, hi, finite agents) of chunks, in parallel. Whichever the chunks, only the sign of a
        // zero bound may change, which moves no agent to another cell (and the net does not
        // depend on the grid anyway).
        let chunks = map_chunks(positions.len(), BOUNDS_CHUNK, |agents| {
            let mut finite = positions[agents].iter().filter(|q| q.is_finite());
            let first = *finite.next()?;
            Some(finite.fold((first, first, 1_usize), |(lo, hi, count), &q| {
                (lo.min(q), hi.max(q), count + 1)
            }))
        });
        let Some((lo, hi, count)) = chunks
            .into_iter()
            .flatten()
            .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1), a.2 + b.2))
        else {
            return bounds;
        };
        for k in 0..V::DIM {
            bounds.lo[k] = lo.coord(k);
            bounds.hi[k] = hi.coord(k);
            bounds.max_abs = bounds.max_abs.max(lo.coord(k).abs()).max(hi.coord(k).abs());
        }
        bounds.finite = count;
        bounds
    }

    /// hi − lo per axis (0 on the unused axes of 2D); may overflow to +∞.
    fn extents(&self) -> [f64; 3] {
        core::array::from_fn(|k| self.hi[k] - self.lo[k])
    }

    /// (volume / n)^(1/m') over the m' axes of non-zero extent: the typical spacing of agents
    /// spread uniformly in their bounding box (0 when they all coincide).
    pub(crate) fn mean_spacing(&self) -> f64 {
        let (log_volume, axes) = self
            .extents()
            .into_iter()
            .filter(|&e| e > 0.0)
            .fold((0.0, 0_u32), |(sum, axes), e| (sum + e.ln(), axes + 1));
        if axes == 0 {
            return 0.0;
        }
        ((log_volume - (self.finite as f64).ln()) / f64::from(axes)).exp()
    }
}

/// The geometry of a uniform grid of cubic cells over the bounding box of the finite agents.
/// Unused axes of 2D have one cell.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Layout {
    /// Lower corner of the grid (the lower corner of the bounding box).
    origin: [f64; 3],
    /// Cell side.
    side: f64,
    /// Cells per axis.
    dims: [usize; 3],
}

impl Layout {
    /// The layout for agents within `bounds` such that two finite agents whose squared distance,
    /// as the predicate computes it, is below `reach²` lie in the same or adjacent cells, with at
    /// most [`CELLS_PER_AGENT`] cells per finite agent (and at most [`MAX_CELLS`]).
    fn new(bounds: &Bounds, reach: f64) -> Self {
        let extents = bounds.extents();
        let side = padded_side(reach, bounds.max_abs);
        let max_cells = (CELLS_PER_AGENT * bounds.finite.max(1)).min(MAX_CELLS);
        if side.is_finite() && extents.iter().all(|e| e.is_finite()) {
            let side = fit_side(side, &extents, max_cells);
            // fit_side bounds the product by max_cells, so each factor fits a usize.
            Self {
                origin: bounds.lo,
                side,
                dims: extents.map(|e| cells_along(e, side) as usize),
            }
        } else {
            // Infinite range or extent: a single cell (every pair is a candidate).
            Self {
                origin: bounds.lo,
                side,
                dims: [1; 3],
            }
        }
    }

    /// Total number of cells.
    #[inline]
    fn cells(&self) -> usize {
        self.dims.iter().product()
    }

    /// Cell coordinate of `q` along `axis`, clamped to the grid.
    #[inline]
    fn axis_cell<V: Vector>(&self, q: V, axis: usize) -> usize {
        if self.dims[axis] == 1 {
            return 0;
        }
        // x − origin ≥ 0 (NaN only for a NaN side), so truncation is the floor; the cast
        // saturates.
        let t = ((q.coord(axis) - self.origin[axis]) / self.side) as usize;
        t.min(self.dims[axis] - 1)
    }

    /// Linear index of the cell with coordinates `c`.
    #[inline]
    fn cell(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    /// The coordinates of the cell of linear index `cell`.
    pub(crate) fn coords(&self, cell: usize) -> [usize; 3] {
        cell_coords(cell, self.dims)
    }

    /// Linear cell of a finite `q` ([`NO_SLOT`] for a non-finite one).
    #[inline]
    fn cell_of<V: Vector>(&self, q: V) -> u32 {
        if q.is_finite() {
            // below MAX_CELLS
            self.cell(core::array::from_fn(|k| self.axis_cell(q, k))) as u32
        } else {
            NO_SLOT
        }
    }
}

/// A uniform cell grid with the finite agents sorted by cell (counting sort, ascending index
/// within a cell). Position `s` in that order is a *slot*.
#[derive(Clone, Debug, Default)]
pub(crate) struct CellGrid {
    pub(crate) layout: Layout,
    /// The agents sorted by cell.
    pub(crate) sorted: CellSort,
}

/// The candidate slots of the agents of one cell: the runs of slots of the rows of up to 3^m
/// adjacent cells (cells x0..=x1 of a row are contiguous).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CandidateRows {
    rows: [(usize, usize); 9],
    count: usize,
}

impl CandidateRows {
    /// The slot ranges, one per row.
    #[inline]
    pub(crate) fn iter(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.rows[..self.count].iter().map(|&(a, b)| a..b)
    }
}

impl CellGrid {
    /// Rebuilds the grid for `positions` (see [`Layout::new`] for `reach`).
    pub(crate) fn rebuild<V: Vector>(&mut self, positions: &[V], reach: f64) {
        let bounds = Bounds::of(positions);
        let layout = Layout::new(&bounds, reach);
        let cells = layout.cells();
        self.layout = layout;
        self.sorted.sort(cells, positions, |q| layout.cell_of(q));
    }

    /// Whether every agent of `positions` (as many as at the last rebuild) is within squared
    /// distance `limit` of where it was then, and every agent then without a cell still has a
    /// non-finite position (a NaN displacement is not within).
    pub(crate) fn moved_within<V: Vector>(&self, positions: &[V], limit: f64) -> bool {
        map_chunks(positions.len(), MOVED_CHUNK, |agents| {
            agents.into_iter().all(|i| match self.sorted.slot_of[i] {
                NO_SLOT => !positions[i].is_finite(),
                slot => {
                    squared_distance(self.sorted.position::<V>(slot as usize), positions[i])
                        <= limit
                }
            })
        })
        .into_iter()
        .all(|within| within)
    }

    /// The cells of ascending slots from `slot` on.
    pub(crate) fn cells_of(&self, slot: usize) -> SlotCells<'_> {
        self.sorted.cells_from(slot, self.layout.dims)
    }

    /// The slots of the agents of the cell with coordinates `[cx, cy, cz]` and of its adjacent
    /// cells (in no useful order).
    #[inline]
    pub(crate) fn candidate_rows(&self, [cx, cy, cz]: [usize; 3]) -> CandidateRows {
        let [dx, dy, dz] = self.layout.dims;
        let (x0, x1) = (cx.saturating_sub(1), (cx + 1).min(dx - 1));
        let mut rows = CandidateRows::default();
        for z in cz.saturating_sub(1)..=(cz + 1).min(dz - 1) {
            for y in cy.saturating_sub(1)..=(cy + 1).min(dy - 1) {
                let row = self.layout.cell([0, y, z]);
                rows.rows[rows.count] =
                    (self.sorted.start(row + x0), self.sorted.start(row + x1 + 1));
                rows.count += 1;
            }
        }
        rows
    }

    /// The smallest squared distance below `threshold` over all pairs, if any (the grid must have
    /// been built with reach `threshold.sqrt()`).
    pub(crate) fn min_squared_distance<V: Vector>(&self, threshold: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        let mut cells = self.cells_of(0);
        for slot in 0..self.sorted.slots() {
            let (i, qi) = (self.sorted.order[slot], self.sorted.position::<V>(slot));
            cells.cell_of(slot);
            for row in self.candidate_rows(cells.coords()).iter() {
                for candidate in row {
                    let d2 = squared_distance(qi, self.sorted.position::<V>(candidate));
                    if self.sorted.order[candidate] > i && in_range(d2, threshold) {
                        best = Some(best.map_or(d2, |b| b.min(d2)));
                    }
                }
            }
        }
        best
    }
}

/// Number of cells of side `side` covering an extent: ⌊extent / side⌋ + 1, as an f64.
#[inline]
#[must_use]
fn cells_along(extent: f64, side: f64) -> f64 {
    (extent / side).floor() + 1.0
}

/// The smallest side (to bisection precision) ≥ `min_side` for which the grid over `extents` has
/// at most `max_cells` cells. `min_side` and the extents must be finite.
#[must_use]
fn fit_side(min_side: f64, extents: &[f64; 3], max_cells: usize) -> f64 {
    let fits = |side: f64| {
        extents
            .iter()
            .map(|&e| cells_along(e, side))
            .product::<f64>()
            <= max_cells as f64
    };
    if fits(min_side) {
        return min_side;
    }
    // Above the largest extent every axis has a single cell.
    let (mut lo, mut hi) = (
        min_side,
        2.0 * extents.iter().fold(min_side, |m, &e| m.max(e)),
    );
    // Geometric bisection: the ratio hi / lo may span hundreds of orders of magnitude.
    for _ in 0..64 {
        let mid = lo.sqrt() * hi.sqrt();
        if !(mid > lo && mid < hi) {
            break;
        }
        if fits(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numbering::Numbering;
    use glam::{DVec2, DVec3};

    fn line<V: Vector>(n: usize, spacing: f64) -> Vec<V> {
        (0..n)
            .map(|k| V::from_fn(|axis| if axis == 0 { k as f64 * spacing } else { 0.0 }))
            .collect()
    }

    fn check_cell_cap<V: Vector>() {
        // 50 agents spread over 1e12 with a range of 1: without the cap, 1e12 cells.
        let q: Vec<V> = line(50, 2e10);
        let mut grid = CellGrid::default();
        grid.rebuild(&q, 1.0);
        let cells = grid.layout.cells();
        assert!(cells <= CELLS_PER_AGENT * 50, "{cells} cells");
        assert!(
            cells >= 50,
            "the cap should still separate the agents: {cells} cells"
        );
        assert_eq!(grid.sorted.starts.len(), cells + 1);
        assert_eq!(grid.sorted.order.len(), 50);
    }

    #[test]
    fn cell_cap_2d() {
        check_cell_cap::<DVec2>();
    }

    #[test]
    fn cell_cap_3d() {
        check_cell_cap::<DVec3>();
    }

    #[test]
    fn fit_side_handles_huge_ratios() {
        let side = fit_side(1e-300, &[1e300, 0.0, 0.0], 8);
        let cells = cells_along(1e300, side);
        assert!((4.0..=8.0).contains(&cells), "{cells}");
        assert_eq!(fit_side(1.0, &[3.0, 3.0, 0.0], 100), 1.0);
    }

    #[test]
    fn lists_are_built_without_branching_for_agents_numbered_off_space() {
        let scattered = |q: &[DVec3], numbering: &Numbering| {
            let mut grid = CellGrid::default();
            grid.rebuild(q, 1.1);
            grid.sorted.scattered(numbering)
        };
        let lattice = |w: usize, layers: usize| -> Vec<DVec3> {
            (0..w * w * layers)
                .map(|k| DVec3::new((k % w) as f64, ((k / w) % w) as f64, (k / (w * w)) as f64))
                .collect()
        };
        let identity = Numbering::identity();
        let shuffle = |mut q: Vec<DVec3>| {
            use rand::SeedableRng;
            use rand::seq::SliceRandom;
            q.shuffle(&mut rand_pcg::Pcg64::seed_from_u64(3));
            q
        };
        // numbered along space, row by row (agents i and i + 1 in one cell or the next), and
        // the same agents in an order unrelated to space: 2D and 3D, from 343 to 10⁴ agents
        for (w, layers) in [(100, 1), (22, 22), (20, 1), (7, 7)] {
            assert!(!scattered(&lattice(w, layers), &identity), "{w}×{layers}");
            assert!(
                scattered(&shuffle(lattice(w, layers)), &identity),
                "{w}×{layers}"
            );
        }
        // too few to pay, whatever the order
        assert!(!scattered(&shuffle(lattice(15, 1)), &identity));
        // stored by cell under a numbering: always
        let mut numbering = Numbering::identity();
        numbering.permute(&(0..961).rev().collect::<Vec<u32>>());
        assert!(scattered(&lattice(31, 1), &numbering));
    }

    #[test]
    fn grid_sorts_agents_by_cell_ascending_within_cells() {
        let q = [
            DVec2::new(5.0, 5.0),
            DVec2::new(0.0, 0.0),
            DVec2::new(5.1, 5.0),
            DVec2::new(0.1, 0.0),
        ];
        let mut grid = CellGrid::default();
        grid.rebuild(&q, 1.0);
        assert_eq!(grid.sorted.order, [1, 3, 0, 2]);
        assert_eq!(grid.sorted.slot_of, [2, 0, 3, 1]);
        let mut cells = grid.cells_of(0);
        let slot_cell: Vec<usize> = (0..4).map(|slot| cells.cell_of(slot)).collect();
        assert_eq!(slot_cell[0], slot_cell[1]);
        assert_eq!(slot_cell[2], slot_cell[3]);
        assert_eq!(grid.cells_of(2).cell_of(2), slot_cell[2]);
        let first = slot_cell[0];
        assert_eq!(grid.sorted.start(first)..grid.sorted.start(first + 1), 0..2);
        for (slot, &i) in grid.sorted.order.iter().enumerate() {
            assert_eq!(grid.sorted.position::<DVec2>(slot), q[i as usize]);
        }
    }

    #[test]
    fn non_finite_agents_are_in_no_cell() {
        let q = [
            DVec3::ZERO,
            DVec3::NAN,
            DVec3::X,
            DVec3::new(f64::INFINITY, 0.0, 0.0),
        ];
        let mut grid = CellGrid::default();
        grid.rebuild(&q, 2.0);
        assert_eq!(grid.sorted.slot_of, [0, NO_SLOT, 1, NO_SLOT]);
        assert_eq!(grid.sorted.order, [0, 2]);
    }

    #[test]
    fn mean_spacing_ignores_flat_axes() {
        let q: Vec<DVec3> = line(11, 1.0);
        let spacing = Bounds::of(&q).mean_spacing();
        assert!((spacing - 10.0 / 11.0).abs() < 1e-12, "{spacing}");
        assert_eq!(Bounds::of(&[DVec2::ONE, DVec2::ONE]).mean_spacing(), 0.0);
    }
}

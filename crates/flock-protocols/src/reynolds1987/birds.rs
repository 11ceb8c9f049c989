//! The boids of one sequential sweep, as the sweep reads and moves them: each bird's position and
//! heading together in a *slot* ([`Bird`], one cache line or less), and how a bird finds the others
//! in sight — by the proximity net in open space, by a uniform grid of cells over the torus in a
//! periodic box ([`Birds::in_cells`]).
//!
//! On the torus the birds are sorted by the cell they are in at the start of the step (a counting
//! sort, ascending original index within a cell), so that the birds of neighbouring cells are
//! neighbours in memory. A cell is at least the visual distance plus one move s h across: a bird
//! moves at most s h in the sweep, so it stays within s h of the cell it is stored in, and every
//! bird within sight of a point lies in the point's cell or the cells around it. The grid is
//! therefore built once a step and never updated during the sweep: a moved bird is rewritten in its
//! own slot.

use core::ops::Range;

use flock_math::{Domain, Vector};

use super::Sums;

/// Slot of a bird in no cell (a non-finite position): it sees no one and no one sees it, as in
/// the proximity net.
const NO_SLOT: u32 = u32::MAX;

/// Cells allowed per bird (and a few more for tiny flocks): a grid over a sparse flock in a large
/// box gets larger cells rather than empty ones.
const CELLS_PER_BIRD: usize = 4;

/// How far ahead of the sweep [`Birds::read_ahead`] reads: the birds activated this many after the
/// current one (and twice as many for their cells).
const AHEAD: usize = 8;

/// The size of the birds above which the sweep reads ahead (bytes): the order of a core's L2.
const READ_AHEAD_FROM: usize = 1 << 19;

/// A bird as the sweep reads it: where the search sees it and its unit heading.
#[derive(Clone, Copy, Debug)]
pub(super) struct Bird<V> {
    /// On a grid of at least 3 cells along every axis, its position as it moved from its cell,
    /// never wrapped (it stays within s h of its cell), for the search's shifted offsets; otherwise
    /// its position in the box.
    pub(super) q: V,
    /// Its unit heading.
    pub(super) v: V,
}

/// The birds of a sweep, stored by slot.
pub(super) struct Birds<V> {
    /// The bird in each slot.
    pub(super) slots: Vec<Bird<V>>,
    /// Slot of each bird (original index), [`NO_SLOT`] for a bird in no cell.
    slot_of: Vec<u32>,
    /// On the torus: the grid; `None` in open space (slot k is bird k).
    grid: Option<Grid<V>>,
    /// On the torus: the cell each bird (original index) is stored in, [`NO_SLOT`] for none; empty
    /// in open space.
    cell_of: Vec<u32>,
}

/// A uniform grid over the periodic box, its cells numbered with axis 0 fastest.
struct Grid<V> {
    /// The sides of the box.
    size: V,
    /// Cells along each axis (1 beyond `V::DIM`).
    cells: [usize; 3],
    /// At least 3 cells along every axis: each cell around a cell is one image of the box, and
    /// the birds are searched unwrapped, with the shift of their cell.
    shifted: bool,
    /// The slots of cell c are `starts[c]..starts[c + 1]` (its birds in ascending original
    /// index).
    starts: Vec<u32>,
}

impl<V: Vector> Birds<V> {
    /// The birds in original order (slot k is bird k), for the search on the proximity net.
    pub(super) fn in_order(positions: &[V], headings: &[V]) -> Self {
        Self {
            slots: positions
                .iter()
                .zip(headings)
                .map(|(&q, &v)| Bird { q, v })
                .collect(),
            slot_of: (0..positions.len() as u32).collect(),
            grid: None,
            cell_of: Vec::new(),
        }
    }

    /// The birds at `positions` with unit `headings` sorted by cell of a grid over the box of
    /// sides `size`, each cell at least `reach` across (`reach` > 0).
    pub(super) fn in_cells(size: V, reach: f64, positions: &[V], headings: &[V]) -> Self {
        let n = positions.len();
        let cells = cells_per_axis(size, reach, n);
        let total: usize = cells.iter().product();
        let shifted = (0..V::DIM).all(|axis| cells[axis] >= 3);
        let cell_of: Vec<u32> = positions
            .iter()
            .map(|&q| match coords(size, cells, q) {
                Some(c) => index(cells, c) as u32,
                None => NO_SLOT,
            })
            .collect();
        // counting sort: starts[c + 1] counts cell c, then the running sum
        let mut starts = vec![0u32; total + 1];
        for &c in cell_of.iter().filter(|&&c| c != NO_SLOT) {
            starts[c as usize + 1] += 1;
        }
        for c in 0..total {
            starts[c + 1] += starts[c];
        }
        let placed = starts[total] as usize;
        let mut next = starts.clone();
        let mut slot_of = vec![NO_SLOT; n];
        let domain = Domain::Periodic { size };
        let unplaced = Bird {
            q: V::ZERO,
            v: V::ZERO,
        };
        let mut slots = vec![unplaced; placed];
        for (i, &c) in cell_of.iter().enumerate() {
            if c == NO_SLOT {
                continue;
            }
            let slot = next[c as usize] as usize;
            next[c as usize] += 1;
            slot_of[i] = slot as u32;
            let q = positions[i];
            slots[slot] = Bird {
                q: if shifted { domain.wrap(q) } else { q },
                v: headings[i],
            };
        }
        Self {
            slots,
            slot_of,
            grid: Some(Grid {
                size,
                cells,
                shifted,
                starts,
            }),
            cell_of,
        }
    }

    /// Whether the sweep reads its birds ahead ([`Birds::read_ahead`]): on the torus, when they
    /// outgrow the core's own caches.
    pub(super) fn reads_ahead(&self) -> bool {
        self.grid.is_some() && self.slots.len() * size_of::<Bird<V>>() > READ_AHEAD_FROM
    }

    /// Reads ahead of the sweep at its `k`-th activation of `order`: the slot and cell of the bird
    /// activated [`AHEAD`] after the next, and one word of each cache line of the cells around the
    /// next [`AHEAD`]-th, so that their cache misses overlap the updates between (the sweep in a
    /// random order over a flock larger than the caches otherwise waits on each in turn). What is
    /// read changes nothing; it is returned to be kept (`core::hint::black_box`) so that it is
    /// read.
    pub(super) fn read_ahead(&self, order: &[u32], k: usize) -> u64 {
        let Some(grid) = &self.grid else {
            return 0;
        };
        let mut read = 0;
        if let Some(&far) = order.get(k + 2 * AHEAD) {
            let far = far as usize;
            read ^= u64::from(self.slot_of[far] ^ self.cell_of[far]);
        }
        let Some(&near) = order.get(k + AHEAD) else {
            return read;
        };
        let cell = self.cell_of[near as usize];
        if cell == NO_SLOT {
            return read;
        }
        let mut c = [0; 3];
        let mut rest = cell as usize;
        for (axis, c) in c.iter_mut().enumerate() {
            *c = rest % grid.cells[axis];
            rest /= grid.cells[axis];
        }
        let per_line = (64 / size_of::<Bird<V>>()).max(1);
        grid.around(c, |slots, _| {
            for bird in self.slots[slots].iter().step_by(per_line) {
                read ^= bird.q.coord(0).to_bits();
            }
        });
        read
    }

    /// The slot of bird `i`, `None` for a bird in no cell.
    pub(super) fn slot(&self, i: usize) -> Option<usize> {
        match self.slot_of[i] {
            NO_SLOT => None,
            slot => Some(slot as usize),
        }
    }

    /// Moves the bird in `slot` by `step` (wrapped into the box unless the search reads it
    /// unwrapped).
    pub(super) fn move_by(&mut self, domain: &Domain<V>, slot: usize, step: V) {
        let shifted = self.grid.as_ref().is_some_and(|grid| grid.shifted);
        let q = &mut self.slots[slot].q;
        *q = if shifted {
            *q + step
        } else {
            domain.wrap(*q + step)
        };
    }

    /// The rule's sums over the birds other than the one in `slot` within sight of it (`sight`
    /// and `apart` the squared visual distance and separation), summed cell by cell around it
    /// (below, its own, above along each axis, axis 0 fastest) and within a cell in ascending
    /// original index: an order of space, not of storage. Only on the torus.
    ///
    /// The offset to a bird of a cell around is its unwrapped position less the bird's, shifted by
    /// the period the cell is across the box's edge, when the grid has at least 3 cells along
    /// every axis (each cell around then is one image; the offset is the minimum image to
    /// round-off); the minimum image otherwise.
    pub(super) fn sums_in_sight(
        &self,
        domain: &Domain<V>,
        slot: usize,
        (sight, apart): (f64, f64),
    ) -> Sums<V> {
        let Some(grid) = &self.grid else {
            unreachable!("the grid's search is the torus's")
        };
        // where the bird is at its activation (it has not moved yet this step: the cell it is
        // stored in)
        let q = if grid.shifted {
            self.slots[slot].q
        } else {
            domain.wrap(self.slots[slot].q)
        };
        let c = coords(grid.size, grid.cells, q).unwrap_or([0; 3]);
        let mut sums = Sums::ZERO;
        grid.around(c, |slots, shift| {
            // the run without the bird itself: the slots before it and after it
            let (before, after) = if slots.contains(&slot) {
                (slots.start..slot, slot + 1..slots.end)
            } else {
                (slots, 0..0)
            };
            for others in [before, after] {
                let others = &self.slots[others];
                if grid.shifted {
                    sums.add_all(others, q - shift, sight, apart);
                } else {
                    for other in others {
                        let offset = domain.displacement(q, other.q);
                        sums.add_in_sight(offset, other.v, sight, apart);
                    }
                }
            }
        });
        sums
    }
}

impl<V: Vector> Sums<V> {
    /// Counts the birds `others` within sight of a bird at `origin` (their unwrapped positions less
    /// `origin`, the bird's less its cell's shift), as [`Sums::add_in_sight`] counts each in turn,
    /// bit for bit, without branching: a bird out of sight adds −0 (x + (−0) = x for every x,
    /// signed zeros included) and takes +0 from the separation (x − (+0) = x).
    #[inline]
    pub(super) fn add_all(&mut self, others: &[Bird<V>], origin: V, sight: f64, apart: f64) {
        let out_of_sight = V::from_fn(|_| -0.0);
        let select = |keep: bool, x: V, otherwise: V| {
            V::from_fn(|axis| {
                if keep {
                    x.coord(axis)
                } else {
                    otherwise.coord(axis)
                }
            })
        };
        for other in others {
            let offset = other.q - origin;
            let d2 = offset.length_squared();
            // as `add_in_sight`: a NaN distance is counted
            let seen = d2 <= sight || d2.is_nan();
            let near = seen & (d2 < apart);
            self.count += u32::from(seen);
            self.cohere += select(seen, offset, out_of_sight);
            self.separate -= select(near, offset, V::ZERO);
            self.matching += select(seen, other.v, out_of_sight);
        }
    }
}

impl<V: Vector> Grid<V> {
    /// Visits the slots of the cells around the cell at `c` (itself included), each cell once,
    /// below, its own, above along each axis, axis 0 fastest, with the shift of the period that
    /// brings them next to `c` across the box's edge (zero along an axis of fewer than 3 cells):
    /// the three cells along axis 0 as one run of slots where none is across the edge.
    #[inline(always)]
    fn around(&self, c: [usize; 3], mut visit: impl FnMut(Range<usize>, V)) {
        let along = |axis: usize| -> ([(usize, f64); 3], usize) {
            let (m, c) = (self.cells[axis], c[axis]);
            let side = if axis < V::DIM {
                self.size.coord(axis)
            } else {
                0.0
            };
            match m {
                1 => ([(0, 0.0); 3], 1),
                2 => ([(0, 0.0), (1, 0.0), (0, 0.0)], 2),
                _ => {
                    let below = if c == 0 { (m - 1, -side) } else { (c - 1, 0.0) };
                    let above = if c + 1 == m { (0, side) } else { (c + 1, 0.0) };
                    ([below, (c, 0.0), above], 3)
                }
            }
        };
        // along axis 0: (first cell, cells, shift) of each run
        let (mx, cx) = (self.cells[0], c[0]);
        let x = if mx >= 3 && (1..mx - 1).contains(&cx) {
            // the three cells are neighbours in memory, none across the edge
            ([(cx - 1, 3, 0.0); 3], 1)
        } else {
            let (cells, count) = along(0);
            (cells.map(|(cell, shift)| (cell, 1, shift)), count)
        };
        let (y, z) = (along(1), along(2));
        for &(cz, sz) in &z.0[..z.1] {
            for &(cy, sy) in &y.0[..y.1] {
                let row = index(self.cells, [0, cy, cz]);
                for &(first, cells, sx) in &x.0[..x.1] {
                    let slots = self.starts[row + first] as usize
                        ..self.starts[row + first + cells] as usize;
                    visit(slots, V::from_fn(|axis| [sx, sy, sz][axis]));
                }
            }
        }
    }
}

/// Cells along each axis of a box of sides `size`: as many as fit with each at least `reach`
/// across (at least one), halved along the most divided axis while there are more than
/// [`CELLS_PER_BIRD`] per bird of `n`. Padded against rounding: a cell is a hair wider than
/// `reach`.
fn cells_per_axis<V: Vector>(size: V, reach: f64, n: usize) -> [usize; 3] {
    let padded = reach * (1.0 + 1e-9);
    let mut cells = [1; 3];
    for (axis, m) in cells.iter_mut().enumerate().take(V::DIM) {
        let fit = (size.coord(axis) / padded).floor();
        *m = if fit >= 1.0 { fit.min(1e6) as usize } else { 1 };
    }
    let most = CELLS_PER_BIRD * n + 64;
    while cells.iter().product::<usize>() > most {
        let widest = (0..3).max_by_key(|&a| cells[a]).unwrap_or(0);
        cells[widest] = cells[widest].div_ceil(2);
    }
    cells
}

/// The cell of a point at `q` on the torus of sides `size` (`None` for a non-finite point).
fn coords<V: Vector>(size: V, cells: [usize; 3], q: V) -> Option<[usize; 3]> {
    if !q.is_finite() {
        return None;
    }
    let mut c = [0; 3];
    for axis in 0..V::DIM {
        let m = cells[axis] as f64;
        let x = q.coord(axis) / size.coord(axis) * m;
        c[axis] = if (0.0..m).contains(&x) {
            // in the box: the floor is the truncation, the remainder the identity
            x as usize
        } else {
            // x in [0, m] (m only by rounding of a point a hair below a whole period)
            (x.floor().rem_euclid(m) as usize).min(cells[axis] - 1)
        };
    }
    Some(c)
}

/// The number of the cell at `c`, axis 0 fastest.
fn index(cells: [usize; 3], c: [usize; 3]) -> usize {
    c[0] + cells[0] * (c[1] + cells[1] * c[2])
}

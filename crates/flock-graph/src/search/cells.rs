//! The agents of a grid, open or periodic, sorted by cell: [`CellSort`] (a counting sort, each
//! agent's *slot* in cell order, its coordinates copied in that order), the walk of ascending
//! slots through their cells ([`SlotCells`]), and what both grids share: the cell numbering
//! ([`cell_coords`]), the cell side padded against rounding ([`padded_side`]) and the cap on cells.

use flock_math::Vector;

use crate::net::node_index;
use crate::numbering::Numbering;
use flock_math::parallel::fill_indexed;

/// Cells allowed per agent: a grid has at most `CELLS_PER_AGENT · n` cells.
pub(crate) const CELLS_PER_AGENT: usize = 4;

/// Slot (and cell) of an agent with a non-finite coordinate: it is in no cell. Slots are below
/// n ≤ `u32::MAX` and cells below [`MAX_CELLS`].
pub(crate) const NO_SLOT: u32 = u32::MAX;

/// Most cells of a grid, so that a cell index fits a `u32` other than [`NO_SLOT`].
pub(crate) const MAX_CELLS: usize = u32::MAX as usize - 1;

/// The fewest agents numbered in their own order whose lists [`CellSort::scattered`] may build
/// without branching: below, 2 m^(2/3) or m/8 slots is too large a share of the m slots to tell
/// agents numbered at random from a lattice by 256 samples. Measured on one thread (2026-11-28),
/// agents numbered at random in a periodic box, medians of 100 steps without branching against
/// with: the Vicsek workload 30 % faster at 400 agents, 28–30 % at 2,000, 5,000 and 10⁴; the
/// boids-large one (400 birds) 15 % faster.
const SCATTERED_MIN: usize = 256;

/// Slots per task of the pair counts
/// ([`NeighbourSearch::count_pairs_in`](crate::NeighbourSearch::count_pairs_in)).
pub(crate) const PAIR_CHUNK: usize = 4096;

/// The agents of a grid (open or periodic) sorted by cell, by a counting sort with the agents of
/// a cell in ascending index; position `s` in that order is a *slot*. Slots are below
/// n ≤ `u32::MAX`, so a cell's start is 4 bytes.
#[derive(Clone, Debug, Default)]
pub(crate) struct CellSort {
    /// The slots of cell c are `starts[c]..starts[c + 1]`.
    pub(crate) starts: Vec<u32>,
    /// Agent in each slot.
    pub(crate) order: Vec<u32>,
    /// Coordinates of the agent in each slot, m per slot (m = `V::DIM` of the last sort), for a
    /// contiguous candidate scan.
    pub(crate) coords: Vec<f64>,
    /// Slot of each agent, [`NO_SLOT`] for non-finite ones (its cell while sorting).
    pub(crate) slot_of: Vec<u32>,
}

impl CellSort {
    /// Sorts the agents of `positions` into `cells` cells, `cell_of(q)` the cell of an agent at q
    /// ([`NO_SLOT`] for none).
    pub(crate) fn sort<V: Vector>(
        &mut self,
        cells: usize,
        positions: &[V],
        cell_of: impl Fn(V) -> u32 + Sync,
    ) {
        let Self {
            starts,
            order,
            coords,
            slot_of,
        } = self;
        slot_of.resize(positions.len(), 0);
        fill_indexed(slot_of, |i| cell_of(positions[i]));
        // count into starts[c + 1], prefix-sum into starts, scatter with starts[c] as cursor
        // (leaving it at the start of c + 1), then shift back
        starts.clear();
        starts.resize(cells + 1, 0);
        for &c in slot_of.iter().filter(|&&c| c != NO_SLOT) {
            starts[c as usize + 1] += 1;
        }
        for c in 0..cells {
            starts[c + 1] += starts[c];
        }
        let placed = starts[cells] as usize;
        order.resize(placed, 0);
        coords.resize(placed * V::DIM, 0.0);
        for (i, (slot_of, q)) in slot_of.iter_mut().zip(positions).enumerate() {
            let c = *slot_of;
            if c != NO_SLOT {
                let slot = starts[c as usize] as usize;
                starts[c as usize] += 1;
                order[slot] = node_index(i);
                for (k, x) in coords[slot * V::DIM..(slot + 1) * V::DIM]
                    .iter_mut()
                    .enumerate()
                {
                    *x = q.coord(k);
                }
                *slot_of = node_index(slot);
            }
        }
        starts.copy_within(0..cells, 1);
        starts[0] = 0;
    }

    /// Whether the lists of agents sorted by cell under `numbering` are built without branching
    /// ([`Block::fill`](crate::search::lists::Block::fill)): for agents stored by cell under a
    /// numbering, and for agents in their own order numbered at random (a simulation sorts them
    /// by cell only when their neighbours are far in memory). The latter is told by 256 pairs of
    /// agents i and i + 1, spread evenly: most are at least min(2 m^(2/3), m/8) slots apart (m
    /// the slots; each pair of agents numbered at random with probability (7/8)² or more), where
    /// agents i and i + 1 of a lattice stored row by row are in the same cell or the next.
    /// Whether a candidate is in range, and where it ranks, is then unpredictable to the
    /// processor, and branching on it costs more than it saves; not below [`SCATTERED_MIN`]
    /// agents. Either way the lists are the same.
    pub(crate) fn scattered(&self, numbering: &Numbering) -> bool {
        const SAMPLED: usize = 256;
        let slots = self.slots();
        if !numbering.is_identity() {
            return true;
        }
        if slots < SCATTERED_MIN {
            return false;
        }
        let apart = (2.0 * (slots as f64).powf(2.0 / 3.0)).min(slots as f64 / 8.0);
        // the slots of agents i and i + 1 (both with one)
        let n = self.slot_of.len();
        let gaps = (0..SAMPLED).filter_map(|k| {
            let i = k * (n - 1) / SAMPLED;
            let (a, b) = (self.slot_of[i], self.slot_of[i + 1]);
            (a != NO_SLOT && b != NO_SLOT).then(|| a.abs_diff(b))
        });
        let (far, sampled) = gaps.fold((0, 0), |(far, sampled), gap| {
            (far + usize::from(f64::from(gap) >= apart), sampled + 1)
        });
        2 * far > sampled
    }

    /// The number of slots: the finite agents sorted.
    #[inline]
    pub(crate) fn slots(&self) -> usize {
        self.order.len()
    }

    /// The first slot of `cell`; for `cell` = the number of cells, the number of slots.
    #[inline]
    pub(crate) fn start(&self, cell: usize) -> usize {
        self.starts[cell] as usize
    }

    /// The cell holding `slot`: the last one starting at or before it.
    fn cell_of_slot(&self, slot: usize) -> usize {
        self.starts.partition_point(|&s| s as usize <= slot) - 1
    }

    /// The cells of ascending slots from `slot` on, in a grid of `dims` cells per axis (x
    /// fastest, [`cell_coords`]): one search for the first, then a walk.
    pub(crate) fn cells_from(&self, slot: usize, dims: [usize; 3]) -> SlotCells<'_> {
        let cell = self.cell_of_slot(slot);
        SlotCells {
            sorted: self,
            dims,
            cell,
            coords: cell_coords(cell, dims),
        }
    }

    /// The position of the agent in `slot`, bit-identical to its entry of the positions sorted.
    #[inline]
    pub(crate) fn position<V: Vector>(&self, slot: usize) -> V {
        let c = &self.coords[slot * V::DIM..(slot + 1) * V::DIM];
        V::from_fn(|k| c[k])
    }

    /// Σ over the cells c of n_c · `candidates(c)`, the agents of c times those of c's candidate
    /// cells: the ordered pairs (self pairs included) a scan of the grid tests, at least twice
    /// the tests of [`NeighbourSearch::count_pairs_in`](crate::NeighbourSearch::count_pairs_in).
    /// Saturates.
    pub(crate) fn candidate_tests(&self, candidates: impl Fn(usize) -> usize) -> usize {
        self.starts
            .windows(2)
            .enumerate()
            .filter(|(_, w)| w[1] > w[0])
            .fold(0_usize, |tests, (cell, w)| {
                tests.saturating_add(((w[1] - w[0]) as usize).saturating_mul(candidates(cell)))
            })
    }
}

/// The cell of each slot, for slots visited in ascending order ([`CellSort::cells_from`]).
pub(crate) struct SlotCells<'a> {
    sorted: &'a CellSort,
    dims: [usize; 3],
    cell: usize,
    /// The coordinates of `cell`.
    coords: [usize; 3],
}

impl SlotCells<'_> {
    /// The cell of `slot`; `slot` must not decrease between calls.
    #[inline]
    pub(crate) fn cell_of(&mut self, slot: usize) -> usize {
        while self.sorted.start(self.cell + 1) <= slot {
            self.cell += 1;
            // the next cell in x-fastest order
            self.coords[0] += 1;
            if self.coords[0] == self.dims[0] {
                self.coords[0] = 0;
                self.coords[1] += 1;
                if self.coords[1] == self.dims[1] {
                    self.coords[1] = 0;
                    self.coords[2] += 1;
                }
            }
        }
        self.cell
    }

    /// The coordinates of the cell last returned by [`SlotCells::cell_of`].
    #[inline]
    pub(crate) fn coords(&self) -> [usize; 3] {
        self.coords
    }
}

/// The coordinates of the cell of linear index `cell` in a grid of `dims` cells per axis, x fastest:
/// the one numbering of the open and the periodic grids.
#[inline]
pub(crate) fn cell_coords(cell: usize, [dx, dy, _]: [usize; 3]) -> [usize; 3] {
    [cell % dx, (cell / dx) % dy, cell / (dx * dy)]
}

/// The cell side for a given reach: the reach padded against rounding.
///
/// If the predicate accepts a pair, `fl(‖fl(q_j − q_i)‖²) < reach²`, then each true coordinate
/// difference is below `reach · (1 + 2ε)` (plus a few subnormals' worth, ≤ 1e-161, when reach² is
/// subnormal). The computed cell coordinates `⌊fl(fl(x − origin) / side)⌋` are off by at most
/// `1.5 ε · extent / side` each, extent ≤ 2 · max_abs. Two agents land in adjacent cells when the
/// difference of their computed cell coordinates is at most 1, which holds with
/// `side ≥ reach · (1 + 2ε) + 6 ε · max_abs`; the padding below has a wide margin.
#[inline]
#[must_use]
pub(crate) fn padded_side(reach: f64, max_abs: f64) -> f64 {
    const PAD: f64 = 64.0 * f64::EPSILON;
    reach * (1.0 + PAD) + PAD * max_abs + f64::MIN_POSITIVE.sqrt()
}

//! Fixed-radius neighbour search on a uniform cell grid: [`NeighbourSearch`] rebuilds a
//! [`ProximityNet`] every step in expected O(n), and [`nearest_pair_distance`] finds the closest
//! pair of agents.
//!
//! The agents are bucketed by a counting sort into cubic cells of side at least the range r, so
//! every neighbour of an agent lies in its own cell or one of the 3^m − 1 adjacent ones. The cell
//! side is padded by a few ulps of the range and of the largest coordinate, so rounding at cell
//! boundaries cannot hide a pair that the predicate accepts, even far from the origin. When the
//! agents are spread thin the cell is enlarged until there are at most 4n cells: memory stays O(n)
//! whatever the configuration.
//!
//! The lists are built agent by agent in cell order (so that consecutive agents scan the same
//! memory), each as agents sorted by neighbour index (original index, for a net with a
//! [`Numbering`]), into per-block buffers; they are then gathered in agent order
//! into the net as agent indices, each distance recomputed there with the predicate's own squared
//! length. The net is canonical: equal to [`ProximityNet::brute_force`] edge for edge and bit for
//! bit (for a numbering, to the brute-force net of the agents in original order, relabelled). With
//! the `parallel` feature the blocks are filled, and the net gathered, on the rayon pool; since the
//! blocks and gather ranges only partition the work, the net is identical with or without it, for
//! any pool size. [`NeighbourSearch::cell_order`] gives the cell order itself, for callers that
//! store their agents in it.
//!
//! In open space the lists are built out to a skin beyond r and kept: while no agent has moved
//! more than half the skin since, the next builds filter them by the predicate instead of
//! scanning the grid again (Verlet lists; the module `skin` says when, and why the net is the
//! same bit for bit).

use core::ops::Range;

use flock_math::{Domain, Vector};

use crate::net::{
    ProximityNet, in_range, node_index, range_squared, squared_distance, squared_distance_in,
};
use crate::numbering::Numbering;
use crate::parallel::{fill_indexed, for_each_indexed_mut, join, map_chunks};
use crate::skin::Skin;
use crate::torus::TorusGrid;

/// log₂ of the agents per block of work (any value gives the same net): 1,024 agents, a unit of
/// rayon work with the `parallel` feature.
const BLOCK_SHIFT: u32 = 10;

/// Agents per chunk of the parallel displacement check ([`CellGrid::moved_within`]).
const MOVED_CHUNK: usize = 1 << 14;

/// Agents per chunk of the parallel bounds.
const BOUNDS_CHUNK: usize = 1 << 16;

/// Cells allowed per agent: the grid has at most `CELLS_PER_AGENT · n` cells.
const CELLS_PER_AGENT: usize = 4;

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

/// Reusable fixed-radius neighbour search. Its buffers (and those of the nets it fills) are kept
/// between calls, so a warm search allocates nothing while the number of agents does not grow.
///
/// # Example
/// ```
/// use flock_graph::{NeighbourSearch, ProximityNet};
/// use glam::DVec3;
///
/// let q: Vec<DVec3> = (0..10).map(|k| DVec3::new(k as f64, 0.0, 0.0)).collect();
/// let mut search = NeighbourSearch::new();
/// let mut net = ProximityNet::new();
/// search.build(&q, 1.5, &mut net);
/// assert_eq!(net.graph().neighbours(4), &[3, 5]);
/// assert_eq!(net, ProximityNet::brute_force(&q, 1.5));
/// ```
#[derive(Clone, Debug, Default)]
pub struct NeighbourSearch {
    grid: CellGrid,
    /// Neighbour lists of blocks of 2^[`BLOCK_SHIFT`] slots (agents in cell order).
    blocks: Vec<Block>,
    /// The grid of a periodic box ([`NeighbourSearch::build_in`]).
    pub(crate) torus: TorusGrid,
    /// Neighbour lists of blocks of slots of the periodic grid.
    pub(crate) torus_blocks: Vec<Block>,
    /// Whether `grid` and `blocks` hold lists the next open-space build may reuse.
    pub(crate) skin: Skin,
}

impl NeighbourSearch {
    /// A search with empty buffers.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Rebuilds `net`, reusing its allocations, as the proximity net of `positions` with range `r`:
    /// N_i = { j ≠ i : ‖q_j − q_i‖ < r }.
    ///
    /// The result is identical to [`ProximityNet::brute_force`]`(positions, r)`: same neighbour
    /// order (ascending), bit-identical distances. A net with a [`Numbering`]
    /// keeps it, and lists each agent's neighbours in ascending original index. A range that is not positive (or NaN) gives no
    /// edges; an infinite range joins every pair of finite agents. Agents with a NaN or infinite
    /// coordinate have no neighbours (and do not panic). A net made by
    /// [`ProximityNet::without_distances`] gets the same graph and no distances.
    ///
    /// The search keeps the lists of its last full build, out to 1.1 r, and serves the next
    /// builds of the same number of agents, range and numbering from them while no agent has
    /// moved more than 0.05 r since (a simulation's agents, step after step): the same net, in
    /// about 0.6 of the time of a full build (10⁶ agents on a lattice).
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    pub fn build<V: Vector>(&mut self, positions: &[V], r: f64, net: &mut ProximityNet) {
        self.build_in_blocks(positions, r, net, BLOCK_SHIFT);
    }

    /// [`NeighbourSearch::build`] with blocks of 2^`block_shift` slots (`block_shift` < 64).
    ///
    /// The lists of the last build are kept, built out to the range plus a skin ([`Skin`]), and
    /// serve the next builds while no agent has moved more than half the skin: the net is then
    /// those lists filtered by the predicate. Same net either way.
    fn build_in_blocks<V: Vector>(
        &mut self,
        positions: &[V],
        r: f64,
        net: &mut ProximityNet,
        block_shift: u32,
    ) {
        let block_len = 1_usize << block_shift;
        let n = positions.len();
        let r2 = range_squared(r);
        // Every array is resized and overwritten below: the retained part is not zeroed first.
        let (offsets, neighbours, distances, numbering) = net.arrays_for_rebuild(n, r);
        if n < 2 || r2 == 0.0 {
            self.skin.forget();
            assemble(n, offsets, neighbours, distances, &|_| 0, &|_, _, _| {});
            return;
        }
        let stamp = numbering.stamp();
        let kept = self.skin.kept_for(n, r, stamp, block_shift);
        if kept.is_some_and(|kept| self.grid.moved_within(positions, kept.limit)) {
            self.skin.reused();
        } else {
            if kept.is_some() {
                self.skin.outgrown();
            }
            let reach = self.skin.reach_for_build(r);
            self.grid.rebuild(positions, reach);
            let (grid, reach2) = (&self.grid, range_squared(reach));
            let scattered = grid.sorted.scattered(numbering);
            Block::fill_all(
                &mut self.blocks,
                grid.sorted.slots(),
                block_len,
                |block, slots| {
                    block.fill::<V>(grid, reach2, numbering, scattered, slots);
                },
            );
            self.skin.built(n, r, reach, stamp, block_shift);
        }
        let grid = &self.grid;
        let blocks = &self.blocks[..grid.sorted.slots().div_ceil(block_len)];
        // agent i's list: agents, in the net's order
        let list = |i| {
            listed(&grid.sorted.slot_of, i, block_shift, |b, k| {
                blocks[b].list(k)
            })
        };
        // the distances recomputed with the predicate's own squared length (so bit-identical)
        if self.skin.has_kept() {
            // the lists reach beyond r, and the grid holds the positions of their build: the
            // agents in range now, from the positions now
            let near = |i: usize| {
                let qi = positions[i];
                list(i).iter().filter_map(move |&j| {
                    let d2 = squared_distance(qi, positions[j as usize]);
                    in_range(d2, r2).then_some((j, d2))
                })
            };
            let write = |i: usize, out: &mut [u32], lengths: &mut [f64]| {
                for (k, (j, d2)) in near(i).enumerate() {
                    out[k] = j;
                    if let Some(l) = lengths.get_mut(k) {
                        *l = d2.sqrt();
                    }
                }
            };
            assemble(
                n,
                offsets,
                neighbours,
                distances,
                &|i| near(i).count(),
                &write,
            );
        } else {
            assemble_lists(
                &Domain::Open,
                positions,
                offsets,
                neighbours,
                distances,
                &list,
            );
        }
    }

    /// The agents with a finite position, in the order of the cells of side at least `r` of a
    /// grid over them (ascending index within a cell): agents near in that order are near in
    /// space. The order [`NeighbourSearch::build`] visits them in; its buffer is reused.
    pub fn cell_order<V: Vector>(&mut self, positions: &[V], r: f64) -> &[u32] {
        &self.regrid(positions, r).sorted.order
    }

    /// The exact minimum distance over all pairs of finite agents, `None` when there are fewer
    /// than two: [`nearest_pair_distance`] reusing this search's buffers.
    #[must_use]
    pub fn nearest_pair_distance<V: Vector>(&mut self, positions: &[V]) -> Option<f64> {
        // An upper bound on the minimum: the closest of the pairs of consecutive finite agents.
        let mut finite = positions.iter().copied().filter(|q| q.is_finite());
        let mut previous = finite.next()?;
        let mut upper: Option<f64> = None;
        for q in finite {
            let d2 = squared_distance(previous, q);
            upper = Some(upper.map_or(d2, |u| u.min(d2)));
            previous = q;
        }
        let upper = upper?;
        if upper == 0.0 {
            return Some(0.0);
        }
        // Grow the search radius from the mean spacing until a pair is found; the pass with the
        // threshold `upper` finds every pair closer than the bound, so the answer is exact.
        let bounds = Bounds::of(positions);
        let mut threshold = bounds.mean_spacing().powi(2).min(upper);
        if threshold.is_nan() || threshold <= 0.0 {
            threshold = upper;
        }
        loop {
            let grid = self.regrid(positions, threshold.sqrt());
            if let Some(d2) = grid.min_squared_distance::<V>(threshold) {
                return Some(d2.sqrt());
            }
            if threshold >= upper {
                return Some(upper.sqrt());
            }
            threshold = (4.0 * threshold).min(upper);
        }
    }
}

/// Slots per task of the pair counts ([`NeighbourSearch::count_pairs_in`]).
pub(crate) const PAIR_CHUNK: usize = 4096;

/// The agents of a grid (open or periodic) sorted by cell, by a counting sort with the agents of
/// a cell in ascending index; position `s` in that order is a *slot*. Slots are below
/// n ≤ `u32::MAX`, so a cell's start is 4 bytes.
#[derive(Clone, Debug, Default)]
pub(crate) struct CellSort {
    /// The slots of cell c are `starts[c]..starts[c + 1]`.
    starts: Vec<u32>,
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
    /// ([`Block::fill`]): for agents stored by cell under a numbering, and for agents in their own
    /// order numbered at random (a simulation sorts them by cell only when their neighbours are
    /// far in memory). The latter is told by 256 pairs of agents i and i + 1, spread evenly: most
    /// are at least min(2 m^(2/3), m/8) slots apart (m the slots; each pair of agents numbered
    /// at random with probability (7/8)² or more), where agents i and i + 1 of a lattice stored
    /// row by row are in the same cell or the next. Whether a candidate is in range, and where it
    /// ranks, is then unpredictable to the processor, and branching on it costs more than it
    /// saves; not below [`SCATTERED_MIN`] agents. Either way the lists are the same.
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
    /// the tests of [`NeighbourSearch::count_pairs_in`]. Saturates.
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

impl NeighbourSearch {
    /// The grid rebuilt for `positions` and `reach` for a use other than a net: the lists it
    /// held are no longer reusable.
    fn regrid<V: Vector>(&mut self, positions: &[V], reach: f64) -> &CellGrid {
        self.skin.forget();
        self.grid.rebuild(positions, reach);
        &self.grid
    }

    /// [`NeighbourSearch::count_pairs_in`] in open space.
    pub(crate) fn count_open_pairs<V: Vector>(
        &mut self,
        positions: &[V],
        r: f64,
        most_tests: usize,
        accept: &(impl Fn(usize, usize) -> bool + Sync),
    ) -> Option<usize> {
        let r2 = range_squared(r);
        if positions.len() < 2 || r2 == 0.0 {
            return Some(0);
        }
        let grid = self.regrid(positions, r);
        let tests = grid.sorted.candidate_tests(|cell| {
            let c = grid.layout.coords(cell);
            grid.candidate_rows(c).iter().map(|row| row.len()).sum()
        });
        if tests > most_tests {
            return None;
        }
        let counts = map_chunks(grid.sorted.slots(), PAIR_CHUNK, |slots| {
            let mut cells = grid.cells_of(slots.start);
            let mut count = 0;
            for slot in slots {
                cells.cell_of(slot);
                let (i, qi) = (
                    grid.sorted.order[slot] as usize,
                    grid.sorted.position::<V>(slot),
                );
                for row in grid.candidate_rows(cells.coords()).iter() {
                    // each pair of slots once, from the lower one
                    for t in row.start.max(slot + 1)..row.end {
                        let j = grid.sorted.order[t] as usize;
                        let d2 = squared_distance(qi, grid.sorted.position::<V>(t));
                        if in_range(d2, r2) && accept(i.min(j), i.max(j)) {
                            count += 1;
                        }
                    }
                }
            }
            count
        });
        Some(counts.iter().sum())
    }

    /// For each agent `pending[p]`, the least squared distance below `threshold` to another finite
    /// agent, +∞ when there is none, in `found[p]`; the grid is rebuilt with `reach`, and
    /// `threshold` must not exceed `reach²`.
    pub(crate) fn open_nearest<V: Vector>(
        &mut self,
        positions: &[V],
        reach: f64,
        threshold: f64,
        pending: &[u32],
        found: &mut [f64],
    ) {
        let grid = self.regrid(positions, reach);
        fill_indexed(found, |p| {
            let slot = grid.sorted.slot_of[pending[p] as usize] as usize;
            let mut cells = grid.cells_of(slot);
            cells.cell_of(slot);
            let qi = grid.sorted.position::<V>(slot);
            let mut best = f64::INFINITY;
            for row in grid.candidate_rows(cells.coords()).iter() {
                for t in row {
                    let d2 = squared_distance(qi, grid.sorted.position::<V>(t));
                    if t != slot && in_range(d2, threshold) && d2 < best {
                        best = d2;
                    }
                }
            }
            best
        });
    }
}

/// Writes the arrays of a net of `n` agents: the offsets first, as the running sum of each
/// agent's number of neighbours `len(i)`, then, in parallel ranges of agents, `write(i,
/// neighbours_i, distances_i)` (`distances_i` empty for a net without distances). The one assembly
/// of the open and the periodic search.
pub(crate) fn assemble(
    n: usize,
    offsets: &mut Vec<usize>,
    neighbours: &mut Vec<u32>,
    distances: Option<&mut Vec<f64>>,
    len: &(impl Fn(usize) -> usize + Sync),
    write: &(impl Fn(usize, &mut [u32], &mut [f64]) + Sync),
) {
    // offsets[i + 1] = |N_i| (in parallel), then the running sum
    offsets.resize(n + 1, 0);
    offsets[0] = 0;
    fill_indexed(&mut offsets[1..], len);
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let edges = offsets[n];
    neighbours.resize(edges, 0);
    let mut no_distances = Vec::new();
    let distances = match distances {
        Some(distances) => {
            distances.resize(edges, 0.0);
            distances
        }
        // a net without distances: the gather fills empty length slices
        None => &mut no_distances,
    };
    let offsets = &offsets[..];
    gather(
        0..n,
        neighbours,
        distances,
        &|i, out, lengths| {
            debug_assert_eq!(out.len(), offsets[i + 1] - offsets[i]);
            write(i, out, lengths);
        },
        offsets,
    );
}

/// [`assemble`] from lists that hold exactly each agent's neighbours (`list(i)`, in the net's
/// order), each distance recomputed from `positions` in `domain` with the predicate's own squared
/// length (so bit-identical).
pub(crate) fn assemble_lists<'a, V: Vector>(
    domain: &Domain<V>,
    positions: &[V],
    offsets: &mut Vec<usize>,
    neighbours: &mut Vec<u32>,
    distances: Option<&mut Vec<f64>>,
    list: &(impl Fn(usize) -> &'a [u32] + Sync),
) {
    let write = |i: usize, out: &mut [u32], lengths: &mut [f64]| {
        let list = list(i);
        out.copy_from_slice(list);
        let qi = positions[i];
        for (l, &j) in lengths.iter_mut().zip(list) {
            *l = squared_distance_in(domain, qi, positions[j as usize]).sqrt();
        }
    };
    let n = positions.len();
    assemble(
        n,
        offsets,
        neighbours,
        distances,
        &|i| list(i).len(),
        &write,
    );
}

/// Agents per task of the parallel gather.
const GATHER_LEN: usize = 4096;

/// Calls `f(i, neighbours_i, distances_i)` for every agent of `agents`, where the slices are agent
/// i's ranges (given by `offsets`) of `neighbours` and `distances`, which start at agent
/// `agents.start` (`distances` may be empty: then every `distances_i` is); halves the range on the
/// rayon pool down to [`GATHER_LEN`] agents.
pub(crate) fn gather(
    agents: Range<usize>,
    neighbours: &mut [u32],
    distances: &mut [f64],
    f: &(impl Fn(usize, &mut [u32], &mut [f64]) + Sync),
    offsets: &[usize],
) {
    if agents.len() > GATHER_LEN {
        let mid = agents.start + agents.len() / 2;
        let split = offsets[mid] - offsets[agents.start];
        let (n_lo, n_hi) = neighbours.split_at_mut(split);
        // empty `distances` (a net without them) stay empty
        let (d_lo, d_hi) = distances.split_at_mut(split.min(distances.len()));
        join(
            || gather(agents.start..mid, n_lo, d_lo, f, offsets),
            || gather(mid..agents.end, n_hi, d_hi, f, offsets),
        );
        return;
    }
    let base = offsets[agents.start];
    for i in agents {
        let edges = offsets[i] - base..offsets[i + 1] - base;
        f(
            i,
            &mut neighbours[edges.clone()],
            distances.get_mut(edges).unwrap_or_default(),
        );
    }
}

/// The exact minimum distance min_{i≠j} ‖q_j − q_i‖ over all pairs of finite agents (agents with
/// a NaN or infinite coordinate are ignored), `None` when there are fewer than two.
///
/// Grid search with a growing radius: expected O(n) for agents spread with a bounded density
/// (degenerate clusters may cost more, never a wrong answer). The value is bit-identical to the
/// minimum of `(q_j − q_i).length()` over all pairs. Used for the minimum-distance metric when the
/// proximity net has no edges.
///
/// # Example
/// ```
/// use flock_graph::nearest_pair_distance;
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(10.0, 0.0), DVec2::new(10.0, 3.0)];
/// assert_eq!(nearest_pair_distance(&q), Some(3.0));
/// assert_eq!(nearest_pair_distance(&q[..1]), None);
/// ```
#[must_use]
pub fn nearest_pair_distance<V: Vector>(positions: &[V]) -> Option<f64> {
    NeighbourSearch::new().nearest_pair_distance(positions)
}

/// The neighbour lists of a block of consecutive slots of the open or the periodic grid, as
/// agents in ascending original index.
#[derive(Clone, Debug, Default)]
pub(crate) struct Block {
    /// End of each slot's list in `neighbours` (a block's lists hold fewer than 2³² agents: more
    /// would need 16 GiB for the block alone, and as much for each block of its neighbours).
    pub(crate) ends: Vec<u32>,
    /// The lists, one after the other (followed by unused space in the open grid's blocks).
    pub(crate) neighbours: Vec<u32>,
    /// Scratch: one slot's neighbours keyed by agent, to be sorted.
    pub(crate) keyed: Vec<u64>,
}

impl Block {
    /// Refills the block with the lists (predicate `d² < r2`) of the agents in `slots`, each in
    /// ascending original index of `numbering`, `scattered` as [`CellSort::scattered`] says.
    fn fill<V: Vector>(
        &mut self,
        grid: &CellGrid,
        r2: f64,
        numbering: &Numbering,
        scattered: bool,
        slots: Range<usize>,
    ) {
        if scattered {
            let original = |j| numbering.original(j as usize) as u32;
            self.fill_keyed::<V, true>(grid, r2, slots, original);
        } else {
            self.fill_keyed::<V, false>(grid, r2, slots, |j| j);
        }
    }

    /// [`Block::fill`] with the original index `original(j)` of each agent j. `SCATTERED` says
    /// whether the original indices of agents near in space are unrelated ([`CellSort::scattered`]:
    /// agents stored by cell under a numbering, or in their own order but numbered at random):
    /// then whether a candidate is in range, and where it falls in its list,
    /// are unpredictable to the processor, and the lists are built without branching on either
    /// (measured: 2D, 10⁶ agents at random, 220 → 172 ms per plain step on one thread). Agents
    /// stored in original order numbered along space follow the scan, whose branches the processor
    /// predicts: branching is faster there (104–107 ms against 116–117).
    #[inline]
    fn fill_keyed<V: Vector, const SCATTERED: bool>(
        &mut self,
        grid: &CellGrid,
        r2: f64,
        slots: Range<usize>,
        original: impl Fn(u32) -> u32,
    ) {
        self.ends.clear();
        let mut end = 0;
        // consecutive slots share their cell, and so its candidate rows
        let mut cells = grid.cells_of(slots.start);
        let (mut rows_of, mut rows) = (usize::MAX, CandidateRows::default());
        let mut candidates = 0;
        for slot in slots {
            let cell = cells.cell_of(slot);
            if cell != rows_of {
                (rows_of, rows) = (cell, grid.candidate_rows(cells.coords()));
                candidates = rows.iter().map(|row| row.len()).sum();
            }
            let qi = grid.sorted.position::<V>(slot);
            // `neighbours` beyond `end` is only grown (and zeroed) when too short
            if self.neighbours.len() < end + candidates {
                // grow by a quarter at least: fewer reallocations than exact growth, less
                // unused memory than doubling
                let len = self.neighbours.len();
                let grown = (end + candidates).max(len + len / 4);
                self.neighbours.reserve_exact(grown - len);
                self.neighbours.resize(grown, 0);
            }
            // each neighbour as (original index << 32 | agent), so that a plain sort orders by
            // original index; scattered, every candidate is written and kept by advancing the
            // length
            self.keyed.resize(candidates, 0);
            // a local slice: its pointer and length stay in registers across the stores
            let keyed = &mut self.keyed[..];
            let mut len = 0;
            for row in rows.iter() {
                let coords = &grid.sorted.coords[row.start * V::DIM..row.end * V::DIM];
                for ((t, c), &j) in row
                    .clone()
                    .zip(coords.chunks_exact(V::DIM))
                    .zip(&grid.sorted.order[row])
                {
                    let d2 = squared_distance(qi, V::from_fn(|k| c[k]));
                    let keep = in_range(d2, r2) & (t != slot);
                    if SCATTERED || keep {
                        keyed[len] = u64::from(original(j)) << 32 | u64::from(j);
                        len += usize::from(keep);
                    }
                }
            }
            let (keyed, out) = (&mut self.keyed[..len], &mut self.neighbours[end..end + len]);
            order_agents::<SCATTERED>(keyed, out);
            end += len;
            self.push_end(end);
        }
    }

    /// The blocks of `slots` slots in runs of `block_len` (the last one shorter), in `blocks`
    /// (grown as needed: their buffers are kept between builds), each filled in parallel by
    /// `fill(block, its slots)`; the blocks in use.
    pub(crate) fn fill_all(
        blocks: &mut Vec<Self>,
        slots: usize,
        block_len: usize,
        fill: impl Fn(&mut Self, Range<usize>) + Sync,
    ) -> &[Self] {
        let count = slots.div_ceil(block_len);
        if blocks.len() < count {
            blocks.resize_with(count, Self::default);
        }
        for_each_indexed_mut(&mut blocks[..count], 1, |b, block| {
            let start = b * block_len;
            fill(block, start..(start + block_len).min(slots));
        });
        &blocks[..count]
    }

    /// Ends the current slot's list at `end`.
    #[inline]
    pub(crate) fn push_end(&mut self, end: usize) {
        let end = u32::try_from(end).expect("a block's lists hold fewer than 2³² agents");
        self.ends.push(end);
    }

    /// The `k`-th slot's list.
    #[inline]
    pub(crate) fn list(&self, k: usize) -> &[u32] {
        let start = if k == 0 { 0 } else { self.ends[k - 1] };
        &self.neighbours[start as usize..self.ends[k] as usize]
    }
}

/// Agent `i`'s list kept in blocks of 2^`block_shift` slots (`slot_of` the grid's slot of each
/// agent), `list(block, k)` the `k`-th list of a block: empty for an agent in no cell.
#[inline]
pub(crate) fn listed<'a>(
    slot_of: &[u32],
    i: usize,
    block_shift: u32,
    list: impl Fn(usize, usize) -> &'a [u32],
) -> &'a [u32] {
    match slot_of[i] {
        NO_SLOT => &[],
        slot => list(
            slot as usize >> block_shift,
            slot as usize & ((1 << block_shift) - 1),
        ),
    }
}

/// Writes the low halves of `keyed` (each `original index << 32 | agent`, all distinct)
/// into `out` in ascending key. A `SCATTERED` list of at most 16 places each key at its rank,
/// the number of smaller keys: no branch depends on the keys, whose order a sort would
/// mispredict. A list of [`RADIX_MIN`] or more (a dense crowd's) is sorted by radix on its
/// original indices, which are distinct: the same order.
pub(crate) fn order_agents<const SCATTERED: bool>(keyed: &mut [u64], out: &mut [u32]) {
    if SCATTERED && keyed.len() <= 8 {
        rank_agents::<8>(keyed, out);
    } else if SCATTERED && keyed.len() <= 16 {
        rank_agents::<16>(keyed, out);
    } else {
        if keyed.len() >= RADIX_MIN {
            radsort::sort_by_key(keyed, |&key| (key >> 32) as u32);
        } else {
            keyed.sort_unstable();
        }
        for (out, &key) in out.iter_mut().zip(&*keyed) {
            *out = key as u32;
        }
    }
}

/// The shortest list [`order_agents`] sorts by radix (`radsort`, by the original index): measured
/// on lists of random original indices below 10⁶ (2026-11-28), radix takes 4.9 ns a key against
/// pdqsort's 5.7 at 128 keys, 3.5 against 7.3 at 512, and loses below 96 (6.9 against 4.9 at 64).
const RADIX_MIN: usize = 128;

/// [`order_agents`] of at most `N` keys by their ranks among the original indices, counted over
/// `N` lanes (those beyond the list hold `u32::MAX`, above every original index).
fn rank_agents<const N: usize>(keyed: &[u64], out: &mut [u32]) {
    let mut originals = [u32::MAX; N];
    for (lane, &key) in originals.iter_mut().zip(keyed) {
        *lane = (key >> 32) as u32;
    }
    for (&key, &original) in keyed.iter().zip(&originals) {
        let rank: usize = originals
            .iter()
            .map(|&other| usize::from(other < original))
            .sum();
        // the agent: below n ≤ u32::MAX
        out[rank] = key as u32;
    }
}

/// Axis-aligned bounds of the finite agents.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    lo: [f64; 3],
    hi: [f64; 3],
    /// Largest coordinate magnitude.
    max_abs: f64,
    /// Number of finite agents.
    finite: usize,
}

impl Bounds {
    /// The bounds of the finite agents of `positions` (all zero when there are none).
    fn of<V: Vector>(positions: &[V]) -> Self {
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
    fn mean_spacing(&self) -> f64 {
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
struct Layout {
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
    fn coords(&self, cell: usize) -> [usize; 3] {
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
struct CellGrid {
    layout: Layout,
    /// The agents sorted by cell.
    sorted: CellSort,
}

/// The candidate slots of the agents of one cell: the runs of slots of the rows of up to 3^m
/// adjacent cells (cells x0..=x1 of a row are contiguous).
#[derive(Clone, Copy, Debug, Default)]
struct CandidateRows {
    rows: [(usize, usize); 9],
    count: usize,
}

impl CandidateRows {
    /// The slot ranges, one per row.
    #[inline]
    fn iter(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.rows[..self.count].iter().map(|&(a, b)| a..b)
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

impl CellGrid {
    /// Rebuilds the grid for `positions` (see [`Layout::new`] for `reach`).
    fn rebuild<V: Vector>(&mut self, positions: &[V], reach: f64) {
        let bounds = Bounds::of(positions);
        let layout = Layout::new(&bounds, reach);
        let cells = layout.cells();
        self.layout = layout;
        self.sorted.sort(cells, positions, |q| layout.cell_of(q));
    }

    /// Whether every agent of `positions` (as many as at the last rebuild) is within squared
    /// distance `limit` of where it was then, and every agent then without a cell still has a
    /// non-finite position (a NaN displacement is not within).
    fn moved_within<V: Vector>(&self, positions: &[V], limit: f64) -> bool {
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
    fn cells_of(&self, slot: usize) -> SlotCells<'_> {
        self.sorted.cells_from(slot, self.layout.dims)
    }

    /// The slots of the agents of the cell with coordinates `[cx, cy, cz]` and of its adjacent
    /// cells (in no useful order).
    #[inline]
    fn candidate_rows(&self, [cx, cy, cz]: [usize; 3]) -> CandidateRows {
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
    fn min_squared_distance<V: Vector>(&self, threshold: f64) -> Option<f64> {
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

    /// `n` points uniform in the square [0, side]², from `seed`.
    fn uniform_square(n: usize, side: f64, seed: u64) -> Vec<DVec2> {
        use rand::{RngExt, SeedableRng};

        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        (0..n)
            .map(|_| DVec2::new(rng.random::<f64>() * side, rng.random::<f64>() * side))
            .collect()
    }

    /// A net built from agents stored out of order, with their numbering, is the net of the
    /// agents in original order relabelled: each list names the same agents in the same order,
    /// with the same distance bits (recomputed ones too, without stored distances). Sorting the
    /// agents by cell makes the net of agents numbered at random no longer scattered.
    #[test]
    fn numbered_nets_are_the_original_nets_relabelled() {
        let mut q = uniform_square(20_000, 860.0, 5);
        q[123] = DVec2::NAN;
        let mut search = NeighbourSearch::new();
        let mut original = ProximityNet::new();
        search.build(&q, 8.4, &mut original);
        assert!(original.graph().directed_edge_count() > 4 * q.len());
        assert!(original.is_scattered());
        // the finite agents by cell, then the NaN one
        let mut order = search.cell_order(&q, 8.4).to_vec();
        assert_eq!(order.len(), q.len() - 1);
        order.push(123);
        let stored: Vec<DVec2> = order.iter().map(|&k| q[k as usize]).collect();
        let mut net = ProximityNet::new();
        net.permute(&order);
        search.build(&stored, 8.4, &mut net);
        assert!(!net.is_scattered());
        let numbering = net.numbering();
        for (s, &k) in order.iter().enumerate() {
            let k = k as usize;
            assert_eq!(numbering.original(s), k);
            assert_eq!(
                net.named_neighbours(s),
                original.graph().neighbours(k),
                "agent {k}"
            );
            let bits = |net: &ProximityNet, i: usize| -> Vec<u64> {
                net.graph()
                    .edge_range(i)
                    .map(|e| net.distances()[e].to_bits())
                    .collect()
            };
            assert_eq!(bits(&net, s), bits(&original, k), "agent {k}");
        }
        let mut lean = ProximityNet::without_distances();
        lean.share_numbering(&net);
        search.build(&stored, 8.4, &mut lean);
        assert_eq!(lean.graph(), net.graph());
        let lengths: Vec<u64> = lean.edge_lengths(&stored).map(f64::to_bits).collect();
        let distances: Vec<u64> = net.distances().iter().map(|d| d.to_bits()).collect();
        assert_eq!(lengths, distances);
    }

    /// The blocks only partition the work: any block length, and any rayon pool size, gives the
    /// same net, so the net does not depend on the `parallel` feature.
    #[test]
    fn net_is_independent_of_blocks_and_threads() {
        let mut q = uniform_square(3000, 40.0, 7);
        q[17] = DVec2::NAN;
        let expected = ProximityNet::brute_force(&q, 1.3);
        assert!(expected.graph().directed_edge_count() > q.len());
        let mut search = NeighbourSearch::new();
        let mut net = ProximityNet::new();
        for block_shift in [0, 3, 10, 12, 63] {
            search.build_in_blocks(&q, 1.3, &mut net, block_shift);
            assert_eq!(net, expected, "blocks of 2^{block_shift}");
        }
        // agents at random in their own order: the lists built without branching
        assert!(search.grid.sorted.scattered(net.numbering()));
        #[cfg(feature = "parallel")]
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| search.build(&q, 1.3, &mut net));
            assert_eq!(net, expected, "{threads} threads");
        }
    }

    /// A reused net is resized and overwritten, not cleared: growing, shrinking and emptying it
    /// leaves no trace of the previous build, with or without distances.
    #[test]
    fn reused_nets_forget_the_previous_build() {
        use rand::{RngExt, SeedableRng};

        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut cloud = |n: usize, side: f64| -> Vec<DVec3> {
            (0..n)
                .map(|_| DVec3::from_fn(|_| rng.random::<f64>() * side))
                .collect()
        };
        let configurations = [
            cloud(2000, 12.0),
            cloud(300, 4.0),
            cloud(2500, 30.0),
            cloud(1, 1.0),
            cloud(700, 3.0),
        ];
        let mut search = NeighbourSearch::new();
        let (mut full, mut lean) = (ProximityNet::new(), ProximityNet::without_distances());
        for (k, q) in configurations.iter().enumerate() {
            let expected = ProximityNet::brute_force(q, 1.1);
            search.build(q, 1.1, &mut full);
            assert_eq!(full, expected, "configuration {k}");
            search.build(q, 1.1, &mut lean);
            assert_eq!(lean.graph(), expected.graph(), "configuration {k}");
            assert!(lean.distances().is_empty());
        }
        search.build(&configurations[0], 0.0, &mut full);
        assert_eq!(full, ProximityNet::brute_force(&configurations[0], 0.0));
    }

    proptest::proptest! {
        /// A list of any length, its keys in any order, comes out in ascending original index
        /// whether placed by ranks (lists of up to 8 and of 9–16), sorted, or sorted by radix
        /// (from 128), with its agents.
        #[test]
        fn lists_come_out_in_ascending_original_index(
            originals in proptest::collection::hash_set(0..u32::MAX, 0..300),
            slots in proptest::collection::vec(proptest::num::u32::ANY, 300),
        ) {
            let keyed: Vec<u64> = originals
                .iter()
                .zip(&slots)
                .map(|(&k, &t)| u64::from(k) << 32 | u64::from(t))
                .collect();
            let mut sorted = keyed.clone();
            sorted.sort_unstable();
            let expected: Vec<u32> = sorted.iter().map(|&key| key as u32).collect();
            let mut scattered = vec![0; keyed.len()];
            order_agents::<true>(&mut keyed.clone(), &mut scattered);
            proptest::prop_assert_eq!(&scattered, &expected);
            let mut along = vec![0; keyed.len()];
            order_agents::<false>(&mut keyed.clone(), &mut along);
            proptest::prop_assert_eq!(&along, &expected);
        }
    }
}

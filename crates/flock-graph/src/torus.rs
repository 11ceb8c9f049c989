//! Fixed-radius neighbour search on a periodic box (a torus): [`NeighbourSearch::build_in`] and
//! the per-agent nearest-neighbour distances [`NeighbourSearch::nearest_distances_in`].
//!
//! The box [0, L₁) × … × [0, L_m) is cut into c_k = ⌊L_k / s⌋ cells per axis (at least one),
//! s the range padded against rounding as in the open search, so every cell is at least s wide and
//! two agents whose minimum-image distance is below r lie in the same cell or in cells adjacent
//! across the wrap. The adjacent cells of cell c along an axis are c − 1, c, c + 1 modulo c_k,
//! taken once each: with two cells per axis c − 1 and c + 1 are the same cell, with one cell there
//! is only c, so no pair is visited twice. When the agents are few the cells are merged (halving
//! the axis with the most cells) until there are at most 4n.
//!
//! Each agent's list is sorted by neighbour index (original index, for a net with a
//! [`Numbering`]) and each distance is the square root of the minimum-image squared length that
//! [`ProximityNet::brute_force_in`] computes, so the net equals the brute-force one bit for bit.
//! The lists are built in blocks of slots (agents in cell order) and gathered in agent order; the
//! blocks only partition the work, so the net is the same for any rayon pool size.

use core::ops::Range;

use flock_math::{Domain, Vector, periodic_displacement};

use crate::net::{ProximityNet, in_range, node_index, range_squared, squared_distance_in};
use crate::numbering::Numbering;
use crate::parallel::{fill_indexed, map_chunks};
use crate::search::{
    Block, CellSort, MAX_CELLS, NO_SLOT, NeighbourSearch, PAIR_CHUNK, SlotCells, assemble,
    assemble_lists, listed, order_agents, padded_side,
};

/// log₂ of the slots per block of work.
const BLOCK_SHIFT: u32 = 10;

/// Cells allowed per agent.
const CELLS_PER_AGENT: usize = 4;

/// A grid of the periodic box, its finite agents sorted by cell ([`CellSort`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct TorusGrid {
    /// Cells per axis (1 on the unused axis of 2D).
    dims: [usize; 3],
    /// Cell width L_k / c_k per axis.
    width: [f64; 3],
    /// The agents sorted by cell.
    sorted: CellSort,
}

/// The slot ranges of up to 27 cells: a cell and its neighbours across the wrap, each once, with
/// the whole periods that take each one's agents to their images next to the cell.
#[derive(Clone, Copy, Debug, Default)]
struct CandidateCells {
    ranges: [(usize, usize); 27],
    /// Per range, per axis, the periods the displacement to its agents loses across the wrap: 1
    /// for the cell before the first (the last cell), −1 for the one after the last (the first
    /// cell), 0 otherwise.
    shifts: [[f64; 3]; 27],
    count: usize,
}

impl CandidateCells {
    #[inline]
    fn iter(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.ranges[..self.count].iter().map(|&(a, b)| a..b)
    }

    /// The ranges with their shifts.
    #[inline]
    fn shifted(&self) -> impl Iterator<Item = (Range<usize>, [f64; 3])> + '_ {
        self.iter().zip(self.shifts.iter().copied())
    }

    /// The number of agents in the cells.
    fn len(&self) -> usize {
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
    fn rebuild<V: Vector>(&mut self, size: V, positions: &[V], reach: f64) {
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
    fn cell_coords(&self, cell: usize) -> [usize; 3] {
        crate::search::cell_coords(cell, self.dims)
    }

    /// The slot ranges of the cell `[cx, cy, cz]` and of its neighbours across the wrap, with
    /// their shifts (meaningful on the axes of at least three cells: see
    /// [`TorusGrid::shifts_are_exact`]).
    fn candidates(&self, [cx, cy, cz]: [usize; 3]) -> CandidateCells {
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
    fn candidates_from(&self, slot: usize) -> SlotCandidates<'_> {
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
    fn shifts_are_exact(&self, dim: usize) -> bool {
        self.dims[..dim].iter().all(|&c| c >= 3)
    }
}

/// The candidate cells of the slots of a [`TorusGrid`] visited in ascending order
/// ([`TorusGrid::candidates_from`]).
struct SlotCandidates<'a> {
    grid: &'a TorusGrid,
    cells: SlotCells<'a>,
    /// The cell whose candidates `candidates` holds (`usize::MAX`: none yet).
    cell: usize,
    candidates: CandidateCells,
}

impl SlotCandidates<'_> {
    /// The candidate cells of `slot`'s cell; `slot` must not decrease between calls.
    #[inline]
    fn of(&mut self, slot: usize) -> &CandidateCells {
        let cell = self.cells.cell_of(slot);
        if cell != self.cell {
            self.cell = cell;
            self.candidates = self.grid.candidates(self.cells.coords());
        }
        &self.candidates
    }
}

impl Block {
    /// The lists of `slots` of the periodic grid (agents in the box of sides `size`), `scattered`
    /// as [`CellSort::scattered`](crate::search::CellSort) says.
    fn fill_in_box<V: Vector>(
        &mut self,
        grid: &TorusGrid,
        size: V,
        r2: f64,
        numbering: &Numbering,
        scattered: bool,
        slots: Range<usize>,
    ) {
        let original = |j| numbering.original(j as usize) as u32;
        match (scattered, grid.shifts_are_exact(V::DIM)) {
            (false, true) => self.fill_periodic::<V, false, true>(grid, size, r2, slots, |j| j),
            (false, false) => self.fill_periodic::<V, false, false>(grid, size, r2, slots, |j| j),
            (true, true) => self.fill_periodic::<V, true, true>(grid, size, r2, slots, original),
            (true, false) => self.fill_periodic::<V, true, false>(grid, size, r2, slots, original),
        }
    }

    /// [`Block::fill_in_box`] with the original index `original(j)` of each agent j. `SCATTERED`
    /// (original indices unrelated to the scan: agents stored by cell under a numbering, or in
    /// their own order but numbered at random) builds each list without branching on whether a
    /// candidate is in range or where it ranks, as [`NeighbourSearch::build`] does. `SHIFTED` (when
    /// [`TorusGrid::shifts_are_exact`]) takes each candidate's displacement as its difference less
    /// its cell's shift, instead of its minimum image.
    #[inline]
    fn fill_periodic<V: Vector, const SCATTERED: bool, const SHIFTED: bool>(
        &mut self,
        grid: &TorusGrid,
        size: V,
        r2: f64,
        slots: Range<usize>,
        original: impl Fn(u32) -> u32,
    ) {
        self.ends.clear();
        self.neighbours.clear();
        // consecutive slots share their cell, and so its candidates
        let mut walk = grid.candidates_from(slots.start);
        for slot in slots {
            let candidates = walk.of(slot);
            let count = candidates.len();
            if self.keyed.len() < count {
                self.keyed.resize(count, 0);
            }
            let qi = grid.sorted.position::<V>(slot);
            // a local slice: its pointer and length stay in registers across the stores
            let keyed = &mut self.keyed[..count];
            let mut len = 0;
            for (range, periods) in candidates.shifted() {
                let shift = V::from_fn(|k| periods[k] * size.coord(k));
                for t in range {
                    let qt = grid.sorted.position::<V>(t);
                    let d = if SHIFTED {
                        (qt - qi) - shift
                    } else {
                        periodic_displacement(qi, qt, size)
                    };
                    let keep = in_range(d.length_squared(), r2) & (t != slot);
                    if SCATTERED || keep {
                        let j = grid.sorted.order[t];
                        keyed[len] = u64::from(original(j)) << 32 | u64::from(j);
                        len += usize::from(keep);
                    }
                }
            }
            let end = self.neighbours.len();
            self.neighbours.resize(end + len, 0);
            order_agents::<SCATTERED>(&mut self.keyed[..len], &mut self.neighbours[end..]);
            self.push_end(self.neighbours.len());
        }
    }
}

impl NeighbourSearch {
    /// Rebuilds `net` as the proximity net of `positions` in `domain` with range `r`:
    /// N_i = { j ≠ i : ‖displacement(q_i, q_j)‖ < r }, the distance of a periodic box being the
    /// minimum image.
    ///
    /// [`Domain::Open`] is [`NeighbourSearch::build`], bit for bit. On a torus the positions must
    /// lie in the box [0, L) (wrapped with [`Domain::wrap`]); the net equals
    /// [`ProximityNet::brute_force_in`]`(domain, positions, r)`: same neighbour order (ascending
    /// index), the stored distances the bit-identical minimum-image distances, whatever the rayon
    /// pool size. The numbering is kept as by [`NeighbourSearch::build`] (lists in ascending
    /// original index). No side is required to exceed 2r: with sides below that, each pair is
    /// still joined once, by its minimum image. A range that is not positive gives no edges;
    /// agents with a non-finite coordinate have none.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let q = [DVec2::new(0.2, 5.0), DVec2::new(9.7, 5.0), DVec2::new(5.0, 5.0)];
    /// let mut net = ProximityNet::new();
    /// NeighbourSearch::new().build_in(&torus, &q, 1.0, &mut net);
    /// assert_eq!(net.graph().neighbours(0), &[1]); // across the wrap
    /// assert!((net.distances()[0] - 0.5).abs() < 1e-12);
    /// assert_eq!(net, ProximityNet::brute_force_in(&torus, &q, 1.0));
    /// ```
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    pub fn build_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        r: f64,
        net: &mut ProximityNet,
    ) {
        match domain {
            Domain::Open => self.build(positions, r, net),
            Domain::Periodic { size } => {
                self.build_on_torus(domain, *size, positions, r, net, BLOCK_SHIFT);
            }
        }
    }

    /// The number of edges {i, j} (i < j, agent indices) of the net that
    /// [`NeighbourSearch::build_in`]`(domain, positions, r, …)` builds for which `accept(i, j)`
    /// holds, counted pair by pair without building the net: memory O(n) whatever the agents'
    /// degree, where the net holds every list. For counts over dense nets, such as the crossings
    /// of a net's edges, whose midpoints can have thousands of neighbours each. The count is the
    /// same for any rayon pool size.
    ///
    /// `None`, before any pair is tested, when the grid's candidate pairs exceed `most_tests`:
    /// Σ over its cells c of n_c times the agents of c and of its adjacent cells (ordered pairs,
    /// each agent with itself included; about twice the pairs the count tests, and n² when every
    /// agent is within r of every other). A bound on the work for callers that must not hang on
    /// a crowd.
    ///
    /// # Example
    /// ```
    /// use flock_graph::{NeighbourSearch, ProximityNet};
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let q: Vec<DVec2> = (0..10).map(|k| DVec2::new(k as f64, 0.0)).collect();
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let mut search = NeighbourSearch::new();
    /// let all = usize::MAX;
    /// // the ring's 10 links
    /// assert_eq!(search.count_pairs_in(&torus, &q, 1.5, all, |_, _| true), Some(10));
    /// // in open space the line has 9 links, 5 of them from an even agent up
    /// let even = |i: usize, _| i % 2 == 0;
    /// assert_eq!(search.count_pairs_in(&Domain::Open, &q, 1.5, all, even), Some(5));
    /// // with a range of 20 every pair of the 10 agents is a candidate: 100 tests
    /// assert_eq!(search.count_pairs_in(&Domain::Open, &q, 20.0, 99, even), None);
    /// assert_eq!(search.count_pairs_in(&Domain::Open, &q, 20.0, 100, even), Some(25));
    /// ```
    ///
    /// # Panics
    /// When `positions.len()` exceeds `u32::MAX`.
    pub fn count_pairs_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        r: f64,
        most_tests: usize,
        accept: impl Fn(usize, usize) -> bool + Sync,
    ) -> Option<usize> {
        let size = match domain {
            Domain::Open => return self.count_open_pairs(positions, r, most_tests, &accept),
            Domain::Periodic { size } => *size,
        };
        let r2 = range_squared(r);
        if positions.len() < 2 || r2 == 0.0 {
            return Some(0);
        }
        let grid = &mut self.torus;
        grid.rebuild(size, positions, r);
        let grid = &*grid;
        let tests = grid
            .sorted
            .candidate_tests(|cell| grid.candidates(grid.cell_coords(cell)).len());
        if tests > most_tests {
            return None;
        }
        let counts = map_chunks(grid.sorted.slots(), PAIR_CHUNK, |slots| {
            let mut walk = grid.candidates_from(slots.start);
            let mut count = 0;
            for slot in slots {
                let candidates = walk.of(slot);
                let (i, qi) = (
                    grid.sorted.order[slot] as usize,
                    grid.sorted.position::<V>(slot),
                );
                for range in candidates.iter() {
                    // each pair of slots once (every cell is a candidate once), from the lower one
                    for t in range.start.max(slot + 1)..range.end {
                        let j = grid.sorted.order[t] as usize;
                        let d = periodic_displacement(qi, grid.sorted.position::<V>(t), size);
                        if in_range(d.length_squared(), r2) && accept(i.min(j), i.max(j)) {
                            count += 1;
                        }
                    }
                }
            }
            count
        });
        Some(counts.iter().sum())
    }

    /// The agents with a finite position in the order of the cells of `domain`'s grid for range
    /// `r` (ascending index within a cell): [`NeighbourSearch::cell_order`] in open space, and on
    /// a torus the order [`NeighbourSearch::build_in`] visits them in. Its buffer is reused.
    pub fn cell_order_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        r: f64,
    ) -> &[u32] {
        match domain {
            Domain::Open => self.cell_order(positions, r),
            Domain::Periodic { size } => {
                self.torus.rebuild(*size, positions, r);
                &self.torus.sorted.order
            }
        }
    }

    /// The periodic net with blocks of 2^`block_shift` slots.
    fn build_on_torus<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        size: V,
        positions: &[V],
        r: f64,
        net: &mut ProximityNet,
        block_shift: u32,
    ) {
        debug_assert!(
            positions.iter().all(|q| !q.is_finite()
                || (0..V::DIM).all(|k| (0.0..=size.coord(k)).contains(&q.coord(k)))),
            "positions outside the periodic box"
        );
        let block_len = 1_usize << block_shift;
        let n = positions.len();
        let r2 = range_squared(r);
        let (offsets, neighbours, distances, numbering) = net.arrays_for_rebuild(n, r);
        if n < 2 || r2 == 0.0 {
            assemble(n, offsets, neighbours, distances, &|_| 0, &|_, _, _| {});
            return;
        }
        let (grid, blocks) = (&mut self.torus, &mut self.torus_blocks);
        grid.rebuild(size, positions, r);
        let grid = &*grid;
        let scattered = grid.sorted.scattered(numbering);
        let blocks = Block::fill_all(blocks, grid.sorted.slots(), block_len, |block, slots| {
            block.fill_in_box::<V>(grid, size, r2, numbering, scattered, slots);
        });
        let list = |i| {
            listed(&grid.sorted.slot_of, i, block_shift, |b, k| {
                blocks[b].list(k)
            })
        };
        assemble_lists(domain, positions, offsets, neighbours, distances, &list);
    }

    /// Fills `out` (resized to `positions.len()`) with the distance from each agent to its nearest
    /// other agent in `domain` (minimum image on a torus): out_i = min_{j≠i} ‖displacement(q_i,
    /// q_j)‖ over the finite agents j, +∞ for an agent with no other finite agent (fewer than two,
    /// or a non-finite position).
    ///
    /// Exact, bit-identical to the minimum of the brute-force distances, whatever the thread count:
    /// a cell grid with a growing reach, starting at the mean spacing of the agents, each pass
    /// searching only the agents not yet settled (expected O(n) for agents of bounded density;
    /// isolated agents cost more passes, never a wrong answer).
    ///
    /// # Example
    /// ```
    /// use flock_graph::NeighbourSearch;
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// let q = [DVec2::new(0.5, 5.0), DVec2::new(9.5, 5.0), DVec2::new(3.5, 1.0)];
    /// let mut d = Vec::new();
    /// NeighbourSearch::new().nearest_distances_in(&torus, &q, &mut d);
    /// assert_eq!(d[..2], [1.0, 1.0]);
    /// NeighbourSearch::new().nearest_distances_in(&Domain::Open, &q, &mut d);
    /// assert_eq!(d[0], 5.0);
    /// ```
    pub fn nearest_distances_in<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        positions: &[V],
        out: &mut Vec<f64>,
    ) {
        let n = positions.len();
        out.clear();
        out.resize(n, f64::INFINITY);
        let finite = positions.iter().filter(|q| q.is_finite()).count();
        if finite < 2 {
            return;
        }
        // The largest squared distance between finite agents (bounded by the box's half
        // diagonal on a torus, by the bounding box's diagonal in open space), and a first reach.
        let (lo, hi) = positions.iter().filter(|q| q.is_finite()).fold(
            (None::<V>, None::<V>),
            |(lo, hi), &q| {
                (
                    Some(lo.map_or(q, |l| l.min(q))),
                    Some(hi.map_or(q, |h| h.max(q))),
                )
            },
        );
        let (lo, hi) = (lo.unwrap_or(V::ZERO), hi.unwrap_or(V::ZERO));
        let extent = match domain {
            Domain::Open => hi - lo,
            Domain::Periodic { size } => V::from_fn(|k| {
                (hi.coord(k) - lo.coord(k))
                    .min(size.coord(k) / 2.0)
                    .max(0.0)
            }),
        };
        let diameter = extent.length();
        let volume = (0..V::DIM)
            .map(|k| extent.coord(k))
            .filter(|&e| e > 0.0)
            .fold(1.0, |v, e| v * e);
        let mut reach = (volume / finite as f64).powf(1.0 / V::DIM as f64);
        if !(reach > 0.0 && reach.is_finite()) || reach > diameter {
            reach = diameter;
        }
        let mut pending: Vec<u32> = (0..n)
            .filter(|&i| positions[i].is_finite())
            .map(node_index)
            .collect();
        loop {
            // the last pass: every pair is a candidate, any distance is accepted
            let last = reach >= diameter || !reach.is_finite();
            let threshold = if last { f64::INFINITY } else { reach * reach };
            let mut found = vec![f64::INFINITY; pending.len()];
            match domain {
                Domain::Open => {
                    let reach = if last { f64::INFINITY } else { reach };
                    self.open_nearest(positions, reach, threshold, &pending, &mut found);
                }
                Domain::Periodic { size } => {
                    let grid = &mut self.torus;
                    grid.rebuild(*size, positions, if last { f64::INFINITY } else { reach });
                    let grid = &*grid;
                    fill_indexed(&mut found, |p| {
                        let slot = grid.sorted.slot_of[pending[p] as usize] as usize;
                        let qi = grid.sorted.position::<V>(slot);
                        let mut best = f64::INFINITY;
                        for range in grid.candidates_from(slot).of(slot).iter() {
                            for t in range {
                                let d2 =
                                    squared_distance_in(domain, qi, grid.sorted.position::<V>(t));
                                if t != slot && in_range(d2, threshold) && d2 < best {
                                    best = d2;
                                }
                            }
                        }
                        best
                    });
                }
            }
            let mut still = Vec::new();
            for (&i, &d2) in pending.iter().zip(&found) {
                if d2.is_finite() {
                    out[i as usize] = d2.sqrt();
                } else {
                    still.push(i);
                }
            }
            pending = still;
            if pending.is_empty() || last {
                return;
            }
            reach = (2.0 * reach).min(diameter);
        }
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

    /// The blocks only partition the work: any block length and pool size gives the same net.
    #[test]
    fn periodic_net_is_independent_of_blocks_and_threads() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let size = DVec2::new(30.0, 20.0);
        let q: Vec<DVec2> = (0..2500)
            .map(|_| DVec2::new(rng.random::<f64>() * 30.0, rng.random::<f64>() * 20.0))
            .collect();
        let domain = Domain::Periodic { size };
        let expected = ProximityNet::brute_force_in(&domain, &q, 1.3);
        assert!(expected.graph().directed_edge_count() > q.len());
        let mut search = NeighbourSearch::new();
        let mut net = ProximityNet::new();
        for block_shift in [0, 3, 10, 12] {
            search.build_on_torus(&domain, size, &q, 1.3, &mut net, block_shift);
            assert_eq!(net, expected, "blocks of 2^{block_shift}");
        }
        // agents at random in their own order: the lists built without branching
        assert!(search.torus.sorted.scattered(net.numbering()));
        #[cfg(feature = "parallel")]
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| search.build_in(&domain, &q, 1.3, &mut net));
            assert_eq!(net, expected, "{threads} threads");
            let mut d = Vec::new();
            pool.install(|| search.nearest_distances_in(&domain, &q, &mut d));
            let bits: Vec<u64> = d.iter().map(|x| x.to_bits()).collect();
            let mut d1 = Vec::new();
            NeighbourSearch::new().nearest_distances_in(&domain, &q, &mut d1);
            assert_eq!(bits, d1.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
        }
    }
}

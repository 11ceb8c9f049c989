//! The fixed-radius search on a periodic box ([`TorusSearch`]): the proximity net by minimum
//! image, its pair counts, cell order and nearest distances on the grid of
//! [`TorusGrid`], and the kernel that fills a block's lists from that grid
//! ([`Block::fill_in_box`]).
//!
//! Each agent's list is sorted by neighbour index (original index, for a net with a
//! [`Numbering`]) and each distance is the square root of the minimum-image squared length that
//! [`ProximityNet::brute_force_in`] computes, so the net equals the brute-force one bit for bit.
//! The lists are built in blocks of slots (agents in cell order) and gathered in agent order; the
//! blocks only partition the work, so the net is the same for any rayon pool size.

use core::ops::Range;

use flock_math::{Domain, Vector, periodic_displacement};

use crate::net::{ProximityNet, in_range, range_squared, squared_distance_in};
use crate::numbering::Numbering;
use crate::search::cells::PAIR_CHUNK;
use crate::search::lists::{BLOCK_SHIFT, Block, assemble, assemble_lists, listed, order_agents};
use crate::search::torus_grid::TorusGrid;
use flock_math::parallel::{fill_indexed, map_chunks};

/// The periodic search: the grid of the box and the lists of its last build in blocks of slots.
/// Its buffers are kept between calls; every build is a full one (its models move a large part
/// of r per step, and a displacement check would need the minimum image).
#[derive(Clone, Debug, Default)]
pub(crate) struct TorusSearch {
    pub(crate) grid: TorusGrid,
    /// Neighbour lists of blocks of slots of the grid.
    blocks: Vec<Block>,
}

impl TorusSearch {
    /// [`NeighbourSearch::build_in`](crate::NeighbourSearch::build_in) on the box of sides
    /// `size` (`domain`).
    pub(crate) fn build<V: Vector>(
        &mut self,
        domain: &Domain<V>,
        size: V,
        positions: &[V],
        r: f64,
        net: &mut ProximityNet,
    ) {
        self.build_in_blocks(domain, size, positions, r, net, BLOCK_SHIFT);
    }

    /// [`TorusSearch::build`] with blocks of 2^`block_shift` slots.
    pub(crate) fn build_in_blocks<V: Vector>(
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
        let (grid, blocks) = (&mut self.grid, &mut self.blocks);
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

    /// [`NeighbourSearch::count_pairs_in`](crate::NeighbourSearch::count_pairs_in) on the box of
    /// sides `size`.
    pub(crate) fn count_pairs<V: Vector>(
        &mut self,
        size: V,
        positions: &[V],
        r: f64,
        most_tests: usize,
        accept: &(impl Fn(usize, usize) -> bool + Sync),
    ) -> Option<usize> {
        let r2 = range_squared(r);
        if positions.len() < 2 || r2 == 0.0 {
            return Some(0);
        }
        let grid = &mut self.grid;
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

    /// [`NeighbourSearch::cell_order_in`](crate::NeighbourSearch::cell_order_in) on the box of
    /// sides `size`.
    pub(crate) fn cell_order<V: Vector>(&mut self, size: V, positions: &[V], r: f64) -> &[u32] {
        self.grid.rebuild(size, positions, r);
        &self.grid.sorted.order
    }

    /// For each agent `pending[p]`, the least minimum-image squared distance below `threshold` to
    /// another finite agent, +∞ when there is none, in `found[p]`; the grid is rebuilt with
    /// `reach`, and `threshold` must not exceed `reach²`.
    pub(crate) fn nearest<V: Vector>(
        &mut self,
        size: V,
        positions: &[V],
        reach: f64,
        threshold: f64,
        pending: &[u32],
        found: &mut [f64],
    ) {
        let domain = Domain::Periodic { size };
        let grid = &mut self.grid;
        grid.rebuild(size, positions, reach);
        let grid = &*grid;
        fill_indexed(found, |p| {
            let slot = grid.sorted.slot_of[pending[p] as usize] as usize;
            let qi = grid.sorted.position::<V>(slot);
            let mut best = f64::INFINITY;
            for range in grid.candidates_from(slot).of(slot).iter() {
                for t in range {
                    let d2 = squared_distance_in(&domain, qi, grid.sorted.position::<V>(t));
                    if t != slot && in_range(d2, threshold) && d2 < best {
                        best = d2;
                    }
                }
            }
            best
        });
    }
}

impl Block {
    /// The lists of `slots` of the periodic grid (agents in the box of sides `size`), `scattered`
    /// as [`CellSort::scattered`](crate::search::cells::CellSort::scattered) says.
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
    /// candidate is in range or where it ranks, as
    /// [`NeighbourSearch::build`](crate::NeighbourSearch::build) does. `SHIFTED` (when
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

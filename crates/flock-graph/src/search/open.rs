//! The fixed-radius search in open space ([`OpenSearch`]): the proximity net of every step, the
//! cell order, pair counts and nearest distances on the open grid ([`CellGrid`]), and the kernel
//! that fills a block's lists from that grid ([`Block::fill`]).
//!
//! The lists are built out to a skin beyond r and kept: while no agent has moved more than half
//! the skin since, the next builds filter them by the predicate instead of scanning the grid
//! again (Verlet lists; [`Skin`] says when, and why the net is the same bit for bit).

use core::ops::Range;

use flock_math::{Domain, Vector};

use crate::net::{ProximityNet, in_range, range_squared, squared_distance};
use crate::numbering::Numbering;
use crate::search::cells::PAIR_CHUNK;
use crate::search::lists::{BLOCK_SHIFT, Block, assemble, assemble_lists, listed, order_agents};
use crate::search::open_grid::{Bounds, CandidateRows, CellGrid};
use crate::search::skin::Skin;
use flock_math::parallel::{fill_indexed, map_chunks};

/// The open-space search: the grid, the lists of its last build in blocks of slots, and whether
/// they may serve the next build. Its buffers are kept between calls.
#[derive(Clone, Debug, Default)]
pub(crate) struct OpenSearch {
    pub(crate) grid: CellGrid,
    /// Neighbour lists of blocks of 2^[`BLOCK_SHIFT`] slots (agents in cell order).
    blocks: Vec<Block>,
    /// Whether `grid` and `blocks` hold lists the next build may reuse.
    pub(crate) skin: Skin,
}

impl OpenSearch {
    /// [`NeighbourSearch::build`](crate::NeighbourSearch::build).
    pub(crate) fn build<V: Vector>(&mut self, positions: &[V], r: f64, net: &mut ProximityNet) {
        self.build_in_blocks(positions, r, net, BLOCK_SHIFT);
    }

    /// [`OpenSearch::build`] with blocks of 2^`block_shift` slots (`block_shift` < 64).
    ///
    /// The lists of the last build are kept, built out to the range plus a skin ([`Skin`]), and
    /// serve the next builds while no agent has moved more than half the skin: the net is then
    /// those lists filtered by the predicate. Same net either way.
    pub(crate) fn build_in_blocks<V: Vector>(
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

    /// [`NeighbourSearch::cell_order`](crate::NeighbourSearch::cell_order).
    pub(crate) fn cell_order<V: Vector>(&mut self, positions: &[V], r: f64) -> &[u32] {
        &self.regrid(positions, r).sorted.order
    }

    /// [`NeighbourSearch::nearest_pair_distance`](crate::NeighbourSearch::nearest_pair_distance).
    #[must_use]
    pub(crate) fn nearest_pair_distance<V: Vector>(&mut self, positions: &[V]) -> Option<f64> {
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

    /// The grid rebuilt for `positions` and `reach` for a use other than a net: the lists it
    /// held are no longer reusable.
    fn regrid<V: Vector>(&mut self, positions: &[V], reach: f64) -> &CellGrid {
        self.skin.forget();
        self.grid.rebuild(positions, reach);
        &self.grid
    }

    /// [`NeighbourSearch::count_pairs_in`](crate::NeighbourSearch::count_pairs_in) in open space.
    pub(crate) fn count_pairs<V: Vector>(
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
    pub(crate) fn nearest<V: Vector>(
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

impl Block {
    /// Refills the block with the lists (predicate `d² < r2`) of the agents in `slots`, each in
    /// ascending original index of `numbering`, `scattered` as
    /// [`CellSort::scattered`](crate::search::cells::CellSort::scattered) says.
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
    /// whether the original indices of agents near in space are unrelated
    /// ([`CellSort::scattered`](crate::search::cells::CellSort::scattered): agents stored by cell
    /// under a numbering, or in their own order but numbered at random):
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
}

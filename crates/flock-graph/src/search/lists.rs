//! Neighbour lists in blocks of slots, and the net assembled from them: the one storage and
//! assembly of the open and the periodic search.
//!
//! - [`Block`]: the lists of a block of consecutive slots (agents in cell order), filled in
//!   parallel ([`Block::fill_all`]) by each grid's kernel (`Block::fill` in the open search,
//!   `Block::fill_in_box` in the periodic one); [`listed`] finds agent i's list.
//! - [`order_agents`]: a list in ascending original index, by ranks without branching, by a sort,
//!   or by radix for long lists.
//! - [`assemble`], [`assemble_lists`]: the net's offsets, then its lists and distances gathered in
//!   agent order on the rayon pool ([`gather`]).

use core::ops::Range;

use flock_math::{Domain, Vector};

use crate::net::squared_distance_in;
use crate::search::cells::NO_SLOT;
use flock_math::parallel::{fill_indexed, for_each_indexed_mut, join};

/// log₂ of the slots per block of work (any value gives the same net): 1,024 slots, a unit of
/// rayon work with the `parallel` feature.
pub(crate) const BLOCK_SHIFT: u32 = 10;

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

#[cfg(test)]
mod tests {
    use super::*;

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

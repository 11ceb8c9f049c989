//! The one switch between rayon and serial loops, shared by the workspace's crates: per-index work
//! whose results do not depend on how it is split, so the output is identical with or without the
//! `parallel` feature, for any pool size.

use crate::interrupt::{self, BLOCK};

/// Minimum number of elements per rayon task in [`fill_indexed`] (small arrays stay on one thread).
const FILL_MIN_LEN: usize = 1024;

/// Calls `f(k, &mut items[k])` for every `k`, on the rayon pool with the `parallel` feature, in
/// tasks of at least `min_len` items (a scheduling hint only).
pub fn for_each_indexed_mut<T: Send>(
    items: &mut [T],
    min_len: usize,
    f: impl Fn(usize, &mut T) + Sync,
) {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_iter_mut()
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(k, item)| f(k, item));
    }
    #[cfg(not(feature = "parallel"))]
    {
        let _ = min_len;
        for (k, item) in items.iter_mut().enumerate() {
            f(k, item);
        }
    }
}

/// Calls `f(c, chunk)` for the consecutive chunks of `chunk` items of `items` (the last one
/// shorter), `c` counting from 0: on the rayon pool with the `parallel` feature.
pub fn for_each_chunk_mut<T: Send>(
    items: &mut [T],
    chunk: usize,
    f: impl Fn(usize, &mut [T]) + Sync,
) {
    for_each_chunk_mut_with(items, chunk, || (), |c, items, ()| f(c, items));
}

/// [`for_each_chunk_mut`] with `f(c, chunk, scratch)`, `scratch` a buffer made by `init` and
/// reused from one chunk to the next on the same thread (rayon's `for_each_init`): its content
/// at the start of a chunk is whatever the last chunk left.
pub fn for_each_chunk_mut_with<T: Send, S>(
    items: &mut [T],
    chunk: usize,
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(usize, &mut [T], &mut S) + Sync,
) {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_chunks_mut(chunk)
            .enumerate()
            .for_each_init(init, |scratch, (c, items)| f(c, items, scratch));
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut scratch = init();
        for (c, items) in items.chunks_mut(chunk).enumerate() {
            f(c, items, &mut scratch);
        }
    }
}

/// The number of threads that work of this module runs on: the rayon pool's with the `parallel`
/// feature, 1 without it.
#[must_use]
pub fn threads() -> usize {
    #[cfg(feature = "parallel")]
    {
        rayon::current_num_threads()
    }
    #[cfg(not(feature = "parallel"))]
    {
        1
    }
}

/// `(a(), b())`, potentially computed in parallel (rayon's `join` with the `parallel` feature).
pub fn join<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(feature = "parallel")]
    {
        rayon::join(a, b)
    }
    #[cfg(not(feature = "parallel"))]
    {
        (a(), b())
    }
}

/// `[f(0..chunk), f(chunk..2 chunk), …]` over `0..len` in chunks of `chunk` indices (the last one
/// shorter), evaluated on the rayon pool with the `parallel` feature, returned in chunk order.
pub fn map_chunks<T: Send>(
    len: usize,
    chunk: usize,
    f: impl Fn(core::ops::Range<usize>) -> T + Sync,
) -> Vec<T> {
    let range = |c: usize| c * chunk..((c + 1) * chunk).min(len);
    let chunks = len.div_ceil(chunk);
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..chunks).into_par_iter().map(|c| f(range(c))).collect()
    }
    #[cfg(not(feature = "parallel"))]
    (0..chunks).map(|c| f(range(c))).collect()
}

/// Indices per chunk of [`chunked_fold`].
const FOLD_CHUNK: usize = 4096;

/// A fold over `0..len` in chunks of 4,096 indices: `f(range)` folds one chunk (in parallel with
/// the `parallel` feature) and the chunks' results are merged in chunk order, from the first
/// (`empty` without indices): the same bits for any thread count, and `f(0..len)` when there is
/// a single chunk.
pub fn chunked_fold<S: Send>(
    len: usize,
    f: impl Fn(core::ops::Range<usize>) -> S + Sync,
    merge: impl Fn(S, S) -> S,
    empty: S,
) -> S {
    let mut chunks = map_chunks(len, FOLD_CHUNK, f).into_iter();
    match chunks.next() {
        Some(first) => chunks.fold(first, merge),
        None => empty,
    }
}

/// `out[k] = f(k)` for every `k`, on the rayon pool with the `parallel` feature.
pub fn fill_indexed<T: Send>(out: &mut [T], f: impl Fn(usize) -> T + Sync) {
    for_each_indexed_mut(out, FILL_MIN_LEN, |k, o| *o = f(k));
}

/// [`fill_indexed`] for the long loop of a step (a protocol's inputs, over every pair of a crowd):
/// it checks for an interrupt every [`BLOCK`] items and, once one
/// [cuts the step short](interrupt::cuts_short), leaves the rest of `out` as it was.
pub fn fill_interruptible<T: Send>(out: &mut [T], f: impl Fn(usize) -> T + Sync) {
    let fill = |(b, block): (usize, &mut [T])| {
        if interrupt::cuts_short() {
            return;
        }
        for (k, o) in block.iter_mut().enumerate() {
            *o = f(b * BLOCK + k);
        }
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        out.par_chunks_mut(BLOCK)
            .with_min_len(FILL_MIN_LEN / BLOCK)
            .enumerate()
            .for_each(fill);
    }
    #[cfg(not(feature = "parallel"))]
    out.chunks_mut(BLOCK).enumerate().for_each(fill);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fills_every_index_in_place() {
        let mut out = vec![0_usize; 5000];
        fill_indexed(&mut out, |k| 3 * k + 1);
        assert!(out.iter().enumerate().all(|(k, &v)| v == 3 * k + 1));
    }

    #[test]
    fn maps_chunks_in_order() {
        assert_eq!(map_chunks(10, 4, |r| r), [0..4, 4..8, 8..10]);
        assert!(map_chunks(0, 4, |r| r).is_empty());
    }

    #[test]
    fn chunks_are_numbered_in_order() {
        let mut items = vec![0_usize; 10];
        for_each_chunk_mut(&mut items, 4, |c, chunk| chunk.fill(c + 1));
        assert_eq!(items, [1, 1, 1, 1, 2, 2, 2, 2, 3, 3]);
        assert!(threads() >= 1);
    }

    #[test]
    fn fills_in_blocks_every_index() {
        let mut out = vec![0_usize; 5003];
        fill_interruptible(&mut out, |k| 2 * k);
        assert!(out.iter().enumerate().all(|(k, &v)| v == 2 * k));
    }

    #[test]
    fn visits_every_item_once() {
        let mut items = vec![vec![0_u32]; 37];
        for_each_indexed_mut(&mut items, 1, |k, item| item.push(k as u32));
        assert!(
            items
                .iter()
                .enumerate()
                .all(|(k, item)| item == &[0, k as u32])
        );
    }
}

//! [`Numbering`]: how the agents of a caller's arrays relate to the agents' own indices, so that
//! agents can be stored in space order (for memory locality) while every sum keeps the order of
//! their original numbering.
//!
//! A simulation that re-sorts its agents by cell stores agent k at some *storage index* s; the
//! numbering maps s to the *original index* k and back. A net built with a numbering lists each
//! agent's neighbours by storage index in ascending original index, and a reduction that visits
//! the agents through [`Numbering::stored_of`] adds their terms in original order: the results
//! are the bits of the same computation on the arrays in original order, however the agents are
//! stored.

use core::ops::Range;
use core::sync::atomic::{AtomicU64, Ordering};
use std::borrow::Cow;

use flock_math::parallel::{chunked_fold, fill_indexed};

/// The original index of each stored agent and the storage index of each original one; the
/// identity (storage index = original index) when empty.
///
/// # Example
/// ```
/// use flock_graph::Numbering;
///
/// let mut numbering = Numbering::identity();
/// // store the agents in the order 2, 0, 1
/// numbering.permute(&[2, 0, 1]);
/// assert_eq!(numbering.original(0), 2);
/// assert_eq!(numbering.stored_of(0..3).collect::<Vec<_>>(), [1, 2, 0]);
/// assert_eq!(numbering.ordered(&['c', 'a', 'b']).collect::<String>(), "abc");
/// ```
///
/// Two numberings are equal when they map the agents alike.
#[derive(Clone, Debug, Default)]
pub struct Numbering {
    /// The original index of the agent at each storage index (empty for the identity).
    ids: Vec<u32>,
    /// The storage index of each original index (empty for the identity).
    stored: Vec<u32>,
    /// Changed by every [`Numbering::permute`] to a value no other permutation of the process
    /// gave (0 for a numbering never permuted); copied with the numbering. A search that keeps
    /// lists between builds ([`crate::NeighbourSearch`]) tells by it, in O(1), that they still
    /// name the agents of the numbering they were built with.
    stamp: u64,
}

impl PartialEq for Numbering {
    fn eq(&self, other: &Self) -> bool {
        self.ids == other.ids
    }
}

impl Eq for Numbering {}

/// The last stamp given by [`Numbering::permute`].
static STAMPS: AtomicU64 = AtomicU64::new(0);

/// Elements per batch of [`Numbering::ordered`].
const GATHER: usize = 64;

/// The iterator of [`Numbering::ordered`].
#[derive(Clone, Debug)]
pub struct Ordered<'a, T> {
    numbering: &'a Numbering,
    stored: &'a [T],
    /// The original index of the next element to read from `stored`.
    next: usize,
    /// Elements read ahead, agents stored out of order.
    batch: [T; GATHER],
    /// The part of `batch` not yet yielded.
    unread: Range<usize>,
}

impl<T: Copy> Iterator for Ordered<'_, T> {
    type Item = T;

    #[inline]
    fn next(&mut self) -> Option<T> {
        if self.numbering.is_identity() {
            let element = self.stored.get(self.next).copied();
            self.next += usize::from(element.is_some());
            return element;
        }
        if self.unread.is_empty() {
            let end = (self.next + GATHER).min(self.stored.len());
            for (slot, k) in self.batch.iter_mut().zip(self.next..end) {
                *slot = self.stored[self.numbering.stored(k)];
            }
            self.unread = 0..end - self.next;
            self.next = end;
        }
        self.unread.next().map(|m| self.batch[m])
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.unread.len() + (self.stored.len() - self.next);
        (left, Some(left))
    }
}

impl<T: Copy> ExactSizeIterator for Ordered<'_, T> {}

impl Numbering {
    /// Storage index = original index.
    #[must_use]
    pub fn identity() -> Self {
        Self::default()
    }

    /// True when every agent is stored at its original index.
    #[inline]
    #[must_use]
    pub fn is_identity(&self) -> bool {
        self.ids.is_empty()
    }

    /// The stamp of the numbering's last permutation: equal stamps are equal numberings.
    #[inline]
    #[must_use]
    pub(crate) fn stamp(&self) -> u64 {
        self.stamp
    }

    /// Whether the numbering applies to `n` agents (the identity applies to any number).
    #[inline]
    #[must_use]
    pub fn numbers(&self, n: usize) -> bool {
        self.is_identity() || self.ids.len() == n
    }

    /// The original index of the agent at storage index `stored`.
    #[inline]
    #[must_use]
    pub fn original(&self, stored: usize) -> usize {
        self.ids.get(stored).map_or(stored, |&k| k as usize)
    }

    /// The storage index of the agent with original index `original`.
    #[inline]
    #[must_use]
    pub fn stored(&self, original: usize) -> usize {
        self.stored.get(original).map_or(original, |&s| s as usize)
    }

    /// The storage indices of the original indices `originals`, in ascending original index.
    #[inline]
    pub fn stored_of(
        &self,
        originals: Range<usize>,
    ) -> impl ExactSizeIterator<Item = usize> + Clone + '_ {
        originals.map(|k| self.stored(k))
    }

    /// The elements of `stored` (one per agent, in storage order) in ascending original index.
    ///
    /// Agents stored out of order are read in batches of 64 (their reads, at random in
    /// memory, issued back to back so that the processor overlaps them, instead of one per
    /// element of whatever computation consumes them): the same elements in the same order.
    #[inline]
    pub fn ordered<'a, T: Copy + Default>(&'a self, stored: &'a [T]) -> Ordered<'a, T> {
        Ordered {
            numbering: self,
            stored,
            next: 0,
            batch: [T::default(); GATHER],
            unread: 0..0,
        }
    }

    /// The rows of `width` entries of `stored` (one row per agent, in storage order) in
    /// ascending original index: `stored` itself when the agents are stored in original order or
    /// it holds nothing (`width` 0, or an array not kept), otherwise a copy.
    #[must_use]
    pub fn rows_in_original_order<'a, T: Clone>(
        &self,
        stored: &'a [T],
        width: usize,
    ) -> Cow<'a, [T]> {
        if self.is_identity() || stored.is_empty() || width == 0 {
            return Cow::Borrowed(stored);
        }
        debug_assert_eq!(stored.len(), self.ids.len() * width, "one row per agent");
        let rows = self.stored_of(0..self.ids.len());
        Cow::Owned(
            rows.flat_map(|s| &stored[s * width..(s + 1) * width])
                .cloned()
                .collect(),
        )
    }

    /// Σ_k value(s_k) over the `n` agents, k the original index and s_k its storage index: the
    /// values of chunks of 4,096 consecutive original indices added as running sums from +0, the
    /// chunk sums then added in order ([`chunked_fold`]). The bits depend only on the values in
    /// original order, not on how the agents are stored, nor on the thread count.
    ///
    /// `value` is evaluated once per agent, in storage order (in parallel with the `parallel`
    /// feature): agents stored in space order read their neighbours from nearby memory. Agents
    /// stored out of order keep the values in a buffer of n `f64` until they are added.
    pub fn ordered_sum(&self, n: usize, value: impl Fn(usize) -> f64 + Sync) -> f64 {
        self.ordered_fold(n, value, |sum, _, v| sum + v, |total, sum| total + sum, 0.0)
    }

    /// [`Numbering::ordered_sum`] for any fold: `add(acc, s_k, value(s_k))` over the `n` agents
    /// in ascending original index k within chunks of 4,096, from `zero`, and the chunks' results
    /// then merged in order ([`chunked_fold`]). Several sums over the same agents thus take one
    /// pass, each with the bits it has alone, however the agents are stored and whatever the
    /// thread count. `add` is also given the agent's storage index, to look at that agent again
    /// when its value calls for it.
    ///
    /// `value` is evaluated once per agent in storage order, as in [`Numbering::ordered_sum`];
    /// agents stored out of order keep the values in a buffer of n `T`.
    pub fn ordered_fold<T, S>(
        &self,
        n: usize,
        value: impl Fn(usize) -> T + Sync,
        add: impl Fn(S, usize, T) -> S + Sync,
        merge: impl Fn(S, S) -> S,
        zero: S,
    ) -> S
    where
        T: Copy + Default + Send + Sync,
        S: Copy + Send + Sync,
    {
        if self.is_identity() {
            let chunk = |agents: Range<usize>| agents.fold(zero, |acc, s| add(acc, s, value(s)));
            return chunked_fold(n, chunk, merge, zero);
        }
        let mut values = vec![T::default(); n];
        fill_indexed(&mut values, value);
        let chunk = |originals: Range<usize>| {
            self.stored_of(originals)
                .fold(zero, |acc, s| add(acc, s, values[s]))
        };
        chunked_fold(n, chunk, merge, zero)
    }

    /// Moves the agents: the agent at storage index `order[s]` goes to storage index s, for every
    /// s (`order` is a permutation of the storage indices). Back to the identity when every
    /// agent then sits at its original index.
    ///
    /// # Panics
    /// When `order` is not a permutation of `0..order.len()` (or of the numbering's agents).
    pub fn permute(&mut self, order: &[u32]) {
        assert!(
            self.is_identity() || self.ids.len() == order.len(),
            "a permutation of {} agents for a numbering of {}",
            order.len(),
            self.ids.len()
        );
        self.stamp = STAMPS.fetch_add(1, Ordering::Relaxed) + 1;
        // the new ids, built in `stored` (the inverse is recomputed below)
        let ids = &self.ids;
        self.stored.clear();
        self.stored
            .extend(order.iter().map(|&s| ids.get(s as usize).map_or(s, |&k| k)));
        core::mem::swap(&mut self.ids, &mut self.stored);
        if self.ids.iter().enumerate().all(|(s, &k)| k as usize == s) {
            self.ids.clear();
            self.stored.clear();
            return;
        }
        const UNSET: u32 = u32::MAX;
        self.stored.clear();
        self.stored.resize(order.len(), UNSET);
        for (s, &k) in self.ids.iter().enumerate() {
            let slot = &mut self.stored[k as usize];
            assert!(*slot == UNSET, "agent {k} stored twice: not a permutation");
            *slot = s as u32;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::{Just, Strategy};

    #[test]
    fn permutations_compose_and_invert() {
        let mut numbering = Numbering::identity();
        numbering.permute(&[3, 1, 0, 2]);
        // storage now holds originals 3, 1, 0, 2
        assert_eq!(
            (0..4).map(|s| numbering.original(s)).collect::<Vec<_>>(),
            [3, 1, 0, 2]
        );
        numbering.permute(&[1, 2, 3, 0]);
        // storage now holds originals 1, 0, 2, 3
        assert_eq!(
            (0..4).map(|s| numbering.original(s)).collect::<Vec<_>>(),
            [1, 0, 2, 3]
        );
        for k in 0..4 {
            assert_eq!(numbering.original(numbering.stored(k)), k);
        }
        assert_eq!(
            numbering.ordered(&[10, 20, 30, 40]).collect::<Vec<_>>(),
            [20, 10, 30, 40]
        );
        // swapping the first two back restores the identity
        numbering.permute(&[1, 0, 2, 3]);
        assert!(numbering.is_identity());
        assert_eq!(numbering, Numbering::identity());
    }

    /// Running sums from +0 over chunks of 4,096 values, then the chunks' sums in order.
    fn chunked_running_sum(xs: &[f64]) -> f64 {
        xs.chunks(4096)
            .map(|c| c.iter().fold(0.0, |s, &v| s + v))
            .reduce(|a, b| a + b)
            .unwrap()
    }

    /// The sum has the bits of the values in original order, summed in chunks of 4,096, however
    /// the agents are stored.
    #[test]
    fn ordered_sums_follow_the_original_order() {
        let n = 10_000;
        let values: Vec<f64> = (0..n)
            .map(|k| ((k * 7919) % 1000) as f64 * 0.1 + 1e-3)
            .collect();
        let expected = chunked_running_sum(&values);
        let identity = Numbering::identity();
        assert_eq!(
            identity.ordered_sum(n, |k| values[k]).to_bits(),
            expected.to_bits()
        );
        // stored as 0, n-1, 1, n-2, …
        let order: Vec<u32> = (0..n as u32)
            .map(|s| {
                if s % 2 == 0 {
                    s / 2
                } else {
                    n as u32 - 1 - s / 2
                }
            })
            .collect();
        let mut numbering = Numbering::identity();
        numbering.permute(&order);
        let stored: Vec<f64> = order.iter().map(|&k| values[k as usize]).collect();
        assert_eq!(
            numbering.ordered_sum(n, |s| stored[s]).to_bits(),
            expected.to_bits()
        );
        // a plain running sum of the stored values differs: the order matters
        assert_ne!(stored.iter().sum::<f64>().to_bits(), expected.to_bits());
    }

    /// Two sums and a least value in one fold have the bits of each alone, whatever the storage
    /// order; `add` is given the storage index of the value it adds.
    #[test]
    fn a_fold_of_several_sums_has_the_bits_of_each_alone() {
        let n = 9_000;
        let values: Vec<f64> = (0..n)
            .map(|k| ((k * 6151) % 977) as f64 * 0.3 - 91.7)
            .collect();
        let order: Vec<u32> = (0..n as u32).map(|s| (s * 7) % n as u32).collect();
        for numbering in [Numbering::identity(), {
            let mut permuted = Numbering::identity();
            permuted.permute(&order);
            permuted
        }] {
            let stored: Vec<f64> = (0..n).map(|s| values[numbering.original(s)]).collect();
            let (sum, squares, least, visited) = numbering.ordered_fold(
                n,
                |s| [stored[s], stored[s] * stored[s]],
                |(sum, squares, least, visited): (f64, f64, f64, usize), s, [v, v2]| {
                    assert_eq!(v.to_bits(), stored[s].to_bits(), "the storage index of v");
                    (sum + v, squares + v2, least.min(v), visited + 1)
                },
                |a, b| (a.0 + b.0, a.1 + b.1, a.2.min(b.2), a.3 + b.3),
                (0.0, 0.0, f64::INFINITY, 0),
            );
            let squared: Vec<f64> = values.iter().map(|v| v * v).collect();
            assert_eq!(sum.to_bits(), chunked_running_sum(&values).to_bits());
            assert_eq!(squares.to_bits(), chunked_running_sum(&squared).to_bits());
            assert_eq!(least, values.iter().copied().fold(f64::INFINITY, f64::min));
            assert_eq!(visited, n);
        }
    }

    #[test]
    #[should_panic(expected = "not a permutation")]
    fn repeated_agents_are_rejected() {
        Numbering::identity().permute(&[0, 0, 1]);
    }

    proptest::proptest! {
        /// `ordered` yields each stored element in ascending original index, across batches of
        /// any length (a whole number of them or not), its length exact at every point.
        #[test]
        fn ordered_gathers_every_element_in_original_order(
            order in (0..300_u32).prop_flat_map(|n| Just((0..n).collect::<Vec<_>>()).prop_shuffle()),
        ) {
            let mut numbering = Numbering::identity();
            numbering.permute(&order);
            // the element of original index k is 10 k + 1
            let stored: Vec<u64> = order.iter().map(|&k| 10 * u64::from(k) + 1).collect();
            let mut ordered = numbering.ordered(&stored);
            for k in 0..stored.len() {
                proptest::prop_assert_eq!(ordered.len(), stored.len() - k);
                proptest::prop_assert_eq!(ordered.next(), Some(10 * k as u64 + 1));
            }
            proptest::prop_assert_eq!(ordered.len(), 0);
            proptest::prop_assert_eq!(ordered.next(), None);
        }

        /// `rows_in_original_order` puts row k (of any width) at place k; empty arrays and width
        /// 0 come back as they are.
        #[test]
        fn rows_come_out_in_original_order(
            order in (0..300_u32).prop_flat_map(|n| Just((0..n).collect::<Vec<_>>()).prop_shuffle()),
            width in 0..4_usize,
        ) {
            let mut numbering = Numbering::identity();
            numbering.permute(&order);
            // entry c of the row of original index k is 10 k + c
            let stored: Vec<u64> = order
                .iter()
                .flat_map(|&k| (0..width as u64).map(move |c| 10 * u64::from(k) + c))
                .collect();
            let rows = numbering.rows_in_original_order(&stored, width);
            let expected: Vec<u64> = (0..order.len() as u64)
                .flat_map(|k| (0..width as u64).map(move |c| 10 * k + c))
                .collect();
            proptest::prop_assert_eq!(&rows[..], &expected[..]);
            proptest::prop_assert!(numbering.rows_in_original_order::<u64>(&[], 1).is_empty());
        }
    }
}

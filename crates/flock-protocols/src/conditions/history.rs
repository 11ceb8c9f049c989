//! The delay line: the last D + 1 measured states, D the longest delay (delay + jitter) in steps.

use flock_math::Vector;

/// A ring of the measured positions and velocities of the last `len` steps; the state of step k
/// is in slot k mod len. Before the first step the history is the first state (a constant
/// initial history, x(t) = x(0) for t < 0).
#[derive(Clone, Debug, PartialEq)]
pub struct History<V> {
    /// Per slot, the positions then the velocities of every agent.
    pub(crate) slots: Vec<(Vec<V>, Vec<V>)>,
}

impl<V: Vector> History<V> {
    /// A history holding `depth` + 1 steps of `n` agents, every slot zero until filled.
    #[must_use]
    pub fn new(depth: u64, n: usize) -> Self {
        let len = usize::try_from(depth + 1).unwrap_or(usize::MAX);
        Self {
            slots: vec![(vec![V::ZERO; n], vec![V::ZERO; n]); len],
        }
    }

    /// The number of steps held, D + 1 (never 0).
    #[must_use]
    pub fn depth(&self) -> u64 {
        self.slots.len() as u64
    }

    /// Records the state of step `k`; at the first step, every slot.
    pub fn record(&mut self, k: u64, first: bool, positions: &[V], velocities: &[V]) {
        let len = self.depth();
        for (s, slot) in self.slots.iter_mut().enumerate() {
            if first || s as u64 == k % len {
                slot.0.copy_from_slice(positions);
                slot.1.copy_from_slice(velocities);
            }
        }
    }

    /// The positions and velocities recorded at step `k` − `lag` (`lag` ≤ D), or at step 0
    /// before it.
    #[inline]
    #[must_use]
    pub fn slot(&self, k: u64, lag: u64) -> (&[V], &[V]) {
        let slot = &self.slots[(k.saturating_sub(lag) % self.depth()) as usize];
        (&slot.0, &slot.1)
    }

    /// Agent `j`'s state recorded at step `k` − `lag` (`lag` ≤ D), or at step 0 before it.
    #[inline]
    #[must_use]
    pub fn at(&self, k: u64, lag: u64, j: usize) -> (V, V) {
        let (q, p) = self.slot(k, lag);
        (q[j], p[j])
    }
}

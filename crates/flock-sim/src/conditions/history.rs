//! The delay line: the last D + 1 measured states, D the longest delay (delay + jitter) in steps.

use std::collections::TryReserveError;

use flock_math::Vector;

/// One slot of the ring: every agent's positions, then their velocities.
pub type Slot<V> = (Vec<V>, Vec<V>);

/// A ring of the measured positions and velocities of the last `len` steps; the state of step k
/// is in slot k mod len. Before the first step the history is the first state (a constant
/// initial history, x(t) = x(0) for t < 0).
#[derive(Clone, Debug, PartialEq)]
pub struct History<V> {
    /// Per slot, the positions then the velocities of every agent.
    pub(crate) slots: Vec<Slot<V>>,
}

impl<V: Vector> History<V> {
    /// A history holding `depth` + 1 steps of `n` agents, every slot zero until filled.
    ///
    /// # Errors
    /// When the memory cannot be had (a delay of 10⁶ s at a step of 0.01 s keeps 10⁸ slots):
    /// the error of the allocation that failed, not an abort.
    pub fn new(depth: u64, n: usize) -> Result<Self, TryReserveError> {
        let len = usize::try_from(depth + 1).unwrap_or(usize::MAX);
        let zeros = || -> Result<Vec<V>, TryReserveError> {
            let mut slot = Vec::new();
            slot.try_reserve_exact(n)?;
            slot.resize(n, V::ZERO);
            Ok(slot)
        };
        let mut slots = Vec::new();
        slots.try_reserve_exact(len)?;
        for _ in 0..len {
            slots.push((zeros()?, zeros()?));
        }
        Ok(Self { slots })
    }

    /// The number of agents whose states it holds.
    #[must_use]
    pub fn agents(&self) -> usize {
        self.slots.first().map_or(0, |slot| slot.0.len())
    }

    /// The number of steps held, D + 1 (never 0).
    #[must_use]
    pub fn depth(&self) -> u64 {
        self.slots.len() as u64
    }

    /// The slot of step `k`, to write the state measured at step `k` into, and the state of
    /// step `k` − 1 (held by a sensor between its updates; the same slot when D = 0).
    pub fn newest(&mut self, k: u64) -> (&mut Slot<V>, Option<&Slot<V>>) {
        let len = self.slots.len();
        let s = (k % self.depth()) as usize;
        let before = (s + len - 1) % len;
        if before == s {
            return (&mut self.slots[s], None);
        }
        let (low, high) = self.slots.split_at_mut(s.max(before));
        if s < before {
            (&mut low[s], Some(&high[0]))
        } else {
            (&mut high[0], Some(&low[before]))
        }
    }

    /// Fills every slot with the state of step `k` (at the first step: a constant history).
    pub fn fill_from(&mut self, k: u64) {
        let s = (k % self.depth()) as usize;
        let (older, rest) = self.slots.split_at_mut(s);
        if let Some((newest, newer)) = rest.split_first_mut() {
            for slot in older.iter_mut().chain(newer) {
                slot.0.copy_from_slice(&newest.0);
                slot.1.copy_from_slice(&newest.1);
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

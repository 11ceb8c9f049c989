//! **Fail**: the agents whose failure time has come fail, each in the mode its faults give
//! ([`faults`]): a failed agent moves and is heard, or not, as its mode
//! says, from this step on.

use flock_graph::Numbering;
use flock_math::Vector;

use crate::conditions::{Stage, faults};

impl<V: Vector> Stage<V> {
    /// Fail at step `k`: every agent whose failure time has come (named by its original index,
    /// `numbering`) is marked failed; nothing without faults.
    pub(crate) fn fail(&mut self, k: u64, numbering: &Numbering) {
        if let Some(f) = &self.conditions.faults {
            faults::update(f, &self.streams, k, self.h, numbering, &mut self.failed);
        }
    }
}

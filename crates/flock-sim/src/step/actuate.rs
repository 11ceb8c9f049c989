//! **Actuate**: what the actuators deliver of the commanded acceleration
//! ([`actuation`](crate::conditions::actuation)): clipped to a_max, then through the first-order
//! lag; agents that do not move get none.

use flock_math::Vector;

use crate::conditions::Stage;
use crate::conditions::actuation::clip;

impl<V: Vector> Stage<V> {
    /// Actuate: the commanded accelerations `inputs` clipped to a_max, then the first-order lag.
    /// The delivered accelerations replace the inputs when no input is held past this step (no
    /// lag, control at every step: [`holds_delivered`](crate::conditions::stage::holds_delivered)).
    pub(crate) fn actuate(&mut self, inputs: &mut [V]) {
        let actuation = self.conditions.actuation.unwrap_or_default();
        let mut clipped = 0usize;
        let in_place = self.delivered.is_empty();
        for (i, input) in inputs.iter_mut().enumerate() {
            let (u, at_limit) = clip(*input, actuation.max_acceleration);
            clipped += usize::from(at_limit);
            let moves = self.moves(i);
            let delivered = if in_place {
                input
            } else {
                &mut self.delivered[i]
            };
            *delivered = match self.lag {
                Some(lag) => lag.advance(*delivered, u),
                None => u,
            };
            if !moves {
                *delivered = V::ZERO;
            }
        }
        self.readings.at_acceleration_limit = clipped as f64;
    }

    /// The accelerations delivered at this step (after [`Stage::actuate`]): `inputs` themselves
    /// when they were delivered in place.
    pub(crate) fn delivered<'a>(&'a self, inputs: &'a [V]) -> &'a [V] {
        if self.delivered.is_empty() {
            inputs
        } else {
            &self.delivered
        }
    }
}

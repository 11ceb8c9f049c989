//! **Disturb**, the part of the integrate stage that the world adds: the wind (a mean and
//! Ornstein–Uhlenbeck gusts, one shared or one per agent) and the process noise
//! ([`Disturbance`](crate::conditions::Disturbance)), keyed by step and original index.

use flock_graph::Numbering;
use flock_math::Vector;
use flock_math::stream::Purpose;

use crate::conditions::Stage;

impl<V: Vector> Stage<V> {
    /// The wind gusts of step `k` (Ornstein–Uhlenbeck, started in its stationary law): one
    /// for all, or one per agent keyed by its original index.
    pub(crate) fn advance_gusts(&mut self, numbering: &Numbering, k: u64) {
        let Some(gusts) = self.gusts else {
            return;
        };
        let per_agent = self.gusts_per_agent();
        for (g, x) in self.gust.iter_mut().enumerate() {
            let key = if per_agent { numbering.original(g) } else { g };
            let xi = self
                .streams
                .draws(Purpose::Wind, key as u64, k)
                .normal_vector();
            *x = if self.started {
                gusts.advance(*x, xi)
            } else {
                gusts.stationary(xi)
            };
        }
    }

    /// Agent i's disturbance at step `k`: the wind w_i = mean + gusts (an acceleration) and the
    /// process noise's velocity kick σ √h ξ (Euler–Maruyama), keyed by its original index.
    pub(crate) fn disturbance(&self, i: usize, numbering: &Numbering, k: u64) -> (V, V) {
        let Some(disturbance) = &self.conditions.disturbance else {
            return (V::ZERO, V::ZERO);
        };
        let mean = disturbance
            .wind
            .as_ref()
            .map_or(V::ZERO, |w| V::from_fn(|d| w.mean[d]));
        let wind = match self.gust.len() {
            0 => mean,
            1 => mean + self.gust[0],
            _ => mean + self.gust[i],
        };
        let kick = disturbance.process_noise * self.h.sqrt();
        let noise = if kick > 0.0 {
            let xi: V = self
                .streams
                .draws(Purpose::ProcessNoise, numbering.original(i) as u64, k)
                .normal_vector();
            xi * kick
        } else {
            V::ZERO
        };
        (wind, noise)
    }
}

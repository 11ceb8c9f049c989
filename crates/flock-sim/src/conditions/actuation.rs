//! What the actuators deliver: a norm clip on the commanded acceleration, a first-order lag,
//! and a norm clip on the speed.

use flock_math::Vector;

/// `v` clipped to norm `max` (`None`: unlimited), and whether it was clipped.
#[inline]
#[must_use]
pub fn clip<V: Vector>(v: V, max: Option<f64>) -> (V, bool) {
    match max {
        Some(max) if v.length_squared() > max * max => (v * (max / v.length()), true),
        _ => (v, false),
    }
}

/// The first-order lag ȧ = (u − a)/τ_a on the delivered acceleration, discretised exactly for
/// an input u held over the step h: a ← u + (a − u) e^(−h/τ_a). From a = 0 and a constant u,
/// a = u (1 − e^(−k h/τ_a)) after k steps, the continuous step response at the steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lag {
    decay: f64,
}

impl Lag {
    /// The lag of time constant `tau` at step `h`.
    #[must_use]
    pub fn new(tau: f64, h: f64) -> Self {
        Self {
            decay: (-h / tau).exp(),
        }
    }

    /// a ← u + (a − u) e^(−h/τ_a).
    #[inline]
    #[must_use]
    pub fn advance<V: Vector>(&self, a: V, u: V) -> V {
        u + (a - u) * self.decay
    }
}

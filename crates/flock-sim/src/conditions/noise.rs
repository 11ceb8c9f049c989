//! Sensor noise and the Ornstein–Uhlenbeck process it may follow (also the wind's gusts).

use flock_math::Vector;

use super::config::Noise;

/// The exact discretisation of an Ornstein–Uhlenbeck process dx = −x/θ dt + σ√(2/θ) dW of
/// stationary standard deviation σ, sampled every Δ: x ← x e^(−Δ/θ) + σ √(1 − e^(−2Δ/θ)) ξ,
/// ξ ~ N(0, 1) (Gillespie, Phys. Rev. E 54, 1996, eq. 1.3): no discretisation error at any Δ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrnsteinUhlenbeck {
    /// The stationary standard deviation σ.
    pub sigma: f64,
    decay: f64,
    spread: f64,
}

impl OrnsteinUhlenbeck {
    /// The process of stationary σ `sigma` and correlation time θ `correlation_time`, sampled
    /// every `interval`.
    #[must_use]
    pub fn new(sigma: f64, correlation_time: f64, interval: f64) -> Self {
        let decay = (-interval / correlation_time).exp();
        Self {
            sigma,
            decay,
            spread: sigma * (-(-2.0 * interval / correlation_time).exp_m1()).sqrt(),
        }
    }

    /// x ← x e^(−Δ/θ) + σ √(1 − e^(−2Δ/θ)) ξ, with ξ the standard normals `xi`.
    #[inline]
    #[must_use]
    pub fn advance<V: Vector>(&self, x: V, xi: V) -> V {
        x * self.decay + xi * self.spread
    }

    /// A draw from the stationary law N(0, σ²), from the standard normals `xi`.
    #[inline]
    #[must_use]
    pub fn stationary<V: Vector>(&self, xi: V) -> V {
        xi * self.sigma
    }
}

/// The noise added to an agent's measured position and velocity at each sensor update.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SensorNoise {
    /// Fresh N(0, σ²) at every update.
    White {
        /// σ_q (m).
        sigma_q: f64,
        /// σ_p (m/s).
        sigma_p: f64,
    },
    /// Ornstein–Uhlenbeck offsets, advanced exactly over each sensor period.
    OrnsteinUhlenbeck {
        /// The position offsets' process.
        q: OrnsteinUhlenbeck,
        /// The velocity offsets' process.
        p: OrnsteinUhlenbeck,
    },
}

impl SensorNoise {
    /// The noise of `noise`, refreshed every `period` seconds.
    #[must_use]
    pub fn new(noise: &Noise, period: f64) -> Self {
        match *noise {
            Noise::White { sigma_q, sigma_p } => Self::White { sigma_q, sigma_p },
            Noise::OrnsteinUhlenbeck {
                sigma_q,
                sigma_p,
                correlation_time,
            } => Self::OrnsteinUhlenbeck {
                q: OrnsteinUhlenbeck::new(sigma_q, correlation_time, period),
                p: OrnsteinUhlenbeck::new(sigma_p, correlation_time, period),
            },
        }
    }

    /// The offsets (position, velocity) after an update from `previous` (`None` at the first
    /// update: an Ornstein–Uhlenbeck offset starts from its stationary law), with the standard
    /// normals `xi_q`, `xi_p`.
    #[must_use]
    pub fn update<V: Vector>(&self, previous: Option<(V, V)>, xi_q: V, xi_p: V) -> (V, V) {
        match (self, previous) {
            (Self::White { sigma_q, sigma_p }, _) => (xi_q * *sigma_q, xi_p * *sigma_p),
            (Self::OrnsteinUhlenbeck { q, p }, None) => (q.stationary(xi_q), p.stationary(xi_p)),
            (Self::OrnsteinUhlenbeck { q, p }, Some((x_q, x_p))) => {
                (q.advance(x_q, xi_q), p.advance(x_p, xi_p))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_exact_step_keeps_the_stationary_variance() {
        // Var' = a² σ² + σ² (1 − a²) = σ²
        let ou = OrnsteinUhlenbeck::new(2.0, 0.5, 0.3);
        let a = ou.decay;
        assert!((a * a * 4.0 + ou.spread * ou.spread - 4.0).abs() < 1e-12);
    }
}

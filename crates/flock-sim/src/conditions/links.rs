//! Packet loss on the links between agents, and what a receiver keeps of each link: the
//! Gilbert–Elliott channel state and the last state received (for [`WhenLost::Hold`]).
//!
//! [`WhenLost::Hold`]: super::config::WhenLost::Hold

use super::config::Loss;

/// The last state received on a link: position, velocity, and the step it was measured at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Held<V> {
    /// Position as received.
    pub position: V,
    /// Velocity as received.
    pub velocity: V,
    /// The step the state is from.
    pub stamp: u64,
}

/// What receiver i keeps of its link from `sender`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link<V> {
    /// The sending agent j, by original index (whatever order the agents are stored in).
    pub sender: u32,
    /// The Gilbert–Elliott state (true: bad, packets lost) and the step it was drawn at.
    pub channel: Option<(bool, u64)>,
    /// The last state received.
    pub held: Option<Held<V>>,
}

impl<V> Link<V> {
    /// A link from `sender` with no history.
    #[must_use]
    pub const fn new(sender: u32) -> Self {
        Self {
            sender,
            channel: None,
            held: None,
        }
    }
}

/// Whether the packet of a link is lost at step `k`, `draw` giving the link's uniform of the step
/// (taken only when the loss model needs it), the link `length` ℓ apart.
///
/// - Bernoulli p: lost with probability p.
/// - Gilbert–Elliott (rates a = p_fail, b = p_recover per second): the channel state moves from
///   its last draw over the elapsed time Δ with the exact transition of the two-state chain,
///   P(bad | bad) = π + (1 − π) e^(−(a+b)Δ), P(bad | good) = π (1 − e^(−(a+b)Δ)), π = a/(a+b);
///   a new link starts from the stationary law (bad with probability π). The long-run loss
///   fraction is π whatever the update times.
/// - Distance: lost with probability min(1, p₀ (ℓ/ℓ₀)²).
#[must_use]
pub fn lost(
    loss: &Loss,
    u: impl FnOnce() -> f64,
    k: u64,
    h: f64,
    length: f64,
    channel: &mut Option<(bool, u64)>,
) -> bool {
    match *loss {
        Loss::None => false,
        Loss::Bernoulli { p } => u() < p,
        Loss::Distance { p0, l0 } => u() < (p0 * (length / l0).powi(2)).min(1.0),
        Loss::GilbertElliott { p_fail, p_recover } => {
            let pi = p_fail / (p_fail + p_recover);
            let p_bad = match *channel {
                None => pi,
                Some((_, since)) if since == k => return channel.is_some_and(|c| c.0),
                Some((bad, since)) => {
                    let elapsed = (k - since) as f64 * h;
                    let relax = (-(p_fail + p_recover) * elapsed).exp();
                    if bad {
                        pi + (1.0 - pi) * relax
                    } else {
                        pi * (1.0 - relax)
                    }
                }
            };
            let bad = u() < p_bad;
            *channel = Some((bad, k));
            bad
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flock_math::stream::{Purpose, Streams};

    fn fraction(loss: &Loss, length: f64, gap: u64) -> f64 {
        let streams = Streams::new(3);
        let mut channel = None;
        let n = 20_000u64;
        let lost_count = (0..n)
            .filter(|&k| {
                let u = || streams.uniform(Purpose::Loss, 5, k * gap);
                lost(loss, u, k * gap, 0.1, length, &mut channel)
            })
            .count();
        lost_count as f64 / n as f64
    }

    #[test]
    fn distance_loss_grows_as_the_square_and_is_capped() {
        let loss = Loss::Distance { p0: 0.1, l0: 2.0 };
        assert!((fraction(&loss, 2.0, 1) - 0.1).abs() < 0.01);
        assert!((fraction(&loss, 4.0, 1) - 0.4).abs() < 0.02);
        assert_eq!(fraction(&loss, 7.0, 1), 1.0);
    }

    #[test]
    fn gilbert_elliott_keeps_its_stationary_fraction_at_any_update_interval() {
        let loss = Loss::GilbertElliott {
            p_fail: 1.0,
            p_recover: 3.0,
        };
        for gap in [1, 7, 100] {
            let f = fraction(&loss, 1.0, gap);
            assert!((f - 0.25).abs() < 0.03, "{gap}: {f}");
        }
    }
}

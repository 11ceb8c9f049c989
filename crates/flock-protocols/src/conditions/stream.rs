//! Keyed, counter-based randomness: every draw of a run is a function of one seed and of what it
//! is for — its [`Purpose`], the agent or link, and the step — never of the order in which the
//! draws are made. A run is therefore bit-identical for any thread count, any storage order of
//! the agents, and after an interruption and resume: no generator state is carried between steps.
//!
//! The generator is ChaCha8 (`chacha20::ChaCha8Rng`, the counter-based generator of the `rand`
//! family): the seed is its key, the purpose and index its 64-bit stream (nonce), and the step
//! its position in the stream ([`WORDS_PER_STEP`] 32-bit words per step).

use chacha20::ChaCha8Rng;
use flock_math::Vector;
use rand_core::{Rng, SeedableRng};
use rand_distr::{Distribution, StandardNormal, StandardUniform};

/// What a draw is for: the top 8 bits of its stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Purpose {
    /// The sensor noise of an agent.
    Sensing = 1,
    /// The jitter of a directed link's packet.
    Jitter = 2,
    /// The loss of a link's packet (directed, or of an unordered pair when symmetric).
    Loss = 3,
    /// Wind gusts (index 0 when shared, the agent when per agent).
    Wind = 4,
    /// The process noise of an agent.
    ProcessNoise = 5,
    /// An agent's random failure.
    Failure = 6,
    /// The noise of a model's own update (the angular noise of Vicsek 1995 and Couzin 2002).
    ModelNoise = 7,
    /// The order in which a sequential model activates its agents (index 0).
    Activation = 8,
}

/// 32-bit words of the stream reserved for each step of each key (512 `u64`s: far more than any
/// draw uses, so two steps' draws never overlap).
pub const WORDS_PER_STEP: u128 = 1 << 10;

/// The indices of a stream: the low 56 bits.
const INDEX_MASK: u64 = (1 << 56) - 1;

/// The streams of one run, from its seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Streams {
    seed: u64,
    /// The generator's key, `ChaCha8Rng::seed_from_u64(seed)`'s, expanded once.
    key: [u8; 32],
}

impl Streams {
    /// The streams of the run with scenario seed `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self {
            seed,
            key: ChaCha8Rng::seed_from_u64(seed).get_seed(),
        }
    }

    /// The seed.
    #[must_use]
    pub const fn seed(&self) -> u64 {
        self.seed
    }

    /// The draws for `purpose`, agent or link `index` (< 2⁵⁶) and `step`.
    #[must_use]
    pub fn draws(&self, purpose: Purpose, index: u64, step: u64) -> Draws {
        let mut rng = ChaCha8Rng::from_seed(self.key);
        rng.set_stream(((purpose as u64) << 56) | (index & INDEX_MASK));
        rng.set_word_pos(u128::from(step) * WORDS_PER_STEP);
        Draws(rng)
    }
}

/// The draws of one key, in the order they are taken.
#[derive(Debug)]
pub struct Draws(ChaCha8Rng);

impl Draws {
    /// A standard normal ξ ~ N(0, 1) (`rand_distr`'s ziggurat).
    #[inline]
    pub fn normal(&mut self) -> f64 {
        StandardNormal.sample(&mut self.0)
    }

    /// A vector of independent standard normals, one per coordinate.
    #[inline]
    pub fn normal_vector<V: Vector>(&mut self) -> V {
        V::from_fn(|_| self.normal())
    }

    /// A uniform number in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        StandardUniform.sample(&mut self.0)
    }

    /// A uniform whole number in [0, `n`] (`n` small: the modulo bias is below 2⁻⁴⁰).
    #[inline]
    pub fn up_to(&mut self, n: u64) -> u64 {
        self.0.next_u64() % (n + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_draw_depends_on_its_key_only() {
        let s = Streams::new(7);
        let a = s.draws(Purpose::Loss, 3, 10).normal();
        let _ = s.draws(Purpose::Loss, 4, 10).normal();
        assert_eq!(
            a.to_bits(),
            s.draws(Purpose::Loss, 3, 10).normal().to_bits()
        );
        assert_ne!(a, s.draws(Purpose::Loss, 3, 11).normal());
        assert_ne!(a, s.draws(Purpose::Jitter, 3, 10).normal());
        assert_ne!(a, Streams::new(8).draws(Purpose::Loss, 3, 10).normal());
    }

    #[test]
    fn uniforms_across_keys_are_uniform() {
        // the per-agent, per-step draws of random failures: P(u < p) = p
        let s = Streams::new(42);
        let (agents, steps, p) = (500u64, 400u64, 0.01);
        let hits = (0..agents)
            .flat_map(|i| (0..steps).map(move |k| (i, k)))
            .filter(|&(i, k)| s.draws(Purpose::Failure, i, k).uniform() < p)
            .count() as f64;
        let expected = (agents * steps) as f64 * p;
        assert!(
            (hits - expected).abs() < 4.0 * expected.sqrt(),
            "{hits} vs {expected}"
        );
    }

    #[test]
    fn normals_have_unit_variance() {
        let s = Streams::new(1);
        let n = 20_000;
        let var = (0..n)
            .map(|k| s.draws(Purpose::Sensing, 0, k).normal().powi(2))
            .sum::<f64>()
            / n as f64;
        assert!((var - 1.0).abs() < 0.05, "{var}");
    }
}

//! Keyed, counter-based randomness: every draw of a run is a function of one seed and of what it
//! is for — its [`Purpose`], the agent or link, and the step — never of the order in which the
//! draws are made. A run is therefore bit-identical for any thread count, any storage order of
//! the agents, and after an interruption and resume: no generator state is carried between steps.
//!
//! The generator is Philox4x32-10 (Salmon, Moraes, Dror & Shaw, "Parallel random numbers: as
//! easy as 1, 2, 3", SC'11; the block function of `rand_philox`, pinned by Random123's
//! known-answer vectors), made for keyed draws: a block of 128 bits is a bijection of a 128-bit
//! counter under a 64-bit key, with nothing to set up. The key is `splitmix64(seed)`; the counter
//! is (purpose, index, step, block) ([`counter`]). A block gives two `u64`, i.e. two uniforms
//! or, by the ziggurat, two normals: a draw computes only the blocks it takes from, and uses
//! every word of them but for an odd last one. The packets a receiver gets at a step take one
//! 32-bit word each of the receiver's blocks ([`Streams::link_words`]), four to a block.

use core::convert::Infallible;

use crate::Vector;
use rand_distr::{Distribution, StandardNormal};
use rand_philox::{philox4x32_10, splitmix64};

/// What a draw is for: the top 8 bits of its counter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Purpose {
    /// The sensor noise of an agent.
    Sensing = 1,
    /// The jitter of a packet (the receiver's words, [`Streams::link_words`]).
    Jitter = 2,
    /// The loss of a packet (the receiver's words, [`Streams::link_words`]; the unordered pair's
    /// draw when losses are symmetric).
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

/// The low 56 bits of a counter's index: an agent, or an unordered pair i n + j (i < j).
const INDEX_BITS: u32 = 56;
/// The low 48 bits of a counter's step (2⁴⁸ steps: 89,000 years at h = 0.01 s).
const STEP_BITS: u32 = 48;
/// The blocks a key may draw from (2¹⁶, far more than any draw takes: at most 3).
const BLOCK_BITS: u32 = 16;

/// The 128-bit Philox counter of block `block` of the draws for (`purpose`, `index`, `step`):
/// purpose in bits 120–127, index in 64–119, step in 16–63, block in 0–15, as four
/// little-endian 32-bit words.
#[must_use]
pub fn counter(purpose: Purpose, index: u64, step: u64, block: u16) -> [u32; 4] {
    let mask = |bits: u32| (1u64 << bits) - 1;
    let high = ((purpose as u64) << INDEX_BITS) | (index & mask(INDEX_BITS));
    let low = ((step & mask(STEP_BITS)) << BLOCK_BITS) | u64::from(block);
    [
        low as u32,
        (low >> 32) as u32,
        high as u32,
        (high >> 32) as u32,
    ]
}

/// The streams of one run, from its seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Streams {
    seed: u64,
    /// The Philox key, `splitmix64(seed)` as two 32-bit words (low first).
    key: [u32; 2],
}

impl Streams {
    /// The streams of the run with scenario seed `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        let k = splitmix64(seed);
        Self {
            seed,
            key: [k as u32, (k >> 32) as u32],
        }
    }

    /// The seed.
    #[must_use]
    pub const fn seed(&self) -> u64 {
        self.seed
    }

    /// The draws for `purpose`, agent or link `index` (< 2⁵⁶) and `step` (< 2⁴⁸). Nothing is
    /// computed until a draw is taken.
    #[inline]
    #[must_use]
    pub fn draws(&self, purpose: Purpose, index: u64, step: u64) -> Draws {
        Draws {
            key: self.key,
            counter: counter(purpose, index, step, 0),
            words: [0; 2],
            taken: 2,
        }
    }

    /// The first uniform of the draws for (`purpose`, `index`, `step`): the bits of
    /// `self.draws(purpose, index, step).uniform()`, from the block computed in place.
    #[inline]
    #[must_use]
    pub fn uniform(&self, purpose: Purpose, index: u64, step: u64) -> f64 {
        uniform(block(counter(purpose, index, step, 0), self.key)[0])
    }

    /// The words of the draws of the links into each of `receivers`, given as (receiver,
    /// candidate count), at `step` for `purpose` (packet loss, jitter), appended to `words`
    /// receiver after receiver, each taking [`link_word_count`] words: the link from a receiver's m-th
    /// candidate sender, in ascending order of the senders' indices, takes 32-bit word m of the
    /// blocks (purpose, receiver, step, 0), (…, 1), …, four words a block. A receiver with 6
    /// candidates computes 2 blocks where one block per directed link would compute 6 and use
    /// half of each. The words of a step are fresh for every link, so a link's draws are
    /// independent across links and steps whatever the candidates; they are keyed by purpose,
    /// receiver, step and the sender's place among the receiver's candidates, which depends on
    /// the agents' indices only (not on threads or storage order). A count above the candidates
    /// finally heard only computes more words: those of the first candidates are the same.
    ///
    /// The blocks of all the receivers are computed in runs before any is used, side by side
    /// (`blocks_in_place`).
    pub fn link_words(
        &self,
        purpose: Purpose,
        step: u64,
        receivers: impl IntoIterator<Item = (u64, usize)>,
        words: &mut Vec<u32>,
    ) {
        // each block's counter first, in the place of its words; then the blocks, one loop
        let start = words.len();
        for (receiver, count) in receivers {
            let first = counter(purpose, receiver, step, 0);
            for block in 0..link_word_count(count) / 4 {
                debug_assert!(block < 1 << BLOCK_BITS, "2¹⁶ blocks drawn");
                let mut counter = first;
                counter[0] |= block as u32;
                words.extend(counter);
            }
        }
        let (blocks, _) = words[start..].as_chunks_mut::<4>();
        for run in blocks.chunks_mut(RUN) {
            blocks_in_place(run, self.key);
        }
    }
}

/// The words [`Streams::link_words`] gives a receiver with `count` candidates: 4 ⌈count / 4⌉,
/// whole Philox blocks of four words.
#[inline]
#[must_use]
pub fn link_word_count(count: usize) -> usize {
    4 * count.div_ceil(4)
}

/// The blocks [`blocks_in_place`] computes in one run.
const RUN: usize = 64;

/// Each of `blocks` (at most [`RUN`]), a counter on entry, replaced by its Philox block under
/// `key`. The counters are laid out word by word (four arrays of `blocks.len()` words) so that
/// the compiler runs the lanes of the block function side by side in vector registers: a block
/// is a chain of 10 dependent rounds, 15 ns one block after the other and 8.3 ns side by side
/// (docs/performance.md, "The link words side by side").
#[inline]
fn blocks_in_place(blocks: &mut [[u32; 4]], key: [u32; 2]) {
    debug_assert!(blocks.len() <= RUN, "at most {RUN} blocks a run");
    let mut lanes = [[0u32; RUN]; 4];
    for (l, block) in blocks.iter().enumerate() {
        for (lane, &word) in lanes.iter_mut().zip(block) {
            lane[l] = word;
        }
    }
    let [c0, c1, c2, c3] = &mut lanes;
    for l in 0..blocks.len() {
        [c0[l], c1[l], c2[l], c3[l]] = philox4x32_10([c0[l], c1[l], c2[l], c3[l]], key);
    }
    for (l, block) in blocks.iter_mut().enumerate() {
        for (word, lane) in block.iter_mut().zip(&lanes) {
            *word = lane[l];
        }
    }
}

/// A uniform number in [0, 1) from a 32-bit word of [`Streams::link_words`]: the word times
/// 2⁻³² (a loss probability is resolved to 2.3·10⁻¹⁰).
#[inline]
#[must_use]
pub fn word_uniform(word: u32) -> f64 {
    f64::from(word) * (1.0 / 4_294_967_296.0)
}

/// A uniform whole number in [0, `n`] from a 32-bit word of [`Streams::link_words`], by
/// Lemire's multiply and shift ⌊w (n + 1) / 2³²⌋ (Lemire, ACM TOMACS 29(1), 2019, without the
/// rejection step: each value's probability is off by at most 2⁻³², relatively (n + 1) 2⁻³²).
#[inline]
#[must_use]
pub fn word_up_to(word: u32, n: u64) -> u64 {
    ((u128::from(word) * (u128::from(n) + 1)) >> 32) as u64
}

/// The Philox block of `counter` under `key` as two `u64`, low word first.
///
/// The block function is not inlined (10 rounds) and leaves its four words in memory by 32-bit
/// stores; a `u64` read of two of them cannot be forwarded from those stores and stalls the
/// load (≈ 12 cycles: 8 % of the conditioned step). Each word is therefore taken alone
/// (`black_box` keeps the compiler from merging the two reads into one).
#[inline]
fn block(counter: [u32; 4], key: [u32; 2]) -> [u64; 2] {
    let words = philox4x32_10(counter, key).map(core::hint::black_box);
    [
        u64::from(words[0]) | (u64::from(words[1]) << 32),
        u64::from(words[2]) | (u64::from(words[3]) << 32),
    ]
}

/// A uniform number in [0, 1) from a word: its top 53 bits, times 2⁻⁵³.
#[inline]
fn uniform(word: u64) -> f64 {
    (word >> 11) as f64 * (f64::EPSILON / 2.0)
}

/// The draws of one key, in the order they are taken: `u64` words two by two from the blocks
/// (purpose, index, step, 0), (…, 1), …
#[derive(Debug)]
pub struct Draws {
    key: [u32; 2],
    /// The counter of the next block to compute (its block number in word 0).
    counter: [u32; 4],
    /// The current block as two `u64` (low word first).
    words: [u64; 2],
    /// The words of `words` already taken (2: none left).
    taken: usize,
}

impl Draws {
    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        if self.taken >= 2 {
            debug_assert!(self.counter[0] & 0xffff != 0xffff, "2¹⁶ blocks drawn");
            self.words = block(self.counter, self.key);
            self.counter[0] += 1;
            self.taken = 0;
        }
        self.taken += 1;
        self.words[self.taken - 1]
    }

    /// A uniform number in [0, 1): the top 53 bits of a word, times 2⁻⁵³.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        uniform(self.next_u64())
    }

    /// A standard normal ξ ~ N(0, 1) by the ziggurat of `rand_distr`'s `StandardNormal`
    /// (Marsaglia & Tsang, J. Stat. Softw. 5(8), 2000, with Doornik's improvement, 2005): one
    /// word per normal but in 1.5 % of draws (the wedges and the tail take more), no logarithm
    /// or sine on the common path.
    #[inline]
    pub fn normal(&mut self) -> f64 {
        StandardNormal.sample(self)
    }

    /// A vector of independent standard normals, one per coordinate.
    #[inline]
    pub fn normal_vector<V: Vector>(&mut self) -> V {
        V::from_fn(|_| self.normal())
    }

    /// A uniform whole number in [0, `n`] (`n` small: the modulo bias is below 2⁻⁴⁰).
    #[inline]
    pub fn up_to(&mut self, n: u64) -> u64 {
        self.next_u64() % (n + 1)
    }
}

/// The words of the draws as a `rand` generator, for `rand_distr`'s distributions.
impl rand_core::TryRng for Draws {
    type Error = Infallible;

    #[inline]
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.next_u64() >> 32) as u32)
    }

    #[inline]
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        Ok(self.next_u64())
    }

    #[inline]
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(8) {
            let bytes = self.next_u64().to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_block_function_gives_random123s_known_answers() {
        // Random123's published known-answer vectors for philox4x32_10 (kat_vectors)
        let kat = [
            (
                [0; 4],
                [0; 2],
                [0x6627_e8d5, 0xe169_c58d, 0xbc57_ac4c, 0x9b00_dbd8],
            ),
            (
                [0xffff_ffff; 4],
                [0xffff_ffff; 2],
                [0x408f_276d, 0x41c8_3b0e, 0xa20b_c7c6, 0x6d54_51fd],
            ),
            (
                [0x243f_6a88, 0x85a3_08d3, 0x1319_8a2e, 0x0370_7344],
                [0xa409_3822, 0x299f_31d0],
                [0xd16c_fe09, 0x94fd_cceb, 0x5001_e420, 0x2412_6ea1],
            ),
        ];
        for (ctr, key, out) in kat {
            assert_eq!(philox4x32_10(ctr, key), out);
        }
    }

    #[test]
    fn a_draw_takes_the_words_of_its_own_counters_in_order() {
        let s = Streams::new(5);
        let k = splitmix64(5);
        let key = [k as u32, (k >> 32) as u32];
        let word = |block: u16, w: usize| {
            let b = philox4x32_10(counter(Purpose::Jitter, 9, 77, block), key);
            u64::from(b[2 * w]) | (u64::from(b[2 * w + 1]) << 32)
        };
        let mut d = s.draws(Purpose::Jitter, 9, 77);
        let taken: Vec<u64> = (0..5).map(|_| d.next_u64()).collect();
        let expected = [word(0, 0), word(0, 1), word(1, 0), word(1, 1), word(2, 0)];
        assert_eq!(taken, expected);
        // purpose, index, step and block each have their own bits
        assert_eq!(
            counter(Purpose::Loss, (1 << 56) - 1, (1 << 48) - 1, 0xffff),
            [0xffff_ffff, 0xffff_ffff, 0xffff_ffff, 0x03ff_ffff]
        );
        assert_eq!(
            counter(Purpose::Sensing, 0, 1, 2),
            [0x0001_0002, 0, 0, 1 << 24]
        );
    }

    #[test]
    fn a_receivers_link_words_are_its_blocks_words_in_order() {
        let s = Streams::new(5);
        let k = splitmix64(5);
        let key = [k as u32, (k >> 32) as u32];
        let block =
            |receiver: u64, b: u16| philox4x32_10(counter(Purpose::Loss, receiver, 77, b), key);
        let mut words = vec![1, 2, 3];
        s.link_words(Purpose::Loss, 77, [(9, 0)], &mut words);
        assert_eq!(words, [1, 2, 3], "no candidate, no block; appended");
        for (count, blocks) in [(1, 1), (4, 1), (5, 2), (8, 2), (9, 3)] {
            words.clear();
            s.link_words(Purpose::Loss, 77, [(9, count)], &mut words);
            let expected: Vec<u32> = (0..blocks).flat_map(|b| block(9, b)).collect();
            assert_eq!(words, expected, "{count} candidates take {blocks} blocks");
        }
        // several receivers: each one's words in turn, link_word_count of them
        words.clear();
        s.link_words(Purpose::Loss, 77, [(9, 5), (3, 0), (12, 4)], &mut words);
        let expected: Vec<u32> = [(9, 0), (9, 1), (12, 0)]
            .into_iter()
            .flat_map(|(r, b)| block(r, b))
            .collect();
        assert_eq!(words, expected);
        // another receiver, step or purpose has other words
        words.clear();
        s.link_words(Purpose::Loss, 77, [(9, 9)], &mut words);
        for (purpose, receiver, step) in [
            (Purpose::Loss, 10, 77),
            (Purpose::Loss, 9, 78),
            (Purpose::Jitter, 9, 77),
        ] {
            let mut other = Vec::new();
            s.link_words(purpose, step, [(receiver, 9)], &mut other);
            assert_ne!(other, words);
        }
    }

    #[test]
    fn word_uniforms_and_whole_numbers_are_uniform_on_their_ranges() {
        assert_eq!(word_uniform(0), 0.0);
        assert!(word_uniform(u32::MAX) < 1.0);
        assert_eq!(word_uniform(1 << 31), 0.5);
        // Lemire's map sends [0, 2³²) onto [0, n] in n + 1 runs of equal length (± 1)
        assert_eq!(word_up_to(0, 3), 0);
        assert_eq!(word_up_to(u32::MAX, 3), 3);
        assert_eq!(word_up_to(u32::MAX, 0), 0);
        let s = Streams::new(17);
        let (n, receivers) = (4u64, 5_000u64);
        let mut words = Vec::new();
        let mut counts = [0usize; 5];
        let mut below = 0usize;
        for i in 0..receivers {
            words.clear();
            s.link_words(Purpose::Jitter, 3, [(i, 8)], &mut words);
            for &w in &words {
                counts[word_up_to(w, n) as usize] += 1;
                below += usize::from(word_uniform(w) < 0.1);
            }
        }
        let draws = (8 * receivers) as f64;
        for c in counts {
            let (p, se) = (0.2, (0.2 * 0.8 / draws).sqrt());
            assert!((c as f64 / draws - p).abs() < 4.0 * se, "{counts:?}");
        }
        let se = (0.1 * 0.9 / draws).sqrt();
        assert!((below as f64 / draws - 0.1).abs() < 4.0 * se, "{below}");
    }

    #[test]
    fn a_normal_takes_one_word_but_in_the_ziggurats_rare_cases() {
        // the word after a normal is the second of the block when the normal took one word:
        // the ziggurat's rectangles accept a first word with probability (1/256) Σ x_{i+1}/x_i
        // = 0.98508 over rand_distr's 256 layers (Marsaglia & Tsang 2000)
        let s = Streams::new(3);
        let keys = 20_000u64;
        let one_word = (0..keys)
            .filter(|&k| {
                let mut d = s.draws(Purpose::Sensing, 1, k);
                d.normal();
                let next = d.next_u64();
                let mut words = s.draws(Purpose::Sensing, 1, k);
                words.next_u64();
                next == words.next_u64()
            })
            .count() as f64
            / keys as f64;
        let (p, se) = (0.985_08, (0.985_08 * 0.014_92 / keys as f64).sqrt());
        assert!((one_word - p).abs() < 4.0 * se, "{one_word}");
        // and a normal is a function of its key's words only
        let a = s.draws(Purpose::Sensing, 1, 2).normal();
        assert_eq!(
            a.to_bits(),
            s.draws(Purpose::Sensing, 1, 2).normal().to_bits()
        );
    }

    #[test]
    fn a_single_uniform_is_the_first_of_its_draws() {
        let s = Streams::new(11);
        for (purpose, index, step) in [(Purpose::Loss, 0, 0), (Purpose::Failure, 1 << 40, 12345)] {
            let mut d = s.draws(purpose, index, step);
            let (first, second) = (d.uniform(), d.uniform());
            assert_eq!(s.uniform(purpose, index, step).to_bits(), first.to_bits());
            assert_ne!(first, second);
        }
    }

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
    fn normals_have_the_moments_and_tails_of_the_standard_law() {
        // both normals of each pair, across steps: mean 0, variance 1, kurtosis 3, and
        // P(|ξ| > 2) = 0.0455, each within 4 standard errors; the pair is uncorrelated
        let s = Streams::new(1);
        let pairs: Vec<(f64, f64)> = (0..50_000)
            .map(|k| {
                let mut d = s.draws(Purpose::Sensing, 0, k);
                (d.normal(), d.normal())
            })
            .collect();
        let xs: Vec<f64> = pairs.iter().flat_map(|&(a, b)| [a, b]).collect();
        let n = xs.len() as f64;
        let moment = |p: i32| xs.iter().map(|x| x.powi(p)).sum::<f64>() / n;
        assert!(moment(1).abs() < 4.0 / n.sqrt(), "{}", moment(1));
        assert!((moment(2) - 1.0).abs() < 4.0 * 2f64.sqrt() / n.sqrt());
        assert!((moment(4) - 3.0).abs() < 4.0 * 96f64.sqrt() / n.sqrt());
        let tail = xs.iter().filter(|x| x.abs() > 2.0).count() as f64 / n;
        let p = 0.045_500_263_896_358_42;
        assert!(
            (tail - p).abs() < 4.0 * (p * (1.0 - p) / n).sqrt(),
            "{tail}"
        );
        let m = pairs.len() as f64;
        let r = pairs.iter().map(|(a, b)| a * b).sum::<f64>() / m;
        assert!(r.abs() < 4.0 / m.sqrt(), "{r}");
    }
}

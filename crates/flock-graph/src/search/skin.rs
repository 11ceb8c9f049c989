//! [`Skin`]: when [`NeighbourSearch`](crate::NeighbourSearch) may keep its lists from one build to
//! the next (Verlet lists: L. Verlet, Phys. Rev. 159, 98 (1967), the "skin" of molecular
//! dynamics' neighbour lists).
//!
//! A full build lists, for each agent, the agents within r_s = (1 + [`SKIN`]) · r, each list in
//! the net's order. While no agent has moved more than half the skin, (r_s − r)/2, from where it
//! was at that build, every pair now within r was within r_s then (the triangle inequality), so
//! the net is those lists with the pairs beyond r left out: the same predicate on the same
//! squared length, the same order, hence the same net, bit for bit, as a full build. Whether the
//! lists are kept changes the time of a build, never its net.

/// The skin as a fraction of the range: lists are built out to (1 + `SKIN`) · r.
pub(crate) const SKIN: f64 = 0.1;

/// Fewer builds than this from one set of lists, and the skin did not pay for its wider
/// candidate scan: the next [`SKINLESS_BUILDS`] builds go without it.
const MIN_REUSES: u32 = 2;

/// Builds without a skin after it did not pay (agents that move a large part of r per build).
const SKINLESS_BUILDS: u32 = 32;

/// The safety factor on the allowed displacement: 2⁻²⁰ of half the skin absorbs the rounding of
/// the squared lengths (a few ulps, relative) for any skin above ≈ 10⁻⁹ · r.
const MARGIN: f64 = 1.0 - 1.0 / (1u64 << 20) as f64;

/// What the last full build kept, and whether the next build may reuse it.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Skin {
    /// The lists kept, if any.
    kept: Option<Kept>,
    /// Builds left without a skin.
    skinless: u32,
}

/// The build whose lists are kept.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Kept {
    /// Agents.
    pub(crate) n: usize,
    /// The range of the nets the lists serve.
    pub(crate) r: f64,
    /// The stamp of the numbering the lists are ordered by.
    pub(crate) stamp: u64,
    /// log₂ of the slots per block of lists.
    pub(crate) block_shift: u32,
    /// The largest squared displacement an agent may have since the build.
    pub(crate) limit: f64,
    /// Builds served by the lists.
    reuses: u32,
}

impl Skin {
    /// The kept lists, when they were built for `n` agents, range `r`, the numbering of `stamp`
    /// and blocks of 2^`block_shift` slots (the caller must still check the displacements).
    pub(crate) fn kept_for(&self, n: usize, r: f64, stamp: u64, block_shift: u32) -> Option<Kept> {
        self.kept.filter(|kept| {
            kept.n == n
                && kept.r.to_bits() == r.to_bits()
                && kept.stamp == stamp
                && kept.block_shift == block_shift
        })
    }

    /// Counts one more build served by the kept lists.
    pub(crate) fn reused(&mut self) {
        if let Some(kept) = self.kept.as_mut() {
            kept.reuses += 1;
        }
    }

    /// Forgets the kept lists, which agents have moved too far from: if they served fewer than
    /// [`MIN_REUSES`] builds, the skin is turned off for [`SKINLESS_BUILDS`].
    pub(crate) fn outgrown(&mut self) {
        if let Some(kept) = self.kept.take()
            && kept.reuses < MIN_REUSES
        {
            self.skinless = SKINLESS_BUILDS;
        }
    }

    /// The reach of the next full build for range `r`: r · (1 + [`SKIN`]), or r itself while
    /// the skin is off (or when the wider reach is not a finite number above r).
    pub(crate) fn reach_for_build(&mut self, r: f64) -> f64 {
        self.kept = None;
        if self.skinless > 0 {
            self.skinless -= 1;
            return r;
        }
        let reach = r * (1.0 + SKIN);
        if reach.is_finite() && reach > r {
            reach
        } else {
            r
        }
    }

    /// Keeps the lists of a full build with `reach` above `r` (a build without a skin keeps
    /// none).
    pub(crate) fn built(&mut self, n: usize, r: f64, reach: f64, stamp: u64, block_shift: u32) {
        self.kept = (reach > r).then(|| {
            let half = 0.5 * (reach - r) * MARGIN;
            Kept {
                n,
                r,
                stamp,
                block_shift,
                limit: half * half,
                reuses: 0,
            }
        });
    }

    /// Whether the last build kept its lists (they reach beyond the range).
    pub(crate) fn has_kept(&self) -> bool {
        self.kept.is_some()
    }

    /// The builds the kept lists served, `None` when none are kept.
    #[cfg(test)]
    pub(crate) fn reuses(&self) -> Option<u32> {
        self.kept.map(|kept| kept.reuses)
    }

    /// Forgets the kept lists (the grid they were built on was rebuilt for something else).
    pub(crate) fn forget(&mut self) {
        self.kept = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The skin is turned off when agents outgrow lists that served fewer than two builds, for
    /// 32 builds, and tried again after them; lists that no longer apply leave it on; a range
    /// whose skin overflows goes without.
    #[test]
    fn a_skin_that_does_not_pay_is_turned_off_for_a_while() {
        let mut skin = Skin::default();
        assert_eq!(skin.reach_for_build(1.0), 1.0 + SKIN);
        skin.built(10, 1.0, 1.0 + SKIN, 0, 10);
        assert!(skin.kept_for(10, 1.0, 0, 10).is_some());
        assert!(skin.kept_for(11, 1.0, 0, 10).is_none());
        assert!(skin.kept_for(10, 1.5, 0, 10).is_none());
        assert!(skin.kept_for(10, 1.0, 3, 10).is_none());
        assert!(skin.kept_for(10, 1.0, 0, 9).is_none());
        skin.reused();
        // one reuse only: off
        skin.outgrown();
        for _ in 0..SKINLESS_BUILDS {
            assert_eq!(skin.reach_for_build(1.0), 1.0);
            skin.built(10, 1.0, 1.0, 0, 10);
            assert!(skin.kept_for(10, 1.0, 0, 10).is_none());
        }
        assert_eq!(skin.reach_for_build(1.0), 1.0 + SKIN);
        skin.built(10, 1.0, 1.0 + SKIN, 0, 10);
        skin.reused();
        skin.reused();
        // two reuses: kept on
        skin.outgrown();
        assert_eq!(skin.reach_for_build(1.0), 1.0 + SKIN);
        // lists that no longer apply (another range): the skin stays on
        skin.built(10, 1.0, 1.0 + SKIN, 0, 10);
        assert_eq!(skin.reach_for_build(2.0), 2.0 * (1.0 + SKIN));
        assert_eq!(skin.reach_for_build(f64::MAX), f64::MAX);
        assert_eq!(skin.reach_for_build(f64::INFINITY), f64::INFINITY);
    }

    /// The allowed displacement is half the skin, less the margin: below (0.05 r)², above
    /// (0.05 r)² (1 − 2⁻¹⁸).
    #[test]
    fn agents_may_move_half_the_skin() {
        let mut skin = Skin::default();
        let r = 8.4;
        let reach = skin.reach_for_build(r);
        skin.built(5, r, reach, 1, 10);
        let limit = skin.kept_for(5, r, 1, 10).map(|k| k.limit).unwrap();
        let half = 0.5 * (reach - r);
        assert!(limit < half * half && limit > half * half * (1.0 - 1.0 / f64::from(1 << 18)));
    }
}

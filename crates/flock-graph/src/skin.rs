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
    use crate::{NeighbourSearch, ProximityNet};
    use glam::{DVec2, DVec3};
    use rand::{RngExt, SeedableRng};

    /// The allowed displacement of lists built for range `r`: √limit.
    fn allowed(r: f64) -> f64 {
        let mut skin = Skin::default();
        let reach = skin.reach_for_build(r);
        skin.built(2, r, reach, 0, 10);
        skin.kept_for(2, r, 0, 10)
            .map(|kept| kept.limit.sqrt())
            .unwrap()
    }

    /// Every agent moved by exactly `step` in a direction of its own.
    fn moved<V: glam_like::Drawn>(q: &[V], step: f64, rng: &mut rand_pcg::Pcg64) -> Vec<V> {
        q.iter().map(|&x| x.moved(step, rng)).collect()
    }

    mod glam_like {
        use flock_math::Vector;
        use rand::RngExt;

        /// A point moved by a given length in a direction drawn uniformly.
        pub(super) trait Drawn: Vector {
            fn moved(self, step: f64, rng: &mut rand_pcg::Pcg64) -> Self {
                let direction = loop {
                    let v = Self::from_fn(|_| rng.random::<f64>() * 2.0 - 1.0);
                    let l2 = v.length_squared();
                    if l2 > 1e-6 && l2 <= 1.0 {
                        break v * (1.0 / l2.sqrt());
                    }
                };
                self + direction * step
            }
        }

        impl Drawn for glam::DVec2 {}
        impl Drawn for glam::DVec3 {}
    }

    /// Agents moved by as much as the skin allows, at every build, a dense cloud in 2D and 3D:
    /// each net is the brute-force net, with and without distances, while the lists built at
    /// the first serve the next ones; a move just beyond the allowance rebuilds them. Lists kept
    /// for a wider allowance (the whole skin) would miss pairs: checked.
    fn kept_lists_serve_moving_agents<V: glam_like::Drawn>(side: f64) {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(23);
        let r = 1.0;
        let step = allowed(r);
        let mut q: Vec<V> = (0..3000)
            .map(|_| V::from_fn(|_| rng.random::<f64>() * side))
            .collect();
        let mut search = NeighbourSearch::new();
        let (mut full, mut lean) = (ProximityNet::new(), ProximityNet::without_distances());
        search.build(&q, r, &mut full);
        let start = q.clone();
        let mut missed = 0;
        for build in 1..=3 {
            // each agent within `step` of the start (a part in 10¹² less, for the rounding of
            // the move): the lists of the start serve
            q = moved(&start, step * (1.0 - 1e-12), &mut rng);
            search.build(&q, r, &mut full);
            assert_eq!(search.skin.reuses(), Some(2 * build - 1), "build {build}");
            assert!(full == ProximityNet::brute_force(&q, r), "build {build}");
            search.build(&q, r, &mut lean);
            assert_eq!(lean.graph(), full.graph());
            // twice the allowance from the start: the start's lists miss pairs
            let far = moved(&start, 2.0 * step, &mut rng);
            let net = ProximityNet::brute_force(&far, r);
            missed += (0..far.len())
                .flat_map(|i| {
                    net.graph()
                        .neighbours(i)
                        .iter()
                        .map(move |&j| (i, j as usize))
                })
                .filter(|&(i, j)| {
                    (start[j] - start[i]).length_squared() >= (r + 2.0 * step).powi(2)
                })
                .count();
        }
        assert!(missed > 0, "the test wants pairs the skin could miss");
        // one agent a hair beyond the allowance: a new build
        q = start.clone();
        q[7] = q[7].moved(step * (1.0 + 1e-9), &mut rng);
        search.build(&q, r, &mut full);
        assert_eq!(search.skin.reuses(), Some(0));
        assert!(full == ProximityNet::brute_force(&q, r));
    }

    #[test]
    fn kept_lists_serve_moving_agents_2d() {
        kept_lists_serve_moving_agents::<DVec2>(30.0);
    }

    #[test]
    fn kept_lists_serve_moving_agents_3d() {
        kept_lists_serve_moving_agents::<DVec3>(8.0);
    }

    /// A search whose lists for `q` and `r` served two builds, and its net.
    fn warm(q: &[DVec2], r: f64) -> (NeighbourSearch, ProximityNet) {
        let mut search = NeighbourSearch::new();
        let mut net = ProximityNet::new();
        for _ in 0..3 {
            search.build(q, r, &mut net);
        }
        assert_eq!(search.skin.reuses(), Some(2));
        (search, net)
    }

    /// Lists are not reused across a new numbering, another range or number of agents, an agent
    /// that entered the finite positions, or a grid rebuilt for another use: each is a new
    /// build, with the skin kept on.
    #[test]
    fn kept_lists_are_rebuilt_when_they_no_longer_apply() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let r = 1.0;
        let mut q: Vec<DVec2> = (0..2000)
            .map(|_| DVec2::new(rng.random::<f64>() * 25.0, rng.random::<f64>() * 25.0))
            .collect();
        let built_anew = |search: &NeighbourSearch| search.skin.reuses() == Some(0);
        // another range
        let (mut search, mut net) = warm(&q, r);
        search.build(&q, 0.9, &mut net);
        assert!(built_anew(&search));
        assert!(net == ProximityNet::brute_force(&q, 0.9));
        // one agent fewer, the others where they were
        let (mut search, mut net) = warm(&q, r);
        search.build(&q[..q.len() - 1], r, &mut net);
        assert!(built_anew(&search));
        // the grid rebuilt for a cell order
        let (mut search, mut net) = warm(&q, r);
        search.cell_order(&q, r);
        search.build(&q, r, &mut net);
        assert!(built_anew(&search));
        // an agent found again where it was lost
        let kept = q[3];
        q[3] = DVec2::NAN;
        let (mut search, mut net) = warm(&q, r);
        q[3] = kept;
        search.build(&q, r, &mut net);
        assert!(built_anew(&search));
        assert!(net == ProximityNet::brute_force(&q, r));
        // two agents a hair apart swap their storage: within the allowance, but the numbering
        // changed, and the lists are ordered by the old one
        let (a, b) = (10, 11);
        q[b] = q[a] + DVec2::new(1e-9, 0.0);
        let original = ProximityNet::brute_force(&q, r);
        let (mut search, mut net) = warm(&q, r);
        let mut order: Vec<u32> = (0..q.len() as u32).collect();
        order.swap(a, b);
        q.swap(a, b);
        net.permute(&order);
        search.build(&q, r, &mut net);
        assert!(built_anew(&search));
        // each list names the original net's agents in the original net's order
        for s in 0..q.len() {
            let k = net.numbering().original(s);
            assert_eq!(
                net.named_neighbours(s),
                original.graph().neighbours(k),
                "agent {s}"
            );
        }
    }

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

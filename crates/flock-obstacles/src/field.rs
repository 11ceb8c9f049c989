//! [`ObstacleField`]: many obstacles, culled by their bounding boxes.

use crate::bvh::Bvh;
use crate::{BetaAgent, Obstacle, ObstacleError, ObstacleSpec, Space};

/// Relative padding of the bounding boxes (times `1 +` their largest coordinate), so that rounding
/// in parry's boxes and projections never culls an obstacle that a loop over all of them keeps.
const BOX_PADDING: f64 = 1e-9;

/// The obstacles `O_1, …, O_n` of a scenario, with a bounding-volume hierarchy over their bounding
/// boxes: the queries of an α-agent at `q` cost `O(log n)` plus the obstacles whose boxes are near
/// `q`, not `O(n)`. Unbounded obstacles (walls) are kept in a list that every query checks.
///
/// Results are deterministic: lists are in increasing obstacle index, and each entry is exactly
/// what [`Obstacle::beta_agent`] returns, the same as a loop over all the obstacles.
///
/// # Example
/// ```
/// use flock_obstacles::{ObstacleField, ObstacleSpec};
/// use glam::DVec2;
///
/// let field = ObstacleField::<DVec2>::from_specs(&[
///     ObstacleSpec::Ball { centre: vec![10.0, 0.0], radius: 2.0 },
///     ObstacleSpec::Wall { point: vec![0.0, -5.0], normal: vec![0.0, 1.0] },
///     ObstacleSpec::Ball { centre: vec![100.0, 0.0], radius: 2.0 },
/// ])?;
/// let mut betas = Vec::new();
/// field.beta_agents(DVec2::new(5.0, 0.0), DVec2::X, 6.0, &mut betas);
/// let near: Vec<usize> = betas.iter().map(|(k, _)| *k).collect();
/// assert_eq!(near, [0, 1]); // the far ball is culled
/// assert_eq!(betas[0].1.distance, 3.0);
/// assert_eq!(field.clearance(DVec2::new(5.0, 0.0)), 3.0);
/// assert_eq!(field.clearance(DVec2::new(10.0, 1.0)), -1.0); // inside ball 0
/// assert_eq!(field.containing(DVec2::new(10.0, 1.0)), Some(0));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct ObstacleField<V: Space> {
    obstacles: Vec<V::Obstacle>,
    /// The indices of the obstacles without a bounding box, increasing.
    unbounded: Vec<usize>,
    bvh: Bvh<V>,
}

impl<V: Space> ObstacleField<V> {
    /// The field of `obstacles`, indexed in the order given.
    #[must_use]
    pub fn new(obstacles: Vec<V::Obstacle>) -> Self {
        let mut unbounded = Vec::new();
        let mut boxes = Vec::with_capacity(obstacles.len());
        for (k, obstacle) in obstacles.iter().enumerate() {
            match obstacle.aabb() {
                Some((min, max)) => {
                    let largest = (0..V::DIM)
                        .map(|axis| min.coord(axis).abs().max(max.coord(axis).abs()))
                        .fold(0.0, f64::max);
                    let pad = V::from_fn(|_| BOX_PADDING * (1.0 + largest));
                    boxes.push((k, min - pad, max + pad));
                }
                None => unbounded.push(k),
            }
        }
        Self {
            obstacles,
            unbounded,
            bvh: Bvh::new(boxes),
        }
    }

    /// The field of the obstacles `specs` describe, validated.
    ///
    /// # Errors
    /// The first invalid description's [`ObstacleError`], wrapped by
    /// [`ObstacleError::at`]`(k)` so that its field path and message start with `obstacles[k].`.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{ObstacleField, ObstacleSpec};
    /// use glam::DVec3;
    ///
    /// let error = ObstacleField::<DVec3>::from_specs(&[
    ///     ObstacleSpec::Ball { centre: vec![0.0; 3], radius: 1.0 },
    ///     ObstacleSpec::Capsule { a: vec![0.0; 3], b: vec![1.0; 3], radius: 0.0 },
    /// ])
    /// .unwrap_err();
    /// assert_eq!(error.field(), "obstacles[1].radius");
    /// ```
    pub fn from_specs(specs: &[ObstacleSpec]) -> Result<Self, ObstacleError> {
        let obstacles = specs
            .iter()
            .enumerate()
            .map(|(k, spec)| V::obstacle(spec).map_err(|error| error.at(k)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::new(obstacles))
    }

    /// The field without obstacles.
    #[must_use]
    pub fn empty() -> Self {
        Self::new(Vec::new())
    }

    /// The number of obstacles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.obstacles.len()
    }

    /// Whether there is no obstacle.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.obstacles.is_empty()
    }

    /// The obstacles, indexed as given.
    #[must_use]
    pub fn obstacles(&self) -> &[V::Obstacle] {
        &self.obstacles
    }

    /// The β-neighbours of the α-agent `(q, p)`: clears `out`, then pushes `(k, β)` for every
    /// obstacle `k` whose β-agent `β = O_k.beta_agent(q, p)` is at distance `< range` or has the
    /// α-agent inside, in increasing `k`.
    ///
    /// `range` is `r′` of Algorithm 3 (Olfati-Saber, IEEE TAC 51(3) 2006); an α-agent inside an
    /// obstacle is always reported, whatever `range` (even `0` or NaN). The cost grows with the
    /// obstacles whose bounding boxes are within `range` of `q`.
    pub fn beta_agents(&self, q: V, p: V, range: f64, out: &mut Vec<(usize, BetaAgent<V>)>) {
        out.clear();
        self.for_each_beta_agent(q, p, range, |k, beta| out.push((k, beta)));
    }

    /// Calls `visit(k, β)` for the β-neighbours of the α-agent `(q, p)`, in increasing `k`: the
    /// entries [`Self::beta_agents`] lists, without a list. Allocates nothing unless more than
    /// 32 obstacles have their bounding boxes within `range` of `q`.
    pub fn for_each_beta_agent(
        &self,
        q: V,
        p: V,
        range: f64,
        mut visit: impl FnMut(usize, BetaAgent<V>),
    ) {
        let mut candidates = Candidates::default();
        for &k in &self.unbounded {
            candidates.push(k);
        }
        self.bvh.visit_near(q, range, &mut |k| candidates.push(k));
        let candidates = candidates.as_mut_slice();
        candidates.sort_unstable();
        for &k in &*candidates {
            let beta = self.obstacles[k].beta_agent(q, p);
            if beta.inside || beta.distance < range {
                visit(k, beta);
            }
        }
    }

    /// The signed distance from `q` to the nearest obstacle: the least
    /// [`Obstacle::signed_distance`] over the obstacles — `‖q̂ − q‖` when `q` is outside all of
    /// them, the most negative `−depth` when it is inside some; `+∞` without obstacles.
    ///
    /// Exact (the same value as a loop over all the obstacles), and culled: the hierarchy is
    /// searched nearest box first, skipping the boxes that cannot hold a nearer obstacle.
    #[must_use]
    pub fn clearance(&self, q: V) -> f64 {
        let mut best = f64::INFINITY;
        for &k in &self.unbounded {
            best = best.min(self.obstacles[k].signed_distance(q));
        }
        self.bvh
            .nearest(q, &mut best, &mut |k| self.obstacles[k].signed_distance(q));
        best
    }

    /// The least index of an obstacle containing `q` (its boundary included), if any: for
    /// reporting an α-agent inside an obstacle, e.g. at the start of a run.
    #[must_use]
    pub fn containing(&self, q: V) -> Option<usize> {
        let mut first: Option<usize> = None;
        let mut check = |k: usize| {
            if first.is_none_or(|first| k < first)
                && self.obstacles[k].beta_agent(q, V::ZERO).inside
            {
                first = Some(k);
            }
        };
        for &k in &self.unbounded {
            check(k);
        }
        self.bvh.visit_near(q, 0.0, &mut check);
        first
    }
}

impl<V: Space> Default for ObstacleField<V> {
    fn default() -> Self {
        Self::empty()
    }
}

/// Obstacle indices near a query: on the stack up to [`Candidates::INLINE`] of them, then on the heap.
struct Candidates {
    inline: [usize; Self::INLINE],
    len: usize,
    spill: Vec<usize>,
}

impl Candidates {
    const INLINE: usize = 32;

    fn push(&mut self, k: usize) {
        if self.spill.is_empty() && self.len < Self::INLINE {
            self.inline[self.len] = k;
            self.len += 1;
        } else {
            if self.spill.is_empty() {
                self.spill.extend_from_slice(&self.inline);
            }
            self.spill.push(k);
        }
    }

    fn as_mut_slice(&mut self) -> &mut [usize] {
        if self.spill.is_empty() {
            &mut self.inline[..self.len]
        } else {
            &mut self.spill
        }
    }
}

impl Default for Candidates {
    fn default() -> Self {
        Self {
            inline: [0; Self::INLINE],
            len: 0,
            spill: Vec::new(),
        }
    }
}

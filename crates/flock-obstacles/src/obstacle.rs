//! The [`Obstacle`] trait: a convex obstacle `O_k ⊂ ℝ^m` as generic code sees it.

use flock_math::Vector;

use crate::{BetaAgent, ObstacleError};

/// A closed convex obstacle `O_k` of ℝ^m, m = `V::DIM`, that induces β-agents (Olfati-Saber, IEEE TAC
/// 51(3) 2006, "Flocking with obstacle avoidance").
///
/// Implemented by [`ConvexObstacle`](crate::ConvexObstacle): [`Obstacle2d`](crate::Obstacle2d) for
/// `DVec2` and [`Obstacle3d`](crate::Obstacle3d) for `DVec3`, so that an algorithm written once for `V: Vector` builds and queries obstacles of its
/// dimension: `fn run<V: Vector, O: Obstacle<V>>(..)`, or `fn run<V: Space>(..)` with
/// `V::Obstacle` (see [`Space`](crate::Space), which also builds any shape from an
/// [`ObstacleSpec`](crate::ObstacleSpec)).
///
/// # Example
/// ```
/// use flock_math::Vector;
/// use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
/// use glam::{DVec2, DVec3};
///
/// /// The distance from `q` to the unit ball at the origin, in any dimension.
/// fn clearance<V: Vector, O: Obstacle<V>>(q: V) -> f64 {
///     let ball = O::ball(V::ZERO, 1.0).unwrap();
///     ball.beta_agent(q, V::ZERO).distance
/// }
/// assert_eq!(clearance::<DVec2, Obstacle2d>(DVec2::new(3.0, 0.0)), 2.0);
/// assert_eq!(clearance::<DVec3, Obstacle3d>(DVec3::new(0.0, 0.0, -3.0)), 2.0);
/// ```
pub trait Obstacle<V: Vector> {
    /// The closed ball `B(centre, radius)`. Fails when `radius` is not a finite number `> 0` or the
    /// centre is not finite.
    fn ball(centre: V, radius: f64) -> Result<Self, ObstacleError>
    where
        Self: Sized;

    /// The wall (closed half-space) `{x : a · (x − point) ≤ 0}` with `a = outward_normal / ‖outward_normal‖`
    /// pointing out of the obstacle, towards the agents. Fails when the normal is zero or not
    /// finite, or the point is not finite.
    fn wall(point: V, outward_normal: V) -> Result<Self, ObstacleError>
    where
        Self: Sized;

    /// The β-agent that the α-agent at `q` with velocity `p` induces on this obstacle:
    /// `q̂ = argmin_{x ∈ O_k} ‖x − q‖` on the boundary, and `p̂` its time derivative as the α-agent
    /// moves with `p` — `μ (I − a aᵀ) p` on balls and flat faces; the rule for every feature is on
    /// [`BetaAgent`].
    ///
    /// An α-agent inside the obstacle is not projected out silently: the β-agent is still the
    /// closest *boundary* point, and [`BetaAgent::inside`] is set. The obstacle is closed: an
    /// α-agent on the boundary is inside, and is its own β-agent. Zero-thickness obstacles
    /// (segments, 3D triangles) have the α-agent inside only when it is on them.
    ///
    /// Where every boundary point in a circle or sphere is closest, the β-agent is deterministic:
    /// at the very centre `y` of a ball (where parry's projection is NaN) `q̂ = y + R e₁`, `a = e₁`
    /// (the first axis), `μ = 1` (the tangent plane there, as for a wall), `inside = true`; on a
    /// capsule's axis, parry's boundary point with its normal, `μ = 1`, `p̂ = P p`.
    #[must_use]
    fn beta_agent(&self, q: V, p: V) -> BetaAgent<V>;

    /// The axis-aligned bounding box `(min, max)` of the obstacle, or `None` when it is unbounded
    /// (a wall). [`ObstacleField`](crate::ObstacleField) culls obstacles with it.
    #[must_use]
    fn aabb(&self) -> Option<(V, V)>;

    /// The signed distance from `q` to the obstacle's boundary: `‖q̂ − q‖` outside, `−‖q̂ − q‖`
    /// inside (the depth; `-0.0` on the boundary).
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d};
    /// use glam::DVec2;
    ///
    /// let disc = Obstacle2d::ball(DVec2::ZERO, 2.0)?;
    /// assert_eq!(disc.signed_distance(DVec2::new(5.0, 0.0)), 3.0);
    /// assert_eq!(disc.signed_distance(DVec2::new(0.5, 0.0)), -1.5);
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    #[must_use]
    fn signed_distance(&self, q: V) -> f64 {
        let beta = self.beta_agent(q, V::ZERO);
        if beta.inside {
            -beta.distance
        } else {
            beta.distance
        }
    }
}

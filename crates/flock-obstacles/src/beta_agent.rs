//! The [`BetaAgent`]: how an α-agent sees a convex obstacle (Olfati-Saber, IEEE TAC 51(3) 2006,
//! β-agents; Caltech CDS 03-006 2003, eq. 53–57).

use flock_math::Vector;
use serde::{Deserialize, Serialize};

/// The β-agent induced on a convex obstacle `O_k` by the α-agent `(q_i, p_i)`.
///
/// - position `q̂_{i,k} = argmin_{x ∈ O_k} ‖x − q_i‖`, the closest point of the obstacle, always on its
///   boundary (TAC 2006; CDS 03-006 eq. 53);
/// - velocity `p̂_{i,k} = μ P p_i` with `P = I − a_k a_kᵀ`, the projection on the tangent plane at
///   `q̂_{i,k}`, and `a_k` the unit outward normal there.
///
/// `μ` is the ratio of the local radius of curvature `ρ` of the boundary at `q̂` to the distance from
/// `q_i` to the centre of curvature, `μ = ρ / (ρ + d)` with `d` the signed distance (negative inside):
/// `μ = 1` on flat faces (walls), `μ = R_k / ‖q_i − y_k‖` on a ball `(y_k, R_k)` (CDS 03-006 eq. 55).
/// With this `μ`, `p̂ = μ P p` is the time derivative of `q̂` as the α-agent moves with velocity `p`.
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle2d};
/// use glam::DVec2;
///
/// // The floor y ≤ 0; an α-agent at height 2 moving diagonally.
/// let floor = Obstacle2d::wall(DVec2::ZERO, DVec2::Y)?;
/// let beta = floor.beta_agent(DVec2::new(3.0, 2.0), DVec2::new(1.0, -1.0));
/// assert_eq!(beta.position, DVec2::new(3.0, 0.0));
/// assert_eq!(beta.normal, DVec2::Y);
/// assert_eq!(beta.velocity, DVec2::new(1.0, 0.0));
/// assert_eq!((beta.mu, beta.distance, beta.inside), (1.0, 2.0, false));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BetaAgent<V> {
    /// `q̂_{i,k}`: the point of the obstacle's boundary closest to the α-agent.
    pub position: V,
    /// `a_k`: the unit outward normal of the boundary at [`position`](Self::position).
    pub normal: V,
    /// `p̂_{i,k} = μ (I − a_k a_kᵀ) p_i`: tangent to the boundary (`p̂ · a_k = 0`).
    pub velocity: V,
    /// `μ`: `1` on flat faces, `R_k / ‖q_i − y_k‖` on a ball (below `1` outside, above `1` inside;
    /// `1` for an α-agent at the centre, see [`Obstacle::beta_agent`](crate::Obstacle::beta_agent)).
    pub mu: f64,
    /// `‖q̂_{i,k} − q_i‖`: the distance from the α-agent to the boundary (the β-neighbour test of
    /// Algorithm 3 is `distance < r′`).
    pub distance: f64,
    /// The α-agent is inside the (closed) obstacle, on its boundary included. The β-agent is still
    /// the closest boundary point; what to do about the collision is the caller's decision.
    pub inside: bool,
}

impl<V: Vector> BetaAgent<V> {
    /// The β-agent of the α-agent `(q, p)` at the boundary point `position` with unit outward
    /// `normal` `a` and ratio `mu`: computes `p̂ = μ (p − a (a · p))` and `distance = ‖q̂ − q‖`.
    ///
    /// The building block of every [`Obstacle`](crate::Obstacle): an obstacle type of your own
    /// finds `q̂`, `a` and `μ`, and calls this.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::BetaAgent;
    /// use glam::DVec2;
    ///
    /// // The unit circle seen from (0, 2): μ = R / ‖q − y‖ = 1/2.
    /// let beta = BetaAgent::new(DVec2::new(0.0, 2.0), DVec2::new(4.0, 3.0), DVec2::Y, DVec2::Y, 0.5, false);
    /// assert_eq!(beta.velocity, DVec2::new(2.0, 0.0));
    /// assert_eq!(beta.distance, 1.0);
    /// ```
    #[inline]
    #[must_use]
    pub fn new(q: V, p: V, position: V, normal: V, mu: f64, inside: bool) -> Self {
        Self {
            position,
            normal,
            velocity: (p - normal * normal.dot(p)) * mu,
            mu,
            distance: (position - q).length(),
            inside,
        }
    }
}

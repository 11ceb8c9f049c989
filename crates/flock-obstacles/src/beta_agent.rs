//! The [`BetaAgent`]: how an α-agent sees a convex obstacle (Olfati-Saber, IEEE TAC 51(3) 2006,
//! β-agents; Caltech CDS 03-006 2003, eq. 53–57).

use flock_math::Vector;
use serde::{Deserialize, Serialize};

/// The β-agent induced on a convex obstacle `O_k` by the α-agent `(q_i, p_i)`.
///
/// - position `q̂_{i,k} = argmin_{x ∈ O_k} ‖x − q_i‖`, the closest point of the obstacle, always on its
///   boundary (TAC 2006; CDS 03-006 eq. 53) — for an α-agent inside too;
/// - velocity `p̂_{i,k}`: the time derivative of `q̂_{i,k}` as the α-agent moves with velocity `p_i`,
///   tangent to the boundary. The paper's `p̂ = μ P p_i`, `P = I − a_k a_kᵀ` the projection on the
///   tangent plane at `q̂` and `a_k` the unit outward normal there, is this derivative for balls and
///   flat faces; other shapes extend it below.
///
/// The derivative of the closest-point map scales each principal direction `t_j` of the boundary
/// at `q̂` by `μ_j = ρ_j / (ρ_j + d)`, `ρ_j` the radius of curvature along `t_j` and `d` the signed
/// distance (negative inside): `p̂ = Σ_j μ_j (t_j · p) t_j`. Per feature:
///
/// | feature at `q̂` | `p̂` | [`mu`](Self::mu) |
/// | --- | --- | --- |
/// | flat face (wall, polygon edge, polyhedron or box face, 2D capsule side, triangle plate) | `P p` | `1` |
/// | ball of centre `y` and radius `R`, capsule end cap (`y` = the cap centre) | `μ P p` | `R / ‖q − y‖` |
/// | 3D capsule side, axis `u`, at distance `ρ` from the axis | `(u·p) u + μ (P p − (u·p) u)` | `R / ρ` |
/// | edge of a polyhedron, box, or triangle plate (3D), segment (3D), direction `e` | `(e·p) e` | `0` |
/// | vertex (corner of a polygon, polyhedron, box, triangle or segment) | `0` | `0` |
///
/// [`mu`](Self::mu) is `μ_j` in the most curved direction (`ρ = 0` at an edge or vertex, whose
/// `μ = 0`). When the boundary curves alike in every direction (flat faces, balls, caps, and every
/// feature in 2D, where the tangent line is one direction) `p̂ = μ P p` as in the paper; the 3D
/// capsule side and 3D edges keep the component along the axis or edge unscaled.
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
    /// `p̂_{i,k}`, the velocity of [`position`](Self::position): tangent to the boundary
    /// (`p̂ · a_k = 0`); `μ (I − a_k a_kᵀ) p_i` on balls and flat faces (see the table above).
    pub velocity: V,
    /// `μ`, the ratio `ρ / (ρ + d)` in the most curved direction: `1` on flat faces, `R_k / ‖q_i − y_k‖`
    /// on a ball (below `1` outside, above `1` inside; `1` for an α-agent at the centre, see
    /// [`Obstacle::beta_agent`](crate::Obstacle::beta_agent)), `0` at edges and vertices.
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

    /// The β-agent of the α-agent at `q` at the boundary point `position` with unit outward
    /// `normal`, whose velocity `velocity` (tangent to the boundary) was computed by the caller,
    /// as for an anisotropic boundary (a 3D capsule side, a 3D edge; see the table on
    /// [`BetaAgent`]); computes `distance = ‖q̂ − q‖`.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::BetaAgent;
    /// use glam::DVec3;
    ///
    /// // An edge along z seen from (1, 1, 0): only the z component of p survives.
    /// let p = DVec3::new(1.0, 2.0, 3.0);
    /// let edge = DVec3::Z * p.z;
    /// let normal = DVec3::new(1.0, 1.0, 0.0).normalize();
    /// let beta = BetaAgent::with_velocity(DVec3::new(1.0, 1.0, 0.0), DVec3::ZERO, normal, edge, 0.0, false);
    /// assert_eq!(beta.velocity, DVec3::new(0.0, 0.0, 3.0));
    /// assert_eq!(beta.distance, 2.0_f64.sqrt());
    /// ```
    #[inline]
    #[must_use]
    pub fn with_velocity(q: V, position: V, normal: V, velocity: V, mu: f64, inside: bool) -> Self {
        Self {
            position,
            normal,
            velocity,
            mu,
            distance: (position - q).length(),
            inside,
        }
    }
}

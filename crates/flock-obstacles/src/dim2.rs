//! [`Obstacle2d`]: convex obstacles of the plane, projected by parry2d-f64.
//!
//! - [`Obstacle2d::ball`]: a disc `B(y, R)`.
//! - [`Obstacle2d::wall`]: a half-plane through `y` with outward normal `a`.
//! - [`Obstacle::beta_agent`]: the β-agent of an α-agent `(q, p)` on it.

use glam::DVec2;
use parry2d_f64::math::Pose;
use parry2d_f64::query::PointQuery;
use parry2d_f64::shape::{Ball, HalfSpace, Shape};

use crate::{BetaAgent, Obstacle, ObstacleError, ball, wall};

/// A convex obstacle of ℝ²: a parry shape placed by a [`Pose`].
///
/// The β-agent's position `q̂` and the inside test come from parry's
/// `project_point(pose, q, solid = false)`, which returns the closest *boundary* point even for an
/// α-agent inside; the normal `a`, `μ` and `p̂ = μ P p` follow the closed forms of Olfati-Saber (IEEE
/// TAC 51(3) 2006) described on [`BetaAgent`].
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle2d};
/// use glam::DVec2;
///
/// let disc = Obstacle2d::ball(DVec2::new(10.0, 0.0), 2.0)?;
/// let beta = disc.beta_agent(DVec2::ZERO, DVec2::new(1.0, 1.0));
/// assert_eq!(beta.position, DVec2::new(8.0, 0.0));
/// assert_eq!(beta.normal, DVec2::new(-1.0, 0.0));
/// assert_eq!(beta.mu, 0.2); // R / ‖q − y‖
/// assert_eq!(beta.velocity, DVec2::new(0.0, 0.2));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Obstacle2d {
    kind: Kind,
    pose: Pose,
}

/// The shapes an [`Obstacle2d`] can be.
#[derive(Clone, Debug)]
enum Kind {
    Ball(Ball),
    Wall(HalfSpace),
}

impl Obstacle2d {
    /// The closed disc of radius `radius` centred at `centre`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle2d;
    /// use glam::DVec2;
    ///
    /// let disc = Obstacle2d::ball(DVec2::new(1.0, 2.0), 0.5)?;
    /// assert_eq!(disc.pose().translation, DVec2::new(1.0, 2.0));
    /// assert_eq!(disc.shape().as_ball().map(|b| b.radius), Some(0.5));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn ball(centre: DVec2, radius: f64) -> Result<Self, ObstacleError> {
        ball::validate(centre, radius)?;
        Ok(Self {
            kind: Kind::Ball(Ball::new(radius)),
            pose: Pose::from_translation(centre),
        })
    }

    /// The closed half-plane `{x : a · (x − point) ≤ 0}` bounded by the line through `point`, with
    /// `a = outward_normal / ‖outward_normal‖` pointing out of the wall, towards the agents.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidNormal`] when `outward_normal` is zero or not finite;
    /// [`ObstacleError::NonFinitePoint`] when `point` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle2d;
    /// use glam::DVec2;
    ///
    /// // The wall x ≥ 5 (agents live at x < 5): its outward normal points to −x.
    /// let wall = Obstacle2d::wall(DVec2::new(5.0, 0.0), DVec2::new(-3.0, 0.0))?;
    /// assert_eq!(wall.shape().as_halfspace().map(|h| h.normal), Some(DVec2::new(-1.0, 0.0)));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn wall(point: DVec2, outward_normal: DVec2) -> Result<Self, ObstacleError> {
        let normal = wall::unit_normal(point, outward_normal)?;
        Ok(Self {
            kind: Kind::Wall(HalfSpace::new(normal)),
            pose: Pose::from_translation(point),
        })
    }

    /// The parry shape, in its local frame (for other parry queries, e.g. `compute_aabb`).
    #[must_use]
    pub fn shape(&self) -> &dyn Shape {
        match &self.kind {
            Kind::Ball(ball) => ball,
            Kind::Wall(half_space) => half_space,
        }
    }

    /// The pose placing [`shape`](Self::shape) in the world.
    #[must_use]
    pub fn pose(&self) -> &Pose {
        &self.pose
    }
}

impl Obstacle<DVec2> for Obstacle2d {
    fn ball(centre: DVec2, radius: f64) -> Result<Self, ObstacleError> {
        Self::ball(centre, radius)
    }

    fn wall(point: DVec2, outward_normal: DVec2) -> Result<Self, ObstacleError> {
        Self::wall(point, outward_normal)
    }

    #[inline]
    fn beta_agent(&self, q: DVec2, p: DVec2) -> BetaAgent<DVec2> {
        match &self.kind {
            Kind::Ball(shape) => {
                let projection = shape.project_point(&self.pose, q, false);
                ball::beta_agent(
                    q,
                    p,
                    self.pose.translation,
                    shape.radius,
                    projection.point,
                    projection.is_inside,
                )
            }
            Kind::Wall(shape) => {
                let projection = shape.project_point(&self.pose, q, false);
                let normal = self.pose.transform_vector(shape.normal);
                wall::beta_agent(q, p, normal, projection.point, projection.is_inside)
            }
        }
    }
}

//! [`Obstacle3d`]: convex obstacles of space, projected by parry3d-f64.
//!
//! - [`Obstacle3d::ball`]: a ball `B(y, R)`.
//! - [`Obstacle3d::wall`]: a half-space through `y` with outward normal `a`.
//! - [`Obstacle::beta_agent`]: the β-agent of an α-agent `(q, p)` on it.

use glam::DVec3;
use parry3d_f64::math::Pose;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{Ball, HalfSpace, Shape};

use crate::{BetaAgent, Obstacle, ObstacleError, ball, wall};

/// A convex obstacle of ℝ³: a parry shape placed by a [`Pose`].
///
/// The β-agent's position `q̂` and the inside test come from parry's
/// `project_point(pose, q, solid = false)`, which returns the closest *boundary* point even for an
/// α-agent inside; the normal `a`, `μ` and `p̂ = μ P p` follow the closed forms of Olfati-Saber (IEEE
/// TAC 51(3) 2006) described on [`BetaAgent`].
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle3d};
/// use glam::DVec3;
///
/// let ball = Obstacle3d::ball(DVec3::new(0.0, 0.0, 10.0), 2.0)?;
/// let beta = ball.beta_agent(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0));
/// assert_eq!(beta.position, DVec3::new(0.0, 0.0, 8.0));
/// assert_eq!(beta.normal, DVec3::new(0.0, 0.0, -1.0));
/// assert_eq!(beta.mu, 0.2); // R / ‖q − y‖
/// assert_eq!(beta.velocity, DVec3::new(0.2, 0.0, 0.0));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Obstacle3d {
    kind: Kind,
    pose: Pose,
}

/// The shapes an [`Obstacle3d`] can be.
#[derive(Clone, Debug)]
enum Kind {
    Ball(Ball),
    Wall(HalfSpace),
}

impl Obstacle3d {
    /// The closed ball of radius `radius` centred at `centre`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle3d;
    /// use glam::DVec3;
    ///
    /// let ball = Obstacle3d::ball(DVec3::new(1.0, 2.0, 3.0), 0.5)?;
    /// assert_eq!(ball.pose().translation, DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!(ball.shape().as_ball().map(|b| b.radius), Some(0.5));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn ball(centre: DVec3, radius: f64) -> Result<Self, ObstacleError> {
        ball::validate(centre, radius)?;
        Ok(Self {
            kind: Kind::Ball(Ball::new(radius)),
            pose: Pose::from_translation(centre),
        })
    }

    /// The closed half-space `{x : a · (x − point) ≤ 0}` bounded by the plane through `point`, with
    /// `a = outward_normal / ‖outward_normal‖` pointing out of the wall, towards the agents.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidNormal`] when `outward_normal` is zero or not finite;
    /// [`ObstacleError::NonFinitePoint`] when `point` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle3d;
    /// use glam::DVec3;
    ///
    /// // The ceiling z ≥ 5 (agents live at z < 5): its outward normal points to −z.
    /// let ceiling = Obstacle3d::wall(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -3.0))?;
    /// assert_eq!(ceiling.shape().as_halfspace().map(|h| h.normal), Some(DVec3::NEG_Z));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn wall(point: DVec3, outward_normal: DVec3) -> Result<Self, ObstacleError> {
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

impl Obstacle<DVec3> for Obstacle3d {
    fn ball(centre: DVec3, radius: f64) -> Result<Self, ObstacleError> {
        Self::ball(centre, radius)
    }

    fn wall(point: DVec3, outward_normal: DVec3) -> Result<Self, ObstacleError> {
        Self::wall(point, outward_normal)
    }

    #[inline]
    fn beta_agent(&self, q: DVec3, p: DVec3) -> BetaAgent<DVec3> {
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

//! [`Space`]: the plane or space a flock lives in, with its obstacle type.

use crate::shapes::Parry;
use crate::{ConvexObstacle, Obstacle, ObstacleError, ObstacleSpec};

/// The space a flock lives in, `DVec2` or `DVec3`, with its obstacle type
/// ([`Obstacle2d`](crate::Obstacle2d) or [`Obstacle3d`](crate::Obstacle3d)): generic code over
/// `V: Space` builds obstacles from scenario descriptions and queries them.
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, ObstacleSpec, Space};
/// use glam::{DVec2, DVec3};
///
/// /// The clearance of the origin to the unit ball at (3, 0) or (3, 0, 0).
/// fn clearance<V: Space>() -> f64 {
///     let mut centre = vec![0.0; V::DIM];
///     centre[0] = 3.0;
///     let ball = V::obstacle(&ObstacleSpec::Ball { centre, radius: 1.0 }).unwrap();
///     ball.signed_distance(V::ZERO)
/// }
/// assert_eq!(clearance::<DVec2>(), 2.0);
/// assert_eq!(clearance::<DVec3>(), 2.0);
/// ```
pub trait Space: flock_math::Vector {
    /// The convex obstacles of this space.
    type Obstacle: Obstacle<Self> + Clone + core::fmt::Debug + Send + Sync;

    /// Builds the obstacle `spec` describes, validated.
    ///
    /// # Errors
    /// An [`ObstacleError`] naming the field at fault when `spec` does not describe a
    /// non-degenerate convex obstacle of this dimension.
    fn obstacle(spec: &ObstacleSpec) -> Result<Self::Obstacle, ObstacleError>;
}

impl<V: Parry> Space for V {
    type Obstacle = ConvexObstacle<V>;

    fn obstacle(spec: &ObstacleSpec) -> Result<ConvexObstacle<V>, ObstacleError> {
        ConvexObstacle::from_spec(spec)
    }
}

//! [`ObstacleError`]: why an obstacle constructor refused its input.

use core::fmt;

use flock_math::Vector;

/// An obstacle description that does not define a convex obstacle.
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle2d, ObstacleError};
/// use glam::DVec2;
///
/// let error = Obstacle2d::ball(DVec2::ZERO, -1.0).unwrap_err();
/// assert_eq!(error, ObstacleError::InvalidRadius { radius: -1.0 });
/// assert!(error.to_string().contains("`radius` is -1.0"));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ObstacleError {
    /// A ball radius that is not a finite number `> 0`.
    InvalidRadius {
        /// The radius given.
        radius: f64,
    },
    /// A wall normal that is zero, too small to normalise, or not finite.
    InvalidNormal {
        /// The normal given, one entry per coordinate.
        normal: Vec<f64>,
    },
    /// A point (a ball's centre, a wall's point) with a NaN or infinite coordinate.
    NonFinitePoint {
        /// The constructor argument: `"centre"` or `"point"`.
        field: &'static str,
        /// The point given, one entry per coordinate.
        point: Vec<f64>,
    },
}

impl fmt::Display for ObstacleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidRadius { radius } => write!(
                f,
                "ball `radius` is {radius:?}, but it must be a finite number > 0: \
                 give the ball a positive radius"
            ),
            Self::InvalidNormal { normal } => write!(
                f,
                "wall `outward_normal` is {}, but it must be finite and non-zero: give a vector \
                 pointing out of the wall towards the agents, e.g. (0.0, 1.0) for a floor",
                Coordinates(normal)
            ),
            Self::NonFinitePoint { field, point } => write!(
                f,
                "obstacle `{field}` is {}, but every coordinate must be finite: \
                 replace the NaN or infinite coordinate",
                Coordinates(point)
            ),
        }
    }
}

impl std::error::Error for ObstacleError {}

/// Writes coordinates as a RON tuple, `(1.0, NaN)`, the way a scenario file spells a vector.
struct Coordinates<'a>(&'a [f64]);

impl fmt::Display for Coordinates<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("(")?;
        for (k, x) in self.0.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{x:?}")?;
        }
        f.write_str(")")
    }
}

/// The coordinates of `v`, for an error message.
pub(crate) fn coordinates<V: Vector>(v: V) -> Vec<f64> {
    (0..V::DIM).map(|k| v.coord(k)).collect()
}

/// Checks that every coordinate of the constructor argument `field` is finite.
pub(crate) fn check_finite<V: Vector>(field: &'static str, point: V) -> Result<(), ObstacleError> {
    if point.is_finite() {
        Ok(())
    } else {
        Err(ObstacleError::NonFinitePoint {
            field,
            point: coordinates(point),
        })
    }
}

//! [`ObstacleError`]: why an obstacle description was refused.

use core::fmt;

use flock_math::Vector;

/// An obstacle description that does not define a (non-degenerate) convex obstacle.
///
/// Each error names the field at fault by its path relative to the obstacle ([`field`](Self::field):
/// `"radius"`, `"half_extents[1]"`, `"points[4]"`), and its message says the value, why it is
/// refused and how to fix it. [`ObstacleField::from_specs`](crate::ObstacleField::from_specs)
/// wraps the error of obstacle `k` in [`InObstacle`](Self::InObstacle), whose path starts with
/// `obstacles[k].`.
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle2d, ObstacleError};
/// use glam::DVec2;
///
/// let error = Obstacle2d::ball(DVec2::ZERO, -1.0).unwrap_err();
/// assert_eq!(error, ObstacleError::InvalidRadius { radius: -1.0 });
/// assert_eq!(error.field(), "radius");
/// assert!(error.to_string().starts_with("`radius` is -1.0, but"));
///
/// let error = error.at(3);
/// assert_eq!(error.field(), "obstacles[3].radius");
/// assert!(error.to_string().starts_with("`obstacles[3].radius` is -1.0, but"));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ObstacleError {
    /// A ball or capsule `radius` that is not a finite number `> 0`.
    InvalidRadius {
        /// The radius given.
        radius: f64,
    },
    /// A wall `normal` that is zero, too small to normalise, or not finite.
    InvalidNormal {
        /// The normal given, one entry per coordinate.
        normal: Vec<f64>,
    },
    /// A point (`centre`, `point`, `a`, `points[i]`, …) with a NaN or infinite coordinate.
    NonFinitePoint {
        /// The path of the field, e.g. `"centre"` or `"points[2]"`.
        field: String,
        /// The point given, one entry per coordinate.
        point: Vec<f64>,
    },
    /// A vector whose number of coordinates is not the dimension of the scenario.
    WrongDimension {
        /// The path of the field, e.g. `"centre"` or `"points[2]"`.
        field: String,
        /// The number of coordinates given.
        len: usize,
        /// The dimension of the scenario, 2 or 3.
        dim: usize,
    },
    /// A cuboid `rotation` of the wrong length (one angle in 2D, an axis-angle vector of 3 numbers
    /// in 3D, or none) or with a non-finite entry.
    InvalidRotation {
        /// The rotation given.
        rotation: Vec<f64>,
        /// The dimension of the scenario, 2 or 3.
        dim: usize,
    },
    /// A cuboid half extent that is not a finite number `> 0`.
    InvalidHalfExtent {
        /// The axis of the half extent (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// The half extent given.
        half_extent: f64,
    },
    /// A convex hull of fewer than `dim + 1` points.
    TooFewPoints {
        /// The number of points given.
        count: usize,
        /// The dimension of the scenario, 2 or 3.
        dim: usize,
    },
    /// A convex hull whose points all lie on one line (2D) or plane (3D): a flat hull.
    FlatHull {
        /// The dimension of the scenario, 2 or 3.
        dim: usize,
    },
    /// A convex hull point strictly inside the hull of the others: the outline is not convex.
    PointInsideHull {
        /// The index of the point in `points`.
        index: usize,
        /// The point given.
        point: Vec<f64>,
    },
    /// A segment whose endpoints coincide.
    DegenerateSegment {
        /// The common endpoint.
        point: Vec<f64>,
    },
    /// A triangle whose vertices are on one line.
    FlatTriangle {
        /// The vertices given, `[a, b, c]`.
        vertices: [Vec<f64>; 3],
    },
    /// The error of the obstacle at `index` of a list (`obstacles[index]` in a scenario).
    InObstacle {
        /// The index of the obstacle in the list.
        index: usize,
        /// What is wrong with it.
        error: Box<ObstacleError>,
    },
}

impl ObstacleError {
    /// Wraps this error as the error of obstacle `index` of a list: its [`field`](Self::field)
    /// and message then start with `obstacles[index].`.
    #[must_use]
    pub fn at(self, index: usize) -> Self {
        Self::InObstacle {
            index,
            error: Box::new(self),
        }
    }

    /// The path of the field at fault, relative to the obstacle (`"radius"`, `"half_extents[1]"`,
    /// `"points[4]"`), or to the list for [`InObstacle`](Self::InObstacle)
    /// (`"obstacles[2].radius"`).
    #[must_use]
    pub fn field(&self) -> String {
        match self {
            Self::InvalidRadius { .. } => "radius".to_owned(),
            Self::InvalidNormal { .. } => "normal".to_owned(),
            Self::NonFinitePoint { field, .. } | Self::WrongDimension { field, .. } => {
                field.clone()
            }
            Self::InvalidRotation { .. } => "rotation".to_owned(),
            Self::InvalidHalfExtent { axis, .. } => format!("half_extents[{axis}]"),
            Self::TooFewPoints { .. } | Self::FlatHull { .. } => "points".to_owned(),
            Self::PointInsideHull { index, .. } => format!("points[{index}]"),
            Self::DegenerateSegment { .. } => "b".to_owned(),
            Self::FlatTriangle { .. } => "c".to_owned(),
            Self::InObstacle { index, error } => format!("obstacles[{index}].{}", error.field()),
        }
    }

    /// Writes the message with `prefix` (e.g. `obstacles[2].`) before every field path.
    fn write(&self, f: &mut fmt::Formatter<'_>, prefix: &str) -> fmt::Result {
        match self {
            Self::InvalidRadius { radius } => write!(
                f,
                "`{prefix}radius` is {radius:?}, but it must be a finite number > 0: \
                 give the obstacle a positive radius"
            ),
            Self::InvalidNormal { normal } => write!(
                f,
                "`{prefix}normal` is {}, but it must be finite and non-zero: give a vector \
                 pointing out of the wall towards the agents, e.g. {} for a floor",
                Coordinates(normal),
                if normal.len() == 3 {
                    "(0.0, 0.0, 1.0)"
                } else {
                    "(0.0, 1.0)"
                }
            ),
            Self::NonFinitePoint { field, point } => write!(
                f,
                "`{prefix}{field}` is {}, but every coordinate must be finite: \
                 replace the NaN or infinite coordinate",
                Coordinates(point)
            ),
            Self::WrongDimension { field, len, dim } => write!(
                f,
                "`{prefix}{field}` has {len} coordinate{}, but the scenario is {dim}D: \
                 give exactly {dim} numbers, e.g. {}",
                if *len == 1 { "" } else { "s" },
                if *dim == 3 {
                    "(0.0, 0.0, 0.0)"
                } else {
                    "(0.0, 0.0)"
                }
            ),
            Self::InvalidRotation { rotation, dim } => {
                write!(f, "`{prefix}rotation` is {}, but ", Coordinates(rotation))?;
                if *dim == 3 {
                    f.write_str(
                        "a 3D rotation is an axis-angle vector of 3 finite numbers (the unit \
                         axis times the angle in radians): give e.g. (0.0, 0.0, 0.5) for 0.5 rad \
                         about z, or leave `rotation` out for none",
                    )
                } else {
                    f.write_str(
                        "a 2D rotation is one finite angle in radians: give e.g. (0.5,) or 0.5, \
                         or leave `rotation` out for none",
                    )
                }
            }
            Self::InvalidHalfExtent { axis, half_extent } => write!(
                f,
                "`{prefix}half_extents[{axis}]` is {half_extent:?}, but every half extent must be \
                 a finite number > 0: give the box a positive half-width along axis {axis}"
            ),
            Self::TooFewPoints { count, dim } => write!(
                f,
                "`{prefix}points` has {count} point{}, but a convex {} needs at least {} points \
                 not all on one {}: add points",
                if *count == 1 { "" } else { "s" },
                hull_name(*dim),
                dim + 1,
                flat_name(*dim),
            ),
            Self::FlatHull { dim } => write!(
                f,
                "`{prefix}points` all lie on one {}, so their convex hull is flat: a convex {} \
                 needs {} points not on one {} (a zero-thickness wall is a `{}`)",
                flat_name(*dim),
                hull_name(*dim),
                dim + 1,
                flat_name(*dim),
                if *dim == 3 { "Triangle" } else { "Segment" },
            ),
            Self::PointInsideHull { index, point } => write!(
                f,
                "`{prefix}points[{index}]` is {}, strictly inside the convex hull of the other \
                 points, so the outline is not convex: the obstacle is the convex hull of \
                 `points`; remove the point, or split a non-convex obstacle into convex ones",
                Coordinates(point)
            ),
            Self::DegenerateSegment { point } => write!(
                f,
                "`{prefix}b` equals `{prefix}a` = {}, so the segment is a single point: \
                 give two distinct endpoints",
                Coordinates(point)
            ),
            Self::FlatTriangle {
                vertices: [a, b, c],
            } => write!(
                f,
                "`{prefix}c` = {} is on the line through `{prefix}a` = {} and `{prefix}b` = {}, \
                 so the triangle is flat: give three vertices not on one line",
                Coordinates(c),
                Coordinates(a),
                Coordinates(b)
            ),
            Self::InObstacle { index, error } => {
                error.write(f, &format!("{prefix}obstacles[{index}]."))
            }
        }
    }
}

impl fmt::Display for ObstacleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, "")
    }
}

impl std::error::Error for ObstacleError {}

/// "polygon" in 2D, "polyhedron" in 3D.
fn hull_name(dim: usize) -> &'static str {
    if dim == 3 { "polyhedron" } else { "polygon" }
}

/// "line" in 2D, "plane" in 3D.
fn flat_name(dim: usize) -> &'static str {
    if dim == 3 { "plane" } else { "line" }
}

/// Writes coordinates as a RON tuple, `(1.0, NaN)`, one way a scenario file spells a vector.
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
        if self.0.len() == 1 {
            f.write_str(",")?;
        }
        f.write_str(")")
    }
}

/// The coordinates of `v`, for an error message.
pub(crate) fn coordinates<V: Vector>(v: V) -> Vec<f64> {
    (0..V::DIM).map(|k| v.coord(k)).collect()
}

/// Checks that every coordinate of the field `field` is finite.
pub(crate) fn check_finite<V: Vector>(field: &str, point: V) -> Result<V, ObstacleError> {
    if point.is_finite() {
        Ok(point)
    } else {
        Err(ObstacleError::NonFinitePoint {
            field: field.to_owned(),
            point: coordinates(point),
        })
    }
}

/// The vector of `V`'s dimension written as `values` in the field `field`: checks the number of
/// coordinates only (the constructors check the values).
pub(crate) fn from_coordinates<V: Vector>(field: &str, values: &[f64]) -> Result<V, ObstacleError> {
    if values.len() == V::DIM {
        Ok(V::from_fn(|k| values[k]))
    } else {
        Err(ObstacleError::WrongDimension {
            field: field.to_owned(),
            len: values.len(),
            dim: V::DIM,
        })
    }
}

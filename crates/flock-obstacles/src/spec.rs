//! [`ObstacleSpec`]: an obstacle as a scenario file writes it, in either dimension.

use core::fmt;

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};

/// A dimension-agnostic description of a convex obstacle, as written in a RON scenario.
///
/// Vectors have the scenario's dimension, and read from RON as a tuple `(1.0, 2.0)` or a list
/// `[1.0, 2.0]`. Every obstacle is closed: its boundary belongs to it. Build one with
/// [`Space::obstacle`](crate::Space::obstacle) (or `Obstacle2d::from_spec` /
/// `Obstacle3d::from_spec`), which validates it; a list with
/// [`ObstacleField::from_specs`](crate::ObstacleField::from_specs).
///
/// # Example
/// ```
/// use flock_obstacles::{ObstacleSpec, Space};
/// use glam::DVec2;
///
/// let specs: Vec<ObstacleSpec> = ron::from_str(
///     "[
///         Ball(centre: (10.0, 0.0), radius: 2.0),
///         Wall(point: (0.0, -5.0), normal: (0.0, 1.0)),
///         Cuboid(centre: (20.0, 3.0), half_extents: (1.0, 4.0), rotation: 0.3),
///         ConvexHull(points: [(0.0, 8.0), (2.0, 8.0), (1.0, 10.0)]),
///         Capsule(a: (30.0, 0.0), b: (30.0, 6.0), radius: 0.5),
///         Segment(a: (-10.0, 0.0), b: (-10.0, 6.0)),
///     ]",
/// )?;
/// for spec in &specs {
///     DVec2::obstacle(spec)?;
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ObstacleSpec {
    /// The closed ball (disc in 2D) `B(centre, radius)`, `radius > 0`.
    Ball {
        /// The centre `y`.
        #[serde(deserialize_with = "vector")]
        centre: Vec<f64>,
        /// The radius `R > 0`.
        radius: f64,
    },
    /// The wall (closed half-space) `{x : n · (x − point) ≤ 0}`, `n = normal / ‖normal‖`.
    Wall {
        /// A point of the boundary line or plane.
        #[serde(deserialize_with = "vector")]
        point: Vec<f64>,
        /// The outward normal, pointing out of the wall towards the agents; any non-zero length.
        #[serde(deserialize_with = "vector")]
        normal: Vec<f64>,
    },
    /// The box (rectangle in 2D) of half-widths `half_extents` along its own axes, centred at
    /// `centre` and turned by `rotation`.
    Cuboid {
        /// The centre.
        #[serde(deserialize_with = "vector")]
        centre: Vec<f64>,
        /// The half-width along each of the box's axes, each `> 0`.
        #[serde(deserialize_with = "vector")]
        half_extents: Vec<f64>,
        /// The rotation from the world axes to the box's: in 2D one angle in radians
        /// (counter-clockwise; `0.3`, `(0.3,)` or `[0.3]`), in 3D an axis-angle vector
        /// `(rx, ry, rz)` (the unit axis times the angle in radians). Left out: none.
        #[serde(
            default,
            deserialize_with = "vector",
            skip_serializing_if = "Vec::is_empty"
        )]
        rotation: Vec<f64>,
    },
    /// The convex hull of `points` (world coordinates, any order): a convex polygon in 2D, a
    /// convex polyhedron in 3D.
    ///
    /// At least `m + 1` points not all on one line (2D) or plane (3D) — a flat hull is refused. A
    /// point strictly inside the hull of the others is refused too, since it means the outline
    /// given is not convex; points on the hull's boundary that are not corners are accepted.
    ConvexHull {
        /// The points whose convex hull is the obstacle.
        #[serde(deserialize_with = "vectors")]
        points: Vec<Vec<f64>>,
    },
    /// The capsule: the points within `radius` of the segment `[a, b]` (a stadium in 2D). With
    /// `a = b` it is the ball `B(a, radius)`.
    Capsule {
        /// One end of the axis.
        #[serde(deserialize_with = "vector")]
        a: Vec<f64>,
        /// The other end of the axis.
        #[serde(deserialize_with = "vector")]
        b: Vec<f64>,
        /// The radius `> 0`.
        radius: f64,
    },
    /// The segment `[a, b]`, `a ≠ b`, of zero thickness: a thin wall in 2D, a thin rod in 3D. Both
    /// sides are boundary; an α-agent is inside only when on the segment.
    Segment {
        /// One endpoint.
        #[serde(deserialize_with = "vector")]
        a: Vec<f64>,
        /// The other endpoint.
        #[serde(deserialize_with = "vector")]
        b: Vec<f64>,
    },
    /// The triangle of vertices `a`, `b`, `c`, not on one line: in 2D a solid triangle (the convex
    /// polygon), in 3D a plate of zero thickness, both sides of which are boundary (an α-agent is
    /// inside only when on the plate).
    Triangle {
        /// The first vertex.
        #[serde(deserialize_with = "vector")]
        a: Vec<f64>,
        /// The second vertex.
        #[serde(deserialize_with = "vector")]
        b: Vec<f64>,
        /// The third vertex.
        #[serde(deserialize_with = "vector")]
        c: Vec<f64>,
    },
}

impl ObstacleSpec {
    /// The variant's name as a scenario writes it: `"Ball"`, `"Wall"`, `"Cuboid"`, …
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Ball { .. } => "Ball",
            Self::Wall { .. } => "Wall",
            Self::Cuboid { .. } => "Cuboid",
            Self::ConvexHull { .. } => "ConvexHull",
            Self::Capsule { .. } => "Capsule",
            Self::Segment { .. } => "Segment",
            Self::Triangle { .. } => "Triangle",
        }
    }
}

/// Reads a vector written as a tuple `(1.0, 2.0)`, a list `[1.0, 2.0]` or a single number `0.5`.
fn vector<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<f64>, D::Error> {
    deserializer.deserialize_any(VectorVisitor)
}

/// Reads a list of vectors, each as [`vector`] reads it.
fn vectors<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<Vec<f64>>, D::Error> {
    deserializer.deserialize_any(VectorsVisitor)
}

struct VectorVisitor;

impl<'de> Visitor<'de> for VectorVisitor {
    type Value = Vec<f64>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a vector of numbers, e.g. (1.0, 2.0) or [1.0, 2.0]")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<f64>, A::Error> {
        let mut values = Vec::with_capacity(seq.size_hint().unwrap_or(3));
        while let Some(x) = seq.next_element::<f64>()? {
            values.push(x);
        }
        Ok(values)
    }

    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Vec<f64>, E> {
        Ok(vec![x])
    }

    fn visit_i64<E: de::Error>(self, x: i64) -> Result<Vec<f64>, E> {
        Ok(vec![x as f64])
    }

    fn visit_u64<E: de::Error>(self, x: u64) -> Result<Vec<f64>, E> {
        Ok(vec![x as f64])
    }
}

/// One element of a list of vectors.
struct Element(Vec<f64>);

impl<'de> Deserialize<'de> for Element {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        vector(deserializer).map(Element)
    }
}

struct VectorsVisitor;

impl<'de> Visitor<'de> for VectorsVisitor {
    type Value = Vec<Vec<f64>>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a list of vectors, e.g. [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<Vec<f64>>, A::Error> {
        let mut points = Vec::with_capacity(seq.size_hint().unwrap_or(8));
        while let Some(Element(point)) = seq.next_element()? {
            points.push(point);
        }
        Ok(points)
    }
}

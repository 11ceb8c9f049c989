//! [`Obstacle2d`]: convex obstacles of the plane, projected by parry2d-f64 — what is particular to
//! the plane of [`ConvexObstacle`]: a rotation is an angle, the hull a convex polygon, a triangle
//! that polygon, and there is no plate.

use glam::DVec2;
use parry2d_f64::math::Pose;
use parry2d_f64::query::{PointQuery, PointQueryWithLocation};
use parry2d_f64::shape::{
    Ball, Capsule, ConvexPolygon, Cuboid, HalfSpace, Segment, SegmentPointLocation, Shape,
};
use parry2d_f64::transformation::convex_hull;

use crate::ConvexObstacle;
use crate::ObstacleError;
use crate::basis::orthogonal_unit;
use crate::parry_calls::parry_calls;
use crate::polytope::Planes;
use crate::shapes::{Hull, Kind, Parry, Placed};
use crate::thin::Feature;

/// A convex obstacle of ℝ², projected by parry2d-f64: a ball is a disc, a wall a half-plane, a
/// cuboid a rectangle turned by an angle, a convex hull a convex polygon, a capsule a stadium, a
/// segment a thin wall and a triangle a convex polygon.
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle2d};
/// use glam::DVec2;
///
/// let disc = Obstacle2d::ball(DVec2::new(10.0, 0.0), 2.0)?;
/// assert_eq!(disc.beta_agent(DVec2::ZERO, DVec2::ZERO).distance, 8.0);
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
pub type Obstacle2d = ConvexObstacle<DVec2>;

/// No plate in the plane (a triangle is a convex polygon there): [`Kind::Plate`] cannot be built.
#[derive(Clone, Copy, Debug)]
pub enum NoPlate {}

/// parry2d-f64's types and projections for the β-agent algorithm of [`shapes`](crate::shapes).
impl Parry for DVec2 {
    type Hull = ConvexPolygon;
    type Plate = NoPlate;
    type Rotation = f64;
    // the types, projections and frames that read the same in both parry crates
    parry_calls!();

    fn rotation(values: &[f64]) -> Option<f64> {
        match *values {
            [] => Some(0.0),
            [angle] => Some(angle),
            _ => None,
        }
    }
    fn rotation_values(angle: f64) -> Vec<f64> {
        vec![angle]
    }

    fn hull(local: &[Self], radius: f64) -> Option<Hull<Self>> {
        // Not `ConvexPolygon::from_convex_hull`: it drops a vertex whose two edges turn by less
        // than about 1.7e-4 rad, which shrinks the polygon below the hull of the points.
        let shape = ConvexPolygon::from_convex_polyline_unmodified(convex_hull(local))?;
        let planes = shape
            .points()
            .iter()
            .zip(shape.normals())
            .map(|(&vertex, &normal)| (normal, normal.dot(vertex)))
            .collect();
        Some(Hull {
            shape,
            planes: Planes::new(planes, radius),
        })
    }

    fn triangle(a: Self, b: Self, c: Self) -> Result<Placed<Self>, ObstacleError> {
        Placed::convex_hull(&[a, b, c])
    }

    #[inline]
    fn project_plate(plate: &NoPlate, _q: Self) -> (Self, bool, Feature<Self>, Self) {
        match *plate {}
    }
    fn plate_shape(plate: &NoPlate) -> &dyn Shape {
        match *plate {}
    }
}

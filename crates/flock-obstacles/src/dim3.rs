//! [`Obstacle3d`]: convex obstacles of space, projected by parry3d-f64 — what is particular to
//! space of [`ConvexObstacle`]: a rotation is an axis-angle vector, the hull a convex polyhedron,
//! and a triangle a plate of zero thickness.

use glam::DVec3;
use parry3d_f64::math::Pose;
use parry3d_f64::query::{PointQuery, PointQueryWithLocation};
use parry3d_f64::shape::{
    Ball, Capsule, ConvexPolyhedron, Cuboid, HalfSpace, Segment, SegmentPointLocation, Shape,
    Triangle, TrianglePointLocation,
};
use parry3d_f64::transformation::try_convex_hull;

use crate::ConvexObstacle;
use crate::ObstacleError;
use crate::basis::orthogonal_unit;
use crate::error::coordinates;
use crate::parry_calls::parry_calls;
use crate::polytope::Planes;
use crate::shapes::{Hull, Kind, Parry, Placed, flat_triangle};
use crate::thin::Feature;

/// A convex obstacle of ℝ³, projected by parry3d-f64: a ball, a wall (a half-space), a cuboid
/// turned by an axis-angle vector, a convex hull (a convex polyhedron), a capsule, a segment (a
/// thin rod) and a triangle (a thin plate).
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle3d};
/// use glam::DVec3;
///
/// let ball = Obstacle3d::ball(DVec3::new(0.0, 0.0, 10.0), 2.0)?;
/// assert_eq!(ball.beta_agent(DVec3::ZERO, DVec3::ZERO).distance, 8.0);
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
pub type Obstacle3d = ConvexObstacle<DVec3>;

/// A triangle of zero thickness, with its unit normal `(b − a) × (c − a)` normalised and the unit
/// directions of its sides `ab`, `bc`, `ac` (parry's edge numbering).
#[derive(Clone, Debug)]
pub struct Plate {
    shape: Triangle,
    normal: DVec3,
    sides: [DVec3; 3],
}

/// parry3d-f64's types and projections for the β-agent algorithm of [`shapes`](crate::shapes).
impl Parry for DVec3 {
    type Hull = ConvexPolyhedron;
    type Plate = Plate;
    type Rotation = DVec3;
    // the types, projections and frames that read the same in both parry crates
    parry_calls!();

    fn rotation(values: &[f64]) -> Option<DVec3> {
        match *values {
            [] => Some(DVec3::ZERO),
            [x, y, z] => Some(DVec3::new(x, y, z)),
            _ => None,
        }
    }
    fn rotation_values(axis_angle: DVec3) -> Vec<f64> {
        coordinates(axis_angle)
    }

    fn hull(local: &[Self], radius: f64) -> Option<Hull<Self>> {
        let (vertices, triangles) = try_convex_hull(local).ok()?;
        // The planes of the hull's triangles, not of parry's faces: parry merges adjacent
        // triangles whose normals differ by less than about 1.7e-4 rad into one face with the
        // normal of one of them, whose plane then misses the others' vertices by up to 1.7e-4
        // times their size (and q̂ inside with it). Outward: the centroid, the local origin, is
        // inside.
        let planes = triangles
            .iter()
            .filter_map(|&[a, b, c]| {
                let [a, b, c] = [a, b, c].map(|k| vertices[k as usize]);
                let normal = (b - a).cross(c - a).normalize_or_zero();
                let offset = normal.dot(a);
                (normal != DVec3::ZERO).then(|| {
                    if offset < 0.0 {
                        (-normal, -offset)
                    } else {
                        (normal, offset)
                    }
                })
            })
            .collect();
        let shape = ConvexPolyhedron::from_convex_mesh(vertices, &triangles)?;
        Some(Hull {
            shape,
            planes: Planes::new(planes, radius),
        })
    }

    fn triangle(a: Self, b: Self, c: Self) -> Result<Placed<Self>, ObstacleError> {
        let normal = (b - a).cross(c - a).normalize_or_zero();
        if normal == DVec3::ZERO {
            return Err(flat_triangle(a, b, c));
        }
        let sides = [b - a, c - b, c - a].map(DVec3::normalize);
        Ok(Placed::in_world(Kind::Plate(Plate {
            shape: Triangle::new(a, b, c),
            normal,
            sides,
        })))
    }

    #[inline]
    fn project_plate(plate: &Plate, q: Self) -> (Self, bool, Feature<Self>, Self) {
        let (projection, location) = plate.shape.project_local_point_and_get_location(q, false);
        let feature = match location {
            TrianglePointLocation::OnVertex(_) => Feature::Vertex,
            TrianglePointLocation::OnEdge(side, _) => Feature::Edge(plate.sides[side as usize]),
            TrianglePointLocation::OnFace(..) | TrianglePointLocation::OnSolid => {
                Feature::Face(plate.normal)
            }
        };
        (
            projection.point,
            projection.is_inside,
            feature,
            plate.normal,
        )
    }
    fn plate_shape(plate: &Plate) -> &dyn Shape {
        &plate.shape
    }
}

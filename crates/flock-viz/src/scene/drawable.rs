//! [`Drawable`]: obstacles as the figures draw them (TAC 2006 Section VII and Figs. 14–17: balls
//! and walls, filled grey), independent of how `flock-obstacles` represents them.
//!
//! Every drawable becomes, in a [`View`], either a circle or a convex polygon of the page plane;
//! polygons are cut to the plotting window before they are drawn. Obstacles of other shapes
//! (rotated boxes, polyhedra) are drawn through [`Drawable::ConvexHull`] of their vertices.

use flock_math::Vector;
use glam::{DVec2, DVec3};

use crate::draw::geometry::{Rect, circle_polygon, convex_hull};

/// A 3D wall whose unit normal n̂ has |n̂ · w| below this (w towards the viewer) is seen nearly
/// edge-on and drawn as a solid region; otherwise as its light boundary plane.
const EDGE_ON: f64 = 0.2;

/// The sides of the regular polygon that draws a circle.
pub(crate) const CIRCLE_SIDES: usize = 72;
use crate::scene::projection::View;
use crate::scene::projection::lift;

/// An obstacle to draw. Points are in the run's space: 2D runs use z = 0 (see [`lift`]).
///
/// # Example
/// ```
/// use flock_viz::Drawable;
/// use glam::{DVec2, DVec3};
///
/// let ball = Drawable::ball(DVec2::new(10.0, 0.0), 3.0); // a disc in 2D
/// let wall = Drawable::half_space(DVec3::ZERO, DVec3::Z); // the floor z ≤ 0 in 3D
/// let room = Drawable::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)); // a box
/// let pillar = Drawable::capsule(DVec3::ZERO, DVec3::Z, 0.5);
/// assert!(matches!(ball, Drawable::Disc { radius: 3.0, .. }));
/// assert!(matches!(room, Drawable::ConvexHull { ref points } if points.len() == 8));
/// # let _ = (wall, pillar);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Drawable {
    /// A disc (2D) or a ball (3D), which any orthographic view shows as a disc of the same radius.
    Disc {
        /// The centre.
        centre: DVec3,
        /// The radius.
        radius: f64,
    },
    /// A polygon with its vertices in order: a 2D obstacle, or a flat face in 3D.
    Polygon {
        /// The vertices, in order around the polygon.
        points: Vec<DVec3>,
    },
    /// A convex body given by points it is the hull of (a box's corners, a polyhedron's vertices):
    /// drawn as the convex hull of the points projected onto the page. This is the generic
    /// "convex polygon in the view plane".
    ConvexHull {
        /// Points whose convex hull is the body.
        points: Vec<DVec3>,
    },
    /// A capsule: the points within `radius` of the segment a–b (a stadium in 2D). Any
    /// orthographic view shows it as the convex hull of two discs.
    Capsule {
        /// One end of the segment.
        a: DVec3,
        /// The other end.
        b: DVec3,
        /// The radius.
        radius: f64,
    },
    /// A wall: the solid side { x : n · (x − p) ≤ 0 } of a line (2D) or plane (3D), with n the
    /// outward normal (parry's `HalfSpace` convention). Drawn cut to the scene. In 3D, a wall
    /// seen nearly edge-on (|n̂ · w| < 0.2, w towards the viewer) is drawn as its part inside
    /// the box that holds the whole run, filled like other obstacles; any other (a floor seen
    /// from above or obliquely) as the light section of its boundary plane by that box, drawn
    /// behind everything else.
    HalfPlane {
        /// A point of the boundary.
        point: DVec3,
        /// The outward normal (towards the free side).
        normal: DVec3,
    },
}

impl Drawable {
    /// A disc (2D) or ball (3D).
    #[must_use]
    pub fn ball<V: Vector>(centre: V, radius: f64) -> Self {
        Self::Disc {
            centre: lift(centre),
            radius,
        }
    }

    /// A polygon (vertices in order).
    #[must_use]
    pub fn polygon<V: Vector>(points: &[V]) -> Self {
        Self::Polygon {
            points: points.iter().map(|&p| lift(p)).collect(),
        }
    }

    /// The convex hull of points.
    #[must_use]
    pub fn convex_hull<V: Vector>(points: &[V]) -> Self {
        Self::ConvexHull {
            points: points.iter().map(|&p| lift(p)).collect(),
        }
    }

    /// An axis-aligned rectangle (2D) or box (3D) from its centre and half-extents.
    #[must_use]
    pub fn cuboid<V: Vector>(centre: V, half_extents: V) -> Self {
        let (c, h) = (lift(centre), lift(half_extents));
        let points = (0..8)
            .map(|k| {
                let sign = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
                c + DVec3::new(sign(1) * h.x, sign(2) * h.y, sign(4) * h.z)
            })
            .collect();
        Self::ConvexHull { points }
    }

    /// A capsule: the points within `radius` of the segment a–b.
    #[must_use]
    pub fn capsule<V: Vector>(a: V, b: V, radius: f64) -> Self {
        Self::Capsule {
            a: lift(a),
            b: lift(b),
            radius,
        }
    }

    /// A wall: the half-space { x : n · (x − p) ≤ 0 }, n the outward normal.
    #[must_use]
    pub fn half_space<V: Vector>(point: V, outward_normal: V) -> Self {
        Self::HalfPlane {
            point: lift(point),
            normal: lift(outward_normal),
        }
    }

    /// The box of space this obstacle lies in, if it is bounded (walls are not).
    pub(crate) fn bounds(&self) -> Option<(DVec3, DVec3)> {
        match self {
            Self::Disc { centre, radius } => Some((
                *centre - DVec3::splat(*radius),
                *centre + DVec3::splat(*radius),
            )),
            Self::Polygon { points } | Self::ConvexHull { points } => {
                let first = *points.first()?;
                Some(
                    points
                        .iter()
                        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
                )
            }
            Self::Capsule { a, b, radius } => {
                let r = DVec3::splat(*radius);
                Some((a.min(*b) - r, a.max(*b) + r))
            }
            Self::HalfPlane { .. } => None,
        }
    }

    /// The page-plane shapes of `obstacles` in `view`, in drawing order: light wall planes
    /// first (they lie behind everything), then the others in their order; each with its
    /// obstacle's [`Drawable::front_depth`].
    pub(crate) fn project_all(
        obstacles: &[Self],
        view: View,
        dim: usize,
        world: (DVec3, DVec3),
    ) -> Vec<(Shape, Option<f64>)> {
        let shapes: Vec<(Shape, Option<f64>)> = obstacles
            .iter()
            .filter_map(|o| Some((o.project(view, dim, world)?, o.front_depth(view))))
            .collect();
        let (mut planes, solids): (Vec<_>, Vec<_>) = shapes
            .into_iter()
            .partition(|(s, _)| matches!(s, Shape::Plane(_)));
        planes.extend(solids);
        planes
    }

    /// How far towards the viewer of `view` the obstacle's nearest point lies ([`View::depth`]);
    /// `None` for a wall, which reaches every depth.
    pub(crate) fn front_depth(&self, view: View) -> Option<f64> {
        let nearest = |points: &[DVec3]| points.iter().map(|&p| view.depth(p)).reduce(f64::max);
        match self {
            Self::Disc { centre, radius } => Some(view.depth(*centre) + radius),
            Self::Polygon { points } | Self::ConvexHull { points } => nearest(points),
            Self::Capsule { a, b, radius } => Some(view.depth(*a).max(view.depth(*b)) + radius),
            Self::HalfPlane { .. } => None,
        }
    }

    /// The page-plane shape of this obstacle in `view` (`dim` 2 draws x, y whatever the view),
    /// with walls cut to `world` (a box of space holding everything drawn).
    pub(crate) fn project(&self, view: View, dim: usize, world: (DVec3, DVec3)) -> Option<Shape> {
        let project = |p: DVec3| project_point(view, dim, p);
        match self {
            Self::Disc { centre, radius } => Some(Shape::Circle {
                centre: project(*centre),
                radius: *radius,
            }),
            Self::Polygon { points } => {
                let points: Vec<DVec2> = points.iter().map(|&p| project(p)).collect();
                (points.len() >= 3).then_some(Shape::Polygon(points))
            }
            Self::ConvexHull { points } => {
                let projected: Vec<DVec2> = points.iter().map(|&p| project(p)).collect();
                let hull = convex_hull(&projected);
                (hull.len() >= 3).then_some(Shape::Polygon(hull))
            }
            Self::Capsule { a, b, radius } => {
                let mut points = circle_polygon(project(*a), *radius, CIRCLE_SIDES);
                points.extend(circle_polygon(project(*b), *radius, CIRCLE_SIDES));
                let hull = convex_hull(&points);
                (hull.len() >= 3).then_some(Shape::Polygon(hull))
            }
            Self::HalfPlane { point, normal } => {
                let seen_edge_on =
                    dim == 2 || normal.normalize_or_zero().dot(view.basis().2).abs() < EDGE_ON;
                if seen_edge_on {
                    let corners = half_space_in_box(*point, *normal, world);
                    let projected: Vec<DVec2> = corners.into_iter().map(project).collect();
                    let hull = convex_hull(&projected);
                    (hull.len() >= 3).then_some(Shape::Polygon(hull))
                } else {
                    let section = plane_in_box(*point, *normal, world);
                    let projected: Vec<DVec2> = section.into_iter().map(project).collect();
                    let hull = convex_hull(&projected);
                    (hull.len() >= 3).then_some(Shape::Plane(hull))
                }
            }
        }
    }
}

/// The page coordinates of a point: (x, y) in 2D, the view's projection in 3D.
pub(crate) fn project_point(view: View, dim: usize, p: DVec3) -> DVec2 {
    if dim == 2 {
        p.truncate()
    } else {
        view.project(p)
    }
}

/// The page-plane shape of an obstacle.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Shape {
    /// A circle.
    Circle { centre: DVec2, radius: f64 },
    /// A simple polygon, vertices in order: a solid obstacle.
    Polygon(Vec<DVec2>),
    /// The boundary plane of a 3D wall seen face-on (a floor from above), as the convex polygon
    /// where it crosses the scene's box: drawn light, behind the flock.
    Plane(Vec<DVec2>),
}

impl Shape {
    /// The page rectangle it lies in.
    pub(crate) fn bounds(&self) -> Rect {
        match self {
            Self::Circle { centre, radius } => Rect {
                min: *centre - DVec2::splat(*radius),
                max: *centre + DVec2::splat(*radius),
            },
            Self::Polygon(points) | Self::Plane(points) => {
                points.iter().fold(Rect::EMPTY, |r, &p| r.with_point(p))
            }
        }
    }
}

/// The vertices of { x ∈ box : n · (x − p) = 0 }: where the box's edges cross the plane.
fn plane_in_box(point: DVec3, normal: DVec3, (lo, hi): (DVec3, DVec3)) -> Vec<DVec3> {
    let corner = |k: usize| box_corner(lo, hi, k);
    let side = |x: DVec3| normal.dot(x - point);
    let mut out: Vec<DVec3> = (0..8).map(corner).filter(|&c| side(c) == 0.0).collect();
    out.extend(edge_crossings(lo, hi, side));
    out
}

/// Corner `k` (bits 0, 1, 2 choosing the upper x, y, z) of the box lo–hi.
fn box_corner(lo: DVec3, hi: DVec3, k: usize) -> DVec3 {
    DVec3::new(
        if k & 1 == 0 { lo.x } else { hi.x },
        if k & 2 == 0 { lo.y } else { hi.y },
        if k & 4 == 0 { lo.z } else { hi.z },
    )
}

/// The points where the box's edges cross the zero set of the affine function `side`.
fn edge_crossings(lo: DVec3, hi: DVec3, side: impl Fn(DVec3) -> f64) -> Vec<DVec3> {
    let mut out = Vec::new();
    for a in 0..8 {
        for bit in [1, 2, 4] {
            if a & bit != 0 {
                continue;
            }
            let (ca, cb) = (box_corner(lo, hi, a), box_corner(lo, hi, a | bit));
            let (sa, sb) = (side(ca), side(cb));
            if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
                out.push(ca + (sa / (sa - sb)) * (cb - ca));
            }
        }
    }
    out
}

/// The vertices of { x ∈ box : n · (x − p) ≤ 0 }: the box's corners on the solid side and the
/// points where the box's edges cross the boundary plane.
fn half_space_in_box(point: DVec3, normal: DVec3, (lo, hi): (DVec3, DVec3)) -> Vec<DVec3> {
    let side = |x: DVec3| normal.dot(x - point);
    let mut out: Vec<DVec3> = (0..8)
        .map(|k| box_corner(lo, hi, k))
        .filter(|&c| side(c) <= 0.0)
        .collect();
    out.extend(edge_crossings(lo, hi, side));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wall_in_2d_is_cut_to_the_world_box() {
        let wall = Drawable::half_space(DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
        let world = (DVec3::new(-2.0, -1.0, 0.0), DVec3::new(2.0, 1.0, 0.0));
        let Some(Shape::Polygon(p)) = wall.project(View::default(), 2, world) else {
            panic!("a wall crossing the box is a polygon");
        };
        let r = Shape::Polygon(p).bounds();
        assert_eq!(r.min, DVec2::new(-2.0, -1.0));
        assert_eq!(r.max, DVec2::new(0.0, 1.0));
    }

    #[test]
    fn a_box_seen_from_above_is_a_rectangle() {
        let b = Drawable::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
        let world = (DVec3::splat(-10.0), DVec3::splat(10.0));
        let Some(Shape::Polygon(p)) = b.project(View::TOP, 3, world) else {
            panic!("a box is a polygon");
        };
        assert_eq!(p.len(), 4);
        let r = Shape::Polygon(p).bounds();
        assert_eq!(
            (r.min, r.max),
            (DVec2::new(-1.0, -2.0), DVec2::new(1.0, 2.0))
        );
    }
}

//! The β-agent of an obstacle's parry shape, written once for both dimensions ([`beta_agent`]).
//!
//! What differs per dimension — parry's types and the calls that project onto them — is the
//! [`Parry`] trait, implemented for `DVec2` in `dim2.rs` and for `DVec3` in `dim3.rs` (as
//! flock-math's `Vector` carries the algebra); the shapes of an obstacle are a [`Kind`] of either.

use core::fmt::Debug;

use flock_math::Vector;

use crate::polytope::{self, Planes};
use crate::thin::{self, Feature};
use crate::{BetaAgent, ball, capsule, cuboid, wall};

/// A dimension's parry types and the projections the β-agent needs of them.
pub(crate) trait Parry: Vector {
    /// A rigid motion (rotation and translation).
    type Pose: Clone + Debug;
    /// A ball (disc in 2D).
    type Ball: Clone + Debug;
    /// A half-space (half-plane in 2D).
    type HalfSpace: Clone + Debug;
    /// A box of half-extents.
    type Cuboid: Clone + Debug;
    /// A convex polygon or polyhedron.
    type Hull: Clone + Debug;
    /// A capsule (stadium in 2D).
    type Capsule: Clone + Debug;
    /// A segment.
    type Segment: Clone + Debug;
    /// A triangle of zero thickness (3D; none in 2D).
    type Plate: Clone + Debug;

    /// The pose's translation.
    fn translation(pose: &Self::Pose) -> Self;
    /// A point of the pose's frame in the world.
    fn to_world_point(pose: &Self::Pose, x: Self) -> Self;
    /// A vector of the pose's frame in the world.
    fn to_world_vector(pose: &Self::Pose, v: Self) -> Self;
    /// A point of the world in the pose's frame.
    fn to_local_point(pose: &Self::Pose, x: Self) -> Self;
    /// A vector of the world in the pose's frame.
    fn to_local_vector(pose: &Self::Pose, v: Self) -> Self;

    /// The ball's radius.
    fn radius(ball: &Self::Ball) -> f64;
    /// parry's projection of the world point `q` on the ball placed by `pose`: the closest
    /// boundary point and whether `q` is inside.
    fn project_ball(ball: &Self::Ball, pose: &Self::Pose, q: Self) -> (Self, bool);
    /// The half-space's outward normal, in its frame.
    fn wall_normal(wall: &Self::HalfSpace) -> Self;
    /// As [`Parry::project_ball`], on the half-space.
    fn project_wall(wall: &Self::HalfSpace, pose: &Self::Pose, q: Self) -> (Self, bool);
    /// The box's half-extents.
    fn half_extents(cuboid: &Self::Cuboid) -> Self;
    /// The projection of a point of the box's frame on the box.
    fn project_cuboid(cuboid: &Self::Cuboid, local_q: Self) -> (Self, bool);
    /// The projection of a point of the hull's frame on the hull.
    fn project_hull(hull: &Self::Hull, local_q: Self) -> (Self, bool);
    /// The capsule's segment `[a, b]` and radius.
    fn capsule(capsule: &Self::Capsule) -> (Self, Self, f64);
    /// The projection of a world point on the capsule (placed in world coordinates).
    fn project_capsule(capsule: &Self::Capsule, q: Self) -> (Self, bool);
    /// The projection of a world point on the segment, the feature it lies on and the normal
    /// to use for an α-agent on it.
    fn project_segment(segment: &Self::Segment, q: Self) -> (Self, bool, Feature<Self>, Self);
    /// As [`Parry::project_segment`], on the plate.
    fn project_plate(plate: &Self::Plate, q: Self) -> (Self, bool, Feature<Self>, Self);
}

/// The shapes an obstacle can be, in the frames noted.
#[derive(Clone, Debug)]
pub(crate) enum Kind<V: Parry> {
    /// World frame through the pose (its translation is the centre).
    Ball(V::Ball),
    /// World frame through the pose.
    Wall(V::HalfSpace),
    /// Local frame: the pose's translation and rotation.
    Cuboid(V::Cuboid),
    /// Local frame: the pose's translation (the centroid of the points).
    Hull(Box<Hull<V>>),
    /// World coordinates (identity pose).
    Capsule(V::Capsule),
    /// World coordinates (identity pose).
    Segment(V::Segment),
    /// World coordinates (identity pose).
    Plate(V::Plate),
}

/// A convex polygon or polyhedron and its edge lines or face planes.
#[derive(Clone, Debug)]
pub(crate) struct Hull<V: Parry> {
    pub(crate) shape: V::Hull,
    pub(crate) planes: Planes<V>,
}

/// The β-agent of the α-agent `(q, p)` on the shape `kind` placed by `pose`.
#[inline]
pub(crate) fn beta_agent<V: Parry>(kind: &Kind<V>, pose: &V::Pose, q: V, p: V) -> BetaAgent<V> {
    match kind {
        Kind::Ball(shape) => {
            let (projected, inside) = V::project_ball(shape, pose, q);
            let centre = V::translation(pose);
            ball::beta_agent(q, p, centre, V::radius(shape), projected, inside)
        }
        Kind::Wall(shape) => {
            let (projected, inside) = V::project_wall(shape, pose, q);
            let normal = V::to_world_vector(pose, V::wall_normal(shape));
            wall::beta_agent(q, p, normal, projected, inside)
        }
        Kind::Cuboid(shape) => {
            let local_q = V::to_local_point(pose, q);
            let local_p = V::to_local_vector(pose, p);
            let (projected, inside) = V::project_cuboid(shape, local_q);
            let half_extents = V::half_extents(shape);
            let local = cuboid::beta_agent(local_q, local_p, half_extents, projected, inside);
            BetaAgent::with_velocity(
                q,
                V::to_world_point(pose, local.position),
                V::to_world_vector(pose, local.normal),
                V::to_world_vector(pose, local.velocity),
                local.mu,
                local.inside,
            )
        }
        Kind::Hull(hull) => {
            let translation = V::translation(pose);
            let local_q = q - translation;
            let (projected, inside) = V::project_hull(&hull.shape, local_q);
            let local = polytope::beta_agent(local_q, p, &hull.planes, projected, inside);
            BetaAgent::with_velocity(
                q,
                local.position + translation,
                local.normal,
                local.velocity,
                local.mu,
                local.inside,
            )
        }
        Kind::Capsule(shape) => {
            let (projected, inside) = V::project_capsule(shape, q);
            let (a, b, radius) = V::capsule(shape);
            capsule::beta_agent(q, p, a, b, radius, projected, inside)
        }
        Kind::Segment(shape) => {
            let (projected, inside, feature, normal) = V::project_segment(shape, q);
            thin::beta_agent(q, p, projected, inside, feature, normal)
        }
        Kind::Plate(plate) => {
            let (projected, inside, feature, normal) = V::project_plate(plate, q);
            thin::beta_agent(q, p, projected, inside, feature, normal)
        }
    }
}

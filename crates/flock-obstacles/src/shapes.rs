//! An obstacle's parry shape, written once for both dimensions: its β-agent ([`beta_agent`]) and
//! the constructors and scenario reading the two dimensions share ([`Placed`]).
//!
//! What differs per dimension — parry's types, the calls that build and project onto them, the
//! convex hull and the triangle — is the [`Parry`] trait, implemented for `DVec2` in `dim2.rs`
//! and for `DVec3` in `dim3.rs` (as flock-math's `Vector` carries the algebra); the calls that
//! read the same in both parry crates are written once, in `parry_calls.rs`. The shapes of an
//! obstacle are a [`Kind`] of either.
//!
//! [`Parry`], [`Kind`], [`Placed`] and [`Hull`] are `pub` in this private module only so that the
//! public [`ConvexObstacle`](crate::ConvexObstacle) may hold them: nothing outside the crate can
//! name them, and so nothing outside can implement [`Parry`].

use core::fmt::Debug;

use flock_math::Vector;

use crate::error::{check_finite, coordinates, from_coordinates};
use crate::polytope::{self, Planes};
use crate::thin::{self, Feature};
use crate::{BetaAgent, ObstacleError, ObstacleSpec, ball, capsule, cuboid, wall};

/// A dimension's parry types and the calls the obstacles make on them.
pub trait Parry: Vector {
    /// A rigid motion (rotation and translation).
    type Pose: Clone + Debug + Send + Sync;
    /// A ball (disc in 2D).
    type Ball: Clone + Debug + Send + Sync;
    /// A half-space (half-plane in 2D).
    type HalfSpace: Clone + Debug + Send + Sync;
    /// A box of half-extents.
    type Cuboid: Clone + Debug + Send + Sync;
    /// A convex polygon or polyhedron.
    type Hull: Clone + Debug + Send + Sync;
    /// A capsule (stadium in 2D).
    type Capsule: Clone + Debug + Send + Sync;
    /// A segment.
    type Segment: Clone + Debug + Send + Sync;
    /// A triangle of zero thickness (3D; none in 2D).
    type Plate: Clone + Debug + Send + Sync;
    /// A rotation: an angle in 2D, an axis-angle vector in 3D.
    type Rotation: Copy;
    /// Any of parry's shapes (`dyn Shape`), for other parry queries.
    type Shape: ?Sized;

    /// The identity pose.
    fn identity() -> Self::Pose;
    /// The translation to `translation`.
    fn at(translation: Self) -> Self::Pose;
    /// The rotation `rotation` followed by the translation to `translation`.
    fn posed(translation: Self, rotation: Self::Rotation) -> Self::Pose;
    /// The rotation a scenario writes as `values` (none for `[]`), or `None` for the wrong count.
    fn rotation(values: &[f64]) -> Option<Self::Rotation>;
    /// The numbers of `rotation`, as a scenario writes them.
    fn rotation_values(rotation: Self::Rotation) -> Vec<f64>;
    /// A ball of radius `radius` at the origin.
    fn ball(radius: f64) -> Self::Ball;
    /// The half-space through the origin with outward unit normal `normal`.
    fn half_space(normal: Self) -> Self::HalfSpace;
    /// A box of half-extents `half_extents` centred at the origin.
    fn cuboid(half_extents: Self) -> Self::Cuboid;
    /// The capsule of the points within `radius` of `[a, b]`.
    fn capsule_between(a: Self, b: Self, radius: f64) -> Self::Capsule;
    /// The segment `[a, b]`.
    fn segment(a: Self, b: Self) -> Self::Segment;
    /// The convex hull of `local` (points about their centroid, checked by
    /// [`Placed::convex_hull`], at most `radius` from it) with the planes `(n_j, o_j)` of its
    /// faces (edges in 2D), unit outward normals `n_j`; `None` when parry finds the points flat.
    fn hull(local: &[Self], radius: f64) -> Option<Hull<Self>>;
    /// The triangle `abc` of finite vertices not on one line, checked by [`Placed::triangle`]: a
    /// convex polygon in 2D, a plate of zero thickness in 3D.
    fn triangle(a: Self, b: Self, c: Self) -> Result<Placed<Self>, ObstacleError>;

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

    /// The plate as a parry shape.
    fn plate_shape(plate: &Self::Plate) -> &Self::Shape;
    /// The shape `kind` holds, as a parry shape in its frame.
    fn shape(kind: &Kind<Self>) -> &Self::Shape;
    /// The bounding box `(mins, maxs)` of `shape` placed by `pose`.
    fn aabb(shape: &Self::Shape, pose: &Self::Pose) -> (Self, Self);
}

/// The shapes an obstacle can be, in the frames noted.
#[derive(Clone, Debug)]
pub enum Kind<V: Parry> {
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

/// An obstacle of either dimension: its shape and the pose placing it in the world (the body of
/// [`ConvexObstacle`](crate::ConvexObstacle), whose constructors document these).
#[derive(Clone, Debug)]
pub struct Placed<V: Parry> {
    pub(crate) kind: Kind<V>,
    pub(crate) pose: V::Pose,
}

impl<V: Parry> Placed<V> {
    /// A shape given in world coordinates (the identity pose).
    pub(crate) fn in_world(kind: Kind<V>) -> Self {
        Self {
            kind,
            pose: V::identity(),
        }
    }

    /// The closed ball `B(centre, radius)`.
    pub(crate) fn ball(centre: V, radius: f64) -> Result<Self, ObstacleError> {
        ball::validate(centre, radius)?;
        Ok(Self {
            kind: Kind::Ball(V::ball(radius)),
            pose: V::at(centre),
        })
    }

    /// The closed half-space `{x : a · (x − point) ≤ 0}`, `a` the unit `outward_normal`.
    pub(crate) fn wall(point: V, outward_normal: V) -> Result<Self, ObstacleError> {
        let normal = wall::unit_normal(point, outward_normal)?;
        Ok(Self {
            kind: Kind::Wall(V::half_space(normal)),
            pose: V::at(point),
        })
    }

    /// The closed box of half-widths `half_extents`, turned by `rotation`, centred at `centre`.
    pub(crate) fn cuboid(
        centre: V,
        half_extents: V,
        rotation: V::Rotation,
    ) -> Result<Self, ObstacleError> {
        check_finite("centre", centre)?;
        cuboid::validate(half_extents)?;
        let values = V::rotation_values(rotation);
        if !values.iter().all(|x| x.is_finite()) {
            return Err(ObstacleError::InvalidRotation {
                rotation: values,
                dim: V::DIM,
            });
        }
        Ok(Self {
            kind: Kind::Cuboid(V::cuboid(half_extents)),
            pose: V::posed(centre, rotation),
        })
    }

    /// The capsule of the points within `radius` of `[a, b]`; the ball `B(a, radius)` when `a = b`.
    pub(crate) fn capsule(a: V, b: V, radius: f64) -> Result<Self, ObstacleError> {
        check_finite("a", a)?;
        check_finite("b", b)?;
        ball::check_radius(radius)?;
        if a == b {
            return Self::ball(a, radius);
        }
        Ok(Self::in_world(Kind::Capsule(V::capsule_between(
            a, b, radius,
        ))))
    }

    /// The segment `[a, b]` of zero thickness.
    pub(crate) fn segment(a: V, b: V) -> Result<Self, ObstacleError> {
        check_finite("a", a)?;
        check_finite("b", b)?;
        if a == b {
            return Err(ObstacleError::DegenerateSegment {
                point: coordinates(a),
            });
        }
        Ok(Self::in_world(Kind::Segment(V::segment(a, b))))
    }

    /// The convex hull of `points` (any order), validated: finite, at least `V::DIM + 1`, not
    /// flat, and none strictly inside the hull of the others. Placed at the points' centroid.
    pub(crate) fn convex_hull(points: &[V]) -> Result<Self, ObstacleError> {
        polytope::validate(points)?;
        let centroid = flock_math::mean(points);
        let local: Vec<V> = points.iter().map(|&x| x - centroid).collect();
        let radius = local.iter().map(|x| x.length()).fold(0.0, f64::max);
        let hull = V::hull(&local, radius).ok_or(ObstacleError::FlatHull { dim: V::DIM })?;
        hull.planes.check_convex(&local, points)?;
        Ok(Self {
            kind: Kind::Hull(Box::new(hull)),
            pose: V::at(centroid),
        })
    }

    /// The triangle of vertices `a`, `b`, `c`, validated: finite, not on one line.
    pub(crate) fn triangle(a: V, b: V, c: V) -> Result<Self, ObstacleError> {
        check_finite("a", a)?;
        check_finite("b", b)?;
        check_finite("c", c)?;
        if polytope::affine_rank(&[a, b, c]) < 2 {
            return Err(flat_triangle(a, b, c));
        }
        V::triangle(a, b, c)
    }

    /// The obstacle `spec` describes, validated: vectors of `V::DIM` coordinates, a cuboid's
    /// `rotation` of [`Parry::rotation`]'s count or none.
    pub(crate) fn from_spec(spec: &ObstacleSpec) -> Result<Self, ObstacleError> {
        match spec {
            ObstacleSpec::Ball { centre, radius } => {
                Self::ball(from_coordinates("centre", centre)?, *radius)
            }
            ObstacleSpec::Wall { point, normal } => Self::wall(
                from_coordinates("point", point)?,
                from_coordinates("normal", normal)?,
            ),
            ObstacleSpec::Cuboid {
                centre,
                half_extents,
                rotation,
            } => {
                let turn = V::rotation(rotation).ok_or_else(|| ObstacleError::InvalidRotation {
                    rotation: rotation.clone(),
                    dim: V::DIM,
                })?;
                Self::cuboid(
                    from_coordinates("centre", centre)?,
                    from_coordinates("half_extents", half_extents)?,
                    turn,
                )
            }
            ObstacleSpec::ConvexHull { points } => {
                let points = points
                    .iter()
                    .enumerate()
                    .map(|(i, x)| from_coordinates(&format!("points[{i}]"), x))
                    .collect::<Result<Vec<V>, _>>()?;
                Self::convex_hull(&points)
            }
            ObstacleSpec::Capsule { a, b, radius } => Self::capsule(
                from_coordinates("a", a)?,
                from_coordinates("b", b)?,
                *radius,
            ),
            ObstacleSpec::Segment { a, b } => {
                Self::segment(from_coordinates("a", a)?, from_coordinates("b", b)?)
            }
            ObstacleSpec::Triangle { a, b, c } => Self::triangle(
                from_coordinates("a", a)?,
                from_coordinates("b", b)?,
                from_coordinates("c", c)?,
            ),
        }
    }

    /// Whether it is a wall (unbounded, without a bounding box).
    pub(crate) fn is_wall(&self) -> bool {
        matches!(self.kind, Kind::Wall(_))
    }

    /// The β-agent of the α-agent `(q, p)` on it.
    #[inline]
    pub(crate) fn beta_agent(&self, q: V, p: V) -> BetaAgent<V> {
        beta_agent(&self.kind, &self.pose, q, p)
    }
}

/// A convex polygon or polyhedron and its edge lines or face planes.
#[derive(Clone, Debug)]
pub struct Hull<V: Parry> {
    pub(crate) shape: V::Hull,
    pub(crate) planes: Planes<V>,
}

/// The error for the triangle `abc` whose vertices are on one line.
pub(crate) fn flat_triangle<V: Vector>(a: V, b: V, c: V) -> ObstacleError {
    ObstacleError::FlatTriangle {
        vertices: [coordinates(a), coordinates(b), coordinates(c)],
    }
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

//! The [`Parry`](crate::shapes::Parry) types and methods that read the same in both dimensions,
//! written once: [`parry_calls!`] expands to them inside `impl Parry for DVec2` (`dim2.rs`) and
//! `impl Parry for DVec3` (`dim3.rs`).
//!
//! parry2d-f64 and parry3d-f64 are one source compiled for two dimensions: their shapes, poses and
//! queries have the same names and calls, but they are the types and traits of two crates, which
//! no generic bound can join (`PointQuery` of one is not `PointQuery` of the other). So the calls
//! are written once as tokens, and each expansion names its own crate's types and traits: those
//! its file imports (`Pose`, `Ball`, …, `PointQuery`, `PointQueryWithLocation`,
//! `SegmentPointLocation`), bound to the impl's associated types (`Self::Ball` is parry2d's `Ball`
//! in one, parry3d's in the other). What differs per dimension (the rotation, the hull and its
//! type, the triangle, the plate) stays in the dimension's file.

/// The associated types and methods of `Parry` whose text is the same for parry2d-f64 and
/// parry3d-f64 (see the module documentation); expanded inside an `impl Parry for …` block whose
/// file imports `Pose`, `Ball`, `HalfSpace`, `Cuboid`, `Capsule`, `Segment` and `Shape` from its
/// parry crate.
macro_rules! parry_calls {
    () => {
        type Pose = Pose;
        type Ball = Ball;
        type HalfSpace = HalfSpace;
        type Cuboid = Cuboid;
        type Capsule = Capsule;
        type Segment = Segment;
        type Shape = dyn Shape;

        fn identity() -> Self::Pose {
            <Self::Pose>::IDENTITY
        }
        fn at(translation: Self) -> Self::Pose {
            <Self::Pose>::from_translation(translation)
        }
        fn posed(translation: Self, rotation: Self::Rotation) -> Self::Pose {
            <Self::Pose>::new(translation, rotation)
        }
        fn ball(radius: f64) -> Self::Ball {
            <Self::Ball>::new(radius)
        }
        fn half_space(normal: Self) -> Self::HalfSpace {
            <Self::HalfSpace>::new(normal)
        }
        fn cuboid(half_extents: Self) -> Self::Cuboid {
            <Self::Cuboid>::new(half_extents)
        }
        fn capsule_between(a: Self, b: Self, radius: f64) -> Self::Capsule {
            <Self::Capsule>::new(a, b, radius)
        }
        fn segment(a: Self, b: Self) -> Self::Segment {
            <Self::Segment>::new(a, b)
        }

        #[inline]
        fn translation(pose: &Self::Pose) -> Self {
            pose.translation
        }
        #[inline]
        fn to_world_point(pose: &Self::Pose, x: Self) -> Self {
            pose.transform_point(x)
        }
        #[inline]
        fn to_world_vector(pose: &Self::Pose, v: Self) -> Self {
            pose.transform_vector(v)
        }
        #[inline]
        fn to_local_point(pose: &Self::Pose, x: Self) -> Self {
            pose.inverse_transform_point(x)
        }
        #[inline]
        fn to_local_vector(pose: &Self::Pose, v: Self) -> Self {
            pose.inverse_transform_vector(v)
        }
        #[inline]
        fn radius(ball: &Self::Ball) -> f64 {
            ball.radius
        }
        #[inline]
        fn project_ball(ball: &Self::Ball, pose: &Self::Pose, q: Self) -> (Self, bool) {
            let projection = ball.project_point(pose, q, false);
            (projection.point, projection.is_inside)
        }
        #[inline]
        fn wall_normal(wall: &Self::HalfSpace) -> Self {
            wall.normal
        }
        #[inline]
        fn project_wall(wall: &Self::HalfSpace, pose: &Self::Pose, q: Self) -> (Self, bool) {
            let projection = wall.project_point(pose, q, false);
            (projection.point, projection.is_inside)
        }
        #[inline]
        fn half_extents(cuboid: &Self::Cuboid) -> Self {
            cuboid.half_extents
        }
        #[inline]
        fn project_cuboid(cuboid: &Self::Cuboid, local_q: Self) -> (Self, bool) {
            let projection = cuboid.project_local_point(local_q, false);
            (projection.point, projection.is_inside)
        }
        #[inline]
        fn project_hull(hull: &Self::Hull, local_q: Self) -> (Self, bool) {
            let projection = hull.project_local_point(local_q, false);
            (projection.point, projection.is_inside)
        }
        #[inline]
        fn capsule(capsule: &Self::Capsule) -> (Self, Self, f64) {
            (capsule.segment.a, capsule.segment.b, capsule.radius)
        }
        #[inline]
        fn project_capsule(capsule: &Self::Capsule, q: Self) -> (Self, bool) {
            let projection = capsule.project_local_point(q, false);
            (projection.point, projection.is_inside)
        }
        #[inline]
        fn project_segment(segment: &Self::Segment, q: Self) -> (Self, bool, Feature<Self>, Self) {
            let (projection, location) = segment.project_local_point_and_get_location(q, false);
            let direction = (segment.b - segment.a).normalize();
            let feature = match location {
                SegmentPointLocation::OnVertex(_) => Feature::Vertex,
                SegmentPointLocation::OnEdge(_) => Feature::Edge(direction),
            };
            let normal = orthogonal_unit(direction);
            (projection.point, projection.is_inside, feature, normal)
        }

        fn shape(kind: &Kind<Self>) -> &Self::Shape {
            match kind {
                Kind::Ball(ball) => ball,
                Kind::Wall(half_space) => half_space,
                Kind::Cuboid(cuboid) => cuboid,
                Kind::Hull(hull) => &hull.shape,
                Kind::Capsule(capsule) => capsule,
                Kind::Segment(segment) => segment,
                Kind::Plate(plate) => Self::plate_shape(plate),
            }
        }
        fn aabb(shape: &Self::Shape, pose: &Self::Pose) -> (Self, Self) {
            let aabb = shape.compute_aabb(pose);
            (aabb.mins, aabb.maxs)
        }
    };
}

pub(crate) use parry_calls;

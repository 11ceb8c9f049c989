//! [`Obstacle2d`]: convex obstacles of the plane, projected by parry2d-f64.
//!
//! - [`Obstacle2d::ball`], [`Obstacle2d::wall`], [`Obstacle2d::cuboid`],
//!   [`Obstacle2d::convex_hull`], [`Obstacle2d::capsule`], [`Obstacle2d::segment`],
//!   [`Obstacle2d::triangle`]: the shapes; [`Obstacle2d::from_spec`] from an [`ObstacleSpec`].
//! - [`Obstacle::beta_agent`]: the β-agent of an α-agent `(q, p)` on it.

use glam::DVec2;
use parry2d_f64::math::Pose;
use parry2d_f64::query::{PointQuery, PointQueryWithLocation};
use parry2d_f64::shape::{
    Ball, Capsule, ConvexPolygon, Cuboid, HalfSpace, Segment, SegmentPointLocation, Shape,
};
use parry2d_f64::transformation::convex_hull;

use crate::basis::orthogonal_unit;
use crate::error::{check_finite, coordinates};
use crate::polytope::{self, Planes};
use crate::shapes::{Hull, Kind, Parry, Placed};
use crate::thin::Feature;
use crate::{BetaAgent, Obstacle, ObstacleError, ObstacleSpec};

/// A convex obstacle of ℝ²: a parry shape placed by a [`Pose`].
///
/// The β-agent's position `q̂` and the inside test come from parry's
/// `project_point(pose, q, solid = false)`, which returns the closest *boundary* point even for an
/// α-agent inside (except inside convex polygons, see [`convex_hull`](Self::convex_hull)); the
/// normal `a`, `μ` and the velocity `p̂` follow the closed forms per feature listed on
/// [`BetaAgent`].
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle2d};
/// use glam::DVec2;
///
/// let disc = Obstacle2d::ball(DVec2::new(10.0, 0.0), 2.0)?;
/// let beta = disc.beta_agent(DVec2::ZERO, DVec2::new(1.0, 1.0));
/// assert_eq!(beta.position, DVec2::new(8.0, 0.0));
/// assert_eq!(beta.normal, DVec2::new(-1.0, 0.0));
/// assert_eq!(beta.mu, 0.2); // R / ‖q − y‖
/// assert_eq!(beta.velocity, DVec2::new(0.0, 0.2));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Obstacle2d(Placed<DVec2>);

impl Obstacle2d {
    /// The closed disc of radius `radius` centred at `centre`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle2d;
    /// use glam::DVec2;
    ///
    /// let disc = Obstacle2d::ball(DVec2::new(1.0, 2.0), 0.5)?;
    /// assert_eq!(disc.pose().translation, DVec2::new(1.0, 2.0));
    /// assert_eq!(disc.shape().as_ball().map(|b| b.radius), Some(0.5));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn ball(centre: DVec2, radius: f64) -> Result<Self, ObstacleError> {
        Placed::ball(centre, radius).map(Self)
    }

    /// The closed half-plane `{x : a · (x − point) ≤ 0}` bounded by the line through `point`, with
    /// `a = outward_normal / ‖outward_normal‖` pointing out of the wall, towards the agents.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidNormal`] when `outward_normal` is zero or not finite;
    /// [`ObstacleError::NonFinitePoint`] when `point` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle2d;
    /// use glam::DVec2;
    ///
    /// // The wall x ≥ 5 (agents live at x < 5): its outward normal points to −x.
    /// let wall = Obstacle2d::wall(DVec2::new(5.0, 0.0), DVec2::new(-3.0, 0.0))?;
    /// assert_eq!(wall.shape().as_halfspace().map(|h| h.normal), Some(DVec2::new(-1.0, 0.0)));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn wall(point: DVec2, outward_normal: DVec2) -> Result<Self, ObstacleError> {
        Placed::wall(point, outward_normal).map(Self)
    }

    /// The closed rectangle of half-widths `half_extents` along its own axes, centred at `centre`
    /// and turned counter-clockwise by `angle` radians.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidHalfExtent`] unless each half extent is finite and `> 0`;
    /// [`ObstacleError::InvalidRotation`] when `angle` is not finite;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d};
    /// use glam::DVec2;
    ///
    /// // A 4 × 2 rectangle turned by 90°: 2 wide along x, 4 tall along y.
    /// let rectangle = Obstacle2d::cuboid(DVec2::ZERO, DVec2::new(2.0, 1.0), core::f64::consts::FRAC_PI_2)?;
    /// let beta = rectangle.beta_agent(DVec2::new(0.5, 5.0), DVec2::new(1.0, 1.0));
    /// assert!((beta.position - DVec2::new(0.5, 2.0)).length() < 1e-12);
    /// assert!((beta.velocity - DVec2::new(1.0, 0.0)).length() < 1e-12); // P p on the top face
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn cuboid(centre: DVec2, half_extents: DVec2, angle: f64) -> Result<Self, ObstacleError> {
        Placed::cuboid(centre, half_extents, angle).map(Self)
    }

    /// The convex polygon that is the convex hull of `points` (any order).
    ///
    /// The β-agent of an α-agent outside is parry's projection; inside, parry's projection (EPA)
    /// is not reliable for polygons, and the β-agent is the foot of the perpendicular on the
    /// nearest edge line, computed here.
    ///
    /// # Errors
    /// [`ObstacleError::NonFinitePoint`] for a point with a NaN or infinite coordinate
    /// (`points[i]`); [`ObstacleError::TooFewPoints`] for fewer than 3 points;
    /// [`ObstacleError::FlatHull`] when they are all on one line;
    /// [`ObstacleError::PointInsideHull`] when a point is strictly inside the hull of the others (the
    /// outline given is not convex).
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d};
    /// use glam::DVec2;
    ///
    /// let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y].map(|v| v * 2.0);
    /// let polygon = Obstacle2d::convex_hull(&square)?;
    /// let corner = polygon.beta_agent(DVec2::new(3.0, 3.0), DVec2::new(1.0, -1.0));
    /// assert!((corner.position - DVec2::new(2.0, 2.0)).length() < 1e-12);
    /// assert_eq!((corner.velocity, corner.mu), (DVec2::ZERO, 0.0)); // a vertex
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn convex_hull(points: &[DVec2]) -> Result<Self, ObstacleError> {
        polytope::validate(points)?;
        let centroid = flock_math::mean(points);
        let local: Vec<DVec2> = points.iter().map(|&x| x - centroid).collect();
        // Not `ConvexPolygon::from_convex_hull`: it drops a vertex whose two edges turn by less
        // than about 1.7e-4 rad, which shrinks the polygon below the hull of the points.
        let shape = ConvexPolygon::from_convex_polyline_unmodified(convex_hull(&local))
            .ok_or(ObstacleError::FlatHull { dim: 2 })?;
        let radius = local.iter().map(|x| x.length()).fold(0.0, f64::max);
        let planes = shape
            .points()
            .iter()
            .zip(shape.normals())
            .map(|(&vertex, &normal)| (normal, normal.dot(vertex)))
            .collect();
        let planes = Planes::new(planes, radius);
        planes.check_convex(&local, points)?;
        Ok(Self(Placed {
            kind: Kind::Hull(Box::new(Hull { shape, planes })),
            pose: Pose::from_translation(centroid),
        }))
    }

    /// The capsule (stadium) of the points within `radius` of the segment `[a, b]`; with `a = b`,
    /// the disc `B(a, radius)`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `a` or `b` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d};
    /// use glam::DVec2;
    ///
    /// let capsule = Obstacle2d::capsule(DVec2::ZERO, DVec2::new(4.0, 0.0), 1.0)?;
    /// let side = capsule.beta_agent(DVec2::new(2.0, 3.0), DVec2::new(1.0, 1.0));
    /// assert_eq!((side.position, side.velocity, side.mu), (DVec2::new(2.0, 1.0), DVec2::X, 1.0));
    /// let cap = capsule.beta_agent(DVec2::new(-2.0, 0.0), DVec2::new(1.0, 1.0));
    /// assert_eq!((cap.position, cap.velocity, cap.mu), (DVec2::new(-1.0, 0.0), DVec2::new(0.0, 0.5), 0.5));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn capsule(a: DVec2, b: DVec2, radius: f64) -> Result<Self, ObstacleError> {
        Placed::capsule(a, b, radius).map(Self)
    }

    /// The segment `[a, b]` of zero thickness: a thin wall, both sides of which are boundary. An
    /// α-agent is inside only when on it (parry's approximate test).
    ///
    /// # Errors
    /// [`ObstacleError::DegenerateSegment`] when `a = b`;
    /// [`ObstacleError::NonFinitePoint`] when `a` or `b` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d};
    /// use glam::DVec2;
    ///
    /// let segment = Obstacle2d::segment(DVec2::ZERO, DVec2::new(0.0, 4.0))?;
    /// let left = segment.beta_agent(DVec2::new(-1.0, 1.0), DVec2::new(1.0, 2.0));
    /// assert_eq!((left.position, left.normal), (DVec2::new(0.0, 1.0), DVec2::new(-1.0, 0.0)));
    /// assert_eq!(left.velocity, DVec2::new(0.0, 2.0));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn segment(a: DVec2, b: DVec2) -> Result<Self, ObstacleError> {
        Placed::segment(a, b).map(Self)
    }

    /// The solid triangle of vertices `a`, `b`, `c`: the convex polygon
    /// [`convex_hull`](Self::convex_hull)`(&[a, b, c])`.
    ///
    /// # Errors
    /// [`ObstacleError::FlatTriangle`] when the vertices are on one line;
    /// [`ObstacleError::NonFinitePoint`] when one has a NaN or infinite coordinate.
    pub fn triangle(a: DVec2, b: DVec2, c: DVec2) -> Result<Self, ObstacleError> {
        check_finite("a", a)?;
        check_finite("b", b)?;
        check_finite("c", c)?;
        if polytope::affine_rank(&[a, b, c]) < 2 {
            return Err(ObstacleError::FlatTriangle {
                vertices: [coordinates(a), coordinates(b), coordinates(c)],
            });
        }
        Self::convex_hull(&[a, b, c])
    }

    /// The obstacle `spec` describes, validated; vectors must have 2 coordinates, and a cuboid's
    /// `rotation` is one angle or none.
    ///
    /// # Errors
    /// [`ObstacleError::WrongDimension`] for a vector without 2 coordinates,
    /// [`ObstacleError::InvalidRotation`] for a rotation of more than one number, and the errors
    /// of the constructor of the shape.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle2d, ObstacleSpec};
    ///
    /// let spec = ObstacleSpec::Ball { centre: vec![1.0, 2.0, 3.0], radius: 1.0 };
    /// let error = Obstacle2d::from_spec(&spec).unwrap_err();
    /// assert_eq!(error.field(), "centre");
    /// assert!(error.to_string().contains("has 3 coordinates, but the scenario is 2D"));
    /// ```
    pub fn from_spec(spec: &ObstacleSpec) -> Result<Self, ObstacleError> {
        Placed::from_spec(spec).map(Self)
    }

    /// The parry shape, in its local frame (for other parry queries, e.g. `compute_aabb`).
    #[must_use]
    pub fn shape(&self) -> &dyn Shape {
        match &self.0.kind {
            Kind::Ball(ball) => ball,
            Kind::Wall(half_space) => half_space,
            Kind::Cuboid(cuboid) => cuboid,
            Kind::Hull(hull) => &hull.shape,
            Kind::Capsule(capsule) => capsule,
            Kind::Segment(segment) => segment,
            Kind::Plate(none) => match *none {},
        }
    }

    /// The pose placing [`shape`](Self::shape) in the world.
    #[must_use]
    pub fn pose(&self) -> &Pose {
        &self.0.pose
    }
}

impl Obstacle<DVec2> for Obstacle2d {
    fn ball(centre: DVec2, radius: f64) -> Result<Self, ObstacleError> {
        Self::ball(centre, radius)
    }

    fn wall(point: DVec2, outward_normal: DVec2) -> Result<Self, ObstacleError> {
        Self::wall(point, outward_normal)
    }

    #[inline]
    fn beta_agent(&self, q: DVec2, p: DVec2) -> BetaAgent<DVec2> {
        self.0.beta_agent(q, p)
    }

    fn aabb(&self) -> Option<(DVec2, DVec2)> {
        if self.0.is_wall() {
            return None;
        }
        let aabb = self.shape().compute_aabb(&self.0.pose);
        Some((aabb.mins, aabb.maxs))
    }
}

/// No plate in the plane (a triangle is a convex polygon there): [`Kind::Plate`] cannot be built.
#[derive(Clone, Copy, Debug)]
pub(crate) enum NoPlate {}

/// parry2d-f64's types and projections for the β-agent algorithm of [`shapes`](crate::shapes).
impl Parry for DVec2 {
    type Pose = Pose;
    type Ball = Ball;
    type HalfSpace = HalfSpace;
    type Cuboid = Cuboid;
    type Hull = ConvexPolygon;
    type Capsule = Capsule;
    type Segment = Segment;
    type Plate = NoPlate;
    type Rotation = f64;

    fn identity() -> Pose {
        Pose::IDENTITY
    }
    fn at(translation: Self) -> Pose {
        Pose::from_translation(translation)
    }
    fn posed(translation: Self, angle: f64) -> Pose {
        Pose::new(translation, angle)
    }
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
    fn ball(radius: f64) -> Ball {
        Ball::new(radius)
    }
    fn half_space(normal: Self) -> HalfSpace {
        HalfSpace::new(normal)
    }
    fn cuboid(half_extents: Self) -> Cuboid {
        Cuboid::new(half_extents)
    }
    fn capsule_between(a: Self, b: Self, radius: f64) -> Capsule {
        Capsule::new(a, b, radius)
    }
    fn segment(a: Self, b: Self) -> Segment {
        Segment::new(a, b)
    }
    fn convex_hull(points: &[Self]) -> Result<Placed<Self>, ObstacleError> {
        Obstacle2d::convex_hull(points).map(|obstacle| obstacle.0)
    }
    fn triangle(a: Self, b: Self, c: Self) -> Result<Placed<Self>, ObstacleError> {
        Obstacle2d::triangle(a, b, c).map(|obstacle| obstacle.0)
    }

    #[inline]
    fn translation(pose: &Pose) -> Self {
        pose.translation
    }
    #[inline]
    fn to_world_point(pose: &Pose, x: Self) -> Self {
        pose.transform_point(x)
    }
    #[inline]
    fn to_world_vector(pose: &Pose, v: Self) -> Self {
        pose.transform_vector(v)
    }
    #[inline]
    fn to_local_point(pose: &Pose, x: Self) -> Self {
        pose.inverse_transform_point(x)
    }
    #[inline]
    fn to_local_vector(pose: &Pose, v: Self) -> Self {
        pose.inverse_transform_vector(v)
    }
    #[inline]
    fn radius(ball: &Ball) -> f64 {
        ball.radius
    }
    #[inline]
    fn project_ball(ball: &Ball, pose: &Pose, q: Self) -> (Self, bool) {
        let projection = ball.project_point(pose, q, false);
        (projection.point, projection.is_inside)
    }
    #[inline]
    fn wall_normal(wall: &HalfSpace) -> Self {
        wall.normal
    }
    #[inline]
    fn project_wall(wall: &HalfSpace, pose: &Pose, q: Self) -> (Self, bool) {
        let projection = wall.project_point(pose, q, false);
        (projection.point, projection.is_inside)
    }
    #[inline]
    fn half_extents(cuboid: &Cuboid) -> Self {
        cuboid.half_extents
    }
    #[inline]
    fn project_cuboid(cuboid: &Cuboid, local_q: Self) -> (Self, bool) {
        let projection = cuboid.project_local_point(local_q, false);
        (projection.point, projection.is_inside)
    }
    #[inline]
    fn project_hull(hull: &ConvexPolygon, local_q: Self) -> (Self, bool) {
        let projection = hull.project_local_point(local_q, false);
        (projection.point, projection.is_inside)
    }
    #[inline]
    fn capsule(capsule: &Capsule) -> (Self, Self, f64) {
        (capsule.segment.a, capsule.segment.b, capsule.radius)
    }
    #[inline]
    fn project_capsule(capsule: &Capsule, q: Self) -> (Self, bool) {
        let projection = capsule.project_local_point(q, false);
        (projection.point, projection.is_inside)
    }
    #[inline]
    fn project_segment(segment: &Segment, q: Self) -> (Self, bool, Feature<Self>, Self) {
        let (projection, location) = segment.project_local_point_and_get_location(q, false);
        let direction = (segment.b - segment.a).normalize();
        let feature = match location {
            SegmentPointLocation::OnVertex(_) => Feature::Vertex,
            SegmentPointLocation::OnEdge(_) => Feature::Edge(direction),
        };
        let normal = orthogonal_unit(direction);
        (projection.point, projection.is_inside, feature, normal)
    }
    #[inline]
    fn project_plate(plate: &NoPlate, _q: Self) -> (Self, bool, Feature<Self>, Self) {
        match *plate {}
    }
}

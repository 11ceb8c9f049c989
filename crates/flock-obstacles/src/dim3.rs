//! [`Obstacle3d`]: convex obstacles of space, projected by parry3d-f64.
//!
//! - [`Obstacle3d::ball`], [`Obstacle3d::wall`], [`Obstacle3d::cuboid`],
//!   [`Obstacle3d::convex_hull`], [`Obstacle3d::capsule`], [`Obstacle3d::segment`],
//!   [`Obstacle3d::triangle`]: the shapes; [`Obstacle3d::from_spec`] from an [`ObstacleSpec`].
//! - [`Obstacle::beta_agent`]: the β-agent of an α-agent `(q, p)` on it.

use glam::DVec3;
use parry3d_f64::math::Pose;
use parry3d_f64::query::{PointQuery, PointQueryWithLocation};
use parry3d_f64::shape::{
    Ball, Capsule, ConvexPolyhedron, Cuboid, HalfSpace, Segment, SegmentPointLocation, Shape,
    Triangle, TrianglePointLocation,
};
use parry3d_f64::transformation::try_convex_hull;

use crate::basis::orthogonal_unit;
use crate::error::{check_finite, coordinates};
use crate::polytope::{self, Planes};
use crate::shapes::{Hull, Kind, Parry, Placed};
use crate::thin::Feature;
use crate::{BetaAgent, Obstacle, ObstacleError, ObstacleSpec};

/// A convex obstacle of ℝ³: a parry shape placed by a [`Pose`].
///
/// The β-agent's position `q̂` and the inside test come from parry's
/// `project_point(pose, q, solid = false)`, which returns the closest *boundary* point even for an
/// α-agent inside (except inside convex polyhedra, see [`convex_hull`](Self::convex_hull)); the
/// normal `a`, `μ` and the velocity `p̂` follow the closed forms per feature listed on
/// [`BetaAgent`].
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle3d};
/// use glam::DVec3;
///
/// let ball = Obstacle3d::ball(DVec3::new(0.0, 0.0, 10.0), 2.0)?;
/// let beta = ball.beta_agent(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0));
/// assert_eq!(beta.position, DVec3::new(0.0, 0.0, 8.0));
/// assert_eq!(beta.normal, DVec3::new(0.0, 0.0, -1.0));
/// assert_eq!(beta.mu, 0.2); // R / ‖q − y‖
/// assert_eq!(beta.velocity, DVec3::new(0.2, 0.0, 0.0));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Obstacle3d(Placed<DVec3>);

/// A triangle of zero thickness, with its unit normal `(b − a) × (c − a)` normalised and the unit
/// directions of its sides `ab`, `bc`, `ac` (parry's edge numbering).
#[derive(Clone, Debug)]
pub(crate) struct Plate {
    shape: Triangle,
    normal: DVec3,
    sides: [DVec3; 3],
}

impl Obstacle3d {
    /// The closed ball of radius `radius` centred at `centre`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle3d;
    /// use glam::DVec3;
    ///
    /// let ball = Obstacle3d::ball(DVec3::new(1.0, 2.0, 3.0), 0.5)?;
    /// assert_eq!(ball.pose().translation, DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!(ball.shape().as_ball().map(|b| b.radius), Some(0.5));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn ball(centre: DVec3, radius: f64) -> Result<Self, ObstacleError> {
        Placed::ball(centre, radius).map(Self)
    }

    /// The closed half-space `{x : a · (x − point) ≤ 0}` bounded by the plane through `point`, with
    /// `a = outward_normal / ‖outward_normal‖` pointing out of the wall, towards the agents.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidNormal`] when `outward_normal` is zero or not finite;
    /// [`ObstacleError::NonFinitePoint`] when `point` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::Obstacle3d;
    /// use glam::DVec3;
    ///
    /// // The ceiling z ≥ 5 (agents live at z < 5): its outward normal points to −z.
    /// let ceiling = Obstacle3d::wall(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -3.0))?;
    /// assert_eq!(ceiling.shape().as_halfspace().map(|h| h.normal), Some(DVec3::NEG_Z));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn wall(point: DVec3, outward_normal: DVec3) -> Result<Self, ObstacleError> {
        Placed::wall(point, outward_normal).map(Self)
    }

    /// The closed box of half-widths `half_extents` along its own axes, centred at `centre` and
    /// turned by the axis-angle vector `axis_angle` (the unit axis times the angle in radians;
    /// zero for none).
    ///
    /// # Errors
    /// [`ObstacleError::InvalidHalfExtent`] unless each half extent is finite and `> 0`;
    /// [`ObstacleError::InvalidRotation`] when `axis_angle` is not finite;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle3d};
    /// use glam::DVec3;
    ///
    /// // A unit cube turned by 45° about z, seen from far along x: its vertical edge is closest.
    /// let turn = DVec3::Z * core::f64::consts::FRAC_PI_4;
    /// let cube = Obstacle3d::cuboid(DVec3::ZERO, DVec3::ONE, turn)?;
    /// let beta = cube.beta_agent(DVec3::new(5.0, 0.0, 0.5), DVec3::new(1.0, 1.0, 1.0));
    /// assert!((beta.position - DVec3::new(2.0_f64.sqrt(), 0.0, 0.5)).length() < 1e-12);
    /// assert!((beta.velocity - DVec3::Z).length() < 1e-12); // (e · p) e along the edge
    /// assert_eq!(beta.mu, 0.0);
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn cuboid(
        centre: DVec3,
        half_extents: DVec3,
        axis_angle: DVec3,
    ) -> Result<Self, ObstacleError> {
        Placed::cuboid(centre, half_extents, axis_angle).map(Self)
    }

    /// The convex polyhedron that is the convex hull of `points` (any order).
    ///
    /// The β-agent of an α-agent outside is parry's projection; inside, parry's projection (EPA)
    /// is not relied on (it is wrong for some 2D polygons), and the β-agent is the foot of the
    /// perpendicular on the nearest face plane, computed here.
    ///
    /// # Errors
    /// [`ObstacleError::NonFinitePoint`] for a point with a NaN or infinite coordinate
    /// (`points[i]`); [`ObstacleError::TooFewPoints`] for fewer than 4 points;
    /// [`ObstacleError::FlatHull`] when they are all on one plane;
    /// [`ObstacleError::PointInsideHull`] when a point is strictly inside the hull of the others (the
    /// outline given is not convex).
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle3d};
    /// use glam::DVec3;
    ///
    /// // The tetrahedron of the origin and the three unit vectors.
    /// let tetrahedron = Obstacle3d::convex_hull(&[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z])?;
    /// let corner = tetrahedron.beta_agent(DVec3::splat(-1.0), DVec3::new(1.0, 2.0, 3.0));
    /// assert!(corner.position.length() < 1e-12);
    /// assert_eq!((corner.velocity, corner.mu), (DVec3::ZERO, 0.0)); // a vertex
    /// let edge = tetrahedron.beta_agent(DVec3::new(-1.0, -1.0, 0.5), DVec3::new(1.0, 2.0, 3.0));
    /// assert!((edge.position - DVec3::new(0.0, 0.0, 0.5)).length() < 1e-12);
    /// assert!((edge.velocity - DVec3::new(0.0, 0.0, 3.0)).length() < 1e-12); // along the edge
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn convex_hull(points: &[DVec3]) -> Result<Self, ObstacleError> {
        polytope::validate(points)?;
        let centroid = flock_math::mean(points);
        let local: Vec<DVec3> = points.iter().map(|&x| x - centroid).collect();
        let (vertices, triangles) =
            try_convex_hull(&local).map_err(|_| ObstacleError::FlatHull { dim: 3 })?;
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
        let shape = ConvexPolyhedron::from_convex_mesh(vertices, &triangles)
            .ok_or(ObstacleError::FlatHull { dim: 3 })?;
        let radius = local.iter().map(|x| x.length()).fold(0.0, f64::max);
        let planes = Planes::new(planes, radius);
        planes.check_convex(&local, points)?;
        Ok(Self(Placed {
            kind: Kind::Hull(Box::new(Hull { shape, planes })),
            pose: Pose::from_translation(centroid),
        }))
    }

    /// The capsule of the points within `radius` of the segment `[a, b]`; with `a = b`, the ball
    /// `B(a, radius)`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `a` or `b` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle3d};
    /// use glam::DVec3;
    ///
    /// // Axis along x; an α-agent above the side at distance ρ = 4 from the axis.
    /// let capsule = Obstacle3d::capsule(DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), 1.0)?;
    /// let side = capsule.beta_agent(DVec3::new(2.0, 0.0, 4.0), DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!((side.position, side.mu), (DVec3::new(2.0, 0.0, 1.0), 0.25));
    /// // Along the axis kept, around it scaled by R/ρ, across dropped.
    /// assert_eq!(side.velocity, DVec3::new(1.0, 0.5, 0.0));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn capsule(a: DVec3, b: DVec3, radius: f64) -> Result<Self, ObstacleError> {
        Placed::capsule(a, b, radius).map(Self)
    }

    /// The segment `[a, b]` of zero thickness: a thin rod. An α-agent is inside only when on it
    /// (parry's approximate test).
    ///
    /// # Errors
    /// [`ObstacleError::DegenerateSegment`] when `a = b`;
    /// [`ObstacleError::NonFinitePoint`] when `a` or `b` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle3d};
    /// use glam::DVec3;
    ///
    /// let rod = Obstacle3d::segment(DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0))?;
    /// let beta = rod.beta_agent(DVec3::new(-1.0, 0.0, 1.0), DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!((beta.position, beta.normal), (DVec3::new(0.0, 0.0, 1.0), DVec3::new(-1.0, 0.0, 0.0)));
    /// assert_eq!((beta.velocity, beta.mu), (DVec3::new(0.0, 0.0, 3.0), 0.0));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn segment(a: DVec3, b: DVec3) -> Result<Self, ObstacleError> {
        Placed::segment(a, b).map(Self)
    }

    /// The triangle of vertices `a`, `b`, `c` as a plate of zero thickness, both sides of which are
    /// boundary. An α-agent is inside only when on it (parry's approximate test).
    ///
    /// # Errors
    /// [`ObstacleError::FlatTriangle`] when the vertices are on one line;
    /// [`ObstacleError::NonFinitePoint`] when one has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle3d};
    /// use glam::DVec3;
    ///
    /// let plate = Obstacle3d::triangle(DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(0.0, 4.0, 0.0))?;
    /// let below = plate.beta_agent(DVec3::new(1.0, 1.0, -2.0), DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!((below.position, below.normal), (DVec3::new(1.0, 1.0, 0.0), DVec3::NEG_Z));
    /// assert_eq!((below.velocity, below.mu), (DVec3::new(1.0, 2.0, 0.0), 1.0));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn triangle(a: DVec3, b: DVec3, c: DVec3) -> Result<Self, ObstacleError> {
        check_finite("a", a)?;
        check_finite("b", b)?;
        check_finite("c", c)?;
        let normal = (b - a).cross(c - a).normalize_or_zero();
        if polytope::affine_rank(&[a, b, c]) < 2 || normal == DVec3::ZERO {
            return Err(ObstacleError::FlatTriangle {
                vertices: [coordinates(a), coordinates(b), coordinates(c)],
            });
        }
        let sides = [b - a, c - b, c - a].map(DVec3::normalize);
        Ok(Self(Placed::in_world(Kind::Plate(Plate {
            shape: Triangle::new(a, b, c),
            normal,
            sides,
        }))))
    }

    /// The obstacle `spec` describes, validated; vectors must have 3 coordinates, and a cuboid's
    /// `rotation` is an axis-angle vector of 3 numbers or none.
    ///
    /// # Errors
    /// [`ObstacleError::WrongDimension`] for a vector without 3 coordinates,
    /// [`ObstacleError::InvalidRotation`] for a rotation of neither 0 nor 3 numbers, and the errors
    /// of the constructor of the shape.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle3d, ObstacleSpec};
    ///
    /// let spec = ObstacleSpec::Ball { centre: vec![1.0, 2.0], radius: 1.0 };
    /// let error = Obstacle3d::from_spec(&spec).unwrap_err();
    /// assert_eq!(error.field(), "centre");
    /// assert!(error.to_string().contains("has 2 coordinates, but the scenario is 3D"));
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
            Kind::Plate(plate) => &plate.shape,
        }
    }

    /// The pose placing [`shape`](Self::shape) in the world.
    #[must_use]
    pub fn pose(&self) -> &Pose {
        &self.0.pose
    }
}

impl Obstacle<DVec3> for Obstacle3d {
    fn ball(centre: DVec3, radius: f64) -> Result<Self, ObstacleError> {
        Self::ball(centre, radius)
    }

    fn wall(point: DVec3, outward_normal: DVec3) -> Result<Self, ObstacleError> {
        Self::wall(point, outward_normal)
    }

    #[inline]
    fn beta_agent(&self, q: DVec3, p: DVec3) -> BetaAgent<DVec3> {
        self.0.beta_agent(q, p)
    }

    fn aabb(&self) -> Option<(DVec3, DVec3)> {
        if self.0.is_wall() {
            return None;
        }
        let aabb = self.shape().compute_aabb(&self.0.pose);
        Some((aabb.mins, aabb.maxs))
    }
}

/// parry3d-f64's types and projections for the β-agent algorithm of [`shapes`](crate::shapes).
impl Parry for DVec3 {
    type Pose = Pose;
    type Ball = Ball;
    type HalfSpace = HalfSpace;
    type Cuboid = Cuboid;
    type Hull = ConvexPolyhedron;
    type Capsule = Capsule;
    type Segment = Segment;
    type Plate = Plate;
    type Rotation = DVec3;

    fn identity() -> Pose {
        Pose::IDENTITY
    }
    fn at(translation: Self) -> Pose {
        Pose::from_translation(translation)
    }
    fn posed(translation: Self, axis_angle: DVec3) -> Pose {
        Pose::new(translation, axis_angle)
    }
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
        Obstacle3d::convex_hull(points).map(|obstacle| obstacle.0)
    }
    fn triangle(a: Self, b: Self, c: Self) -> Result<Placed<Self>, ObstacleError> {
        Obstacle3d::triangle(a, b, c).map(|obstacle| obstacle.0)
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
    fn project_hull(hull: &ConvexPolyhedron, local_q: Self) -> (Self, bool) {
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
}

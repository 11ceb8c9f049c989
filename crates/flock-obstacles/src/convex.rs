//! [`ConvexObstacle`]: a convex obstacle of either dimension, [`Obstacle2d`](crate::Obstacle2d)
//! in the plane (parry2d-f64) and [`Obstacle3d`](crate::Obstacle3d) in space (parry3d-f64).
//!
//! - [`ConvexObstacle::ball`], [`ConvexObstacle::wall`], [`ConvexObstacle::cuboid`],
//!   [`ConvexObstacle::convex_hull`], [`ConvexObstacle::capsule`], [`ConvexObstacle::segment`],
//!   [`ConvexObstacle::triangle`]: the shapes; [`ConvexObstacle::from_spec`] from an
//!   [`ObstacleSpec`].
//! - [`Obstacle::beta_agent`]: the β-agent of an α-agent `(q, p)` on it.

use crate::shapes::{Parry, Placed};
use crate::{BetaAgent, Obstacle, ObstacleError, ObstacleSpec};

/// A convex obstacle of ℝ^m, m = `V::DIM`: a parry shape placed by a pose. Named
/// [`Obstacle2d`](crate::Obstacle2d) for `DVec2` and [`Obstacle3d`](crate::Obstacle3d) for `DVec3`.
///
/// The β-agent's position `q̂` and the inside test come from parry's
/// `project_point(pose, q, solid = false)`, which returns the closest *boundary* point even for an
/// α-agent inside (except inside convex polygons and polyhedra, see
/// [`convex_hull`](Self::convex_hull)); the normal `a`, `μ` and the velocity `p̂` follow the
/// closed forms per feature listed on [`BetaAgent`].
///
/// # Example
/// ```
/// use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
/// use glam::{DVec2, DVec3};
///
/// let disc = Obstacle2d::ball(DVec2::new(10.0, 0.0), 2.0)?;
/// let beta = disc.beta_agent(DVec2::ZERO, DVec2::new(1.0, 1.0));
/// assert_eq!(beta.position, DVec2::new(8.0, 0.0));
/// assert_eq!(beta.normal, DVec2::new(-1.0, 0.0));
/// assert_eq!(beta.mu, 0.2); // R / ‖q − y‖
/// assert_eq!(beta.velocity, DVec2::new(0.0, 0.2));
///
/// let ball = Obstacle3d::ball(DVec3::new(0.0, 0.0, 10.0), 2.0)?;
/// let beta = ball.beta_agent(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0));
/// assert_eq!(beta.position, DVec3::new(0.0, 0.0, 8.0));
/// assert_eq!(beta.normal, DVec3::new(0.0, 0.0, -1.0));
/// assert_eq!(beta.mu, 0.2);
/// assert_eq!(beta.velocity, DVec3::new(0.2, 0.0, 0.0));
/// # Ok::<(), flock_obstacles::ObstacleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct ConvexObstacle<V: Parry>(Placed<V>);

impl<V: Parry> ConvexObstacle<V> {
    /// The closed ball (a disc in 2D) of radius `radius` centred at `centre`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle2d, Obstacle3d};
    /// use glam::{DVec2, DVec3};
    ///
    /// let disc = Obstacle2d::ball(DVec2::new(1.0, 2.0), 0.5)?;
    /// assert_eq!(disc.pose().translation, DVec2::new(1.0, 2.0));
    /// assert_eq!(disc.shape().as_ball().map(|b| b.radius), Some(0.5));
    ///
    /// let ball = Obstacle3d::ball(DVec3::new(1.0, 2.0, 3.0), 0.5)?;
    /// assert_eq!(ball.pose().translation, DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!(ball.shape().as_ball().map(|b| b.radius), Some(0.5));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn ball(centre: V, radius: f64) -> Result<Self, ObstacleError> {
        Placed::ball(centre, radius).map(Self)
    }

    /// The closed half-space `{x : a · (x − point) ≤ 0}` (a half-plane in 2D) bounded by the
    /// hyperplane through `point` (a line in 2D, a plane in 3D), with
    /// `a = outward_normal / ‖outward_normal‖` pointing out of the wall, towards the agents.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidNormal`] when `outward_normal` is zero or not finite;
    /// [`ObstacleError::NonFinitePoint`] when `point` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle2d, Obstacle3d};
    /// use glam::{DVec2, DVec3};
    ///
    /// // The wall x ≥ 5 (agents live at x < 5): its outward normal points to −x.
    /// let wall = Obstacle2d::wall(DVec2::new(5.0, 0.0), DVec2::new(-3.0, 0.0))?;
    /// assert_eq!(wall.shape().as_halfspace().map(|h| h.normal), Some(DVec2::new(-1.0, 0.0)));
    ///
    /// // The ceiling z ≥ 5 (agents live at z < 5): its outward normal points to −z.
    /// let ceiling = Obstacle3d::wall(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -3.0))?;
    /// assert_eq!(ceiling.shape().as_halfspace().map(|h| h.normal), Some(DVec3::NEG_Z));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn wall(point: V, outward_normal: V) -> Result<Self, ObstacleError> {
        Placed::wall(point, outward_normal).map(Self)
    }

    /// The closed box (a rectangle in 2D) of half-widths `half_extents` along its own axes,
    /// centred at `centre` and turned by `rotation`: in 2D an angle in radians, counter-clockwise;
    /// in 3D an axis-angle vector (the unit axis times the angle in radians; zero for none).
    ///
    /// # Errors
    /// [`ObstacleError::InvalidHalfExtent`] unless each half extent is finite and `> 0`;
    /// [`ObstacleError::InvalidRotation`] when `rotation` is not finite;
    /// [`ObstacleError::NonFinitePoint`] when `centre` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
    /// use glam::{DVec2, DVec3};
    ///
    /// // A 4 × 2 rectangle turned by 90°: 2 wide along x, 4 tall along y.
    /// let rectangle = Obstacle2d::cuboid(DVec2::ZERO, DVec2::new(2.0, 1.0), core::f64::consts::FRAC_PI_2)?;
    /// let beta = rectangle.beta_agent(DVec2::new(0.5, 5.0), DVec2::new(1.0, 1.0));
    /// assert!((beta.position - DVec2::new(0.5, 2.0)).length() < 1e-12);
    /// assert!((beta.velocity - DVec2::new(1.0, 0.0)).length() < 1e-12); // P p on the top face
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
        centre: V,
        half_extents: V,
        rotation: V::Rotation,
    ) -> Result<Self, ObstacleError> {
        Placed::cuboid(centre, half_extents, rotation).map(Self)
    }

    /// The convex polygon (2D) or polyhedron (3D) that is the convex hull of `points` (any order).
    ///
    /// The β-agent of an α-agent outside is parry's projection; inside, parry's projection (EPA)
    /// is not relied on (it is wrong for some polygons), and the β-agent is the foot of the
    /// perpendicular on the nearest edge line (2D) or face plane (3D), computed here.
    ///
    /// # Errors
    /// [`ObstacleError::NonFinitePoint`] for a point with a NaN or infinite coordinate
    /// (`points[i]`); [`ObstacleError::TooFewPoints`] for fewer than m + 1 points (3 in 2D, 4 in
    /// 3D); [`ObstacleError::FlatHull`] when they are all on one line (2D) or plane (3D);
    /// [`ObstacleError::PointInsideHull`] when a point is strictly inside the hull of the others (the
    /// outline given is not convex).
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
    /// use glam::{DVec2, DVec3};
    ///
    /// let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y].map(|v| v * 2.0);
    /// let polygon = Obstacle2d::convex_hull(&square)?;
    /// let corner = polygon.beta_agent(DVec2::new(3.0, 3.0), DVec2::new(1.0, -1.0));
    /// assert!((corner.position - DVec2::new(2.0, 2.0)).length() < 1e-12);
    /// assert_eq!((corner.velocity, corner.mu), (DVec2::ZERO, 0.0)); // a vertex
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
    pub fn convex_hull(points: &[V]) -> Result<Self, ObstacleError> {
        Placed::convex_hull(points).map(Self)
    }

    /// The capsule of the points within `radius` of the segment `[a, b]` (a stadium in 2D); with
    /// `a = b`, the ball `B(a, radius)`.
    ///
    /// # Errors
    /// [`ObstacleError::InvalidRadius`] unless `radius` is finite and `> 0`;
    /// [`ObstacleError::NonFinitePoint`] when `a` or `b` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
    /// use glam::{DVec2, DVec3};
    ///
    /// let capsule = Obstacle2d::capsule(DVec2::ZERO, DVec2::new(4.0, 0.0), 1.0)?;
    /// let side = capsule.beta_agent(DVec2::new(2.0, 3.0), DVec2::new(1.0, 1.0));
    /// assert_eq!((side.position, side.velocity, side.mu), (DVec2::new(2.0, 1.0), DVec2::X, 1.0));
    /// let cap = capsule.beta_agent(DVec2::new(-2.0, 0.0), DVec2::new(1.0, 1.0));
    /// assert_eq!((cap.position, cap.velocity, cap.mu), (DVec2::new(-1.0, 0.0), DVec2::new(0.0, 0.5), 0.5));
    ///
    /// // Axis along x; an α-agent above the side at distance ρ = 4 from the axis.
    /// let capsule = Obstacle3d::capsule(DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), 1.0)?;
    /// let side = capsule.beta_agent(DVec3::new(2.0, 0.0, 4.0), DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!((side.position, side.mu), (DVec3::new(2.0, 0.0, 1.0), 0.25));
    /// // Along the axis kept, around it scaled by R/ρ, across dropped.
    /// assert_eq!(side.velocity, DVec3::new(1.0, 0.5, 0.0));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn capsule(a: V, b: V, radius: f64) -> Result<Self, ObstacleError> {
        Placed::capsule(a, b, radius).map(Self)
    }

    /// The segment `[a, b]` of zero thickness: a thin wall in 2D, both sides of which are
    /// boundary, a thin rod in 3D. An α-agent is inside only when on it (parry's approximate test).
    ///
    /// # Errors
    /// [`ObstacleError::DegenerateSegment`] when `a = b`;
    /// [`ObstacleError::NonFinitePoint`] when `a` or `b` has a NaN or infinite coordinate.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d};
    /// use glam::{DVec2, DVec3};
    ///
    /// let segment = Obstacle2d::segment(DVec2::ZERO, DVec2::new(0.0, 4.0))?;
    /// let left = segment.beta_agent(DVec2::new(-1.0, 1.0), DVec2::new(1.0, 2.0));
    /// assert_eq!((left.position, left.normal), (DVec2::new(0.0, 1.0), DVec2::new(-1.0, 0.0)));
    /// assert_eq!(left.velocity, DVec2::new(0.0, 2.0));
    ///
    /// let rod = Obstacle3d::segment(DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0))?;
    /// let beta = rod.beta_agent(DVec3::new(-1.0, 0.0, 1.0), DVec3::new(1.0, 2.0, 3.0));
    /// assert_eq!((beta.position, beta.normal), (DVec3::new(0.0, 0.0, 1.0), DVec3::new(-1.0, 0.0, 0.0)));
    /// assert_eq!((beta.velocity, beta.mu), (DVec3::new(0.0, 0.0, 3.0), 0.0));
    /// # Ok::<(), flock_obstacles::ObstacleError>(())
    /// ```
    pub fn segment(a: V, b: V) -> Result<Self, ObstacleError> {
        Placed::segment(a, b).map(Self)
    }

    /// The triangle of vertices `a`, `b`, `c`: in 2D the solid triangle, the convex polygon
    /// [`convex_hull`](Self::convex_hull)`(&[a, b, c])`; in 3D a plate of zero thickness, both
    /// sides of which are boundary (an α-agent is inside only when on it, parry's approximate
    /// test).
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
    pub fn triangle(a: V, b: V, c: V) -> Result<Self, ObstacleError> {
        Placed::triangle(a, b, c).map(Self)
    }

    /// The obstacle `spec` describes, validated; vectors must have m coordinates, and a cuboid's
    /// `rotation` is none, or one angle in 2D and an axis-angle vector of 3 numbers in 3D.
    ///
    /// # Errors
    /// [`ObstacleError::WrongDimension`] for a vector without m coordinates,
    /// [`ObstacleError::InvalidRotation`] for a rotation of another count of numbers, and the
    /// errors of the constructor of the shape.
    ///
    /// # Example
    /// ```
    /// use flock_obstacles::{Obstacle2d, Obstacle3d, ObstacleSpec};
    ///
    /// let spec = ObstacleSpec::Ball { centre: vec![1.0, 2.0, 3.0], radius: 1.0 };
    /// let error = Obstacle2d::from_spec(&spec).unwrap_err();
    /// assert_eq!(error.field(), "centre");
    /// assert!(error.to_string().contains("has 3 coordinates, but the scenario is 2D"));
    ///
    /// let spec = ObstacleSpec::Ball { centre: vec![1.0, 2.0], radius: 1.0 };
    /// let error = Obstacle3d::from_spec(&spec).unwrap_err();
    /// assert_eq!(error.field(), "centre");
    /// assert!(error.to_string().contains("has 2 coordinates, but the scenario is 3D"));
    /// ```
    pub fn from_spec(spec: &ObstacleSpec) -> Result<Self, ObstacleError> {
        Placed::from_spec(spec).map(Self)
    }

    /// The parry shape (`dyn Shape` of parry2d-f64 or parry3d-f64), in its local frame (for other
    /// parry queries, e.g. `compute_aabb`).
    #[must_use]
    pub fn shape(&self) -> &V::Shape {
        V::shape(&self.0.kind)
    }

    /// The pose placing [`shape`](Self::shape) in the world.
    #[must_use]
    pub fn pose(&self) -> &V::Pose {
        &self.0.pose
    }
}

impl<V: Parry> Obstacle<V> for ConvexObstacle<V> {
    fn ball(centre: V, radius: f64) -> Result<Self, ObstacleError> {
        Self::ball(centre, radius)
    }

    fn wall(point: V, outward_normal: V) -> Result<Self, ObstacleError> {
        Self::wall(point, outward_normal)
    }

    #[inline]
    fn beta_agent(&self, q: V, p: V) -> BetaAgent<V> {
        self.0.beta_agent(q, p)
    }

    fn aabb(&self) -> Option<(V, V)> {
        if self.0.is_wall() {
            return None;
        }
        Some(V::aabb(self.shape(), &self.0.pose))
    }
}

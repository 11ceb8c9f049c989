//! Convex polygons (2D) and polyhedra (3D) given by points: validation of the point set and the
//! β-agent rule shared by both dimensions, from the hull's face planes `n_j · x = o_j` (local frame,
//! unit outward normals `n_j`).

use flock_math::Vector;

use crate::basis::Basis;
use crate::error::{check_finite, coordinates};
use crate::{BetaAgent, ObstacleError};

/// Relative tolerance (times the hull's radius about its centroid) for a point to be on a face
/// plane, and for a point set to be flat.
const PLANE_TOLERANCE: f64 = 1e-9;

/// Relative tolerance (times the hull's radius) for a given point to count as strictly inside the
/// hull. Looser than [`PLANE_TOLERANCE`]: parry merges nearly coplanar triangles into one face.
const CONVEXITY_TOLERANCE: f64 = 1e-7;

/// The face planes of a convex polytope in its local frame, `(n_j, o_j)` with unit outward `n_j`,
/// and the absolute tolerance for a point to be on one.
#[derive(Clone, Debug)]
pub(crate) struct Planes<V> {
    planes: Box<[(V, f64)]>,
    tolerance: f64,
}

impl<V: Vector> Planes<V> {
    /// The planes `(n_j, o_j)` of a polytope of radius `radius` about its local origin.
    pub(crate) fn new(planes: Vec<(V, f64)>, radius: f64) -> Self {
        Self {
            planes: planes.into_boxed_slice(),
            tolerance: PLANE_TOLERANCE * radius,
        }
    }

    /// The plane nearest to the inside point `q`: least `o_j − n_j · q`, first on ties.
    fn nearest(&self, q: V) -> (V, f64) {
        let mut nearest = (V::ZERO, f64::INFINITY);
        let mut gap = f64::INFINITY;
        for &(n, o) in &*self.planes {
            let gap_j = o - n.dot(q);
            if gap_j < gap {
                gap = gap_j;
                nearest = (n, o);
            }
        }
        nearest
    }

    /// Checks that no point of `points` (local frame; `world` for the message) is strictly inside
    /// the polytope: each is on some face plane, within the convexity tolerance.
    pub(crate) fn check_convex(&self, points: &[V], world: &[V]) -> Result<(), ObstacleError> {
        let tolerance = self.tolerance * (CONVEXITY_TOLERANCE / PLANE_TOLERANCE);
        for (index, &x) in points.iter().enumerate() {
            if self.planes.iter().all(|&(n, o)| n.dot(x) - o < -tolerance) {
                return Err(ObstacleError::PointInsideHull {
                    index,
                    point: coordinates(world[index]),
                });
            }
        }
        Ok(())
    }
}

/// Checks the points of a convex hull: finite (`points[i]`), at least `DIM + 1`, not all on one
/// line (2D) or plane (3D).
pub(crate) fn validate<V: Vector>(points: &[V]) -> Result<(), ObstacleError> {
    for (index, &x) in points.iter().enumerate() {
        check_finite(&format!("points[{index}]"), x)?;
    }
    if points.len() <= V::DIM {
        return Err(ObstacleError::TooFewPoints {
            count: points.len(),
            dim: V::DIM,
        });
    }
    if affine_rank(points) < V::DIM {
        return Err(ObstacleError::FlatHull { dim: V::DIM });
    }
    Ok(())
}

/// The dimension of the affine hull of `points` (0 for one point, 1 for points on a line, …), up to
/// [`PLANE_TOLERANCE`] times the extent of the points. Greedy: from the first point, repeatedly
/// adds the point farthest from the span found so far.
pub(crate) fn affine_rank<V: Vector>(points: &[V]) -> usize {
    let Some(&origin) = points.first() else {
        return 0;
    };
    let extent = points
        .iter()
        .map(|&x| (x - origin).length())
        .fold(0.0, f64::max);
    let mut basis = Basis::new();
    while basis.rank() < V::DIM {
        let farthest = points
            .iter()
            .map(|&x| basis.reject(x - origin))
            .max_by(|u, v| u.length_squared().total_cmp(&v.length_squared()))
            .unwrap_or(V::ZERO);
        if !basis.push(farthest, PLANE_TOLERANCE * extent) {
            break;
        }
    }
    basis.rank()
}

/// The β-agent of the α-agent `(q, p)` (local frame) on the polytope with face planes `planes`,
/// given parry's projection of `q` (`projected`, `inside`).
///
/// Outside, `q̂` is parry's (GJK) projection and the normal `(q − q̂)/‖q − q̂‖`. The feature of `q̂`
/// is the set of face planes through it (within the tolerance): `p̂` is `p` minus its components
/// along the span of their normals, which is the derivative of the projection — `P p` on a face
/// (`μ = 1`), `(e·p) e` on a 3D edge of direction `e` (`μ = 0`), `0` at a vertex (`μ = 0`).
///
/// Inside (or on the boundary), `q̂ = q + n (o − n · q)` on the nearest face plane `(n, o)` — the
/// foot of the perpendicular, on the face since the ball of that radius about `q` is inside —
/// computed here rather than taken from parry, whose EPA projection of inside points on 2D polygons
/// was measured wrong by up to 1 in parry2d-f64 0.31.1; `p̂ = P p`, `μ = 1`.
#[inline]
#[must_use]
pub(crate) fn beta_agent<V: Vector>(
    q: V,
    p: V,
    planes: &Planes<V>,
    projected: V,
    inside: bool,
) -> BetaAgent<V> {
    let normal = (q - projected).normalize_or_zero();
    if inside || normal == V::ZERO {
        let (n, o) = planes.nearest(q);
        return BetaAgent::new(q, p, q + n * (o - n.dot(q)), n, 1.0, true);
    }
    // The face normals first (well conditioned, at the dihedral angles), then `normal`, which is in
    // their span and only counts when no plane was found within the tolerance.
    let mut span = Basis::new();
    for &(n, o) in &*planes.planes {
        if (n.dot(projected) - o).abs() <= planes.tolerance {
            span.push(n, 1e-6);
        }
    }
    span.push(normal, 1e-6);
    let (velocity, mu) = match span.rank() {
        1 => (span.reject(p), 1.0),
        rank if rank == V::DIM => (V::ZERO, 0.0),
        _ => (span.reject(p), 0.0),
    };
    BetaAgent::with_velocity(q, projected, normal, velocity, mu, false)
}

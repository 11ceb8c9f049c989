//! The order of the agents' headings: the polarisation P (Vicsek et al. 1995's v_a, Couzin et al.
//! 2002's p_group) and the milling M (Couzin et al. 2002's m_group), the order parameters of the
//! models that set their velocities, read by [`FlockMetrics`](crate::FlockMetrics).

use flock_math::{Domain, Vector};

/// The polarisation Φ = ‖Σ_i p_i/‖p_i‖‖ / N of [`FlockMetrics::polarisation`](crate::FlockMetrics::polarisation) (Vicsek et al.
/// 1995 v_a; Couzin et al. 2002 p_group), summed in the iterator's order; agents at rest add
/// nothing but count in N; 0 for no agent.
///
/// # Example
/// ```
/// use flock_metrics::polarisation;
/// use glam::DVec2;
///
/// assert_eq!(polarisation(&[DVec2::X, DVec2::new(3.0, 0.0)]), 1.0);
/// assert_eq!(polarisation(&[DVec2::X, -DVec2::X]), 0.0);
/// assert_eq!(polarisation(&[DVec2::X, DVec2::ZERO]), 0.5); // one at rest
/// ```
#[must_use]
pub fn polarisation<V: Vector>(p: &[V]) -> f64 {
    polarisation_of(p.iter().copied())
}

/// [`polarisation`] of the velocities in the iterator's order.
pub(crate) fn polarisation_of<V: Vector>(p: impl ExactSizeIterator<Item = V>) -> f64 {
    let n = p.len();
    if n == 0 {
        return 0.0;
    }
    p.fold(V::ZERO, |sum, pi| sum + pi.normalize_or_zero())
        .length()
        / n as f64
}

/// The milling M = ‖Σ_i r̂_ic × p̂_i‖ / N of [`FlockMetrics::milling`](crate::FlockMetrics::milling) (Couzin et al. 2002,
/// m_group) about the centre q_c of the agents in `domain` ([`Domain::centre_of`]: the mean in
/// open space, the circular mean on a torus), r_ic = displacement(q_c, q_i).
///
/// # Example
/// ```
/// use flock_math::Domain;
/// use flock_metrics::milling;
/// use glam::DVec2;
///
/// // four agents circling the origin anticlockwise: a perfect mill
/// let q = [DVec2::X, DVec2::Y, -DVec2::X, -DVec2::Y];
/// let p = [DVec2::Y, -DVec2::X, -DVec2::Y, DVec2::X];
/// assert!((milling(&Domain::Open, &q, &p) - 1.0).abs() < 1e-15);
/// assert_eq!(milling(&Domain::Open, &q, &[DVec2::X; 4]), 0.0); // polarised
/// ```
#[must_use]
pub fn milling<V: Vector>(domain: &Domain<V>, q: &[V], p: &[V]) -> f64 {
    let centre = domain.centre_of(q.iter().copied());
    milling_about(domain, centre, q.iter().copied(), p.iter().copied())
}

/// M about `centre`, summed in the iterators' order.
pub(crate) fn milling_about<V: Vector>(
    domain: &Domain<V>,
    centre: V,
    q: impl ExactSizeIterator<Item = V>,
    p: impl Iterator<Item = V>,
) -> f64 {
    let n = q.len();
    if n == 0 {
        return 0.0;
    }
    let sum = q.zip(p).fold([0.0; 3], |sum, (qi, pi)| {
        let r = domain.displacement(centre, qi).normalize_or_zero();
        let c = cross(r, pi.normalize_or_zero());
        [sum[0] + c[0], sum[1] + c[1], sum[2] + c[2]]
    });
    let norm = if V::DIM == 2 {
        sum[2].abs()
    } else {
        (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt()
    };
    norm / n as f64
}

/// a × b, the plane embedded at z = 0 in 2D (only the z component then).
#[inline]
fn cross<V: Vector>(a: V, b: V) -> [f64; 3] {
    let (ax, ay, bx, by) = (a.coord(0), a.coord(1), b.coord(0), b.coord(1));
    let z = ax * by - ay * bx;
    if V::DIM == 2 {
        [0.0, 0.0, z]
    } else {
        let (az, bz) = (a.coord(2), b.coord(2));
        [ay * bz - az * by, az * bx - ax * bz, z]
    }
}

//! Capsules (the points within `R` of the segment `[a, b]`): the β-agent rule shared by both
//! dimensions.

use flock_math::Vector;

use crate::BetaAgent;

/// The β-agent of the α-agent `(q, p)` on the capsule of axis `[a, b]` and radius `R`, given
/// parry's projection of `q` on its boundary (`projected`, `inside`).
///
/// With `s` the point of `[a, b]` closest to `q` (parry's segment projection) and `ρ = ‖q − s‖`, the
/// normal is `n = (q − s)/ρ` and `q̂ = s + R n`:
///
/// - end caps (`s = a` or `b`): the ball formula about the cap centre, `μ = R/ρ`, `p̂ = μ P p`;
/// - side (`s` inside the segment, axis direction `u`): in 3D `p̂ = (u·p) u + (R/ρ) (P p − (u·p) u)`,
///   the axial component kept and the circumferential one scaled as on a ball, `μ = R/ρ`; in 2D the
///   side is flat (there is no circumferential direction): `p̂ = P p`, `μ = 1`.
///
/// On the axis (`ρ` below parry's threshold `f64::EPSILON`, where every direction is closest) the
/// β-agent is parry's point, with normal `(q̂ − s)/R`, `μ = 1` and `p̂ = P p`, like an α-agent at a
/// ball's centre.
#[inline]
#[must_use]
pub(crate) fn beta_agent<V: Vector>(
    q: V,
    p: V,
    a: V,
    b: V,
    radius: f64,
    projected: V,
    inside: bool,
) -> BetaAgent<V> {
    let ab = b - a;
    let ab_aq = ab.dot(q - a);
    let length_squared = ab.length_squared();
    let (centre, on_side) = if ab_aq <= 0.0 {
        (a, false)
    } else if ab_aq >= length_squared {
        (b, false)
    } else {
        (a + ab * (ab_aq / length_squared), true)
    };
    let offset = q - centre;
    let rho = offset.length();
    if rho < f64::EPSILON {
        let normal = (projected - centre).normalize_or_zero();
        return BetaAgent::new(q, p, projected, normal, 1.0, inside);
    }
    let normal = offset / rho;
    let mu = radius / rho;
    if !on_side {
        return BetaAgent::new(q, p, projected, normal, mu, inside);
    }
    if V::DIM == 2 {
        return BetaAgent::new(q, p, projected, normal, 1.0, inside);
    }
    let u = ab / length_squared.sqrt();
    let axial = u * u.dot(p);
    let around = p - normal * normal.dot(p) - axial;
    BetaAgent::with_velocity(q, projected, normal, axial + around * mu, mu, inside)
}

//! Balls `B(y_k, R_k)`: validation and the β-agent rule shared by both dimensions (Olfati-Saber, IEEE
//! TAC 51(3) 2006, β-agents of spherical obstacles; Caltech CDS 03-006 2003, eq. 55).

use flock_math::Vector;

use crate::error::check_finite;
use crate::{BetaAgent, ObstacleError};

/// Checks a ball's `centre` (finite) and `radius` (finite, `> 0`).
pub(crate) fn validate<V: Vector>(centre: V, radius: f64) -> Result<(), ObstacleError> {
    check_finite("centre", centre)?;
    check_radius(radius)
}

/// Checks a `radius` (finite, `> 0`), of a ball or a capsule.
pub(crate) fn check_radius(radius: f64) -> Result<(), ObstacleError> {
    if radius.is_finite() && radius > 0.0 {
        Ok(())
    } else {
        Err(ObstacleError::InvalidRadius { radius })
    }
}

/// The β-agent of the α-agent `(q, p)` on the ball `B(centre, radius)`, given parry's projection of
/// `q` on its boundary (`projected`, `inside`):
///
/// `a = (q − y)/‖q − y‖`, `μ = R/‖q − y‖`, `q̂ = μ q + (1 − μ) y` (the value parry returns), `p̂ = μ P p`.
///
/// Degenerate case: when `q − y` cannot be normalised (the α-agent at the centre, where every
/// boundary point is closest and parry returns NaN), the β-agent is placed deterministically at
/// `y + R e₁` with normal `a = e₁` (the first axis), `μ = 1` (the tangent plane there, as for a wall)
/// and `inside = true`.
#[inline]
#[must_use]
pub(crate) fn beta_agent<V: Vector>(
    q: V,
    p: V,
    centre: V,
    radius: f64,
    projected: V,
    inside: bool,
) -> BetaAgent<V> {
    let offset = q - centre;
    let normal = offset.normalize_or_zero();
    if normal == V::ZERO {
        let first_axis = V::from_fn(|k| if k == 0 { 1.0 } else { 0.0 });
        return BetaAgent::new(q, p, centre + first_axis * radius, first_axis, 1.0, true);
    }
    BetaAgent::new(q, p, projected, normal, radius / offset.length(), inside)
}

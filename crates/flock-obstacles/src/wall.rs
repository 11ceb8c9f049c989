//! Walls (half-spaces) through `y_k` with outward normal `a_k`: validation and the β-agent rule shared
//! by both dimensions (Olfati-Saber, IEEE TAC 51(3) 2006, β-agents of walls).

use flock_math::Vector;

use crate::error::{check_finite, coordinates};
use crate::{BetaAgent, ObstacleError};

/// Checks a wall's `point` (finite) and `outward_normal` (the `normal` field: finite, non-zero);
/// returns the unit normal.
pub(crate) fn unit_normal<V: Vector>(point: V, outward_normal: V) -> Result<V, ObstacleError> {
    check_finite("point", point)?;
    let unit = outward_normal.normalize_or_zero();
    if outward_normal.is_finite() && unit != V::ZERO {
        Ok(unit)
    } else {
        Err(ObstacleError::InvalidNormal {
            normal: coordinates(outward_normal),
        })
    }
}

/// The β-agent of the α-agent `(q, p)` on the wall with unit outward `normal` `a`, given parry's
/// projection of `q` on the boundary plane (`projected`, `inside`):
///
/// `μ = 1`, `q̂ = P q + (I − P) y = q − a (a · (q − y))` (the value parry returns), `p̂ = P p`,
/// `P = I − a aᵀ`. The normal is `a` on both sides of the wall.
#[inline]
#[must_use]
pub(crate) fn beta_agent<V: Vector>(
    q: V,
    p: V,
    normal: V,
    projected: V,
    inside: bool,
) -> BetaAgent<V> {
    BetaAgent::new(q, p, projected, normal, 1.0, inside)
}

//! Boxes (cuboids): validation and the β-agent rule shared by both dimensions, in the box's local
//! frame (centre at the origin, edges along the axes, half extents `h`).

use flock_math::Vector;

use crate::{BetaAgent, ObstacleError};

/// Checks every half extent (finite, `> 0`).
pub(crate) fn validate<V: Vector>(half_extents: V) -> Result<(), ObstacleError> {
    for axis in 0..V::DIM {
        let half_extent = half_extents.coord(axis);
        if !(half_extent.is_finite() && half_extent > 0.0) {
            return Err(ObstacleError::InvalidHalfExtent { axis, half_extent });
        }
    }
    Ok(())
}

/// The β-agent of the α-agent `(q, p)` (local frame) on the box `[−h, h]`, given parry's projection
/// of `q` on its boundary (`projected`, `inside`).
///
/// Outside, `q̂ = clamp(q, −h, h)` and its derivative keeps the components of `p` along the axes
/// where `q` is within the slab `|q_k| ≤ h_k` and drops the others: one clamped axis is a face
/// (`p̂ = P p`, `μ = 1`), two (in 3D) an edge (`p̂ = (e·p) e`, `μ = 0`), all of them a vertex
/// (`p̂ = 0`, `μ = 0`); the normal is `(q − q̂)/‖q − q̂‖`.
///
/// Inside (the boundary included), `q̂` is on the nearest face, the first axis of least
/// `h_k − |q_k|` (parry's rule): the normal is that face's, `p̂ = P p`, `μ = 1`.
#[inline]
#[must_use]
pub(crate) fn beta_agent<V: Vector>(
    q: V,
    p: V,
    half_extents: V,
    projected: V,
    inside: bool,
) -> BetaAgent<V> {
    if inside {
        let mut axis = 0;
        let mut gap = f64::INFINITY;
        for k in 0..V::DIM {
            let gap_k = half_extents.coord(k) - q.coord(k).abs();
            if gap_k < gap {
                gap = gap_k;
                axis = k;
            }
        }
        let sign = if projected.coord(axis) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let normal = V::from_fn(|k| if k == axis { sign } else { 0.0 });
        return BetaAgent::new(q, p, projected, normal, 1.0, true);
    }
    let clamped = |k: usize| q.coord(k).abs() > half_extents.coord(k);
    let count = (0..V::DIM).filter(|&k| clamped(k)).count();
    let velocity = V::from_fn(|k| if clamped(k) { 0.0 } else { p.coord(k) });
    let normal = (q - projected).normalize_or_zero();
    let mu = if count == 1 { 1.0 } else { 0.0 };
    BetaAgent::with_velocity(q, projected, normal, velocity, mu, false)
}

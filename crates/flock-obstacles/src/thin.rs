//! Zero-thickness obstacles: segments (a thin wall in 2D, a rod in 3D) and triangles in 3D (a thin
//! plate). The β-agent rule shared by both dimensions, from parry's feature location.

use flock_math::Vector;

use crate::BetaAgent;

/// The feature of a segment or a triangle plate on which a projection lies.
#[derive(Clone, Copy, Debug)]
pub enum Feature<V> {
    /// An endpoint or a corner.
    Vertex,
    /// The inside of a segment or of a plate's side, with unit direction `e`.
    Edge(V),
    /// The inside of a plate, with unit normal `n` (either side).
    Face(V),
}

/// The β-agent of the α-agent `(q, p)` on a segment or a plate, given parry's projection
/// (`projected`, `inside` — on the obstacle), the feature it lies on, and the normal to use for an
/// α-agent on the obstacle (`on_normal`).
///
/// The normal is `(q − q̂)/‖q − q̂‖`, pointing to the side of the α-agent (both sides of a thin
/// obstacle are its boundary); for an α-agent on the obstacle it is `on_normal`: the plate's
/// normal, or a unit vector orthogonal to the segment (`basis::orthogonal_unit`). The velocity is the
/// derivative of the projection: `p̂ = P p`, `μ = 1` inside a plate; `p̂ = (e·p) e` along an edge,
/// with `μ = 1` in 2D (the edge is the segment's flat side) and `μ = 0` in 3D (around the edge, the
/// radius of curvature is 0); `p̂ = 0`, `μ = 0` at a vertex.
#[inline]
#[must_use]
pub(crate) fn beta_agent<V: Vector>(
    q: V,
    p: V,
    projected: V,
    inside: bool,
    feature: Feature<V>,
    on_normal: V,
) -> BetaAgent<V> {
    let mut normal = (q - projected).normalize_or_zero();
    if inside || normal == V::ZERO {
        // On the obstacle, `q − q̂` is rounding noise.
        normal = on_normal;
    }
    let (velocity, mu) = match feature {
        Feature::Vertex => (V::ZERO, 0.0),
        Feature::Edge(e) => (e * e.dot(p), if V::DIM == 2 { 1.0 } else { 0.0 }),
        Feature::Face(n) => (p - n * n.dot(p), 1.0),
    };
    BetaAgent::with_velocity(q, projected, normal, velocity, mu, inside)
}

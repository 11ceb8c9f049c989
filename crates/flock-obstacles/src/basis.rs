//! [`Basis`]: an orthonormal basis of a growing subspace (Gram–Schmidt), for the tangent space of a
//! polytope feature and the affine rank of a point set.

use flock_math::Vector;

/// An orthonormal basis `b_1, …, b_r` (r ≤ 3) of the span of the vectors pushed so far.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Basis<V> {
    vectors: [V; 3],
    rank: usize,
}

impl<V: Vector> Basis<V> {
    /// The basis of `{0}`.
    #[inline]
    pub(crate) fn new() -> Self {
        Self {
            vectors: [V::ZERO; 3],
            rank: 0,
        }
    }

    /// The number of basis vectors.
    #[inline]
    pub(crate) fn rank(&self) -> usize {
        self.rank
    }

    /// The component of `v` orthogonal to the span: `v − Σ_j (b_j · v) b_j`.
    #[inline]
    pub(crate) fn reject(&self, v: V) -> V {
        let mut rest = v;
        for &b in &self.vectors[..self.rank] {
            rest -= b * b.dot(rest);
        }
        rest
    }

    /// Adds `v` to the span when its component orthogonal to the span is longer than
    /// `min_length`; returns whether it did.
    #[inline]
    pub(crate) fn push(&mut self, v: V, min_length: f64) -> bool {
        if self.rank == V::DIM {
            return false;
        }
        // Twice: one pass of Gram–Schmidt loses orthogonality when `v` is nearly in the span.
        let rest = self.reject(self.reject(v));
        let length = rest.length();
        if length > min_length && length.is_finite() {
            self.vectors[self.rank] = rest / length;
            self.rank += 1;
            true
        } else {
            false
        }
    }
}

/// A unit vector orthogonal to the unit vector `u`, chosen deterministically: the first axis least
/// aligned with `u`, made orthogonal to it.
#[inline]
pub(crate) fn orthogonal_unit<V: Vector>(u: V) -> V {
    let axis = (0..V::DIM)
        .min_by(|&i, &j| u.coord(i).abs().total_cmp(&u.coord(j).abs()))
        .unwrap_or(0);
    let e = V::from_fn(|k| if k == axis { 1.0 } else { 0.0 });
    (e - u * u.dot(e)).normalize_or_zero()
}

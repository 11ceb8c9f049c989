//! The [`Vector`] trait: one code path for 2D and 3D.
//!
//! Every algorithm of flock is written once, generic over `V: Vector`, and instantiated for glam's
//! [`DVec2`] and [`DVec3`]. The trait carries only what the algorithms call; it is sealed so that
//! the set of dimensions stays the two the theory is checked in.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

use glam::{DVec2, DVec3};

mod sealed {
    pub trait Sealed {}
    impl Sealed for glam::DVec2 {}
    impl Sealed for glam::DVec3 {}
}

/// A point or vector of ℝ^m, m ∈ {2, 3}, with f64 components.
///
/// # Example
/// ```
/// use flock_math::Vector;
/// use glam::DVec2;
///
/// fn centroid<V: Vector>(points: &[V]) -> V {
///     points.iter().fold(V::ZERO, |acc, &p| acc + p) / points.len() as f64
/// }
/// assert_eq!(centroid(&[DVec2::new(0.0, 0.0), DVec2::new(2.0, 4.0)]), DVec2::new(1.0, 2.0));
/// ```
pub trait Vector:
    sealed::Sealed
    + Copy
    + Debug
    + Default
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign<f64>
{
    /// The dimension m of the space.
    const DIM: usize;
    /// The zero vector.
    const ZERO: Self;

    /// Euclidean inner product.
    #[must_use]
    fn dot(self, other: Self) -> f64;
    /// Squared Euclidean norm ‖v‖².
    #[must_use]
    fn length_squared(self) -> f64;
    /// Euclidean norm ‖v‖.
    #[must_use]
    fn length(self) -> f64;
    /// The unit vector along `self`, or zero when `self` is zero or not finite.
    #[must_use]
    fn normalize_or_zero(self) -> Self;
    /// Component `axis` (0 = x, 1 = y, 2 = z). Panics when `axis >= DIM`.
    #[must_use]
    fn coord(self, axis: usize) -> f64;
    /// Builds a vector from its components, `f(0), …, f(DIM − 1)`.
    #[must_use]
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    /// Component-wise minimum.
    #[must_use]
    fn min(self, other: Self) -> Self;
    /// Component-wise maximum.
    #[must_use]
    fn max(self, other: Self) -> Self;
    /// True when every component is finite (neither NaN nor ±∞).
    #[must_use]
    fn is_finite(self) -> bool;
}

macro_rules! impl_vector {
    ($ty:ty, $dim:expr) => {
        impl Vector for $ty {
            const DIM: usize = $dim;
            const ZERO: Self = <$ty>::ZERO;

            #[inline]
            fn dot(self, other: Self) -> f64 {
                <$ty>::dot(self, other)
            }
            #[inline]
            fn length_squared(self) -> f64 {
                <$ty>::length_squared(self)
            }
            #[inline]
            fn length(self) -> f64 {
                <$ty>::length(self)
            }
            #[inline]
            fn normalize_or_zero(self) -> Self {
                <$ty>::normalize_or_zero(self)
            }
            #[inline]
            fn coord(self, axis: usize) -> f64 {
                self[axis]
            }
            #[inline]
            fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
                let mut v = <$ty>::ZERO;
                for axis in 0..$dim {
                    v[axis] = f(axis);
                }
                v
            }
            #[inline]
            fn min(self, other: Self) -> Self {
                <$ty>::min(self, other)
            }
            #[inline]
            fn max(self, other: Self) -> Self {
                <$ty>::max(self, other)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$ty>::is_finite(self)
            }
        }
    };
}

impl_vector!(DVec2, 2);
impl_vector!(DVec3, 3);

/// The arithmetic mean of vectors, summed in index order (deterministic); zero for none.
#[must_use]
pub fn mean<V: Vector>(vectors: &[V]) -> V {
    mean_of(vectors.iter().copied())
}

/// The arithmetic mean of the vectors of an iterator, summed in its order; zero for none.
/// [`mean`] of a slice is `mean_of` its elements.
#[must_use]
pub fn mean_of<V: Vector>(vectors: impl ExactSizeIterator<Item = V>) -> V {
    let n = vectors.len();
    if n == 0 {
        return V::ZERO;
    }
    vectors.fold(V::ZERO, |acc, v| acc + v) / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check<V: Vector>() {
        let v = V::from_fn(|k| k as f64 + 1.0);
        for k in 0..V::DIM {
            assert_eq!(v.coord(k), k as f64 + 1.0);
        }
        let expected: f64 = (1..=V::DIM).map(|k| (k * k) as f64).sum();
        assert_eq!(v.length_squared(), expected);
        assert_eq!(v.dot(v), expected);
        assert!((v.normalize_or_zero().length() - 1.0).abs() < 1e-15);
        assert_eq!(V::ZERO.normalize_or_zero(), V::ZERO);
        assert!(!V::from_fn(|_| f64::NAN).is_finite());
        assert_eq!(v.min(-v), -v);
        assert_eq!(v.max(-v), v);
        assert_eq!(mean(&[v, -v, v * 4.0]), v * (4.0 / 3.0));
        assert_eq!(mean::<V>(&[]), V::ZERO);
    }

    #[test]
    fn vector_contract_2d() {
        check::<DVec2>();
    }

    #[test]
    fn vector_contract_3d() {
        check::<DVec3>();
    }
}

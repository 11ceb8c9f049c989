//! The space the agents live in: open ℝ^m, or a periodic box [0, L₁) × … × [0, L_m), a torus,
//! on which every displacement is the minimum image (Allen & Tildesley, *Computer Simulation of
//! Liquids*, 2nd ed. 2017, § 1.6.3), as Vicsek et al. (PRL 75, 1995) and the ABM frameworks'
//! boids benchmark (JuliaDynamics ABMFrameworksComparison, `Flocking/DECLARATION.md`) use it.

use crate::Vector;

/// Open space, or a periodic box with its origin at 0.
///
/// # Example
/// ```
/// use flock_math::Domain;
/// use glam::DVec2;
///
/// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
/// // from x = 9.5 to x = 0.5 is one step forward across the wrap, not nine back
/// let d = torus.displacement(DVec2::new(9.5, 5.0), DVec2::new(0.5, 5.0));
/// assert_eq!(d, DVec2::new(1.0, 0.0));
/// assert_eq!(torus.wrap(DVec2::new(10.5, -0.5)), DVec2::new(0.5, 9.5));
/// assert_eq!(Domain::Open.displacement(DVec2::ZERO, DVec2::X), DVec2::X);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Domain<V> {
    /// ℝ^m: displacements are differences, positions are never wrapped.
    #[default]
    Open,
    /// The torus [0, L₁) × … × [0, L_m), every side L_k > 0.
    Periodic {
        /// The sides (L₁, …, L_m).
        size: V,
    },
}

/// `x` reduced to [−L/2, L/2] by whole periods: the minimum image of a coordinate difference.
#[inline]
#[must_use]
pub fn minimum_image(x: f64, period: f64) -> f64 {
    x - period * (x / period).round()
}

/// `x` reduced to [0, L) by whole periods.
#[inline]
#[must_use]
pub fn wrap_coordinate(x: f64, period: f64) -> f64 {
    let y = x - period * (x / period).floor();
    // x just below 0 rounds to y = L; the box is half-open
    if y >= period { y - period } else { y }
}

impl<V: Vector> Domain<V> {
    /// Whether the domain is a periodic box.
    #[inline]
    #[must_use]
    pub const fn is_periodic(&self) -> bool {
        matches!(self, Self::Periodic { .. })
    }

    /// The displacement `to − from`: on a torus its minimum image, each component in
    /// [−L_k/2, L_k/2]. Open space gives the difference, bit for bit.
    #[inline]
    #[must_use]
    pub fn displacement(&self, from: V, to: V) -> V {
        match self {
            Self::Open => to - from,
            Self::Periodic { size } => {
                let d = to - from;
                V::from_fn(|k| minimum_image(d.coord(k), size.coord(k)))
            }
        }
    }

    /// The distance ‖displacement(a, b)‖.
    #[inline]
    #[must_use]
    pub fn distance(&self, a: V, b: V) -> f64 {
        self.displacement(a, b).length()
    }

    /// `q` brought into the box [0, L) by whole periods; unchanged in open space.
    #[inline]
    #[must_use]
    pub fn wrap(&self, q: V) -> V {
        match self {
            Self::Open => q,
            Self::Periodic { size } => V::from_fn(|k| wrap_coordinate(q.coord(k), size.coord(k))),
        }
    }

    /// The point of the image lattice of `to` nearest `from`: `from + displacement(from, to)`,
    /// the position of `to` as an agent at `from` sees it.
    #[inline]
    #[must_use]
    pub fn image_near(&self, from: V, to: V) -> V {
        match self {
            Self::Open => to,
            Self::Periodic { .. } => from + self.displacement(from, to),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;
    use glam::{DVec2, DVec3};
    use proptest::prelude::*;

    #[test]
    fn wrap_keeps_the_box_half_open() {
        assert_eq!(wrap_coordinate(-1e-300, 10.0), 0.0);
        assert_eq!(wrap_coordinate(10.0, 10.0), 0.0);
        assert_eq!(wrap_coordinate(-10.0, 10.0), 0.0);
        assert_eq!(wrap_coordinate(23.0, 10.0), 3.0);
        assert!(wrap_coordinate(-f64::EPSILON, 10.0) < 10.0);
    }

    #[test]
    fn minimum_image_in_3d() {
        let torus = Domain::Periodic {
            size: DVec3::new(10.0, 20.0, 30.0),
        };
        let d = torus.displacement(DVec3::new(1.0, 19.0, 2.0), DVec3::new(9.0, 1.0, 28.0));
        assert_eq!(d, DVec3::new(-2.0, 2.0, -4.0));
        assert_eq!(
            torus.image_near(DVec3::new(1.0, 19.0, 2.0), DVec3::new(9.0, 1.0, 28.0)),
            DVec3::new(-1.0, 21.0, -2.0)
        );
    }

    proptest! {
        #[test]
        fn minimum_image_is_the_nearest_image(
            a in prop::array::uniform2(0.0f64..10.0),
            b in prop::array::uniform2(0.0f64..10.0),
            shift in prop::array::uniform2(-3i32..4),
        ) {
            let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
            let (a, b) = (DVec2::from(a), DVec2::from(b));
            let d = torus.displacement(a, b);
            prop_assert!(d.x.abs() <= 5.0 && d.y.abs() <= 5.0);
            // no image of b is nearer to a than the minimum image (brute force over 5 × 5 images)
            for i in -2..=2 {
                for j in -2..=2 {
                    let image = b + DVec2::new(10.0 * f64::from(i), 10.0 * f64::from(j));
                    prop_assert!(d.length() <= (image - a).length() + 1e-12);
                }
            }
            // shifting either point by whole periods changes nothing
            let moved = b + DVec2::new(10.0 * f64::from(shift[0]), 10.0 * f64::from(shift[1]));
            let d2 = torus.displacement(a, moved);
            assert_abs_diff_eq!(d2.length(), d.length(), epsilon = 1e-12);
            let w = torus.wrap(moved);
            prop_assert!((0.0..10.0).contains(&w.x) && (0.0..10.0).contains(&w.y));
            assert_abs_diff_eq!(w, b, epsilon = 1e-12);
        }
    }
}

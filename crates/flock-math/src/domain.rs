//! The space the agents live in: open ℝ^m, or a periodic box [0, L₁) × … × [0, L_m), a torus,
//! on which every displacement is the minimum image (Allen & Tildesley, *Computer Simulation of
//! Liquids*, 2nd ed. 2017, § 1.6.3), as Vicsek et al. (PRL 75, 1995) and the ABM frameworks'
//! boids benchmark (JuliaDynamics ABMFrameworksComparison, `Flocking/DECLARATION.md`) use it.

use crate::{Vector, mean_of};

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
    x - period * periods_in(x, period)
}

/// `(x / period).round()` (half away from zero, the sign of a zero kept), bit for bit, without
/// the division nor the library call that baseline x86-64 (no SSE4.1 `roundsd`) makes for
/// `round`, when |x| ≤ period, as for the difference of two coordinates in a box: comparisons
/// with ±period/2 give −1, ±0 or 1. A periodic neighbour search takes one per candidate pair and
/// axis; the call to `round` alone was 21 % of a Vicsek step at 10⁵ particles.
///
/// Exact: period/2 is exact, and the quotient, correctly rounded, reaches ±0.5 exactly when x
/// reaches ±period/2, since no double lies within half an ulp of 0.5 · period below period/2.
#[inline]
fn periods_in(x: f64, period: f64) -> f64 {
    if x.abs() <= period && (1e-300..1e300).contains(&period) {
        let half = 0.5 * period;
        (f64::from(u8::from(x >= half)) - f64::from(u8::from(x <= -half))).copysign(x)
    } else {
        (x / period).round()
    }
}

/// `x.floor()`, bit for bit, without the library call for −1 ≤ x < 2, as for a coordinate in
/// or next to its box divided by the side: comparisons give −1, ±0 or 1.
#[inline]
fn floor_near_zero(x: f64) -> f64 {
    if (-1.0..2.0).contains(&x) {
        (f64::from(u8::from(x >= 1.0)) - f64::from(u8::from(x < 0.0))).copysign(x)
    } else {
        x.floor()
    }
}

/// The minimum image of `to − from` in the periodic box of sides `size`, each component in
/// [−L_k/2, L_k/2]: [`Domain::displacement`] on a torus, for a caller that holds the sides
/// (a neighbour search, per candidate pair, without matching the domain).
#[inline]
#[must_use]
pub fn periodic_displacement<V: Vector>(from: V, to: V, size: V) -> V {
    let d = to - from;
    V::from_fn(|k| minimum_image(d.coord(k), size.coord(k)))
}

/// `x` reduced to [0, L) by whole periods.
#[inline]
#[must_use]
pub fn wrap_coordinate(x: f64, period: f64) -> f64 {
    let y = x - period * floor_near_zero(x / period);
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
            Self::Periodic { size } => periodic_displacement(from, to, *size),
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

    /// The centre of mass of `points`. In open space their mean, bit for bit [`mean_of`] (zero for
    /// no point). On a torus, where the mean of the coordinates depends on where the box is cut,
    /// the circular mean per axis (Bai & Breen, "Calculating center of mass in an unbounded 2D
    /// environment", J. Graphics Tools 13(4), 2008): each coordinate is mapped to an angle
    /// θ_i = 2π x_i / L on the circle of circumference L, the unit vectors (cos θ_i, sin θ_i) are
    /// averaged into (ξ̄, ζ̄), and the mean angle θ̄ = atan2(−ζ̄, −ξ̄) + π ∈ [0, 2π] is mapped back,
    /// x̄ = L θ̄ / 2π, wrapped into [0, L). The sums run in the order of `points`. The centre of a
    /// single point is that point, bit for bit (the round trip through the angle would move it
    /// by round-off, and a lone agent would seem to circle a centre beside it; issue 49).
    ///
    /// For agents within a quarter of the box of each other on an axis this is close to their
    /// mean taken in one unwrapped image; it is ill-conditioned when (ξ̄, ζ̄) is near zero (agents
    /// spread evenly round an axis), where no centre is meaningful (the result is then some point
    /// of the box, never NaN for finite points).
    ///
    /// # Example
    /// ```
    /// use flock_math::Domain;
    /// use glam::DVec2;
    ///
    /// let torus = Domain::Periodic { size: DVec2::new(10.0, 10.0) };
    /// // two agents either side of the wrap at x = 0: their centre is on the wrap, not at x = 5
    /// let c = torus.centre_of([DVec2::new(9.0, 4.0), DVec2::new(1.0, 6.0)].into_iter());
    /// assert!(c.x.min(10.0 - c.x) < 1e-12 && (c.y - 5.0).abs() < 1e-12);
    /// let open = Domain::Open.centre_of([DVec2::new(9.0, 4.0), DVec2::new(1.0, 6.0)].into_iter());
    /// assert_eq!(open, DVec2::new(5.0, 5.0));
    /// let lone = DVec2::new(0.1, 9.3);
    /// assert_eq!(torus.centre_of([lone].into_iter()), lone);
    /// ```
    #[must_use]
    pub fn centre_of(&self, points: impl ExactSizeIterator<Item = V>) -> V {
        match self {
            Self::Open => mean_of(points),
            Self::Periodic { size } => {
                let (count, mut points) = (points.len(), points.peekable());
                match (count, points.peek()) {
                    (0, _) | (_, None) => return V::ZERO,
                    (1, Some(&only)) => return only,
                    _ => {}
                }
                let (mut cos, mut sin) = ([0.0; 3], [0.0; 3]);
                for q in points {
                    for k in 0..V::DIM {
                        let theta = core::f64::consts::TAU * (q.coord(k) / size.coord(k));
                        cos[k] += theta.cos();
                        sin[k] += theta.sin();
                    }
                }
                // atan2 is invariant under scaling: the sums stand for the means
                V::from_fn(|k| {
                    let theta = (-sin[k]).atan2(-cos[k]) + core::f64::consts::PI;
                    let l = size.coord(k);
                    wrap_coordinate(l * (theta / core::f64::consts::TAU), l)
                })
            }
        }
    }

    /// The point of the image lattice of `to` nearest `from`, `to` shifted by whole periods
    /// (`to` itself, bit for bit, when it is the nearest): the position of `to` as an agent at
    /// `from` sees it.
    #[inline]
    #[must_use]
    pub fn image_near(&self, from: V, to: V) -> V {
        match self {
            Self::Open => to,
            Self::Periodic { size } => V::from_fn(|k| {
                let (x, period) = (to.coord(k), size.coord(k));
                let shift = periods_in(x - from.coord(k), period);
                if shift == 0.0 { x } else { x - shift * period }
            }),
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

    #[test]
    fn circular_mean_of_a_flock_across_the_wrap() {
        let size = DVec3::new(10.0, 20.0, 30.0);
        let torus = Domain::Periodic { size };
        // a flock round (9.8, 0.1, 15) cut by the faces x = 0 and y = 0: the circular mean is its
        // centre; the plain mean of the wrapped coordinates is far from every agent
        let offsets = [
            DVec3::new(-0.4, 0.3, 0.1),
            DVec3::new(0.4, -0.3, -0.1),
            DVec3::new(0.2, 0.2, 0.2),
            DVec3::new(-0.2, -0.2, -0.2),
        ];
        let centre = DVec3::new(9.8, 0.1, 15.0);
        let q: Vec<DVec3> = offsets.iter().map(|&o| torus.wrap(centre + o)).collect();
        let c = torus.centre_of(q.iter().copied());
        assert!(torus.distance(c, centre) < 1e-12, "{c}");
        assert!(torus.distance(mean_of(q.iter().copied()), centre) > 4.0);
        // shifting every agent by a vector shifts the centre by it
        let shift = DVec3::new(3.3, -7.1, 29.0);
        let moved = torus.centre_of(q.iter().map(|&p| torus.wrap(p + shift)));
        assert!(torus.distance(moved, torus.wrap(centre + shift)) < 1e-12);
        assert_eq!(torus.centre_of(core::iter::empty()), DVec3::ZERO);
        // open space is the mean, bit for bit
        assert_eq!(
            Domain::Open.centre_of(q.iter().copied()),
            mean_of(q.iter().copied())
        );
        // evenly spread: some point of the box, not NaN
        let ring = [DVec2::new(0.0, 1.0), DVec2::new(5.0, 1.0)];
        let c = Domain::Periodic {
            size: DVec2::new(10.0, 10.0),
        }
        .centre_of(ring.into_iter());
        assert!((0.0..10.0).contains(&c.x) && (c.y - 1.0).abs() < 1e-12);
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

        /// The comparisons give `floor` bit for bit: near zero, where they replace it, at the
        /// integers where it changes, and anywhere else.
        #[test]
        fn flooring_near_zero_is_the_library_floor(
            x in prop_oneof![
                -3.0f64..3.0,
                prop::sample::select(vec![
                    -2.0, -1.5, -1.0, -0.5, -0.0, 0.0, 0.5, 1.0, 1.5, 2.0,
                    1.999_999_999_999_999_8, -0.999_999_999_999_999_9, -1e-300, 1e-300,
                    f64::NAN, f64::INFINITY, f64::NEG_INFINITY,
                ]),
                any::<f64>(),
            ],
        ) {
            prop_assert_eq!(floor_near_zero(x).to_bits(), x.floor().to_bits(), "floor({})", x);
        }

        /// The comparisons with ±period/2 give `(x / period).round()` bit for bit: for x
        /// anywhere in and beyond [−period, period], within a few ulps of ±period/2 and of
        /// ±period, at ±0, NaN and ±∞, for periods from 10⁻³⁰⁰ to 10³⁰⁰ and beyond (10⁻³⁰⁷ to
        /// 10³⁰⁷, where the quotient is taken).
        #[test]
        fn periods_by_comparison_are_the_rounded_quotient(
            exponent in -307.0f64..307.0,
            mantissa in 1.0f64..2.0,
            t in -2.5f64..2.5,
            ulps in -3i32..4,
            pick in 0usize..8,
        ) {
            let period = mantissa * 10f64.powf(exponent);
            let step = |x: f64| (0..ulps.unsigned_abs()).fold(x, |x, _| {
                if ulps < 0 { x.next_down() } else { x.next_up() }
            });
            let x = match pick {
                0 => t * period,
                1 => step(0.5 * period),
                2 => step(-0.5 * period),
                3 => step(period),
                4 => step(-period),
                5 => step(0.0),
                6 => [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][ulps.unsigned_abs() as usize % 3],
                _ => step(t * 1e-3 * period),
            };
            let want = (x / period).round();
            prop_assert_eq!(periods_in(x, period).to_bits(), want.to_bits(), "{} / {}", x, period);
            prop_assert_eq!(
                minimum_image(x, period).to_bits(),
                (x - period * want).to_bits(),
                "{} mod {}", x, period
            );
        }
    }
}

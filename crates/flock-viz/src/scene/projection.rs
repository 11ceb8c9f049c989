//! [`View`]: the orthographic projection that draws a 3D run on the page, as TAC 2006 Fig. 13 draws
//! its 3D flocks; 2D runs are drawn in their own plane whatever the view; [`lift`]: a run's
//! vectors in the 3D space every view projects.

use flock_math::Vector;
use glam::{DVec2, DVec3};

/// A point or vector of a 2D or 3D run in 3D, z = 0 in 2D: how scenes store positions.
///
/// # Example
/// ```
/// use flock_viz::lift;
/// use glam::{DVec2, DVec3};
///
/// assert_eq!(lift(DVec2::new(1.0, 2.0)), DVec3::new(1.0, 2.0, 0.0));
/// ```
#[inline]
#[must_use]
pub fn lift<V: Vector>(v: V) -> DVec3 {
    DVec3::new(
        v.coord(0),
        v.coord(1),
        if V::DIM > 2 { v.coord(2) } else { 0.0 },
    )
}

/// An orthographic view of 3D space from a direction given by azimuth and elevation (degrees), as
/// matplotlib's 3D axes define them: the viewer looks at the origin from
/// (cos el cos az, cos el sin az, sin el); the page's horizontal axis u is
/// (−sin az, cos az, 0) and its vertical axis v is (−sin el cos az, −sin el sin az, cos el).
///
/// [`View::TOP`] looks down the z-axis (u = x, v = y); [`View::default`] is matplotlib's default
/// view, azimuth −60°, elevation 30°.
///
/// # Example
/// ```
/// use flock_viz::View;
/// use glam::{DVec2, DVec3};
///
/// assert_eq!(View::TOP.project(DVec3::new(1.0, 2.0, 3.0)), DVec2::new(1.0, 2.0));
/// let side = View::new(-90.0, 0.0); // looking along +y: u = x, v = z
/// assert_eq!(side.project(DVec3::new(1.0, 2.0, 3.0)), DVec2::new(1.0, 3.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Azimuth in degrees, about the z-axis from the x-axis.
    pub azimuth: f64,
    /// Elevation in degrees above the xy-plane.
    pub elevation: f64,
}

impl Default for View {
    fn default() -> Self {
        Self::new(-60.0, 30.0)
    }
}

impl View {
    /// The top view: looking down the z-axis, x to the right, y up.
    pub const TOP: Self = Self {
        azimuth: -90.0,
        elevation: 90.0,
    };

    /// The front view: looking along +y, x to the right, z up.
    pub const FRONT: Self = Self {
        azimuth: -90.0,
        elevation: 0.0,
    };

    /// The side view: looking along −x, y to the right, z up.
    pub const SIDE: Self = Self {
        azimuth: 0.0,
        elevation: 0.0,
    };

    /// The view from azimuth and elevation in degrees.
    #[must_use]
    pub const fn new(azimuth: f64, elevation: f64) -> Self {
        Self { azimuth, elevation }
    }

    /// The view looking down `axis` (towards the viewer: `axis` points out of the page), e.g. a
    /// mill's axis, so that agents circling it are drawn as a ring.
    ///
    /// # Example
    /// ```
    /// use flock_viz::View;
    /// use glam::DVec3;
    ///
    /// let (_, _, w) = View::along(DVec3::new(0.0, 3.0, 4.0)).basis();
    /// assert!((w - DVec3::new(0.0, 0.6, 0.8)).length() < 1e-12);
    /// ```
    #[must_use]
    pub fn along(axis: DVec3) -> Self {
        let a = axis.normalize();
        Self::new(
            a.y.atan2(a.x).to_degrees(),
            a.z.clamp(-1.0, 1.0).asin().to_degrees(),
        )
    }

    /// The page axes (u, v) and the direction towards the viewer w, orthonormal and right-handed
    /// (u × v = w).
    #[must_use]
    pub fn basis(self) -> (DVec3, DVec3, DVec3) {
        let (sa, ca) = sin_cos_degrees(self.azimuth);
        let (se, ce) = sin_cos_degrees(self.elevation);
        let u = DVec3::new(-sa, ca, 0.0);
        let v = DVec3::new(-se * ca, -se * sa, ce);
        let w = DVec3::new(ce * ca, ce * sa, se);
        (u, v, w)
    }

    /// The page coordinates (u, v) of a point.
    #[inline]
    #[must_use]
    pub fn project(self, p: DVec3) -> DVec2 {
        let (u, v, _) = self.basis();
        DVec2::new(p.dot(u), p.dot(v))
    }

    /// How far a point is towards the viewer (larger is nearer): the order in which to draw.
    #[inline]
    #[must_use]
    pub fn depth(self, p: DVec3) -> f64 {
        p.dot(self.basis().2)
    }

    /// Whether this is [`View::TOP`] (the page axes are x and y).
    #[must_use]
    pub fn is_top(self) -> bool {
        self.page_axes() == Some(("x", "y"))
    }

    /// The names of the page axes when both are coordinate axes (`("x", "y")` for the top view,
    /// `("x", "z")` for the front view, `("y", "z")` for the side view).
    fn page_axes(self) -> Option<(&'static str, &'static str)> {
        let name = |a: DVec3| match a {
            DVec3::X => Some("x"),
            DVec3::Y => Some("y"),
            DVec3::Z => Some("z"),
            _ => None,
        };
        let (u, v, _) = self.basis();
        Some((name(u)?, name(v)?))
    }

    /// The names of the page axes: the coordinate axes when the page shows two of them (top,
    /// front and side views), `("u", "v")` otherwise.
    #[must_use]
    pub fn axis_names(self) -> (&'static str, &'static str) {
        self.page_axes().unwrap_or(("u", "v"))
    }

    /// A short description for titles: `top view`, `front view`, `side view` or
    /// `view az −60°, el 30°`.
    #[must_use]
    pub fn describe(self) -> String {
        match self.page_axes() {
            Some(("x", "y")) => "top view".to_owned(),
            Some(("x", "z")) => "front view".to_owned(),
            Some(("y", "z")) => "side view".to_owned(),
            _ => format!(
                "view az {}°, el {}°",
                crate::draw::format::number(self.azimuth, 1),
                crate::draw::format::number(self.elevation, 1)
            ),
        }
    }
}

/// sin and cos of an angle in degrees, exact at multiples of 90° (so that [`View::TOP`] projects
/// onto x and y without rounding).
fn sin_cos_degrees(degrees: f64) -> (f64, f64) {
    let quarter = degrees / 90.0;
    if quarter == quarter.round() && quarter.abs() < 1e9 {
        match (quarter as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        degrees.to_radians().sin_cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        for view in [View::default(), View::TOP, View::new(17.0, -40.0)] {
            let (u, v, w) = view.basis();
            assert!((u.length() - 1.0).abs() < 1e-12);
            assert!((v.length() - 1.0).abs() < 1e-12);
            assert!(u.dot(v).abs() < 1e-12);
            assert!((u.cross(v) - w).length() < 1e-12);
        }
    }

    #[test]
    fn top_view_is_exact() {
        assert!(View::TOP.is_top());
        assert!(!View::default().is_top());
        assert_eq!(View::TOP.describe(), "top view");
        assert_eq!(View::default().describe(), "view az -60°, el 30°");
    }

    #[test]
    fn front_and_side_views_show_two_coordinate_axes() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(View::FRONT.project(p), DVec2::new(1.0, 3.0));
        assert_eq!(View::SIDE.project(p), DVec2::new(2.0, 3.0));
        assert_eq!(View::FRONT.axis_names(), ("x", "z"));
        assert_eq!(View::SIDE.axis_names(), ("y", "z"));
        assert_eq!(View::default().axis_names(), ("u", "v"));
        assert_eq!(View::FRONT.describe(), "front view");
        assert_eq!(View::SIDE.describe(), "side view");
        // the viewer looks along +y (front) and −x (side): nearer is smaller y, larger x
        assert!(View::FRONT.depth(DVec3::new(0.0, -1.0, 0.0)) > View::FRONT.depth(DVec3::Y));
        assert!(View::SIDE.depth(DVec3::X) > View::SIDE.depth(-DVec3::X));
    }
}

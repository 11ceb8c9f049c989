//! Plane geometry on the page: rectangles, convex hulls and clipping, so that every mark is cut to
//! the plotting window before plotters sees it.

use glam::DVec2;

/// An axis-aligned rectangle of the page plane (data units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rect {
    pub(crate) min: DVec2,
    pub(crate) max: DVec2,
}

impl Rect {
    /// The rectangle holding no point (the identity of [`Rect::union`]).
    pub(crate) const EMPTY: Self = Self {
        min: DVec2::splat(f64::INFINITY),
        max: DVec2::splat(f64::NEG_INFINITY),
    };

    /// Whether no point was added.
    pub(crate) fn is_empty(self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y)
    }

    /// The rectangle grown to hold `p` (non-finite points are ignored).
    pub(crate) fn with_point(self, p: DVec2) -> Self {
        if !p.is_finite() {
            return self;
        }
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest rectangle holding both.
    pub(crate) fn union(self, other: Self) -> Self {
        if other.is_empty() {
            return self;
        }
        if self.is_empty() {
            return other;
        }
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The rectangle grown by `pad` on every side.
    pub(crate) fn padded(self, pad: f64) -> Self {
        Self {
            min: self.min - DVec2::splat(pad),
            max: self.max + DVec2::splat(pad),
        }
    }

    pub(crate) fn size(self) -> DVec2 {
        self.max - self.min
    }

    pub(crate) fn centre(self) -> DVec2 {
        0.5 * (self.min + self.max)
    }

    /// The rectangle of size `size` centred on `centre`.
    pub(crate) fn centred(centre: DVec2, size: DVec2) -> Self {
        Self {
            min: centre - 0.5 * size,
            max: centre + 0.5 * size,
        }
    }

    pub(crate) fn contains(self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// A usable window: an empty rectangle becomes the unit square about the origin, a degenerate
    /// side gets a width of 1 (or 10 % of the other side).
    pub(crate) fn non_degenerate(self) -> Self {
        if self.is_empty() {
            return Self::centred(DVec2::ZERO, DVec2::ONE);
        }
        let size = self.size();
        let fallback = size.max_element().max(1e-9) * 0.1;
        let fallback = if size.max_element() > 0.0 {
            fallback
        } else {
            1.0
        };
        let size = DVec2::new(
            if size.x > 0.0 { size.x } else { fallback },
            if size.y > 0.0 { size.y } else { fallback },
        );
        Self::centred(self.centre(), size)
    }

    /// The rectangle grown about its centre along one axis so that width / height = `aspect`.
    pub(crate) fn with_aspect(self, aspect: f64) -> Self {
        let size = self.size();
        if size.x / size.y < aspect {
            Self::centred(self.centre(), DVec2::new(size.y * aspect, size.y))
        } else {
            Self::centred(self.centre(), DVec2::new(size.x, size.x / aspect))
        }
    }
}

/// The convex hull of `points`, counter-clockwise, without repeated or collinear vertices
/// (Andrew's monotone chain; non-finite points are ignored).
pub(crate) fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// The part of a polygon inside a rectangle (Sutherland–Hodgman). Convex polygons stay convex.
pub(crate) fn clip_polygon(polygon: &[DVec2], rect: Rect) -> Vec<DVec2> {
    // Each edge of the rectangle as (axis, bound, keep points with coordinate >= bound?).
    let edges = [
        (0, rect.min.x, true),
        (0, rect.max.x, false),
        (1, rect.min.y, true),
        (1, rect.max.y, false),
    ];
    let mut out: Vec<DVec2> = polygon.to_vec();
    for (axis, bound, keep_above) in edges {
        if out.is_empty() {
            break;
        }
        let inside = |p: DVec2| {
            if keep_above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let input = std::mem::take(&mut out);
        let mut prev = input[input.len() - 1];
        for &cur in &input {
            match (inside(prev), inside(cur)) {
                (true, true) => out.push(cur),
                (true, false) => out.push(intersect(prev, cur, axis, bound)),
                (false, true) => {
                    out.push(intersect(prev, cur, axis, bound));
                    out.push(cur);
                }
                (false, false) => {}
            }
            prev = cur;
        }
    }
    out
}

/// The point of segment a–b whose coordinate `axis` is `bound` (a and b on either side).
fn intersect(a: DVec2, b: DVec2, axis: usize, bound: f64) -> DVec2 {
    let s = (bound - a[axis]) / (b[axis] - a[axis]);
    let mut p = a + s * (b - a);
    p[axis] = bound;
    p
}

/// The part of segment a–b inside a rectangle (Liang–Barsky), if any.
pub(crate) fn clip_segment(a: DVec2, b: DVec2, rect: Rect) -> Option<(DVec2, DVec2)> {
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-d.x, a.x - rect.min.x),
        (d.x, rect.max.x - a.x),
        (-d.y, a.y - rect.min.y),
        (d.y, rect.max.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    Some((a + t0 * d, a + t1 * d))
}

/// The parts of a polyline inside a rectangle, as polylines.
pub(crate) fn clip_polyline(points: &[DVec2], rect: Rect) -> Vec<Vec<DVec2>> {
    let mut runs: Vec<Vec<DVec2>> = Vec::new();
    let mut current: Vec<DVec2> = Vec::new();
    for pair in points.windows(2) {
        match clip_segment(pair[0], pair[1], rect) {
            Some((a, b)) => {
                if current.last() != Some(&a) {
                    if current.len() >= 2 {
                        runs.push(std::mem::take(&mut current));
                    }
                    current.clear();
                    current.push(a);
                }
                current.push(b);
            }
            None => {
                if current.len() >= 2 {
                    runs.push(std::mem::take(&mut current));
                }
                current.clear();
            }
        }
    }
    if current.len() >= 2 {
        runs.push(current);
    }
    runs
}

/// A circle as a regular polygon of `sides` vertices.
pub(crate) fn circle_polygon(centre: DVec2, radius: f64, sides: usize) -> Vec<DVec2> {
    (0..sides)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / sides as f64;
            centre + radius * DVec2::new(angle.cos(), angle.sin())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Rect {
        Rect {
            min: DVec2::ZERO,
            max: DVec2::ONE,
        }
    }

    #[test]
    fn hull_of_a_square_with_inner_points() {
        let pts = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 0.5),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.5, 0.0),
        ];
        let hull = convex_hull(&pts);
        assert_eq!(
            hull,
            [
                DVec2::new(0.0, 0.0),
                DVec2::new(1.0, 0.0),
                DVec2::new(1.0, 1.0),
                DVec2::new(0.0, 1.0)
            ]
        );
    }

    #[test]
    fn polygon_clipping_cuts_to_the_rectangle() {
        let big = [
            DVec2::new(-1.0, -1.0),
            DVec2::new(2.0, -1.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(-1.0, 2.0),
        ];
        let clipped = clip_polygon(&big, unit());
        assert_eq!(clipped.len(), 4);
        assert!(clipped.iter().all(|&p| unit().contains(p)));
        let outside = [
            DVec2::new(3.0, 3.0),
            DVec2::new(4.0, 3.0),
            DVec2::new(4.0, 4.0),
        ];
        assert!(clip_polygon(&outside, unit()).is_empty());
    }

    #[test]
    fn segment_and_polyline_clipping() {
        let (a, b) = clip_segment(DVec2::new(-1.0, 0.5), DVec2::new(2.0, 0.5), unit()).unwrap();
        assert_eq!((a, b), (DVec2::new(0.0, 0.5), DVec2::new(1.0, 0.5)));
        assert!(clip_segment(DVec2::new(-1.0, 2.0), DVec2::new(2.0, 2.0), unit()).is_none());
        let runs = clip_polyline(
            &[
                DVec2::new(0.2, 0.2),
                DVec2::new(0.8, 0.2),
                DVec2::new(3.0, 0.2),
                DVec2::new(3.0, 0.8),
                DVec2::new(0.5, 0.8),
            ],
            unit(),
        );
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0].len(), 3);
    }

    #[test]
    fn aspect_grows_the_short_side() {
        let r = unit().with_aspect(2.0);
        assert_eq!(r.size(), DVec2::new(2.0, 1.0));
        assert_eq!(r.centre(), DVec2::splat(0.5));
    }
}

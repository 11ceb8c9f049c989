//! [`Framing`]: which part of the plane a snapshot or an animation shows.

use std::sync::OnceLock;

use glam::{DVec2, DVec3};

use crate::draw::geometry::Rect;
use crate::scene::drawable::{Drawable, Shape, project_point};
use crate::scene::frames::Scene;
use crate::scene::projection::View;

/// Which part of the page plane a panel shows. The window is then widened along one axis so that
/// both axes have the same scale (equal aspect ratio, as in the papers' figures).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Framing {
    /// The agents (and γ-agent and trails) of the frame drawn, with a margin: each snapshot is
    /// zoomed on the flock, as TAC 2006 Figs. 10–13 are.
    #[default]
    Flock,
    /// A window of fixed size (the largest flock of the run) that follows the flock's centre.
    Follow,
    /// Everything the run ever occupies, obstacles included: the same window for every frame.
    Run,
    /// A fixed window of the page plane (data units).
    Fixed {
        /// The lower-left corner.
        min: DVec2,
        /// The upper-right corner.
        max: DVec2,
    },
}

/// Lays out panels: windows of frames under a framing, and the box of space a wall is cut to.
/// What depends on the whole run is computed once, when first asked for.
pub(crate) struct Framer<'a> {
    scene: &'a Scene,
    view: View,
    trail: usize,
    world: OnceLock<(DVec3, DVec3)>,
    run_window: OnceLock<Rect>,
    follow_size: OnceLock<DVec2>,
}

impl<'a> Framer<'a> {
    pub(crate) fn new(scene: &'a Scene, view: View, trail: usize) -> Self {
        Self {
            scene,
            view,
            trail,
            world: OnceLock::new(),
            run_window: OnceLock::new(),
            follow_size: OnceLock::new(),
        }
    }

    /// The scene.
    pub(crate) fn scene(&self) -> &'a Scene {
        self.scene
    }

    /// The view of 3D scenes.
    pub(crate) fn view(&self) -> View {
        self.view
    }

    /// The page coordinates of a point of the scene.
    pub(crate) fn project(&self, p: DVec3) -> DVec2 {
        project_point(self.view, self.scene.dim, p)
    }

    /// The page components of a vector of the scene (the projection is linear).
    pub(crate) fn project_vector(&self, v: DVec3) -> DVec2 {
        project_point(self.view, self.scene.dim, v)
    }

    /// The window of `frame` (before the aspect correction).
    pub(crate) fn window(&self, framing: Framing, frame: usize) -> Rect {
        let window = match framing {
            Framing::Flock => self.padded(self.flock_bounds(frame)),
            Framing::Follow => {
                let size = *self.follow_size.get_or_init(|| {
                    (0..self.scene.frames.len())
                        .map(|k| self.padded(self.flock_bounds(k)).size())
                        .fold(DVec2::ZERO, DVec2::max)
                });
                Rect::centred(self.padded(self.flock_bounds(frame)).centre(), size)
            }
            Framing::Run => self.run_window(),
            Framing::Fixed { min, max } => Rect { min, max },
        };
        window.non_degenerate()
    }

    /// The window that holds the whole run and every bounded obstacle.
    pub(crate) fn run_window(&self) -> Rect {
        *self.run_window.get_or_init(|| self.compute_run_window())
    }

    fn compute_run_window(&self) -> Rect {
        let agents = (0..self.scene.frames.len())
            .map(|k| self.points_bounds(k, 0))
            .fold(Rect::EMPTY, Rect::union);
        let obstacles = self
            .scene
            .obstacles
            .iter()
            // Bounded obstacles do not use the box walls are cut to.
            .filter(|o| o.bounds().is_some())
            .filter_map(|o| o.project(self.view, self.scene.dim, (DVec3::ZERO, DVec3::ZERO)))
            .map(|s: Shape| s.bounds())
            .fold(Rect::EMPTY, Rect::union);
        self.padded(agents).union(obstacles).non_degenerate()
    }

    /// The box of space that holds every agent of the run, every bounded obstacle and the given
    /// point of every wall, padded: walls are drawn as their part inside it.
    pub(crate) fn world(&self) -> (DVec3, DVec3) {
        *self.world.get_or_init(|| self.compute_world())
    }

    fn compute_world(&self) -> (DVec3, DVec3) {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for frame in &self.scene.frames {
            for &q in frame.positions.iter().chain(frame.gamma.iter()) {
                if q.is_finite() {
                    lo = lo.min(q);
                    hi = hi.max(q);
                }
            }
        }
        for obstacle in &self.scene.obstacles {
            // A wall's point puts its boundary inside the box, however far from the flock.
            let (a, b) = match obstacle {
                Drawable::HalfPlane { point, .. } => (*point, *point),
                other => match other.bounds() {
                    Some(bounds) => bounds,
                    None => continue,
                },
            };
            if a.is_finite() && b.is_finite() {
                lo = lo.min(a);
                hi = hi.max(b);
            }
        }
        if lo.x > hi.x {
            (lo, hi) = (DVec3::splat(-1.0), DVec3::splat(1.0));
        }
        let pad = self.pad((hi - lo).truncate().max_element());
        let mut pad3 = DVec3::splat(pad);
        if self.scene.dim == 2 {
            pad3.z = 0.0;
        }
        (lo - pad3, hi + pad3)
    }

    /// The box of space walls are cut to in a panel showing `window`: [`Framer::world`], and in
    /// 2D the window itself, so that a wall fills the panel up to its boundary line.
    pub(crate) fn world_for(&self, window: Rect) -> (DVec3, DVec3) {
        let (lo, hi) = self.world();
        if self.scene.dim == 2 {
            (
                lo.min(window.min.extend(0.0)),
                hi.max(window.max.extend(0.0)),
            )
        } else {
            (lo, hi)
        }
    }

    /// The bounds of the agents, γ-agent and trails drawn for `frame`.
    fn flock_bounds(&self, frame: usize) -> Rect {
        self.points_bounds(frame, self.trail)
    }

    /// The bounds of the agents and γ-agent of frames `frame − trail ..= frame`.
    fn points_bounds(&self, frame: usize, trail: usize) -> Rect {
        let mut r = Rect::EMPTY;
        for f in &self.scene.frames[frame.saturating_sub(trail)..=frame] {
            for &q in f.positions.iter().chain(f.gamma.iter()) {
                r = r.with_point(self.project(q));
            }
        }
        r
    }

    /// A rectangle with the margin of [`Framer::pad`].
    fn padded(&self, r: Rect) -> Rect {
        if r.is_empty() {
            return r;
        }
        r.padded(self.pad(r.size().max_element()))
    }

    /// The margin around a flock of extent `extent`: half the range (so that markers and edges at
    /// the border are whole), at least 4 % of the extent.
    fn pad(&self, extent: f64) -> f64 {
        let range = if self.scene.range.is_finite() {
            self.scene.range
        } else {
            0.0
        };
        (0.5 * range).max(0.04 * extent).max(1e-9)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::frames::Frame;

    /// Two agents 10 apart in frame 0, 20 apart in frame 1, moving right by 100.
    fn spreading() -> Scene {
        let frame = |t: f64, gap: f64| {
            Frame::new(
                t,
                vec![
                    DVec3::new(100.0 * t, 0.0, 0.0),
                    DVec3::new(100.0 * t + gap, 0.0, 0.0),
                ],
                vec![DVec3::X; 2],
            )
        };
        Scene::new(2, 2.0)
            .with_frame(frame(0.0, 10.0))
            .with_frame(frame(1.0, 20.0))
    }

    #[test]
    fn flock_framing_zooms_on_each_frame() {
        let scene = spreading();
        let framer = Framer::new(&scene, View::default(), 0);
        let w0 = framer.window(Framing::Flock, 0);
        let w1 = framer.window(Framing::Flock, 1);
        // Margin: half the range (1) beats 4 % of the extent (0.4, 0.8).
        assert_eq!((w0.min.x, w0.max.x), (-1.0, 11.0));
        assert_eq!((w1.min.x, w1.max.x), (99.0, 121.0));
    }

    #[test]
    fn follow_framing_keeps_the_largest_size_and_run_framing_holds_everything() {
        let scene = spreading();
        let framer = Framer::new(&scene, View::default(), 0);
        let f0 = framer.window(Framing::Follow, 0);
        let f1 = framer.window(Framing::Follow, 1);
        assert_eq!(f0.size(), f1.size());
        assert_eq!(f0.centre().x, 5.0);
        let run = framer.window(Framing::Run, 0);
        assert_eq!(run, framer.window(Framing::Run, 1));
        assert!(run.min.x <= 0.0 && run.max.x >= 120.0);
        let fixed = Framing::Fixed {
            min: DVec2::new(-5.0, -5.0),
            max: DVec2::new(5.0, 5.0),
        };
        assert_eq!(framer.window(fixed, 1).size(), DVec2::splat(10.0));
    }

    #[test]
    fn trails_widen_the_flock_window() {
        let scene = spreading();
        let with_trail = Framer::new(&scene, View::default(), 1).window(Framing::Flock, 1);
        assert!(with_trail.min.x < 0.0);
    }
}

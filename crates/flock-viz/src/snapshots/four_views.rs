//! [`views_svg`], [`views_png`]: one frame of a 3D run in four orthographic views, as a drawing
//! office draws a solid: the oblique view of the snapshots, the top view (x–y), the front view
//! (x–z) and the side view (y–z), each depth-cued (near marks dark, far ones faded), so that a 3D
//! α-lattice (TAC 2006 Fig. 13) reads as the net of near-equilateral triangles it is rather than
//! as one tangle of crossing edges.

use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};

use crate::draw::format;
use crate::draw::render::{self, Figure};
use crate::error::VizError;
use crate::scene::frames::Scene;
use crate::scene::framing::Framer;
use crate::scene::projection::View;
use crate::snapshots::snapshot::{SnapshotOptions, below_title, draw_panel, grid_size};

/// The views of [`views_svg`] beside `oblique`: the top, front and side views.
#[must_use]
pub fn four_views(oblique: View) -> [View; 4] {
    [oblique, View::TOP, View::FRONT, View::SIDE]
}

/// An SVG figure of frame `frame` of a 3D scene in the four views of [`four_views`] of
/// `options.style.view`, two panels a row, each titled by its view; drawn as the snapshots are
/// (`options`' panel size and style; its `columns` and `view` aside).
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn, is not 3D, or has no frame `frame`.
///
/// # Example
/// ```
/// use flock_viz::{Frame, Scene, SnapshotOptions, views_svg};
/// use glam::DVec3;
///
/// let q = [DVec3::ZERO, DVec3::new(7.0, 0.0, 0.0), DVec3::new(3.5, 6.06, 0.0), DVec3::new(3.5, 2.02, 5.72)];
/// let scene = Scene::new(3, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec3::ONE; 4]));
/// let svg = views_svg(&scene, 0, &SnapshotOptions::default()).unwrap();
/// for title in ["top view", "front view", "side view", "view az -60°, el 30°"] {
///     assert!(svg.contains(title));
/// }
/// assert_eq!(svg.matches("<polygon").count(), 16); // a tetrahedron's 4 agents in 4 panels
/// ```
pub fn views_svg(
    scene: &Scene,
    frame: usize,
    options: &SnapshotOptions,
) -> Result<String, VizError> {
    render::svg(&Views::new(scene, frame, options)?)
}

/// The figure of [`views_svg`] as a PNG image.
///
/// # Errors
/// As [`views_svg`]; [`VizError::Encode`] if PNG encoding fails.
pub fn views_png(
    scene: &Scene,
    frame: usize,
    options: &SnapshotOptions,
) -> Result<Vec<u8>, VizError> {
    render::png(&Views::new(scene, frame, options)?)
}

/// The four-view figure, checked and ready to draw.
struct Views<'a> {
    scene: &'a Scene,
    frame: usize,
    options: &'a SnapshotOptions,
}

impl<'a> Views<'a> {
    fn new(scene: &'a Scene, frame: usize, options: &'a SnapshotOptions) -> Result<Self, VizError> {
        scene.validate()?;
        if scene.dim != 3 {
            return Err(VizError::invalid(format!(
                "four views are drawn of a 3D run; this one is {}D",
                scene.dim
            )));
        }
        if frame >= scene.frames.len() {
            return Err(VizError::invalid(format!(
                "frame {frame} chosen, but the scene has {} frames",
                scene.frames.len()
            )));
        }
        Ok(Self {
            scene,
            frame,
            options,
        })
    }

    fn title(&self) -> String {
        let t = format!(
            "t = {} s",
            format::number(self.scene.frames[self.frame].t, 2)
        );
        if self.scene.title.is_empty() {
            t
        } else {
            format!("{} at {t}", self.scene.title)
        }
    }
}

impl Figure for Views<'_> {
    fn size(&self) -> (u32, u32) {
        grid_size(self.options.panel_size, 2, 2, &self.title())
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body: DrawingArea<DB, Shift> = below_title(root, &self.title())?;
        let style = &self.options.style;
        for (panel, view) in body.split_evenly((2, 2)).iter().zip(four_views(style.view)) {
            let framer = Framer::new(self.scene, view, style.trail);
            draw_panel(panel, &framer, self.frame, style, &view.describe())?;
        }
        Ok(())
    }
}

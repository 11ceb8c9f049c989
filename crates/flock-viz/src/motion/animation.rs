//! The whole run as an animated GIF: each recorded frame (subsampled to a bounded count) drawn as a
//! snapshot panel (TAC 2006 Figs. 10–13 in motion), rasterised with plotters' bitmap backend and
//! encoded with the `gif` crate (NeuQuant palette per frame, looping forever).
//!
//! - [`animation_gif`]: the GIF's bytes.
//! - [`AnimationOptions`]: size, frame budget, delay, view, framing, trails, edges.

use gif::{Encoder, Frame as GifFrame, Repeat};
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};
use rayon::prelude::*;

use crate::draw::palette::Palette;
use crate::draw::render::{self, Figure, TextMode};
use crate::error::VizError;
use crate::scene::frames::Scene;
use crate::scene::framing::Framer;
use crate::snapshots::snapshot::{PanelStyle, below_title, draw_panel, figure_title, time_title};

/// How the animation is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct AnimationOptions {
    /// The image size in pixels (width, height), at most 65535 each.
    pub size: (u32, u32),
    /// At most this many frames: a longer run is subsampled evenly, first and last frames kept.
    pub max_frames: usize,
    /// The time each frame is shown, in milliseconds (GIF counts in hundredths of a second).
    pub frame_delay_ms: u32,
    /// What each frame draws and how (by default the whole run's window, which stays still).
    pub style: PanelStyle,
}

impl Default for AnimationOptions {
    fn default() -> Self {
        Self {
            size: (640, 640),
            max_frames: 120,
            frame_delay_ms: 80,
            style: PanelStyle::default(),
        }
    }
}

/// How many frames, spread over the animation, its palette is learned from.
const PALETTE_SAMPLES: usize = 8;

/// The frames of `scene` an animation with `options` shows (indices into `scene.frames`).
#[must_use]
pub fn animation_frames(scene: &Scene, options: &AnimationOptions) -> Vec<usize> {
    scene.evenly_spaced_frames(options.max_frames.max(1).min(scene.frames.len()))
}

/// The run as an animated GIF (see the module documentation); [`animation_frames`] tells which
/// frames it shows.
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn or the size is out of bounds;
/// [`VizError::Encode`] if GIF encoding fails.
pub fn animation_gif(scene: &Scene, options: &AnimationOptions) -> Result<Vec<u8>, VizError> {
    scene.validate()?;
    let (w, h) = options.size;
    let (Ok(w16), Ok(h16)) = (u16::try_from(w), u16::try_from(h)) else {
        return Err(VizError::invalid(format!(
            "a GIF of {w} × {h} pixels: each side must be at most 65535"
        )));
    };
    let frames = animation_frames(scene, options);
    let panel = &options.style;
    let framer = Framer::new(scene, panel.view, panel.trail);
    let title = figure_title(scene, panel.view);
    let delay = u16::try_from(options.frame_delay_ms.div_ceil(10)).unwrap_or(u16::MAX);
    let figure = |frame: usize| AnimationFrame {
        framer: &framer,
        frame,
        panel,
        title: &title,
        size: options.size,
    };
    // the palette of a few frames spread over the run: the first, the last and six between
    let samples: Vec<usize> = (0..PALETTE_SAMPLES.min(frames.len()))
        .map(|k| frames[k * (frames.len() - 1) / (PALETTE_SAMPLES - 1).max(1)])
        .collect();
    let samples = samples
        .par_iter()
        .map(|&frame| render::rgb(&figure(frame)))
        .collect::<Result<Vec<_>, _>>()?;
    let palette = Palette::learn(&samples);
    let encoded = frames
        .par_iter()
        .enumerate()
        .map(|(k, &frame)| {
            let rgb = render::rgb(&figure(frame))?;
            let mut gif_frame =
                GifFrame::from_indexed_pixels(w16, h16, palette.indices(&rgb), None);
            // Hold the last frame a little longer before the loop starts again.
            gif_frame.delay = if k + 1 == frames.len() {
                delay.saturating_mul(10)
            } else {
                delay
            };
            gif_frame.make_lzw_pre_encoded();
            Ok(gif_frame)
        })
        .collect::<Result<Vec<_>, VizError>>()?;
    let mut out = Vec::new();
    {
        let mut encoder =
            Encoder::new(&mut out, w16, h16, &palette.table()).map_err(VizError::encode)?;
        encoder
            .set_repeat(Repeat::Infinite)
            .map_err(VizError::encode)?;
        for gif_frame in &encoded {
            encoder
                .write_lzw_pre_encoded_frame(gif_frame)
                .map_err(VizError::encode)?;
        }
    }
    Ok(out)
}

/// One frame of the animation, and of [`snapshot_rgb`](crate::snapshot_rgb): the title band and
/// one snapshot panel, on an image of `size` pixels.
pub(crate) struct AnimationFrame<'a> {
    /// The scene's framer.
    pub(crate) framer: &'a Framer<'a>,
    /// The frame drawn (an index into the scene's frames).
    pub(crate) frame: usize,
    /// What the panel draws and how.
    pub(crate) panel: &'a PanelStyle,
    /// The figure's title ([`figure_title`]), in a band above the panel unless empty.
    pub(crate) title: &'a str,
    /// The image size in pixels (width, height).
    pub(crate) size: (u32, u32),
}

impl Figure for AnimationFrame<'_> {
    fn size(&self) -> (u32, u32) {
        self.size
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        text: TextMode,
    ) -> Result<(), VizError> {
        let body = below_title(root, self.title, text)?;
        draw_panel(
            &body,
            self.framer,
            self.frame,
            self.panel,
            &time_title(self.framer.scene(), self.frame),
        )
    }
}

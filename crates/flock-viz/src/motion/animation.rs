//! The whole run as an animated GIF: each recorded frame (subsampled to a bounded count) drawn as a
//! snapshot panel (TAC 2006 Figs. 10–13 in motion), rasterised with plotters' bitmap backend and
//! encoded with the `gif` crate: one palette for the whole animation, each frame after the first
//! only the rectangle that changed since the one before, drawn over it, looping forever.
//!
//! - [`animation_gif`]: the GIF's bytes.
//! - [`AnimationOptions`]: size, frame budget, delay, view, framing, trails, edges.

use gif::{Encoder, Frame as GifFrame, Repeat};
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};
use rayon::prelude::*;

use crate::draw::palette::Palette;
use crate::draw::render::{self, Figure};
use crate::draw::style::BACKGROUND;
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

/// How many frames are drawn and compressed at a time (in parallel).
const CHUNK: usize = 16;

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
    let palette = Palette::learn(&samples, BACKGROUND);
    let last = frames.len() - 1;
    // Drawn, given their palette indices and compressed in parallel, CHUNK frames at a time (the
    // memory of CHUNK images); each frame is the rectangle that changed since the one before.
    let mut encoded = Vec::with_capacity(frames.len());
    let mut previous: Option<Vec<u8>> = None;
    for (c, chunk) in frames.chunks(CHUNK).enumerate() {
        let drawn = chunk
            .par_iter()
            .map(|&frame| render::rgb(&figure(frame)))
            .collect::<Result<Vec<_>, VizError>>()?;
        encoded.par_extend(drawn.par_iter().enumerate().map(|(i, rgb)| {
            let before = if i == 0 {
                previous.as_deref()
            } else {
                Some(&drawn[i - 1][..])
            };
            let changed = Changed::between(before, rgb, options.size);
            let mut gif_frame = GifFrame::from_indexed_pixels(
                changed.width,
                changed.height,
                palette.indices(&changed.crop(rgb, w)),
                None,
            );
            (gif_frame.left, gif_frame.top) = (changed.left, changed.top);
            // Hold the last frame a little longer before the loop starts again.
            gif_frame.delay = if c * CHUNK + i == last {
                delay.saturating_mul(10)
            } else {
                delay
            };
            gif_frame.make_lzw_pre_encoded();
            gif_frame
        }));
        previous = drawn.into_iter().last();
    }
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

/// The rectangle of an image, in pixels, that a GIF frame replaces (drawn over the frame before:
/// disposal "keep").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Changed {
    left: u16,
    top: u16,
    width: u16,
    height: u16,
}

impl Changed {
    /// The smallest rectangle holding every pixel of `after` that differs from `before` (RGB,
    /// rows top to bottom, `size` pixels of at most 65535 a side): one pixel when none does, the
    /// whole image when there is nothing before.
    fn between(before: Option<&[u8]>, after: &[u8], (w, h): (u32, u32)) -> Self {
        // within a GIF's 65535 pixels a side
        let side = |v: usize| v as u16;
        let (w, h) = (w as usize, h as usize);
        let whole = Self {
            left: 0,
            top: 0,
            width: side(w),
            height: side(h),
        };
        let Some(before) = before else {
            return whole;
        };
        let row = 3 * w;
        // the first and last pixels of row y that changed
        let span = |y: usize| {
            let (old, new) = (
                &before[row * y..row * (y + 1)],
                &after[row * y..row * (y + 1)],
            );
            if old == new {
                return None;
            }
            let first = old.iter().zip(new).position(|(a, b)| a != b)?;
            let last = row
                - 1
                - old
                    .iter()
                    .rev()
                    .zip(new.iter().rev())
                    .position(|(a, b)| a != b)?;
            Some((first / 3, last / 3))
        };
        let spans: Vec<(usize, (usize, usize))> =
            (0..h).filter_map(|y| Some((y, span(y)?))).collect();
        let (Some(&(top, _)), Some(&(bottom, _))) = (spans.first(), spans.last()) else {
            return Self {
                width: 1,
                height: 1,
                ..whole
            };
        };
        let left = spans.iter().map(|(_, (a, _))| *a).min().unwrap_or(0);
        let right = spans.iter().map(|(_, (_, b))| *b).max().unwrap_or(left);
        Self {
            left: side(left),
            top: side(top),
            width: side(right + 1 - left),
            height: side(bottom + 1 - top),
        }
    }

    /// The rectangle's pixels of `rgb`, an image `width` pixels wide, rows top to bottom.
    fn crop(self, rgb: &[u8], width: u32) -> Vec<u8> {
        let (left, top) = (usize::from(self.left), usize::from(self.top));
        let (row, span) = (3 * width as usize, 3 * usize::from(self.width));
        let mut out = Vec::with_capacity(span * usize::from(self.height));
        for y in top..top + usize::from(self.height) {
            let start = row * y + 3 * left;
            out.extend_from_slice(&rgb[start..start + span]);
        }
        out
    }
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

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body = below_title(root, self.title)?;
        draw_panel(
            &body,
            self.framer,
            self.frame,
            self.panel,
            &time_title(self.framer.scene(), self.frame),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_changed_rectangle_holds_every_changed_pixel_and_no_more() {
        let (w, h) = (5u32, 4u32);
        let before = vec![7u8; 3 * 5 * 4];
        let mut after = before.clone();
        // pixels (1, 2) and (3, 1) change one channel each
        after[3 * (2 * 5 + 1)] = 8;
        after[3 * (5 + 3) + 2] = 9;
        let changed = Changed::between(Some(&before), &after, (w, h));
        let rectangle = Changed {
            left: 1,
            top: 1,
            width: 3,
            height: 2,
        };
        assert_eq!(changed, rectangle);
        assert_eq!(
            changed.crop(&after, w),
            [&after[3 * 6..3 * 9], &after[3 * 11..3 * 14]].concat()
        );
        let whole = Changed {
            left: 0,
            top: 0,
            width: 5,
            height: 4,
        };
        assert_eq!(Changed::between(None, &after, (w, h)), whole);
        let one = Changed {
            width: 1,
            height: 1,
            ..whole
        };
        assert_eq!(Changed::between(Some(&after), &after, (w, h)), one);
    }
}

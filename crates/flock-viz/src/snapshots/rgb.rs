//! One frame of a run as an RGB pixel buffer in memory, drawn as a snapshot panel (TAC 2006
//! Figs. 10–13: agents, the edges of the proximity net, obstacles, the γ-agent) under the figure's
//! title band: the `render_mode="rgb_array"` image of the Python environments, and the frame of
//! [`animation_gif`](crate::animation_gif) before its palette.

use crate::draw::render;
use crate::error::VizError;
use crate::motion::animation::AnimationFrame;
use crate::scene::frames::Scene;
use crate::scene::framing::Framer;
use crate::snapshots::snapshot::{PanelStyle, check_frames, figure_title};

/// Frame `frame` of `scene` drawn with `style` on an image of `width` × `height` pixels, as
/// `height · width · 3` bytes: rows top to bottom, each pixel's red, green and blue. It is the
/// image of [`snapshot_png`](crate::snapshot_png) for the same frame and style whose single
/// panel leaves room for the title band, bit for bit.
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn (no frames, a dimension other than 2 or
/// 3), `frame` is out of range, or a side is outside 16–16384 pixels.
///
/// # Example
/// ```
/// use flock_viz::{Frame, PanelStyle, Scene, snapshot_rgb};
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)];
/// let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]));
/// let pixels = snapshot_rgb(&scene, 0, &PanelStyle::default(), 640, 480).unwrap();
/// assert_eq!(pixels.len(), 480 * 640 * 3);
/// ```
pub fn snapshot_rgb(
    scene: &Scene,
    frame: usize,
    style: &PanelStyle,
    width: u32,
    height: u32,
) -> Result<Vec<u8>, VizError> {
    check_frames(scene, &[frame])?;
    let framer = Framer::new(scene, style.view, style.trail);
    render::rgb(&AnimationFrame {
        framer: &framer,
        frame,
        panel: style,
        title: &figure_title(scene, style.view),
        size: (width, height),
    })
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use super::*;
    use crate::draw::style::{AGENT, BACKGROUND};
    use crate::scene::drawable::Drawable;
    use crate::scene::frames::Frame;
    use crate::scene::framing::Framing;
    use crate::snapshots::snapshot::{SnapshotOptions, grid_size, snapshot_png};

    const W: u32 = 640;
    const H: u32 = 480;

    /// The pixels of a buffer, in row-major order.
    fn pixels(buffer: &[u8]) -> impl Iterator<Item = [u8; 3]> + '_ {
        buffer.chunks_exact(3).map(|p| [p[0], p[1], p[2]])
    }

    /// The mean (column, row) of the pixels of colour `colour`, and how many there are.
    fn centroid(buffer: &[u8], colour: [u8; 3]) -> (DVec2, usize) {
        let (sum, count) = pixels(buffer)
            .enumerate()
            .filter(|&(_, p)| p == colour)
            .fold((DVec2::ZERO, 0), |(sum, count), (k, _)| {
                let (col, row) = (k % W as usize, k / W as usize);
                (sum + DVec2::new(col as f64, row as f64), count + 1)
            });
        (sum / count.max(1) as f64, count)
    }

    /// One agent at `q` heading along +x, in a fixed window [−10, 10]², so that its pixels move
    /// with it alone.
    fn lone_agent(q: DVec2) -> (Scene, PanelStyle) {
        let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &[q], &[DVec2::X]));
        let style = PanelStyle {
            framing: Framing::Fixed {
                min: DVec2::splat(-10.0),
                max: DVec2::splat(10.0),
            },
            ..PanelStyle::default()
        };
        (scene, style)
    }

    #[test]
    fn the_buffer_is_the_snapshot_png_of_the_same_frame_bit_for_bit() {
        let q = [
            DVec2::new(0.0, 0.0),
            DVec2::new(7.0, 0.0),
            DVec2::new(3.0, 6.0),
        ];
        let p = [DVec2::X, DVec2::Y, DVec2::new(1.0, 1.0)];
        let scene = Scene::new(2, 8.4)
            .with_title("three agents")
            .with_frame(Frame::from_vectors(0.0, &q, &p))
            .with_frame(Frame::from_vectors(1.0, &q.map(|q| q + DVec2::X), &p))
            .with_obstacle(Drawable::ball(DVec2::new(4.0, -4.0), 1.5))
            .with_gamma(|t| DVec3::new(10.0 + t, 2.0, 0.0));
        // the snapshot's one panel under the title band: the whole figure W × H
        let band = grid_size((W, 0), 1, 1, &scene.title).1;
        assert!(band > 0);
        let options = SnapshotOptions {
            panel_size: (W, H - band),
            columns: 1,
            ..SnapshotOptions::default()
        };
        for frame in [0, 1] {
            let rgb = snapshot_rgb(&scene, frame, &options.style, W, H).unwrap();
            assert_eq!(rgb.len(), (H * W * 3) as usize);
            assert!(pixels(&rgb).any(|p| p != BACKGROUND));
            assert_eq!(
                render::encode_png(&rgb, W, H).unwrap(),
                snapshot_png(&scene, &[frame], &options).unwrap(),
                "frame {frame}"
            );
        }
    }

    #[test]
    fn an_agent_is_drawn_where_it_stands() {
        let (scene, style) = lone_agent(DVec2::new(-5.0, 0.0));
        let left = snapshot_rgb(&scene, 0, &style, W, H).unwrap();
        let (scene, style) = lone_agent(DVec2::new(5.0, 0.0));
        let right = snapshot_rgb(&scene, 0, &style, W, H).unwrap();
        let ((a, n), (b, m)) = (centroid(&left, AGENT), centroid(&right, AGENT));
        // a triangle of the default 9-pixel marker: some pixels, fewer than its bounding box
        assert!((10..=81).contains(&n) && n == m, "{n} and {m} agent pixels");
        // 10 units, on the same row: half the plotting area's height, the window's 20 units
        // (equal scales, the window widened along x), so at most half its width (640 − 86
        // pixels of margins and label area) and more than a third of the image's height
        let shift = b - a;
        assert!((160.0..=277.0).contains(&shift.x), "{shift}");
        assert!(shift.y.abs() < 0.5, "{shift}");
        for (k, p) in pixels(&left).enumerate() {
            let at = DVec2::new((k % W as usize) as f64, (k / W as usize) as f64);
            if (at - a).length() < 2.0 {
                assert_ne!(p, BACKGROUND, "pixel {at} at the agent");
            }
        }
    }

    #[test]
    fn a_3d_frame_fills_the_requested_size_under_its_view_title() {
        let q = [
            DVec3::ZERO,
            DVec3::new(5.0, 2.0, 3.0),
            DVec3::new(-3.0, 4.0, 6.0),
        ];
        let scene = Scene::new(3, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec3::X; 3]));
        let rgb = snapshot_rgb(&scene, 0, &PanelStyle::default(), W, H).unwrap();
        assert_eq!(rgb.len(), (H * W * 3) as usize);
        // the nearest agent in its own colour, the others depth-faded
        assert!(pixels(&rgb).any(|p| p == AGENT));
        let other = snapshot_rgb(&scene, 0, &PanelStyle::default(), 320, 200).unwrap();
        assert_eq!(other.len(), 200 * 320 * 3);
    }

    #[test]
    fn a_missing_frame_or_a_tiny_image_is_refused() {
        let (scene, style) = lone_agent(DVec2::ZERO);
        let error = snapshot_rgb(&scene, 1, &style, W, H).unwrap_err();
        assert_eq!(
            error.to_string(),
            VizError::invalid("frame 1 chosen, but the scene has 1 frames").to_string()
        );
        let error = snapshot_rgb(&scene, 0, &style, 8, H).unwrap_err();
        assert!(error.to_string().contains("8 × 480 pixels"), "{error}");
    }
}

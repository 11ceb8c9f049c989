//! The animated GIF of a run.

use flock_viz::{AnimationOptions, animation_frames, animation_gif, snapshot_rgb};

use crate::support::{FRAMES, cube_scene, lattice_scene};

/// A frame of a decoded GIF: its RGBA pixels, the whole image as shown once it is drawn over
/// the frames before, and its delay in hundredths of a second.
type DecodedFrame = (Vec<u8>, u16);

/// A decoded GIF: its size, its frames as shown, and each frame's rectangle (left, top, width,
/// height).
type Decoded = ((u16, u16), Vec<DecodedFrame>, Vec<(u16, u16, u16, u16)>);

/// Decodes a GIF, drawing each frame's rectangle over the image before (disposal "keep", the
/// only one the animation uses).
fn decode_with_rectangles(bytes: &[u8]) -> Decoded {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(bytes).unwrap();
    let size = (decoder.width(), decoder.height());
    let width = usize::from(size.0);
    let mut canvas = vec![0u8; 4 * width * usize::from(size.1)];
    let (mut frames, mut rectangles) = (Vec::new(), Vec::new());
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(frame.dispose, gif::DisposalMethod::Keep);
        let (left, top) = (usize::from(frame.left), usize::from(frame.top));
        let span = 4 * usize::from(frame.width);
        for (y, row) in frame.buffer.chunks_exact(span).enumerate() {
            let start = 4 * ((top + y) * width + left);
            canvas[start..start + span].copy_from_slice(row);
        }
        frames.push((canvas.clone(), frame.delay));
        rectangles.push((frame.left, frame.top, frame.width, frame.height));
    }
    (size, frames, rectangles)
}

/// Decodes a GIF: its size and its frames as shown.
fn decode(bytes: &[u8]) -> ((u16, u16), Vec<DecodedFrame>) {
    let (size, frames, _) = decode_with_rectangles(bytes);
    (size, frames)
}

fn small() -> AnimationOptions {
    AnimationOptions {
        size: (200, 180),
        ..AnimationOptions::default()
    }
}

#[test]
fn one_gif_frame_per_recorded_frame() {
    let gif = animation_gif(&lattice_scene(), &small()).unwrap();
    assert_eq!(&gif[..6], b"GIF89a");
    let (size, frames) = decode(&gif);
    assert_eq!(size, (200, 180));
    assert_eq!(frames.len(), FRAMES);
    assert_eq!(frames[0].1, 8, "80 ms");
    assert_eq!(frames[FRAMES - 1].1, 80, "the last frame is held");
    // The flock moves: consecutive frames differ; none is a single colour.
    for pair in frames.windows(2) {
        assert_ne!(pair[0].0, pair[1].0);
    }
    for (rgba, _) in &frames {
        assert!(rgba.chunks(4).any(|p| p != &rgba[..4]));
    }
}

#[test]
fn long_runs_are_subsampled() {
    let options = AnimationOptions {
        max_frames: 3,
        ..small()
    };
    let scene = lattice_scene();
    assert_eq!(animation_frames(&scene, &options), [0, 2, 4]);
    let (_, frames) = decode(&animation_gif(&scene, &options).unwrap());
    assert_eq!(frames.len(), 3);
}

#[test]
fn three_d_runs_animate_too() {
    let (_, frames) = decode(&animation_gif(&cube_scene(), &small()).unwrap());
    assert_eq!(frames.len(), 3);
}

#[test]
fn oversized_gifs_are_refused() {
    let options = AnimationOptions {
        size: (70_000, 100),
        ..AnimationOptions::default()
    };
    assert!(animation_gif(&lattice_scene(), &options).is_err());
}

/// One palette for the whole animation ([`animation_gif`]'s): every decoded frame is its drawn
/// frame ([`snapshot_rgb`]) within a few levels per channel on average, the background exact.
#[test]
fn each_frame_is_its_drawing_in_the_shared_palette() {
    let scene = lattice_scene();
    let options = small();
    let (_, frames) = decode(&animation_gif(&scene, &options).unwrap());
    for (k, (rgba, _)) in frames.iter().enumerate() {
        let drawn = snapshot_rgb(&scene, k, &options.style, 200, 180).unwrap();
        let error: u64 = rgba
            .chunks_exact(4)
            .zip(drawn.chunks_exact(3))
            .map(|(a, b)| (0..3).map(|c| u64::from(a[c].abs_diff(b[c]))).sum::<u64>())
            .sum();
        let mean = error as f64 / (3 * 200 * 180) as f64;
        assert!(mean < 2.0, "frame {k}: mean error {mean} levels");
        assert_eq!(&rgba[..3], &drawn[..3], "the background");
    }
}

/// The frames are drawn and compressed in parallel: the same bytes on one thread as on four.
#[test]
fn the_gif_is_the_same_on_any_number_of_threads() {
    let scene = lattice_scene();
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| animation_gif(&scene, &small()).unwrap())
    };
    assert_eq!(on(1), on(4));
}

/// Each frame after the first is only the rectangle that changed, and the picture shown is every
/// drawn frame ([`snapshot_rgb`]) exactly, each pixel in its nearest colour of the GIF's palette
/// (squared RGB distance, the first of equals).
#[test]
fn each_frame_is_the_changed_rectangle_and_shows_the_whole_drawing() {
    let scene = lattice_scene();
    let options = small();
    let gif = animation_gif(&scene, &options).unwrap();
    let palette: Vec<[u8; 3]> = {
        let decoder = gif::DecodeOptions::new().read_info(&gif[..]).unwrap();
        decoder
            .global_palette()
            .unwrap()
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect()
    };
    let nearest = |p: &[u8]| {
        let distance =
            |c: &[u8; 3]| -> u32 { (0..3).map(|k| u32::from(c[k].abs_diff(p[k])).pow(2)).sum() };
        *palette
            .iter()
            .enumerate()
            .min_by_key(|&(k, c)| (distance(c), k))
            .unwrap()
            .1
    };
    let (_, frames, rectangles) = decode_with_rectangles(&gif);
    assert_eq!(rectangles[0], (0, 0, 200, 180), "the first frame is whole");
    assert!(
        rectangles[1..].iter().all(|r| *r != (0, 0, 200, 180)),
        "every later frame is a part of the image: {rectangles:?}"
    );
    for (k, (rgba, _)) in frames.iter().enumerate() {
        let drawn = snapshot_rgb(&scene, k, &options.style, 200, 180).unwrap();
        for (pixel, (shown, drawn)) in rgba.chunks_exact(4).zip(drawn.chunks_exact(3)).enumerate() {
            assert_eq!(shown[..3], nearest(drawn), "frame {k}, pixel {pixel}");
        }
    }
}

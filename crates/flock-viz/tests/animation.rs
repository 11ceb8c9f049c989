//! The animated GIF of a run.

use flock_viz::{AnimationOptions, animation_frames, animation_gif, snapshot_rgb};

use crate::support::{FRAMES, cube_scene, lattice_scene};

/// A frame of a decoded GIF: its RGBA pixels and its delay in hundredths of a second.
type DecodedFrame = (Vec<u8>, u16);

/// Decodes a GIF: its size and its frames.
fn decode(bytes: &[u8]) -> ((u16, u16), Vec<DecodedFrame>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(bytes).unwrap();
    let size = (decoder.width(), decoder.height());
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        frames.push((frame.buffer.to_vec(), frame.delay));
    }
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

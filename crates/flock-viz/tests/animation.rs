//! The animated GIF of a run.

use flock_viz::{AnimationOptions, animation_frames, animation_gif};

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

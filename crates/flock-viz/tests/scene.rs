//! Scenes: edges of the proximity net, frame choice, validation.

use flock_viz::{Frame, Scene, SnapshotOptions, lift, snapshot_svg};
use glam::{DVec2, DVec3};

use crate::support::{FRAMES, lattice_scene};

#[test]
fn edges_are_the_pairs_closer_than_the_range() {
    let scene = lattice_scene();
    let edges = scene.edges(0);
    assert!(edges.iter().all(|&(i, j)| i < j));
    assert!(edges.contains(&(0, 1)) && edges.contains(&(0, 4)));
    assert!(
        !edges.contains(&(0, 5)),
        "the diagonal 7√2 ≈ 9.9 is not < 8.4"
    );
    // The predicate is strict: agents exactly r apart are not neighbours.
    let pair = Scene::new(2, 7.0).with_frame(Frame::from_vectors(
        0.0,
        &[DVec2::ZERO, DVec2::new(7.0, 0.0)],
        &[DVec2::ZERO; 2],
    ));
    assert!(pair.edges(0).is_empty());
}

#[test]
fn snapshot_times_are_spread_over_the_run() {
    let scene = lattice_scene();
    assert_eq!(scene.evenly_spaced_frames(3), [0, 2, 4]);
    assert_eq!(scene.evenly_spaced_frames(1), [FRAMES - 1]);
    assert_eq!(scene.evenly_spaced_frames(10), [0, 1, 2, 3, 4]);
    assert!(scene.evenly_spaced_frames(0).is_empty());
    assert_eq!(scene.frame_nearest(2.4), Some(2));
    assert_eq!(
        scene.frame_nearest(2.5),
        Some(2),
        "ties go to the earlier frame"
    );
    assert_eq!(scene.frame_nearest(-7.0), Some(0));
    // chosen times: the nearest records, a repeat drawn once
    assert_eq!(scene.frames_nearest(&[0.0, 2.4, 2.6, 100.0]), [0, 2, 3, 4]);
    assert_eq!(scene.frames_nearest(&[1.1, 0.9]), [1]);
    assert_eq!(Scene::new(2, 1.0).frame_nearest(0.0), None);
}

#[test]
fn vectors_are_lifted_to_3d() {
    assert_eq!(lift(DVec2::new(1.0, 2.0)), DVec3::new(1.0, 2.0, 0.0));
    assert_eq!(lift(DVec3::new(1.0, 2.0, 3.0)), DVec3::new(1.0, 2.0, 3.0));
    let frame = Frame::from_vectors(0.5, &[DVec2::ONE], &[DVec2::X]).with_gamma(DVec3::Z);
    assert_eq!(frame.positions, [DVec3::new(1.0, 1.0, 0.0)]);
    assert_eq!(frame.gamma, Some(DVec3::Z));
}

#[test]
fn inconsistent_scenes_are_refused() {
    let options = SnapshotOptions::default();
    let mut scene = lattice_scene();
    scene.frames[1].velocities.pop();
    let e = snapshot_svg(&scene, &[0], &options).unwrap_err();
    assert!(
        e.to_string()
            .contains("frame 1 (t = 1) has 12 positions but 11 velocities"),
        "{e}"
    );
    let mut scene = lattice_scene();
    scene.dim = 4;
    assert!(snapshot_svg(&scene, &[0], &options).is_err());
}

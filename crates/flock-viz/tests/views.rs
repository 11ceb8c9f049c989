//! The four views of a 3D frame (oblique, top, front, side), depth-cued.

use flock_viz::{Frame, Scene, SnapshotOptions, View, VizError, four_views, views_png, views_svg};
use glam::DVec3;

use crate::support::{agent_fades, cube_scene, decode_png, lattice_scene};

#[test]
fn a_frame_is_drawn_in_four_views_each_titled_and_labelled() {
    let scene = cube_scene();
    let svg = views_svg(&scene, 2, &SnapshotOptions::default()).unwrap();
    assert!(svg.contains("synthetic cube at t = 2 s"));
    for (title, axes) in [
        ("view az -60°, el 30°", ["u (m)", "v (m)"]),
        ("top view", ["x (m)", "y (m)"]),
        ("front view", ["x (m)", "z (m)"]),
        ("side view", ["y (m)", "z (m)"]),
    ] {
        assert!(svg.contains(title), "{title} missing");
        for axis in axes {
            assert!(svg.contains(axis), "{axis} missing");
        }
    }
    assert_eq!(agent_fades(&svg).len(), 4 * 27);
    assert_eq!(
        four_views(View::default()),
        [View::default(), View::TOP, View::FRONT, View::SIDE]
    );
    // 2 × 2 panels of 480 px under the title band
    let image = decode_png(&views_png(&scene, 2, &SnapshotOptions::default()).unwrap());
    assert_eq!(image.size, (960, 996));
}

#[test]
fn each_view_fades_by_its_own_depth() {
    // Two agents, one above the other: the same depth seen from the front and the side (both
    // drawn unfaded), the upper one nearer seen from the top (the lower one faded fully).
    let q = [DVec3::ZERO, DVec3::new(0.0, 0.0, 7.0)];
    let scene = Scene::new(3, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec3::X; 2]));
    let fades = agent_fades(&views_svg(&scene, 0, &SnapshotOptions::default()).unwrap());
    assert_eq!(fades.len(), 8);
    let top = &fades[2..4];
    assert!(top[0] > 0.79 && top[1] == 0.0, "{top:?}");
    assert_eq!(&fades[4..], [0.0; 4]);
}

#[test]
fn only_3d_frames_that_exist_are_drawn() {
    let options = SnapshotOptions::default();
    assert!(matches!(
        views_svg(&lattice_scene(), 0, &options),
        Err(VizError::Invalid(m)) if m.contains("3D")
    ));
    assert!(matches!(
        views_svg(&cube_scene(), 3, &options),
        Err(VizError::Invalid(m)) if m.contains("frame 3")
    ));
}

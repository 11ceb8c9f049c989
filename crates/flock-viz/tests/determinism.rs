//! The same input gives byte-identical files, and a small SVG is pinned by an insta snapshot.

use flock_viz::{
    AnimationOptions, Frame, MetricsOptions, PlayerOptions, Scene, SnapshotOptions, animation_gif,
    metrics_png, metrics_svg, player_html, snapshot_png, snapshot_svg,
};
use glam::DVec2;

use crate::support::{cube_scene, flocking_metrics, fnv1a, lattice_scene};

#[test]
fn every_figure_is_byte_identical_when_drawn_twice() {
    let scene = lattice_scene();
    let cube = cube_scene();
    let metrics = flocking_metrics(true);
    let mut snap = SnapshotOptions {
        panel_size: (240, 240),
        ..SnapshotOptions::default()
    };
    snap.style.trail = 2;
    let small_metrics = MetricsOptions {
        panel_size: (300, 200),
        ..MetricsOptions::default()
    };
    let anim = AnimationOptions {
        size: (160, 160),
        ..AnimationOptions::default()
    };
    let draw = || -> Vec<Vec<u8>> {
        vec![
            snapshot_svg(&scene, &[0, 4], &snap).unwrap().into_bytes(),
            snapshot_png(&scene, &[0, 4], &snap).unwrap(),
            snapshot_png(&cube, &[1], &snap).unwrap(),
            metrics_svg(&metrics, &small_metrics).unwrap().into_bytes(),
            metrics_png(&metrics, &small_metrics).unwrap(),
            animation_gif(&scene, &anim).unwrap(),
            player_html(&cube, None, &PlayerOptions::default())
                .unwrap()
                .into_bytes(),
        ]
    };
    let (first, second) = (draw(), draw());
    for (k, (a, b)) in first.iter().zip(&second).enumerate() {
        assert!(!a.is_empty(), "figure {k} is empty");
        assert_eq!(fnv1a(a), fnv1a(b), "figure {k} differs");
        assert_eq!(a, b, "figure {k} differs");
    }
}

#[test]
fn a_two_agent_snapshot_svg_is_pinned() {
    let scene = Scene::new(2, 8.4)
        .with_title("two agents")
        .with_frame(Frame::from_vectors(
            1.5,
            &[DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)],
            &[DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0)],
        ));
    let options = SnapshotOptions {
        panel_size: (220, 200),
        ..SnapshotOptions::default()
    };
    insta::assert_snapshot!(snapshot_svg(&scene, &[0], &options).unwrap());
}

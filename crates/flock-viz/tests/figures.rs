//! `write_figures`: every figure of a run into a directory.

use std::fs;

use flock_viz::{
    AnimationOptions, FigureOptions, MetricsOptions, PlayerOptions, SnapshotOptions, write_figures,
};

use crate::support::{cube_scene, flocking_metrics, lattice_scene, temp_dir};

fn small() -> FigureOptions {
    FigureOptions {
        snapshot_count: 3,
        snapshot_times: None,
        snapshot: SnapshotOptions {
            panel_size: (200, 200),
            ..SnapshotOptions::default()
        },
        metrics: MetricsOptions {
            panel_size: (300, 180),
            ..MetricsOptions::default()
        },
        animation: Some(AnimationOptions {
            size: (160, 160),
            ..AnimationOptions::default()
        }),
        player: Some(PlayerOptions::default()),
        reynolds_time: None,
        svg: true,
        png: true,
    }
}

#[test]
fn a_2d_run_gets_snapshots_metrics_animation_and_player() {
    let dir = temp_dir("figures-2d");
    let written = write_figures(
        &lattice_scene(),
        Some(&flocking_metrics(false)),
        &dir,
        &small(),
    )
    .unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "snapshots.svg",
            "snapshots.png",
            "metrics.svg",
            "metrics.png",
            "animation.gif",
            "player.html"
        ]
    );
    for path in &written {
        assert!(
            fs::metadata(path).unwrap().len() > 1000,
            "{}",
            path.display()
        );
    }
    let metrics = fs::read_to_string(dir.join("metrics.svg")).unwrap();
    assert!(metrics.contains("synthetic lattice: metrics"));
    fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_3d_run_gets_a_top_view_too() {
    let dir = temp_dir("figures-3d");
    let options = FigureOptions {
        animation: None,
        player: None,
        png: false,
        ..small()
    };
    let written = write_figures(&cube_scene(), None, &dir, &options).unwrap();
    assert_eq!(
        written,
        [
            dir.join("snapshots.svg"),
            dir.join("snapshots_top.svg"),
            dir.join("views.svg")
        ]
    );
    let top = fs::read_to_string(dir.join("snapshots_top.svg")).unwrap();
    assert!(top.contains("top view"));
    fs::remove_dir_all(dir).unwrap();
}

//! `write_figures`: every figure of a run into a directory.

use std::fs;

use flock_viz::{
    AnimationOptions, FigureOptions, MetricsOptions, Output, PlayerOptions, SnapshotOptions,
    write_figures,
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
        outputs: Output::ALL.to_vec(),
        animation: AnimationOptions {
            size: (160, 160),
            ..AnimationOptions::default()
        },
        player: PlayerOptions::default(),
        reynolds_time: None,
        svg: true,
        png: true,
    }
}

#[test]
fn a_2d_run_gets_snapshots_metrics_animation_and_player() {
    let dir_tmp = temp_dir("figures-2d");
    let dir = dir_tmp.path();
    let written = write_figures(
        &lattice_scene(),
        Some(&flocking_metrics(false)),
        dir,
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
}

#[test]
fn a_3d_run_gets_a_top_view_too() {
    let dir_tmp = temp_dir("figures-3d");
    let dir = dir_tmp.path();
    let options = FigureOptions {
        outputs: vec![Output::Snapshots],
        png: false,
        ..small()
    };
    let written = write_figures(&cube_scene(), None, dir, &options).unwrap();
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
}

/// Each choice of outputs writes its files and no other; those it writes are the bytes of the
/// same files when every output is drawn.
#[test]
fn the_outputs_chosen_are_drawn_alone_and_the_same() {
    let all_dir_tmp = temp_dir("figures-all");
    let all_dir = all_dir_tmp.path();
    let all = write_figures(
        &cube_scene(),
        Some(&flocking_metrics(false)),
        all_dir,
        &small(),
    )
    .unwrap();
    for (outputs, names) in [
        (
            vec![Output::Snapshots],
            &[
                "snapshots.svg",
                "snapshots.png",
                "snapshots_top.svg",
                "snapshots_top.png",
                "views.svg",
                "views.png",
            ][..],
        ),
        (vec![Output::Metrics], &["metrics.svg", "metrics.png"][..]),
        (
            vec![Output::Gif, Output::Player],
            &["animation.gif", "player.html"][..],
        ),
    ] {
        let dir_tmp = temp_dir("figures-some");
        let dir = dir_tmp.path();
        let options = FigureOptions { outputs, ..small() };
        let written =
            write_figures(&cube_scene(), Some(&flocking_metrics(false)), dir, &options).unwrap();
        let expected: Vec<_> = names.iter().map(|name| dir.join(name)).collect();
        assert_eq!(written, expected);
        for name in names {
            assert_eq!(
                fs::read(dir.join(name)).unwrap(),
                fs::read(all_dir.join(name)).unwrap(),
                "{name}"
            );
        }
        assert!(all.contains(&all_dir.join(names[0])));
    }
}

#[test]
fn outputs_are_named_as_the_command_line_names_them() {
    assert_eq!(
        Output::parse_list("gif, snapshots,gif"),
        Ok(vec![Output::Gif, Output::Snapshots])
    );
    let error = Output::parse_list("snapshots,movie").unwrap_err();
    assert!(
        error.contains("\"movie\"") && error.contains("snapshots, metrics, gif, player"),
        "{error}"
    );
}

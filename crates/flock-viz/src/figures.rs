//! [`write_figures`]: every figure of a run into one directory, as `flocking plot DIR` writes them
//! into `DIR/figures/`.

use std::fs;
use std::path::{Path, PathBuf};

use crate::curves::metric_curves::{MetricsOptions, metrics_png, metrics_svg};
use crate::data::metric_series::Metrics;
use crate::error::VizError;
use crate::motion::animation::{AnimationOptions, animation_gif};
use crate::motion::player::{PlayerOptions, player_html};
use crate::scene::frames::Scene;
use crate::scene::projection::View;
use crate::snapshots::four_views::{views_png, views_svg};
use crate::snapshots::snapshot::{SnapshotOptions, snapshot_png, snapshot_svg};

/// Which figures [`write_figures`] writes, and how.
#[derive(Clone, Debug, PartialEq)]
pub struct FigureOptions {
    /// How many snapshot times, spread evenly over the run (first and last included), when
    /// `snapshot_times` is `None`.
    pub snapshot_count: usize,
    /// The snapshot times (s), each drawn at the record nearest it (a scenario's `snapshots`).
    pub snapshot_times: Option<Vec<f64>>,
    /// How snapshots are drawn (for 3D runs `snapshot.view` is the oblique view; a top view is
    /// written beside it).
    pub snapshot: SnapshotOptions,
    /// How the metric figure is drawn (its title defaults to the scene's).
    pub metrics: MetricsOptions,
    /// The animated GIF, or `None` to skip it.
    pub animation: Option<AnimationOptions>,
    /// The HTML player, or `None` to skip it.
    pub player: Option<PlayerOptions>,
    /// The time (s) of the figure of ACC 2004's reading of an (α, α) run as Reynolds's rules
    /// (`reynolds.svg/png`, [`plot_run`](crate::plot_run) only), drawn at the record nearest it;
    /// `None`: [`crate::plot::reynolds_time`].
    pub reynolds_time: Option<f64>,
    /// Whether to write SVG files.
    pub svg: bool,
    /// Whether to write PNG files.
    pub png: bool,
}

impl Default for FigureOptions {
    fn default() -> Self {
        Self {
            snapshot_count: 6,
            snapshot_times: None,
            snapshot: SnapshotOptions::default(),
            metrics: MetricsOptions::default(),
            animation: Some(AnimationOptions::default()),
            player: Some(PlayerOptions::default()),
            reynolds_time: None,
            svg: true,
            png: true,
        }
    }
}

/// Writes the figures of a run into `dir` (created if needed) and returns the files written:
///
/// | file | figure |
/// | --- | --- |
/// | `snapshots.svg`, `snapshots.png` | agents, net, obstacles at `snapshot_times`, or `snapshot_count` even times (TAC 2006 Figs. 10–13) |
/// | `snapshots_top.svg`, `snapshots_top.png` | 3D runs: the same from above ([`View::TOP`]) |
/// | `views.svg`, `views.png` | 3D runs: the last snapshot in four depth-cued views, oblique, top, front and side ([`views_svg`]) |
/// | `metrics.svg`, `metrics.png` | C, R, Ẽ, K̃, H, min distance, clearance against t (Fig. 18) |
/// | `animation.gif` | the whole run, animated |
/// | `player.html` | the whole run in a self-contained canvas player |
///
/// # Errors
/// [`VizError::Io`] when a file cannot be written; any error of the figures' functions.
pub fn write_figures(
    scene: &Scene,
    metrics: Option<&Metrics>,
    dir: &Path,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>, VizError> {
    scene.validate()?;
    if fs::symlink_metadata(dir).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(VizError::Io {
            path: dir.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                "a link, which flocking did not create: flocking never writes through it; move it away",
            ),
        });
    }
    fs::create_dir_all(dir).map_err(|source| VizError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    let mut write = |name: &str, bytes: &[u8]| -> Result<(), VizError> {
        let path = dir.join(name);
        // never through a link: a user's file it points to is left as it is
        flocking::owned::write_no_follow(&path, bytes).map_err(|source| VizError::Io {
            path: path.clone(),
            source,
        })?;
        written.push(path);
        Ok(())
    };

    let frames = match &options.snapshot_times {
        Some(times) => scene.frames_nearest(times),
        None => scene.evenly_spaced_frames(options.snapshot_count.max(1)),
    };
    let mut views = vec![("snapshots", options.snapshot.style.view)];
    if scene.dim == 3 {
        views.push(("snapshots_top", View::TOP));
    }
    for (name, view) in views {
        let mut snapshot = options.snapshot.clone();
        snapshot.style.view = view;
        if options.svg {
            write(
                &format!("{name}.svg"),
                snapshot_svg(scene, &frames, &snapshot)?.as_bytes(),
            )?;
        }
        if options.png {
            write(
                &format!("{name}.png"),
                &snapshot_png(scene, &frames, &snapshot)?,
            )?;
        }
    }

    if scene.dim == 3 {
        let last = frames[frames.len() - 1];
        if options.svg {
            write(
                "views.svg",
                views_svg(scene, last, &options.snapshot)?.as_bytes(),
            )?;
        }
        if options.png {
            write("views.png", &views_png(scene, last, &options.snapshot)?)?;
        }
    }

    if let Some(metrics) = metrics {
        let mut metrics_options = options.metrics.clone();
        if metrics_options.title.is_empty() && !scene.title.is_empty() {
            metrics_options.title = format!("{}: metrics", scene.title);
        }
        if options.svg {
            write(
                "metrics.svg",
                metrics_svg(metrics, &metrics_options)?.as_bytes(),
            )?;
        }
        if options.png {
            write("metrics.png", &metrics_png(metrics, &metrics_options)?)?;
        }
    }

    if let Some(animation) = &options.animation {
        write("animation.gif", &animation_gif(scene, animation)?)?;
    }
    if let Some(player) = &options.player {
        write(
            "player.html",
            player_html(scene, metrics, player)?.as_bytes(),
        )?;
    }
    Ok(written)
}

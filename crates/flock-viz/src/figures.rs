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

use rayon::prelude::*;

/// How one figure is drawn: its file's bytes.
type Drawing<'a> = Box<dyn Fn() -> Result<Vec<u8>, VizError> + Send + Sync + 'a>;

/// A kind of figure of a run, as `flocking plot --outputs` and Python's `Run.plot(outputs=…)`
/// name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Output {
    /// `snapshots.svg/png` (3D: `snapshots_top`, `views`), and an (α, α) run's `reynolds.svg/png`.
    Snapshots,
    /// `metrics.svg/png`, the metric curves.
    Metrics,
    /// `animation.gif`.
    Gif,
    /// `player.html`.
    Player,
}

impl Output {
    /// Every kind, in the order they are drawn: what `flocking plot` draws by default.
    pub const ALL: [Self; 4] = [Self::Snapshots, Self::Metrics, Self::Gif, Self::Player];

    /// The name a user gives: `snapshots`, `metrics`, `gif`, `player`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Snapshots => "snapshots",
            Self::Metrics => "metrics",
            Self::Gif => "gif",
            Self::Player => "player",
        }
    }

    /// A comma-separated list of names (`snapshots,gif`), each once.
    ///
    /// # Errors
    /// A name that is not one of [`Output::ALL`]'s, or an empty list, naming the names there are.
    pub fn parse_list(text: &str) -> Result<Vec<Self>, String> {
        let mut outputs = Vec::new();
        for name in text.split(',').map(str::trim) {
            let output: Self = name.parse()?;
            if !outputs.contains(&output) {
                outputs.push(output);
            }
        }
        Ok(outputs)
    }
}

impl std::str::FromStr for Output {
    type Err = String;

    fn from_str(name: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|output| output.name() == name)
            .ok_or_else(|| {
                format!(
                    "{name:?} is not a figure: give some of {}, separated by commas",
                    Self::ALL.map(Self::name).join(", ")
                )
            })
    }
}

impl std::fmt::Display for Output {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

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
    /// Which figures are drawn (default [`Output::ALL`]).
    pub outputs: Vec<Output>,
    /// How the animated GIF is drawn.
    pub animation: AnimationOptions,
    /// How the HTML player is drawn.
    pub player: PlayerOptions,
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
            outputs: Output::ALL.to_vec(),
            animation: AnimationOptions::default(),
            player: PlayerOptions::default(),
            reynolds_time: None,
            svg: true,
            png: true,
        }
    }
}

impl FigureOptions {
    /// The options of `flocking plot` and Python's `flocking.plot`: the `outputs` (default
    /// [`Output::ALL`]), the snapshot `times` (default: the scenario's, else
    /// [`snapshot_count`](Self::snapshot_count) even ones), and edges coloured by the sign of
    /// their stress when `stress_edges`.
    #[must_use]
    pub fn plot(outputs: Option<Vec<Output>>, times: Option<Vec<f64>>, stress_edges: bool) -> Self {
        let mut options = Self {
            snapshot_times: times,
            ..Self::default()
        };
        if let Some(outputs) = outputs {
            options.outputs = outputs;
        }
        options.snapshot.style.stress_edges = stress_edges;
        options.animation.style.stress_edges = stress_edges;
        options
    }

    /// Whether `output` is drawn.
    #[must_use]
    pub fn draws(&self, output: Output) -> bool {
        self.outputs.contains(&output)
    }
}

/// Writes the figures of a run into `dir` (created if needed) and returns the files written, those
/// of `options.outputs` among:
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
    let frames = match &options.snapshot_times {
        Some(times) => scene.frames_nearest(times),
        None => scene.evenly_spaced_frames(options.snapshot_count.max(1)),
    };
    let mut views = vec![("snapshots", options.snapshot.style.view)];
    if scene.dim == 3 {
        views.push(("snapshots_top", View::TOP));
    }
    if !options.draws(Output::Snapshots) {
        views.clear();
    }
    let snapshots: Vec<(&str, SnapshotOptions)> = views
        .into_iter()
        .map(|(name, view)| {
            let mut snapshot = options.snapshot.clone();
            snapshot.style.view = view;
            (name, snapshot)
        })
        .collect();
    // each figure: its file name and how to draw it, in the order they are written
    let mut figures: Vec<(String, Drawing<'_>)> = Vec::new();
    for (name, snapshot) in &snapshots {
        let frames = &frames;
        if options.svg {
            figures.push((
                format!("{name}.svg"),
                Box::new(move || Ok(snapshot_svg(scene, frames, snapshot)?.into_bytes())),
            ));
        }
        if options.png {
            figures.push((
                format!("{name}.png"),
                Box::new(move || snapshot_png(scene, frames, snapshot)),
            ));
        }
    }
    if scene.dim == 3 && options.draws(Output::Snapshots) {
        let last = frames[frames.len() - 1];
        let snapshot = &options.snapshot;
        if options.svg {
            figures.push((
                "views.svg".into(),
                Box::new(move || Ok(views_svg(scene, last, snapshot)?.into_bytes())),
            ));
        }
        if options.png {
            figures.push((
                "views.png".into(),
                Box::new(move || views_png(scene, last, snapshot)),
            ));
        }
    }
    if let Some(metrics) = metrics.filter(|_| options.draws(Output::Metrics)) {
        let mut metrics_options = options.metrics.clone();
        if metrics_options.title.is_empty() && !scene.title.is_empty() {
            metrics_options.title = format!("{}: metrics", scene.title);
        }
        if options.svg {
            let metrics_options = metrics_options.clone();
            figures.push((
                "metrics.svg".into(),
                Box::new(move || Ok(metrics_svg(metrics, &metrics_options)?.into_bytes())),
            ));
        }
        if options.png {
            figures.push((
                "metrics.png".into(),
                Box::new(move || metrics_png(metrics, &metrics_options)),
            ));
        }
    }
    if options.draws(Output::Gif) {
        figures.push((
            "animation.gif".into(),
            Box::new(|| animation_gif(scene, &options.animation)),
        ));
    }
    if options.draws(Output::Player) {
        figures.push((
            "player.html".into(),
            Box::new(|| Ok(player_html(scene, metrics, &options.player)?.into_bytes())),
        ));
    }

    // drawn at once (each figure's bytes depend on nothing but its inputs), then written in
    // order, none of them when one cannot be drawn
    let drawn: Vec<Vec<u8>> = figures
        .par_iter()
        .map(|(_, draw)| draw())
        .collect::<Result<_, _>>()?;
    let mut written = Vec::with_capacity(figures.len());
    for ((name, _), bytes) in figures.iter().zip(drawn) {
        let path = dir.join(name);
        // never through a link: a user's file it points to is left as it is
        flocking::owned::write_no_follow(&path, &bytes).map_err(|source| VizError::Io {
            path: path.clone(),
            source,
        })?;
        written.push(path);
    }
    Ok(written)
}

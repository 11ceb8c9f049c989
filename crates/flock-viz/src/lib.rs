//! Figures of flocking runs, drawn as Olfati-Saber's *Flocking for multi-agent dynamic systems:
//! algorithms and theory* (IEEE TAC 51(3), 2006) draws them, from the same runs, so that they can
//! be put beside the paper's figures. Drawn with plotters and an embedded font (DejaVu Sans): no
//! system font is needed, and the same input gives byte-identical files.
//!
//! The modules are folders by what they make: [`scene`] (what is drawn, independent of files),
//! [`data`] (a run directory read back), [`snapshots`] (chosen frames), [`curves`] (metrics and the
//! report's functions), [`motion`] (the whole run moving), [`sweeps`] (phase diagrams),
//! [`gallery`] (the page of `flocking figures`) and [`draw`] (what every figure is drawn with);
//! [`figures`] and [`plot`] write a run's figures. The names below are re-exported here.
//!
//! - [`RunData::load`]: a run directory's `metrics.csv` and `trajectory.csv`; [`RunData::scene`].
//! - [`Scene`], [`Frame`], [`Drawable`], [`View`], [`Framing`]: what is drawn and how it is
//!   framed, independent of files.
//! - [`snapshot_svg`], [`snapshot_png`]: agents, net and obstacles at chosen times
//!   (TAC 2006 Figs. 10–17); [`snapshot_rgb`]: one frame as RGB pixels in memory (the
//!   `render_mode="rgb_array"` of the Python environments).
//! - [`views_svg`], [`views_png`]: one frame of a 3D run in four depth-cued views (oblique, top,
//!   front, side).
//! - [`metrics_svg`], [`metrics_png`]: C, R, Ẽ, K̃ against t (TAC 2006 Fig. 18), energy,
//!   distances.
//! - [`reynolds_svg`], [`reynolds_png`]: one frame of an (α, α) run read as Reynolds's three rules
//!   (ACC 2004 § 4): each agent's motion-planning and velocity-matching terms, the sign of its
//!   local stress, and beside them cohesion, separation and alignment.
//! - [`animation_gif`]: the whole run as an animated GIF.
//! - [`function_svg`], [`function_png`]: the report's plots of ρ, ψ_α, φ_α and the pair
//!   potential (CDS 03-006 Figs. 2, 4, 5), from the functions the simulations use.
//! - [`player_html`]: the whole run as one self-contained HTML page with a canvas player.
//! - [`phase_svg`], [`phase_png`], [`phase_table`]: the phase diagram of a parameter sweep;
//!   [`plot_sweep`]: a sweep directory's, as `flocking sweep plot` and Python's `SweepResult.plot`
//!   draw it.
//! - [`write_figures`]: all of them (or the [`Output`]s chosen) into a directory, as `flocking plot`
//!   writes them.
//! - [`plot_run`]: the figures of a run directory, decorated from its `scenario.ron`.
//! - [`index_html`]: the page of every fixture's figures that `flocking figures` writes, each beside
//!   the paper's caption and statements ([`paper_figure`]) and its whole-run measures
//!   ([`whole_run_rows`]).
//!
//! # Example
//! ```
//! use flock_viz::{FigureOptions, Frame, Output, Scene, write_figures};
//! use glam::DVec2;
//!
//! let q = [DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)];
//! let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]));
//! let dir = std::env::temp_dir().join(format!("flock-viz-doc-{}", std::process::id()));
//! let outputs = vec![Output::Snapshots, Output::Player];
//! let options = FigureOptions { outputs, png: false, ..FigureOptions::default() };
//! let written = write_figures(&scene, None, &dir, &options).unwrap();
//! assert_eq!(written, [dir.join("snapshots.svg"), dir.join("player.html")]);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```

pub mod curves;
pub mod data;
pub mod draw;
pub mod error;
pub mod figures;
pub mod gallery;
pub mod motion;
pub mod plot;
pub mod scene;
pub mod snapshots;
pub mod sweeps;

pub use curves::functions::{ReportFunction, function_png, function_svg};
pub use curves::metric_curves::{MetricsOptions, metrics_png, metrics_svg};
pub use data::metric_series::Metrics;
pub use data::run_data::{RunData, load_metrics, load_trajectory, load_trajectory_npy};
pub use draw::style;
pub use error::VizError;
pub use figures::{FigureOptions, Output, write_figures};
pub use gallery::index::{FUNCTIONS_DIR, FigureEntry, function_image, index_html, paper_reference};
pub use gallery::papers::{Measure, PaperFigure, Parameter, Source, Statement, paper_figure};
pub use gallery::whole_run::{WholeRun, whole_run_rows};
pub use motion::animation::{AnimationOptions, animation_frames, animation_gif};
pub use motion::player::{PlayerOptions, player_html};
pub use plot::{PlotError, plot_run, plot_run_with, run_scene};
pub use scene::drawable::Drawable;
pub use scene::frames::{Frame, Scene};
pub use scene::framing::Framing;
pub use scene::projection::{View, lift};
pub use snapshots::four_views::{four_views, views_png, views_svg};
pub use snapshots::reynolds::{ReynoldsOptions, reynolds_png, reynolds_svg};
pub use snapshots::rgb::snapshot_rgb;
pub use snapshots::snapshot;
pub use snapshots::snapshot::{PanelStyle, SnapshotOptions, snapshot_png, snapshot_svg};
pub use sweeps::phase;
pub use sweeps::phase::{Band, PhaseOptions, PhasePoint, phase_png, phase_svg, phase_table};
pub use sweeps::plot::{Plotted, SweepPlot, SweepPlotError, plot_sweep};

//! Figures of flocking runs, drawn as Olfati-Saber's *Flocking for multi-agent dynamic systems:
//! algorithms and theory* (IEEE TAC 51(3), 2006) draws them, from the same runs, so that they can
//! be put beside the paper's figures. Drawn with plotters and an embedded font (DejaVu Sans): no
//! system font is needed, and the same input gives byte-identical files.
//!
//! - [`RunData::load`]: a run directory's `metrics.csv` and `trajectory.csv`; [`RunData::scene`].
//! - [`Scene`], [`Frame`], [`Drawable`], [`View`], [`Framing`]: what is drawn and how it is
//!   framed, independent of files.
//! - [`snapshot_svg`], [`snapshot_png`]: agents, net and obstacles at chosen times
//!   (TAC 2006 Figs. 10–17).
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
//! - [`phase_svg`], [`phase_png`], [`phase_table`]: the phase diagram of a parameter sweep (`flocking sweep plot`).
//! - [`write_figures`]: all of them into a directory, as `flocking plot` writes them.
//! - [`plot_run`]: the figures of a run directory, decorated from its `scenario.ron`.
//! - [`index_html`]: the page of every fixture's figures that `flocking figures` writes, each beside
//!   the paper's caption and statements ([`paper_figure`]) and its whole-run measures
//!   ([`whole_run_rows`]).
//!
//! # Example
//! ```
//! use flock_viz::{FigureOptions, Frame, Scene, write_figures};
//! use glam::DVec2;
//!
//! let q = [DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)];
//! let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]));
//! let dir = std::env::temp_dir().join(format!("flock-viz-doc-{}", std::process::id()));
//! let options = FigureOptions { animation: None, png: false, ..FigureOptions::default() };
//! let written = write_figures(&scene, None, &dir, &options).unwrap();
//! assert_eq!(written, [dir.join("snapshots.svg"), dir.join("player.html")]);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```

pub mod animation;
pub mod drawable;
pub mod error;
pub mod figures;
pub mod font;
mod format;
pub mod framing;
pub mod functions;
pub mod gallery;
mod geometry;
pub mod metrics;
pub mod metrics_plot;
pub mod papers;
pub mod phase;
pub mod player;
pub mod plot;
mod render;
pub mod reynolds;
pub mod run_data;
pub mod scene;
pub mod snapshot;
pub mod style;
pub mod view;
pub mod views;
pub mod whole_run;

pub use animation::{AnimationOptions, animation_frames, animation_gif};
pub use drawable::Drawable;
pub use error::VizError;
pub use figures::{FigureOptions, write_figures};
pub use framing::Framing;
pub use functions::{ReportFunction, function_png, function_svg};
pub use gallery::{FUNCTIONS_DIR, FigureEntry, function_image, index_html, paper_reference};
pub use metrics::Metrics;
pub use metrics_plot::{MetricsOptions, metrics_png, metrics_svg};
pub use papers::{Measure, PaperFigure, Parameter, Source, Statement, paper_figure};
pub use phase::{Band, PhaseOptions, PhasePoint, phase_png, phase_svg, phase_table};
pub use player::{PlayerOptions, player_html};
pub use plot::{PlotError, plot_run, plot_run_with, run_scene};
pub use reynolds::{ReynoldsOptions, reynolds_png, reynolds_svg};
pub use run_data::{RunData, load_metrics, load_trajectory, load_trajectory_npy};
pub use scene::{Frame, Scene, lift};
pub use snapshot::{PanelStyle, SnapshotOptions, snapshot_png, snapshot_svg};
pub use view::View;
pub use views::{four_views, views_png, views_svg};
pub use whole_run::{WholeRun, whole_run_rows};

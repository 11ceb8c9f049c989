//! `flocking figures`: every fixture run and drawn into one directory, with a static `index.html`.
//!
//! For each `*.ron` of the fixtures directory (sorted by name), [`figures()`] runs the scenario into
//! `OUT/<fixture stem>/` (a [`RunDirectory`], replaced if present and flocking's: a directory
//! there holding anything else is refused, untouched), draws its figures with
//! [`plot_run_with`] (all but the GIF: the player shows the same motion), then keeps only what
//! the page and a reader need:
//!
//! | kept | dropped |
//! | --- | --- |
//! | `scenario.ron`, `metrics.csv` (small, rerunnable, plottable) | `trajectory.csv`, `final.csv` (large, regenerable) |
//! | `figures/snapshots*.{svg,png}`, `figures/metrics.{svg,png}`, `figures/reynolds.{svg,png}` (the (α, α) fixtures), `figures/player.html` (unless `--no-player`, which does not draw it) | |
//!
//! `OUT/index.html` is [`flock_viz::index_html`]'s page: per fixture its paper reference, the
//! paper's caption and statements quoted beside our measures, its parameters (the paper's or
//! ours), its description, our measures over the whole run with the model's verdict of its
//! `flocking.txt`, the snapshot and metric PNGs and a table of the final metrics; a figure our
//! run does not reproduce says so at its top. `OUT/functions/` holds the report's plots of its
//! functions (CDS 03-006 Figs. 2, 4, 5; [`flock_viz::function_svg`]) as SVG and PNG, shown at the
//! end of the page.
//!
//! `OUT` itself must be new, empty or a gallery flocking wrote (its `.flocking` marker says
//! `figures`; files of other names in it are left alone), and is locked while it is written.

use std::fs;
use std::io::{self, IsTerminal};
use std::path::{Path, PathBuf};

use flock_viz::{
    FUNCTIONS_DIR, FigureEntry, FigureOptions, Output, PlotError, ReportFunction, function_png,
    function_svg, index_html, load_metrics, paper_reference, plot_run_with,
};
use flocking::owned::{self, DirError, DirLock, Kind};
use flocking::run_dir::CreateError;
use flocking::{RunDirectory, RunError, Scenario, ScenarioError};

use crate::progress::Progress;

/// The run files deleted once the figures are drawn.
pub const DROPPED_RUN_FILES: [&str; 2] = ["trajectory.csv", "final.csv"];

/// Why `flocking figures` stopped.
#[derive(Debug)]
pub enum FiguresError {
    /// The fixtures directory does not exist or holds no `*.ron`.
    NoFixtures(PathBuf),
    /// A file or directory could not be read or written.
    Io {
        /// The path.
        path: PathBuf,
        /// The error.
        source: io::Error,
    },
    /// The output directory is not flocking's gallery, or is being written.
    Dir(DirError),
    /// A fixture is invalid.
    Scenario(ScenarioError),
    /// A fixture's run directory could not be created.
    Create {
        /// The fixture's stem.
        fixture: String,
        /// The error.
        source: CreateError,
    },
    /// A fixture's run failed.
    Run {
        /// The fixture's stem.
        fixture: String,
        /// The error.
        source: Box<RunError<io::Error>>,
    },
    /// A fixture's figures failed.
    Plot {
        /// The fixture's stem.
        fixture: String,
        /// The error.
        source: PlotError,
    },
}

impl std::fmt::Display for FiguresError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoFixtures(dir) => write!(
                f,
                "no fixtures: {} is not a directory holding *.ron scenarios; run `flocking figures` from the workspace root",
                dir.display()
            ),
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Dir(e) => write!(f, "{e}"),
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Create { fixture, source } => write!(f, "{fixture}: {source}"),
            Self::Run { fixture, source } => write!(f, "{fixture}: run failed: {source}"),
            Self::Plot { fixture, source } => write!(f, "{fixture}: figures failed: {source}"),
        }
    }
}

impl std::error::Error for FiguresError {}

impl FiguresError {
    /// Whether the command was refused as asked (no fixtures, an invalid one, a directory that is
    /// not flocking's or is being written: exit code 2), rather than failed while doing it (1).
    #[must_use]
    pub const fn is_refusal(&self) -> bool {
        match self {
            Self::NoFixtures(_) | Self::Scenario(_) => true,
            Self::Dir(e)
            | Self::Create {
                source: CreateError::Dir(e),
                ..
            } => !matches!(e, DirError::Io(_)),
            Self::Create { source, .. } => !matches!(source, CreateError::Io(_)),
            Self::Io { .. } | Self::Run { .. } | Self::Plot { .. } => false,
        }
    }
}

/// Runs and draws every `*.ron` of `fixtures_dir` into `out/<stem>/` and writes `out/index.html`;
/// prints one line per fixture unless `quiet`; keeps each run's `player.html` if `player` (the
/// players are most of the page's bytes). Returns the page's entries, in order.
///
/// # Errors
/// [`FiguresError::NoFixtures`] when `fixtures_dir` is missing or holds no `*.ron`;
/// [`FiguresError::Dir`] when `out` holds files but no gallery marker, or is being written;
/// [`FiguresError::Create`] for an `out/<stem>` that flocking did not write; the first
/// fixture that fails to load, run or draw; any I/O error.
pub fn figures(
    fixtures_dir: &Path,
    out: &Path,
    quiet: bool,
    player: bool,
) -> Result<Vec<FigureEntry>, FiguresError> {
    let io_err = |path: &Path| {
        let path = path.to_path_buf();
        move |source| FiguresError::Io { path, source }
    };
    if !fixtures_dir.is_dir() {
        return Err(FiguresError::NoFixtures(fixtures_dir.to_path_buf()));
    }
    let mut paths: Vec<PathBuf> = fs::read_dir(fixtures_dir)
        .map_err(io_err(fixtures_dir))?
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "ron"))
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(FiguresError::NoFixtures(fixtures_dir.to_path_buf()));
    }
    owned::check_owned(out, Kind::Figures).map_err(FiguresError::Dir)?;
    // Issue 27: everything the gallery replaces is checked before anything is written — the
    // gallery's own files and each fixture's run directory, by name and, where a manifest
    // records them, by size and content
    let own_files = gallery_files();
    owned::check_files(out, &own_files).map_err(FiguresError::Dir)?;
    for path in &paths {
        let stem = path.file_stem().unwrap_or_default().to_string_lossy();
        let dir = out.join(&*stem);
        if fs::symlink_metadata(&dir).is_ok() {
            owned::check_removable(&dir, Kind::Run).map_err(|e| FiguresError::Create {
                fixture: stem.clone().into_owned(),
                source: CreateError::Dir(e),
            })?;
        }
    }
    fs::create_dir_all(out).map_err(io_err(out))?;
    if !owned::marked(out, Kind::Figures) {
        owned::mark(out, Kind::Figures).map_err(io_err(out))?;
    }
    let _lock = DirLock::acquire(out).map_err(FiguresError::Dir)?;
    // a gallery of an older flocking has no manifest: its files are recognised by name once
    owned::start_manifest(out, &own_files).map_err(FiguresError::Dir)?;

    // the GIF is dropped (the player shows the same motion): not drawn at all
    let options = FigureOptions {
        outputs: [Output::Snapshots, Output::Metrics]
            .into_iter()
            .chain(player.then_some(Output::Player))
            .collect(),
        ..FigureOptions::default()
    };
    let mut entries = Vec::with_capacity(paths.len());
    for path in &paths {
        let stem = path
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let scenario = Scenario::load(path).map_err(FiguresError::Scenario)?;
        let dir = out.join(&stem);
        let run_err = |source| FiguresError::Run {
            fixture: stem.clone(),
            source: Box::new(source),
        };
        let recorder =
            RunDirectory::create(&dir, &scenario, true).map_err(|source| FiguresError::Create {
                fixture: stem.clone(),
                source,
            })?;
        let mut recorder = Progress::new(recorder, &scenario, !quiet && io::stderr().is_terminal());
        let summary = match flocking::run(&scenario, &mut recorder) {
            Ok(summary) => summary,
            Err(e) => {
                recorder.into_inner().abandon();
                return Err(run_err(e));
            }
        };
        recorder
            .into_inner()
            .finish()
            .map_err(|e| run_err(RunError::Record(e)))?;
        plot_run_with(&dir, &options).map_err(|source| FiguresError::Plot {
            fixture: stem.clone(),
            source,
        })?;
        for name in DROPPED_RUN_FILES {
            owned::remove_file(&dir, name).map_err(FiguresError::Dir)?;
        }
        let images: Vec<String> = [
            "snapshots.png",
            "snapshots_top.png",
            "views.png",
            "metrics.png",
            "reynolds.png",
        ]
        .iter()
        .filter(|name| dir.join("figures").join(name).is_file())
        .map(|name| format!("{stem}/figures/{name}"))
        .collect();
        if !quiet {
            outln!(
                "flocking figures: {stem:<36} {}D n = {:<4} {:>6} steps  {:>7.2} s  -> {}",
                summary.dim,
                summary.agents,
                summary.steps,
                summary.elapsed.as_secs_f64(),
                dir.display()
            );
        }
        let metrics =
            load_metrics(&dir.join("metrics.csv")).map_err(|source| FiguresError::Plot {
                fixture: stem.clone(),
                source: PlotError::Viz(source),
            })?;
        let flocking_txt = dir.join("flocking.txt");
        let verdict = fs::read_to_string(&flocking_txt)
            .map_err(io_err(&flocking_txt))?
            .lines()
            .next()
            .unwrap_or_default()
            .to_owned();
        entries.push(FigureEntry {
            reference: paper_reference(&stem),
            description: scenario.description.clone(),
            stem,
            summary,
            metrics,
            verdict,
            images,
            player,
        });
    }
    let functions = out.join(FUNCTIONS_DIR);
    fs::create_dir_all(&functions).map_err(io_err(&functions))?;
    for function in ReportFunction::ALL {
        let plot = |source| FiguresError::Plot {
            fixture: function.stem().to_owned(),
            source: PlotError::Viz(source),
        };
        // never through a link (issue 27)
        let png = functions.join(format!("{}.png", function.stem()));
        owned::write_no_follow(&png, &function_png(function).map_err(plot)?)
            .map_err(io_err(&png))?;
        let svg = functions.join(format!("{}.svg", function.stem()));
        owned::write_no_follow(&svg, function_svg(function).map_err(plot)?.as_bytes())
            .map_err(io_err(&svg))?;
    }
    let index = out.join("index.html");
    owned::write_no_follow(
        &index,
        index_html(&entries, &ReportFunction::ALL).as_bytes(),
    )
    .map_err(io_err(&index))?;
    if !quiet {
        outln!(
            "flocking figures: {} fixture(s), {}",
            entries.len(),
            index.display()
        );
    }
    Ok(entries)
}

/// The files of a gallery's own, relative to it: its page and the function plots.
fn gallery_files() -> Vec<String> {
    let mut files = vec!["index.html".to_owned()];
    for function in ReportFunction::ALL {
        for extension in ["png", "svg"] {
            files.push(format!("{FUNCTIONS_DIR}/{}.{extension}", function.stem()));
        }
    }
    files
}

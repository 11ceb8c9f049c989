//! `flock figures`: every fixture run and drawn into one directory, with a static `index.html`.
//!
//! For each `*.ron` of the fixtures directory (sorted by name), [`figures()`] runs the scenario into
//! `OUT/<fixture stem>/` (a [`RunDirectory`], replaced if present), draws its figures with
//! [`plot_run`], then keeps only what the page and a reader need:
//!
//! | kept | dropped |
//! | --- | --- |
//! | `scenario.ron`, `metrics.csv` (small, rerunnable, plottable) | `trajectory.csv`, `final.csv` (large, regenerable) |
//! | `figures/snapshots*.{svg,png}`, `figures/metrics.{svg,png}`, `figures/player.html` | `figures/animation.gif` (the largest file, and the player shows the same motion) |
//!
//! `OUT/index.html` is one self-contained page (no script, no network): per fixture its paper
//! reference and description, the snapshot and metric PNGs and a table of the final metrics from the
//! run's [`RunSummary`].

use std::fmt::Write as _;
use std::fs;
use std::io::{self, IsTerminal};
use std::path::{Path, PathBuf};

use crate::error::ScenarioError;
use crate::output::RunDirectory;
use crate::plot::{PlotError, plot_run};
use crate::progress::Progress;
use crate::run::{RunError, RunSummary, run_scenario};
use crate::scenario::Scenario;

/// The run files deleted once the figures are drawn.
pub const DROPPED_RUN_FILES: [&str; 2] = ["trajectory.csv", "final.csv"];

/// The figure files deleted once drawn.
pub const DROPPED_FIGURES: [&str; 1] = ["animation.gif"];

/// Why `flock figures` stopped.
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
    /// A fixture is invalid.
    Scenario(ScenarioError),
    /// A fixture's run failed.
    Run {
        /// The fixture's stem.
        fixture: String,
        /// The error.
        source: RunError<io::Error>,
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
                "no fixtures: {} is not a directory holding *.ron scenarios; run `flock figures` from the workspace root",
                dir.display()
            ),
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Run { fixture, source } => write!(f, "{fixture}: run failed: {source}"),
            Self::Plot { fixture, source } => write!(f, "{fixture}: figures failed: {source}"),
        }
    }
}

impl std::error::Error for FiguresError {}

/// One fixture on the page.
#[derive(Clone, Debug)]
pub struct FigureEntry {
    /// The fixture's file stem (its directory under the output directory).
    pub stem: String,
    /// The paper and figure the stem names, e.g. "TAC 2006 Fig. 11".
    pub reference: String,
    /// The scenario's `description`.
    pub description: String,
    /// The run's summary.
    pub summary: RunSummary,
    /// The figure files kept, relative to the output directory (`/`-separated).
    pub images: Vec<String>,
}

/// Runs and draws every `*.ron` of `fixtures_dir` into `out/<stem>/` and writes `out/index.html`;
/// prints one line per fixture unless `quiet`. Returns the page's entries, in order.
///
/// # Errors
/// [`FiguresError::NoFixtures`] when `fixtures_dir` is missing or holds no `*.ron`; the first
/// fixture that fails to load, run or draw; any I/O error.
pub fn figures(
    fixtures_dir: &Path,
    out: &Path,
    quiet: bool,
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
    fs::create_dir_all(out).map_err(io_err(out))?;

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
            source,
        };
        let recorder = RunDirectory::create(&dir, &scenario, true)
            .map_err(|e| run_err(RunError::Record(e)))?;
        let mut recorder = Progress::new(recorder, &scenario, !quiet && io::stderr().is_terminal());
        let summary = match run_scenario(&scenario, &mut recorder) {
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
        plot_run(&dir).map_err(|source| FiguresError::Plot {
            fixture: stem.clone(),
            source,
        })?;
        for name in DROPPED_RUN_FILES {
            remove_if_present(&dir.join(name))?;
        }
        for name in DROPPED_FIGURES {
            remove_if_present(&dir.join("figures").join(name))?;
        }
        let images: Vec<String> = ["snapshots.png", "snapshots_top.png", "metrics.png"]
            .iter()
            .filter(|name| dir.join("figures").join(name).is_file())
            .map(|name| format!("{stem}/figures/{name}"))
            .collect();
        if !quiet {
            println!(
                "flock figures: {stem:<36} {}D n = {:<4} {:>6} steps  {:>7.2} s  -> {}",
                summary.dim,
                summary.agents,
                summary.steps,
                summary.elapsed.as_secs_f64(),
                dir.display()
            );
        }
        entries.push(FigureEntry {
            reference: paper_reference(&stem),
            description: scenario.description.clone(),
            stem,
            summary,
            images,
        });
    }
    let index = out.join("index.html");
    fs::write(&index, index_html(&entries)).map_err(io_err(&index))?;
    if !quiet {
        println!(
            "flock figures: {} fixture(s), {}",
            entries.len(),
            index.display()
        );
    }
    Ok(entries)
}

fn remove_if_present(path: &Path) -> Result<(), FiguresError> {
    match fs::remove_file(path) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => Err(FiguresError::Io {
            path: path.to_path_buf(),
            source: e,
        }),
        _ => Ok(()),
    }
}

/// The paper and figure a fixture's stem names: `tac2006_fig11_…` → "TAC 2006 Fig. 11"; stems of
/// no paper (or unknown prefixes) give "no paper".
#[must_use]
pub fn paper_reference(stem: &str) -> String {
    let mut parts = stem.split('_');
    let paper = match parts.next().unwrap_or_default() {
        "tac2006" => "Olfati-Saber, TAC 2006",
        "tr2003" => "Olfati-Saber, CDS 03-006 (2003)",
        "acc2004" => "Olfati-Saber, ACC 2004",
        "tanner2003" => "Tanner, Jadbabaie & Pappas 2003",
        _ => return "no paper".to_owned(),
    };
    match parts.next().and_then(|p| p.strip_prefix("fig")) {
        Some(number) if !number.is_empty() => format!("{paper}, Fig. {number}"),
        _ => paper.to_owned(),
    }
}

/// Escapes text for HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The rows of a fixture's final-metrics table: name and value.
fn metric_rows(summary: &RunSummary) -> Vec<(String, String)> {
    let m = &summary.metrics;
    let mut rows = vec![
        (
            "connectivity C".to_owned(),
            format!("{:.4} ({} component(s))", m.connectivity, m.components),
        ),
        (
            "giant component C*".to_owned(),
            format!("{:.4}", m.giant_component),
        ),
        (
            "deviation energy Ẽ".to_owned(),
            format!("{:.3e}", m.deviation_energy),
        ),
        (
            "velocity mismatch K̃".to_owned(),
            format!("{:.3e}", m.velocity_mismatch),
        ),
        ("min distance".to_owned(), format!("{:.4}", m.min_distance)),
        ("colliding pairs".to_owned(), m.collisions.to_string()),
    ];
    for (name, value) in &summary.extra {
        let value = if *name == "inside_obstacles" {
            format!("{value}")
        } else {
            format!("{value:.4e}")
        };
        rows.push(((*name).replace('_', " "), value));
    }
    rows
}

/// The static page: per fixture its reference, description, PNGs and final metrics.
#[must_use]
pub fn index_html(entries: &[FigureEntry]) -> String {
    let mut html = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>flock: the papers' figures</title>\n<style>\n\
         body { font-family: sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #222; }\n\
         section { border-top: 1px solid #ccc; padding: 1em 0; }\n\
         img { max-width: 100%; display: block; margin: 0.5em 0; }\n\
         table { border-collapse: collapse; }\n\
         td { padding: 0.15em 0.8em; border-bottom: 1px solid #eee; }\n\
         td.v { font-family: monospace; text-align: right; }\n\
         </style>\n</head>\n<body>\n<h1>flock: the papers' figures</h1>\n\
         <p>Written by <code>flock figures</code>: every fixture run and drawn; the tables give the \
         metrics at the final time.</p>\n<ul>\n",
    );
    for e in entries {
        let _ = writeln!(
            html,
            "<li><a href=\"#{0}\">{1}</a>: {2}</li>",
            escape(&e.stem),
            escape(&e.reference),
            escape(&e.stem)
        );
    }
    html.push_str("</ul>\n");
    for e in entries {
        let s = &e.summary;
        let _ = writeln!(
            html,
            "<section id=\"{0}\">\n<h2>{1}: <code>{0}</code></h2>\n<p>{2}</p>\n\
             <p>{3}D, n = {4}, {5} steps to t = {6}; \
             <a href=\"{0}/figures/player.html\">player</a>, \
             <a href=\"{0}/scenario.ron\">scenario</a>, \
             <a href=\"{0}/metrics.csv\">metrics.csv</a></p>",
            escape(&e.stem),
            escape(&e.reference),
            escape(&e.description),
            s.dim,
            s.agents,
            s.steps,
            s.t
        );
        for image in &e.images {
            let _ = writeln!(
                html,
                "<img src=\"{0}\" alt=\"{0}\" loading=\"lazy\">",
                escape(image)
            );
        }
        html.push_str("<table>\n");
        for (name, value) in metric_rows(s) {
            let _ = writeln!(
                html,
                "<tr><td>{}</td><td class=\"v\">{}</td></tr>",
                escape(&name),
                escape(&value)
            );
        }
        html.push_str("</table>\n</section>\n");
    }
    html.push_str("</body>\n</html>\n");
    html
}

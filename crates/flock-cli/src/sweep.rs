//! `flocking sweep`: a sweep file run on this machine's cores (or one shard of it), its shards merged,
//! and its phase diagrams drawn. The sweep itself is the `flocking` library's ([`flocking::sweep`]).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

use clap::{Args, Subcommand, ValueEnum};
use flock_viz::phase::{
    Band, Bound, PhaseOptions, PhasePoint, Reference, phase_png, phase_svg, phase_table,
};
use flocking::estimate::Outputs;
use flocking::owned::{self, DirError};
use flocking::sweep::store::{self, RUNS_FILE, StoreError};
use flocking::sweep::{
    ExecuteOptions, ParameterLabel, RunRow, Shard, Sweep, execute, metric_label, share, value_field,
};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// `flocking sweep SWEEP.ron --out DIR [--jobs N] [--keep-runs] [--shard i/N]`, or one of its
/// subcommands.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    #[command(subcommand)]
    action: Option<SweepAction>,
    /// The sweep file (.ron).
    #[arg(required = true)]
    sweep: Option<PathBuf>,
    /// The output directory: runs.csv, times.csv, sweep.ron, rows/ (the same command resumes a
    /// killed sweep from it).
    #[arg(long, required = true)]
    out: Option<PathBuf>,
    /// Workers, each running one single-threaded run at a time (default: all cores; at most 4
    /// per core).
    #[arg(long, value_parser = crate::resources::parse_threads)]
    jobs: Option<usize>,
    /// Start even when the estimated memory or disk exceeds what this machine has free, or a
    /// run's start is too dense to estimate.
    #[arg(long)]
    no_resource_check: bool,
    /// Keep each run's directory in `DIR/runs/<id>` (as `flocking run` writes it).
    #[arg(long)]
    keep_runs: bool,
    /// Run only shard i of N (run k belongs to shard k mod N), e.g. `--shard $SLURM_ARRAY_TASK_ID/N`;
    /// join the shards with `flocking sweep merge`.
    #[arg(long, value_name = "i/N")]
    shard: Option<Shard>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// Parsed once per command: the size of its largest variant costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
enum SweepAction {
    /// Join the output directories of a sweep's shards into one runs.csv.
    Merge {
        /// The merged output directory.
        #[arg(long)]
        out: PathBuf,
        /// The shards' output directories.
        #[arg(required = true)]
        shards: Vec<PathBuf>,
    },
    /// Draw a phase diagram of a finished sweep: a heatmap of the mean over seeds on two axes, or
    /// a line with a band on one; the other axes fixed (--where), one panel per value (--facet)
    /// or pooled (the title says over what).
    Plot {
        /// The sweep's output directory.
        dir: PathBuf,
        /// The axis along x (a parameter path of the sweep).
        #[arg(long)]
        x: String,
        /// The axis along y (a heatmap).
        #[arg(long)]
        y: Option<String>,
        /// Only the runs with this value of an axis, as runs.csv writes it (`--where agents=50`);
        /// repeatable.
        #[arg(long = "where", value_name = "AXIS=VALUE", value_parser = parse_where)]
        fixed: Vec<(String, String)>,
        /// One panel per value of this axis, on shared scales.
        #[arg(long, value_name = "AXIS", conflicts_with = "series")]
        facet: Option<String>,
        /// One series per value of this axis on one set of axes (a line diagram): a colour and a
        /// marker each, with a legend.
        #[arg(long, value_name = "AXIS")]
        series: Option<String>,
        /// Values from a source drawn beside the sweep's: a CSV file (lines from `#` on are
        /// comments) with the header `series,label,x,y`, consecutive rows of the same series and label one reference — over
        /// a line diagram its points (x, metric) as black markers of its series (a value of the
        /// --series or --facet axis as runs.csv writes it, or empty), over a heatmap a labelled
        /// line through its points (x, y).
        #[arg(long, value_name = "FILE")]
        reference: Option<PathBuf>,
        /// The runs.csv column to draw (alpha_flock and strict_alpha_flock count as 1 or 0: their
        /// mean is the fraction of seeds that flock).
        #[arg(long)]
        metric: String,
        /// The figure (.svg or .png; default DIR/<metric>.svg), or .csv for the numbers it draws
        /// (panel, x, y, runs, mean, band).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The band of a line: min-max or the 25–75 % quantiles.
        #[arg(long, default_value = "minmax")]
        band: BandArg,
        /// Logarithmic x axis.
        #[arg(long)]
        log_x: bool,
        /// Logarithmic y axis.
        #[arg(long)]
        log_y: bool,
        /// A theoretical bound on x (e.g. a stability bound of the swept delay), drawn as a
        /// labelled vertical line in every panel; it must lie within the x values drawn.
        #[arg(long, value_name = "X", allow_negative_numbers = true)]
        bound: Option<f64>,
        /// The bound's label.
        #[arg(long, value_name = "TEXT", requires = "bound", default_value = "bound")]
        bound_label: String,
    },
}

/// The band of a one-axis phase diagram.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BandArg {
    /// Minimum to maximum over the seeds.
    Minmax,
    /// The 25 % and 75 % quantiles.
    Quantiles,
}

/// `AXIS=VALUE` of `--where`.
fn parse_where(text: &str) -> Result<(String, String), String> {
    text.split_once('=')
        .map(|(axis, value)| (axis.trim().to_owned(), value.trim().to_owned()))
        .ok_or_else(|| format!("{text:?}: give AXIS=VALUE, e.g. agents=50"))
}

/// Why `flocking sweep` failed: a command that cannot be done as asked (exit code 2, as an
/// invalid scenario), or a failure while doing it (1).
enum Failure {
    Usage(String),
    Failed(String),
    /// Stopped by Ctrl-C before every run finished.
    Interrupted(String),
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Self::Failed(message)
    }
}

impl From<StoreError> for Failure {
    /// A refusal (a directory not flocking's or being written, another sweep) is exit code 2,
    /// an I/O error 1.
    fn from(error: StoreError) -> Self {
        if error.is_refusal() {
            Self::Usage(error.to_string())
        } else {
            Self::Failed(error.to_string())
        }
    }
}

/// Exit code of a sweep stopped by Ctrl-C (128 + SIGINT), as `flocking run`'s.
const INTERRUPTED: u8 = 130;

/// Exit code of a command that asks for what the sweep does not have.
const USAGE: u8 = 2;

/// Runs `flocking sweep …`; `writing` is set once the output directory is about to be written
/// (until then an interrupt may quit at once).
pub fn main(args: SweepArgs, writing: &AtomicBool) -> ExitCode {
    let result = match args.action {
        Some(SweepAction::Merge { out, shards }) => merge(&out, &shards),
        Some(SweepAction::Plot {
            dir,
            x,
            y,
            fixed,
            facet,
            series,
            reference,
            metric,
            out,
            band,
            log_x,
            log_y,
            bound,
            bound_label,
        }) => {
            let request = PlotRequest {
                x,
                y,
                fixed,
                panels: match (facet, series) {
                    (Some(axis), _) => Some((axis, false)),
                    (None, Some(axis)) => Some((axis, true)),
                    (None, None) => None,
                },
                reference,
                metric,
                band,
                log_x,
                log_y,
                bound: bound.map(|x| Bound {
                    x,
                    label: bound_label,
                }),
            };
            plot(&dir, &request, out)
        }
        None => {
            let (Some(sweep), Some(out)) = (args.sweep, args.out) else {
                unreachable!("clap requires SWEEP and --out without a subcommand")
            };
            let options = ExecuteOptions {
                jobs: args.jobs.unwrap_or_else(|| {
                    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
                }),
                shard: args.shard,
                keep_runs: args.keep_runs,
            };
            run(
                &sweep,
                &out,
                &options,
                (args.quiet, args.no_resource_check),
                writing,
            )
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            errln!("error: {message}");
            ExitCode::from(USAGE)
        }
        Err(Failure::Failed(message)) => {
            errln!("error: {message}");
            ExitCode::FAILURE
        }
        Err(Failure::Interrupted(message)) => {
            errln!("{message}");
            ExitCode::from(INTERRUPTED)
        }
    }
}

/// Loads, checks and estimates the sweep (an invalid one is a usage error, exit 2), then runs it.
fn run(
    path: &Path,
    out: &Path,
    options: &ExecuteOptions,
    (quiet, unchecked): (bool, bool),
    writing: &AtomicBool,
) -> Result<(), Failure> {
    let sweep = Sweep::load(path).map_err(|e| Failure::Usage(e.to_string()))?;
    let outputs = if options.keep_runs {
        Outputs::RUN
    } else {
        Outputs::NONE
    };
    if sweep.runs().is_empty() {
        return Err(Failure::Usage("the sweep has no runs".into()));
    }
    // what this command will run: its shard's runs not found done in `out`
    let pending = share(&sweep, out, options.shard).map_or_else(
        |_| {
            let mine = sweep.runs().into_iter();
            mine.filter(|run| options.shard.is_none_or(|s| s.owns(run.index)))
                .collect()
        },
        |(_, pending)| pending,
    );
    match flocking::sweep::estimate(&sweep, &pending, &outputs, options.jobs) {
        Some(estimate) => {
            crate::resources::announce(&estimate, Some(out), (unchecked, true))
                .map_err(Failure::Usage)?;
        }
        None => outln!(
            "estimate: nothing left to run, every run is done in {}",
            out.display()
        ),
    }
    writing.store(true, std::sync::atomic::Ordering::SeqCst);
    run_checked(&sweep, out, options, quiet)
}

fn run_checked(
    sweep: &Sweep,
    out: &Path,
    options: &ExecuteOptions,
    quiet: bool,
) -> Result<(), Failure> {
    let (done, pending) = share(sweep, out, options.shard)?;
    let total = (done + pending.len()) as u64;
    let bar = if quiet || !std::io::stderr().is_terminal() {
        ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden())
    } else {
        ProgressBar::new(total)
    };
    bar.set_style(
        ProgressStyle::with_template(
            "[{elapsed_precise}] {wide_bar} {pos}/{len} runs  {per_sec}  ETA {eta}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_position(done as u64);
    bar.reset_eta();
    let failed = std::sync::atomic::AtomicUsize::new(0);
    let done = |row: &RunRow| {
        if let Err(error) = &row.outcome {
            failed.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            bar.suspend(|| errln!("run {} ({}): {error}", row.index, row.id));
        }
        bar.inc(1);
    };
    let executed = execute(sweep, out, options, &|| false, &done)?;
    bar.finish_and_clear();
    outln!(
        "flocking sweep: {} run(s) now, {} found done, {} failed; {} row(s) in {}",
        executed.ran,
        executed.skipped,
        failed.into_inner(),
        executed.rows,
        out.join(RUNS_FILE).display()
    );
    if executed.stopped {
        return Err(Failure::Interrupted(format!(
            "stopped before every run finished; the same command resumes from {}",
            out.display()
        )));
    }
    if executed.unwritten > 0 {
        return Err(Failure::Failed(format!(
            "{} run(s) could not be written (see above); they have no row, and the same command makes them again once that is fixed",
            executed.unwritten
        )));
    }
    Ok(())
}

fn merge(out: &Path, shards: &[PathBuf]) -> Result<(), Failure> {
    let rows = store::merge(out, shards)?;
    outln!(
        "flocking sweep merge: {} shard(s), {rows} row(s) in {}",
        shards.len(),
        out.join(RUNS_FILE).display()
    );
    Ok(())
}

/// A value of runs.csv as a number: booleans as 1 or 0, empty as NaN.
fn number(field: &str) -> Option<f64> {
    match field {
        "true" => Some(1.0),
        "false" => Some(0.0),
        "" => Some(f64::NAN),
        other => other.parse().ok(),
    }
}

/// What `flocking sweep plot` draws.
struct PlotRequest {
    x: String,
    y: Option<String>,
    fixed: Vec<(String, String)>,
    /// The axis of the panels (`--facet`), or of the series (`--series`: true).
    panels: Option<(String, bool)>,
    reference: Option<PathBuf>,
    metric: String,
    band: BandArg,
    log_x: bool,
    log_y: bool,
    bound: Option<Bound>,
}

/// An axis of the sweep as the plot uses it: its column of runs.csv, its values as runs.csv
/// writes them (in the sweep's order) and its label.
struct AxisColumn {
    column: usize,
    values: Vec<String>,
    label: ParameterLabel,
}

impl AxisColumn {
    /// "n = 50".
    fn equals(&self, value: &str) -> String {
        format!("{} = {}", self.label.short(), shown(value))
    }

    /// "n ∈ {25, 50, 100, 200}".
    fn among(&self) -> String {
        let values: Vec<String> = self.values.iter().map(|v| shown(v)).collect();
        format!("{} ∈ {{{}}}", self.label.short(), values.join(", "))
    }
}

/// A value for a title: as written, or to 3 significant digits when that is shorter
/// (0.006324555320336759 is 0.00632).
fn shown(field: &str) -> String {
    if field.starts_with('{') || field.starts_with('[') {
        // a whole value (an enum variant and its fields) as the scenario writes it
        if let Ok(value) = flocking::serde_json::from_str::<flocking::serde_json::Value>(field) {
            return as_scenario_writes(&value);
        }
    }
    let Some(x) = field
        .parse::<f64>()
        .ok()
        .filter(|x| x.is_finite() && *x != 0.0)
    else {
        return field.to_owned();
    };
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    let short = format!("{x:.decimals$}");
    if short.len() < field.len() {
        short
    } else {
        field.to_owned()
    }
}

/// A value of `runs.csv` as a scenario file writes it: `{"Quadrotor":{"inner_step":0.001}}` is
/// `Quadrotor(inner_step: 0.001)`, `{"Bernoulli":{"p":0.1}}` is `Bernoulli(p: 0.1)`.
fn as_scenario_writes(value: &flocking::serde_json::Value) -> String {
    use flocking::serde_json::{Map, Value};
    let fields = |map: &Map<String, Value>| {
        map.iter()
            .map(|(name, v)| format!("{name}: {}", as_scenario_writes(v)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match value {
        Value::Object(map) if map.len() == 1 => {
            let (variant, inner) = map.iter().next().expect("one entry");
            match inner {
                Value::Null => variant.clone(),
                Value::Object(inner) => format!("{variant}({})", fields(inner)),
                other => format!("{variant}({})", as_scenario_writes(other)),
            }
        }
        Value::Object(map) => format!("({})", fields(map)),
        Value::Array(items) => format!(
            "[{}]",
            items
                .iter()
                .map(as_scenario_writes)
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Value::String(text) => text.clone(),
        other => other.to_string(),
    }
}

/// "20 seeds", "1 seed".
fn seeds(count: u64) -> String {
    if count == 1 {
        "1 seed".to_owned()
    } else {
        format!("{count} seeds")
    }
}

fn plot(dir: &Path, request: &PlotRequest, out: Option<PathBuf>) -> Result<(), Failure> {
    let sweep = store::read_sweep(dir)?;
    let base = sweep
        .base_scenario()
        .map_err(|e| Failure::Usage(e.to_string()))?;
    let path = dir.join(RUNS_FILE);
    let mut reader =
        csv::Reader::from_path(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let header = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let column = |name: &str, what: &str| {
        header.iter().position(|h| h == name).ok_or_else(|| {
            Failure::Usage(format!(
                "--{what} {name:?} is not a column of {}; it has {}",
                path.display(),
                header.iter().collect::<Vec<_>>().join(", ")
            ))
        })
    };
    let axis = |name: &str, what: &str| {
        let Some(axis) = sweep.axes.iter().find(|a| a.path == name) else {
            let axes: Vec<&str> = sweep.axes.iter().map(|a| a.path.as_str()).collect();
            return Err(Failure::Usage(format!(
                "--{what} {name:?} is not an axis of the sweep; its axes are {}",
                axes.join(", ")
            )));
        };
        Ok(AxisColumn {
            column: column(name, what)?,
            values: axis.values.expand().iter().map(value_field).collect(),
            label: ParameterLabel::of(&base, name),
        })
    };
    let (cx, cm) = (column(&request.x, "x")?, column(&request.metric, "metric")?);
    // the measured columns lie between `seed` and `error`; the others are not metrics
    let measured = match (
        header.iter().position(|h| h == "seed"),
        header.iter().position(|h| h == "error"),
    ) {
        (Some(seed), Some(error)) if seed < error => seed + 1..error,
        _ => 0..header.len(),
    };
    if !measured.contains(&cm) {
        return Err(Failure::Usage(format!(
            "--metric {:?} is not a measured column of {}; the metrics are {}",
            request.metric,
            path.display(),
            header
                .iter()
                .skip(measured.start)
                .take(measured.len())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let cy = request.y.as_deref().map(|y| column(y, "y")).transpose()?;
    let mut shown_axes = vec![request.x.as_str()];
    shown_axes.extend(request.y.as_deref());
    let (facet, series) = match &request.panels {
        Some((name, series)) => {
            let what = if *series { "series" } else { "facet" };
            if shown_axes.contains(&name.as_str()) {
                return Err(Failure::Usage(format!(
                    "--{what} {name} is drawn along an axis already; give another axis"
                )));
            }
            if *series && cy.is_some() {
                return Err(Failure::Usage(format!(
                    "--series {name} draws lines on one set of axes; a heatmap (--y) takes --facet"
                )));
            }
            (Some(axis(name, what)?), *series)
        }
        None => (None, false),
    };
    shown_axes.extend(request.panels.as_ref().map(|(name, _)| name.as_str()));
    let mut fixed = Vec::new();
    for (name, value) in &request.fixed {
        if shown_axes.contains(&name.as_str())
            || fixed
                .iter()
                .any(|(a, _): &(AxisColumn, String)| a.label.path == *name)
        {
            return Err(Failure::Usage(format!(
                "--where {name}={value}: {name} is drawn or fixed already; fix another axis"
            )));
        }
        let fixed_axis = axis(name, "where")?;
        let same = |v: &String| {
            v == value
                || matches!((v.parse::<f64>(), value.parse::<f64>()), (Ok(a), Ok(b)) if a == b)
        };
        let Some(chosen) = fixed_axis.values.iter().find(|v| same(v)).cloned() else {
            return Err(Failure::Usage(format!(
                "--where {name}={value}: no run has {name} = {value}; its values are {}",
                fixed_axis.values.join(", ")
            )));
        };
        fixed.push((fixed_axis, chosen));
    }
    let pooled: Vec<AxisColumn> = sweep
        .axes
        .iter()
        .filter(|a| {
            !shown_axes.contains(&a.path.as_str())
                && !fixed.iter().any(|(f, _)| f.label.path == a.path)
        })
        .map(|a| axis(&a.path, "x"))
        .collect::<Result<_, _>>()?;

    let mut points = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
        if fixed.iter().any(|(a, value)| record[a.column] != **value) {
            continue;
        }
        let value = |c: usize, what: &str| {
            number(&record[c]).ok_or_else(|| {
                format!(
                    "{} row {}: {what} {:?} is not a number",
                    path.display(),
                    k + 1,
                    &record[c]
                )
            })
        };
        let panel = match &facet {
            Some(a) => a
                .values
                .iter()
                .position(|v| *v == record[a.column])
                .ok_or_else(|| {
                    format!(
                        "{} row {}: {} {:?} is not a value of the sweep",
                        path.display(),
                        k + 1,
                        a.label.path,
                        &record[a.column]
                    )
                })?,
            None => 0,
        };
        points.push(PhasePoint {
            x: value(cx, "x")?,
            y: cy.map(|c| value(c, "y")).transpose()?,
            value: value(cm, "the metric")?,
            panel,
        });
    }

    let metric = metric_label(&request.metric);
    let per_point = pooled
        .iter()
        .map(|a| a.values.len() as u64)
        .product::<u64>()
        * sweep.seeds;
    let mut title = if pooled.is_empty() {
        format!("{metric}: mean over {}", seeds(sweep.seeds))
    } else {
        let over: Vec<String> = pooled.iter().map(AxisColumn::among).collect();
        format!(
            "{metric}: mean over {per_point} runs pooled over {} × {}",
            over.join(" × "),
            seeds(sweep.seeds)
        )
    };
    for (a, value) in &fixed {
        title = format!("{title}, {}", a.equals(value));
    }
    if !pooled.is_empty() {
        let names: Vec<&str> = pooled.iter().map(|a| a.label.path.as_str()).collect();
        errln!(
            "warning: each point pools {per_point} runs over {}: fix {} with --where {}=VALUE, or draw one panel per value with --facet {}",
            names.join(", "),
            if names.len() == 1 { "it" } else { "them" },
            names[0],
            names[0]
        );
    }
    let label = |name: &str| ParameterLabel::of(&base, name).axis();
    let options = PhaseOptions {
        title,
        x_label: label(&request.x),
        y_label: request.y.as_deref().map(label),
        metric: metric.to_owned(),
        panels: facet
            .as_ref()
            .map_or_else(Vec::new, |a| a.values.iter().map(|v| a.equals(v)).collect()),
        log_x: request.log_x,
        log_y: request.log_y,
        band: match request.band {
            BandArg::Minmax => Band::MinMax,
            BandArg::Quantiles => Band::Quantiles,
        },
        size: if facet.is_some() && !series {
            FACET_PANEL
        } else {
            PhaseOptions::default().size
        },
        bound: request.bound.clone(),
        series,
        references: match &request.reference {
            Some(file) => references(file, facet.as_ref())?,
            None => Vec::new(),
        },
    };
    let out = out.unwrap_or_else(|| dir.join(format!("{}.svg", request.metric)));
    let bytes = match out.extension().and_then(|e| e.to_str()) {
        Some("png") => phase_png(&points, &options),
        Some("csv") => phase_table(&points, &options).map(String::into_bytes),
        _ => phase_svg(&points, &options).map(String::into_bytes),
    }
    .map_err(|e| e.to_string())?;
    // never over a file that flocking did not write
    owned::write_file(&out, &bytes).map_err(|e| match e {
        DirError::Io(e) => Failure::Failed(e.to_string()),
        refused => Failure::Usage(refused.to_string()),
    })?;
    outln!("flocking sweep plot: {}", out.display());
    Ok(())
}

/// The references of `--reference FILE` (`series,label,x,y`), the series matched to the values
/// of the panels' axis `panels`.
fn references(file: &Path, panels: Option<&AxisColumn>) -> Result<Vec<Reference>, Failure> {
    let at = |line: u64| format!("{} line {line}", file.display());
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(file)
        .map_err(|e| Failure::Usage(format!("--reference {}: {e}", file.display())))?;
    let header = reader
        .headers()
        .map_err(|e| Failure::Usage(format!("--reference {}: {e}", file.display())))?;
    if header != vec!["series", "label", "x", "y"] {
        return Err(Failure::Usage(format!(
            "--reference {}: the header is {:?}; give series,label,x,y",
            file.display(),
            header.iter().collect::<Vec<_>>().join(",")
        )));
    }
    let mut references: Vec<Reference> = Vec::new();
    let mut last: Option<(String, String)> = None;
    for record in reader.records() {
        let record = record.map_err(|e| Failure::Usage(format!("--reference {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let number = |k: usize| {
            record[k]
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    Failure::Usage(format!(
                        "{}: {:?} is not a finite number",
                        at(line),
                        &record[k]
                    ))
                })
        };
        let point = (number(2)?, number(3)?);
        let key = (record[0].to_owned(), record[1].to_owned());
        if last.as_ref() == Some(&key) {
            references
                .last_mut()
                .expect("the last reference")
                .points
                .push(point);
            continue;
        }
        let series = match (record[0].is_empty(), panels) {
            (true, _) => None,
            (false, Some(axis)) => Some(
                axis.values
                    .iter()
                    .position(|v| {
                        *v == record[0]
                            || matches!((v.parse::<f64>(), record[0].parse::<f64>()), (Ok(a), Ok(b)) if a == b)
                    })
                    .ok_or_else(|| {
                        Failure::Usage(format!(
                            "{}: series {:?} is not a value of {}; its values are {}",
                            at(line),
                            &record[0],
                            axis.label.path,
                            axis.values.join(", ")
                        ))
                    })?,
            ),
            (false, None) => {
                return Err(Failure::Usage(format!(
                    "{}: a series ({:?}) needs --series or --facet",
                    at(line),
                    &record[0]
                )));
            }
        };
        references.push(Reference {
            label: key.1.clone(),
            series,
            points: vec![point],
        });
        last = Some(key);
    }
    Ok(references)
}

/// The size of each panel of a faceted diagram.
const FACET_PANEL: (u32, u32) = (560, 420);

#[cfg(test)]
mod tests {
    use super::shown;

    /// A panel's value as the scenario writes it: an enum variant with its fields, a bare one,
    /// numbers shortened, text as it is.
    #[test]
    fn values_are_shown_as_the_scenario_writes_them() {
        assert_eq!(
            shown(r#"{"Quadrotor":{"inner_step":0.001}}"#),
            "Quadrotor(inner_step: 0.001)"
        );
        assert_eq!(shown(r#"{"Bernoulli":{"p":0.1}}"#), "Bernoulli(p: 0.1)");
        assert_eq!(shown("PointMass"), "PointMass");
        assert_eq!(shown("0.123456789"), "0.123");
    }
}

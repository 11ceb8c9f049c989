//! `flocking sweep`: a sweep file run on this machine's cores (or one shard of it), its shards merged,
//! and its phase diagrams drawn. The sweep itself is the `flocking` library's ([`flocking::sweep`]).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

use clap::{Args, Subcommand, ValueEnum};
use flock_viz::phase::{Band, Bound};
use flock_viz::{SweepPlot, SweepPlotError, plot_sweep};
use flocking::estimate::Outputs;
use flocking::sweep::store::{self, RUNS_FILE, StoreError};
use flocking::sweep::{ExecuteOptions, RunRow, Shard, Sweep, execute, share};
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
        /// The axis along x (a parameter path of the sweep; an axis of names, such as `algorithm`,
        /// `vehicle` or a loss model, is drawn as categories in the sweep's order).
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
        /// One series per value of this axis overlaid on one set of axes (a line diagram): a
        /// colour and a marker each, with a legend.
        #[arg(long, value_name = "AXIS", visible_alias = "overlay")]
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
        /// Logarithmic x axis (when every x drawn is positive).
        #[arg(long)]
        log_x: bool,
        /// Logarithmic y axis: a line diagram's metric, a heatmap's y (when every value is positive).
        #[arg(long)]
        log_y: bool,
        /// Logarithmic colour scale (a heatmap of positive values).
        #[arg(long)]
        log_colour: bool,
        /// A heatmap's numeric axes in equal cells, in the order of their values (each cell is
        /// otherwise at its value): for values crowded at one end that include 0, such as delays
        /// 0, 0.01, …, 0.8, which --log-x cannot spread.
        #[arg(long)]
        even_cells: bool,
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
            log_colour,
            even_cells,
            bound,
            bound_label,
        }) => {
            let request = SweepPlot {
                x,
                y,
                fixed,
                facet,
                series,
                reference,
                metric,
                band: match band {
                    BandArg::Minmax => Band::MinMax,
                    BandArg::Quantiles => Band::Quantiles,
                },
                log_x,
                log_y,
                log_colour,
                even_cells,
                bound: bound.map(|x| Bound {
                    x,
                    label: bound_label,
                }),
            };
            plot(&dir, &request, out.as_deref())
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

/// Draws `flocking sweep plot`'s diagram ([`plot_sweep`]), its warnings on stderr.
fn plot(dir: &Path, request: &SweepPlot, out: Option<&Path>) -> Result<(), Failure> {
    let plotted = plot_sweep(dir, request, out).map_err(|e| match e {
        SweepPlotError::Refused(message) => Failure::Usage(message),
        SweepPlotError::Failed(message) => Failure::Failed(message),
    })?;
    for warning in &plotted.warnings {
        errln!("warning: {warning}");
    }
    outln!("flocking sweep plot: {}", plotted.path.display());
    Ok(())
}

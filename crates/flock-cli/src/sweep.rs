//! `flocking sweep`: a sweep file run on this machine's cores (or one shard of it), its shards merged,
//! and its phase diagrams drawn. The sweep itself is the `flocking` library's ([`flocking::sweep`]).

use std::fs;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

use clap::{Args, Subcommand, ValueEnum};
use flock_viz::phase::{Band, PhaseOptions, PhasePoint, phase_png, phase_svg};
use flocking::sweep::store::{self, RUNS_FILE};
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
    /// Workers, each running one single-threaded run at a time (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
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
    /// a line with a band on one.
    Plot {
        /// The sweep's output directory.
        dir: PathBuf,
        /// The axis along x (a parameter path of the sweep).
        #[arg(long)]
        x: String,
        /// The axis along y (a heatmap).
        #[arg(long)]
        y: Option<String>,
        /// The runs.csv column to draw (alpha_flock and strict_alpha_flock count as 1 or 0: their
        /// mean is the fraction of seeds that flock).
        #[arg(long)]
        metric: String,
        /// The figure (.svg or .png; default DIR/<metric>.svg).
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

/// Runs `flocking sweep …`.
pub fn main(args: SweepArgs, stop: &AtomicBool) -> ExitCode {
    let result = match args.action {
        Some(SweepAction::Merge { out, shards }) => merge(&out, &shards),
        Some(SweepAction::Plot {
            dir,
            x,
            y,
            metric,
            out,
            band,
            log_x,
            log_y,
        }) => plot(&dir, &x, y.as_deref(), &metric, out, band, (log_x, log_y)),
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
            run(&sweep, &out, &options, args.quiet, stop)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(
    path: &Path,
    out: &Path,
    options: &ExecuteOptions,
    quiet: bool,
    stop: &AtomicBool,
) -> Result<(), String> {
    let sweep = Sweep::load(path).map_err(|e| e.to_string())?;
    let (done, pending) = share(&sweep, out, options.shard).map_err(|e| e.to_string())?;
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
            bar.suspend(|| eprintln!("run {} ({}): {error}", row.index, row.id));
        }
        bar.inc(1);
    };
    let executed = execute(&sweep, out, options, stop, &done).map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    println!(
        "flocking sweep: {} run(s) now, {} found done, {} failed; {} row(s) in {}",
        executed.ran,
        executed.skipped,
        failed.into_inner(),
        executed.rows,
        out.join(RUNS_FILE).display()
    );
    if executed.stopped {
        return Err(format!(
            "stopped before every run finished; the same command resumes from {}",
            out.display()
        ));
    }
    Ok(())
}

fn merge(out: &Path, shards: &[PathBuf]) -> Result<(), String> {
    let rows = store::merge(out, shards).map_err(|e| e.to_string())?;
    println!(
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

fn plot(
    dir: &Path,
    x: &str,
    y: Option<&str>,
    metric: &str,
    out: Option<PathBuf>,
    band: BandArg,
    (log_x, log_y): (bool, bool),
) -> Result<(), String> {
    let sweep = store::read_sweep(dir).map_err(|e| e.to_string())?;
    let path = dir.join(RUNS_FILE);
    let mut reader =
        csv::Reader::from_path(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let header = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let column = |name: &str, what: &str| {
        header.iter().position(|h| h == name).ok_or_else(|| {
            format!(
                "--{what} {name:?} is not a column of {}; it has {}",
                path.display(),
                header.iter().collect::<Vec<_>>().join(", ")
            )
        })
    };
    let (cx, cm) = (column(x, "x")?, column(metric, "metric")?);
    let cy = y.map(|y| column(y, "y")).transpose()?;
    let mut points = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
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
        points.push(PhasePoint {
            x: value(cx, "x")?,
            y: cy.map(|c| value(c, "y")).transpose()?,
            value: value(cm, "the metric")?,
        });
    }
    let options = PhaseOptions {
        title: if sweep.name.is_empty() {
            format!("{metric}, mean over {} seed(s)", sweep.seeds)
        } else {
            format!(
                "{}: {metric}, mean over {} seed(s)",
                sweep.name, sweep.seeds
            )
        },
        x_label: x.to_owned(),
        y_label: y.map(str::to_owned),
        metric: metric.to_owned(),
        log_x,
        log_y,
        band: match band {
            BandArg::Minmax => Band::MinMax,
            BandArg::Quantiles => Band::Quantiles,
        },
        ..PhaseOptions::default()
    };
    let out = out.unwrap_or_else(|| dir.join(format!("{metric}.svg")));
    let bytes = if out.extension().is_some_and(|e| e == "png") {
        phase_png(&points, &options)
    } else {
        phase_svg(&points, &options).map(String::into_bytes)
    }
    .map_err(|e| e.to_string())?;
    fs::write(&out, bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    println!("flocking sweep plot: {}", out.display());
    Ok(())
}

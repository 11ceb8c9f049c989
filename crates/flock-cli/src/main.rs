//! `flocking`: run flocking scenarios from RON files.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::{Parser, Subcommand};
use flock_cli::summary::padded;
use flock_cli::{Progress, Report, errln, out, outln};
use flock_viz::{FigureOptions, Output, plot_run_with};
use flocking::bench::BenchError;
use flocking::estimate::Outputs;
use flocking::metrics::{Closest, FlockingCriteria};
use flocking::run_dir::{CreateError, ResumeError, read_records};
use flocking::workload::{WorkloadConfig, time_seeds};
use flocking::{
    DynSimulation, OutputOptions, RunDirectory, RunError, Scenario, ScenarioProtocol, Start,
    TrajectoryFormat,
};

/// Flocking simulations of Olfati-Saber (TAC 2006) and relatives, from RON scenario files.
#[derive(Debug, Parser)]
#[command(name = "flocking", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a scenario and write metrics.csv, the trajectory, final.csv and scenario.ron to DIR
    /// (through DIR.partial, which holds a killed or interrupted run until `--resume DIR`).
    #[command(
        override_usage = "flocking run [OPTIONS] <SCENARIO>\n       flocking run --resume <DIR> [OPTIONS]"
    )]
    Run {
        /// The scenario file (.ron); required unless --resume.
        #[arg(required_unless_present = "resume")]
        scenario: Option<PathBuf>,
        /// The output directory (default: `out/<scenario file stem>`).
        #[arg(long, conflicts_with = "resume")]
        out: Option<PathBuf>,
        /// Change a value of the scenario before it is used: PATH a dotted parameter path as in
        /// sweeps (`agents`, `algorithm.c1`, `vehicle.max_bank`), VALUE a JSON number, bool or
        /// list, else RON text for the enums of the conditions (`Bernoulli(p: 0.1)`); repeatable.
        #[arg(long = "set", value_name = "PATH=VALUE", value_parser = parse_set, conflicts_with = "resume")]
        set: Vec<(String, serde_json::Value)>,
        /// Replace an existing output directory that flocking wrote (never one holding anything
        /// else, the working directory, its parents or a mount point).
        #[arg(long, conflicts_with = "resume")]
        force: bool,
        /// Continue the interrupted or killed run DIR (or DIR.partial) from its last checkpoint;
        /// the outputs are bit-identical to those of an uninterrupted run.
        #[arg(long, value_name = "DIR", conflicts_with = "scenario")]
        resume: Option<PathBuf>,
        /// The trajectory's format: csv (trajectory.csv) or npy (trajectory.npy, for large runs;
        /// `numpy.load` reads it).
        #[arg(long, default_value = "csv", conflicts_with = "resume")]
        trajectory_format: TrajectoryFormat,
        /// Keep a checkpoint every N steps for `--resume` (0: only on Ctrl-C).
        #[arg(long, value_name = "N", default_value_t = 1000)]
        checkpoint_every: u64,
        /// Worker threads (default: all cores; at most 4 per core); results are identical for any count.
        #[arg(long, value_parser = flock_cli::resources::parse_threads)]
        threads: Option<usize>,
        /// Start even when the estimated memory or disk exceeds what this machine has free, or the
        /// start is too dense to estimate.
        #[arg(long)]
        no_resource_check: bool,
        /// Also draw the run's figures into DIR/figures (as `flocking plot DIR`).
        #[arg(long)]
        plot: bool,
        /// With --plot: colour each edge by the sign of its stress weight (as `flocking plot`).
        #[arg(long, requires = "plot")]
        stress_edges: bool,
        /// With --plot: the figures to draw, some of snapshots, metrics, gif, player (as
        /// `flocking plot --outputs`; default all).
        #[arg(long, value_name = "LIST", requires = "plot", value_delimiter = ',')]
        plot_outputs: Option<Vec<Output>>,
        /// With --plot: the snapshot times in seconds, e.g. `0,5,10` (as `flocking plot --times`).
        #[arg(long, value_name = "LIST", requires = "plot", value_delimiter = ',', value_parser = parse_time)]
        plot_times: Option<Vec<f64>>,
        /// No progress bar (it is shown only on a terminal, for runs longer than about a second).
        #[arg(long)]
        quiet: bool,
        /// ε₁ of TAC 2006 Definition 5 (Ẽ ≤ ε₁), judged over the last quarter in flocking.txt.
        #[arg(long, value_name = "E1", default_value_t = 0.01, value_parser = flock_cli::resources::parse_epsilon)]
        epsilon1: f64,
        /// ε₂ of TAC 2006 Definition 5, relative to the group's speed: K̃ ≤ ε₂ ‖p_c‖² (for a group
        /// at rest, relative to the speed of its approach; docs/outputs.md).
        #[arg(long, value_name = "E2", default_value_t = 0.01, value_parser = flock_cli::resources::parse_epsilon)]
        epsilon2: f64,
        /// The fraction of the duration after which the run has settled: the summary gives the
        /// least distance and the most colliding pairs over the whole run and from then on.
        #[arg(long, value_name = "FRACTION", default_value_t = Closest::SETTLE, value_parser = parse_settle)]
        settle: f64,
    },
    /// Run every `fixtures/*.ron` (relative to the current directory) into `DIR/<fixture stem>/`,
    /// draw its figures (GIF and trajectory CSVs dropped), and write `DIR/index.html`, a static page
    /// of the papers' figures and final metrics.
    Figures {
        /// The output directory (default `figures` in the current directory; the repository's
        /// gallery is regenerated with `--out docs/figures --no-player`).
        #[arg(long, default_value = "figures")]
        out: PathBuf,
        /// Print nothing but errors.
        #[arg(long)]
        quiet: bool,
        /// Drop each run's player.html (most of the bytes; the committed gallery has none).
        #[arg(long)]
        no_player: bool,
    },
    /// Draw the figures of a finished run into DIR/figures: snapshots (SVG, PNG), the metric curves
    /// of TAC 2006 Fig. 18, an animated GIF and a self-contained HTML player.
    Plot {
        /// A run directory written by `flocking run`.
        dir: PathBuf,
        /// Colour each edge by the sign of its stress weight (ACC 2004, Reynolds' rules): orange
        /// beyond d (attraction, F⁺), purple within (repulsion, F⁻), grey within 1 % of d (F⁰).
        #[arg(long)]
        stress_edges: bool,
        /// For a Flocking2003 run, the time (s) of `reynolds.svg/png`, ACC 2004's reading of the
        /// (α, α) protocol as Reynolds's rules (the record nearest it); default the second of the
        /// scenario's `snapshots`, else a tenth of the run.
        #[arg(long, value_name = "T")]
        reynolds_at: Option<f64>,
        /// The figures to draw, separated by commas: some of snapshots (with the 3D views and
        /// an (α, α) run's Reynolds reading), metrics, gif, player; default all.
        #[arg(long, value_name = "LIST", value_delimiter = ',')]
        outputs: Option<Vec<Output>>,
        /// The snapshot times in seconds, separated by commas (`0,5,10`), each drawn at the record
        /// nearest it; default the scenario's `snapshots`, else six even times. A time outside
        /// the run is refused.
        #[arg(long, value_name = "LIST", value_delimiter = ',', value_parser = parse_time)]
        times: Option<Vec<f64>>,
        /// No progress spinner (it is shown only on a terminal).
        #[arg(long)]
        quiet: bool,
    },
    /// Run a sweep file — a scenario over a grid of parameter values × seeds — into DIR/runs.csv,
    /// one row per run; or merge its shards, or plot its phase diagrams.
    Sweep(flock_cli::sweep::SweepArgs),
    /// Check a scenario file and print it with every default filled in to standard output (a
    /// scenario file that validates and runs as the original), its warnings to standard error.
    Validate {
        /// The scenario file (.ron).
        scenario: PathBuf,
        /// Change a value of the scenario before it is used: PATH a dotted parameter path as in
        /// sweeps (`agents`, `algorithm.c1`, `vehicle.max_bank`), VALUE a JSON number, bool or
        /// list, else RON text for the enums of the conditions (`Bernoulli(p: 0.1)`); repeatable.
        #[arg(long = "set", value_name = "PATH=VALUE", value_parser = parse_set)]
        set: Vec<(String, serde_json::Value)>,
    },
    /// Time a synthetic scenario of n agents on an α-lattice and print agent-steps/s and memory.
    Bench {
        /// The number of agents.
        #[arg(long, default_value_t = 100_000, conflicts_with = "workload")]
        n: usize,
        /// The dimension, 2 or 3.
        #[arg(long, default_value_t = 2, conflicts_with = "workload")]
        dim: usize,
        /// Timed steps (metrics recorded every 10).
        #[arg(long, default_value_t = 20, conflicts_with = "workload")]
        steps: u64,
        /// The algorithm: 1, 2 or 3 (3 adds 1,000 obstacles).
        #[arg(long, default_value = "2", conflicts_with = "workload")]
        algorithm: flocking::bench::BenchAlgorithm,
        /// Worker threads (default: all cores; at most 4 per core).
        #[arg(long, value_parser = flock_cli::resources::parse_threads)]
        threads: Option<usize>,
        /// Untimed steps before the timed ones.
        #[arg(long, default_value_t = 3, conflicts_with = "workload")]
        warmup: u64,
        /// Number the agents at random instead of along the lattice (as random initial states are).
        #[arg(long, conflicts_with = "workload")]
        shuffled: bool,
        /// Real conditions to run under (none: the ideal loop).
        #[command(flatten)]
        conditions: flock_cli::bench::ConditionFlags,
        /// Fly the agents on this vehicle with its default parameters (docs/vehicles.md):
        /// unicycle (2D), fixed-wing, quadrotor (3D); default point masses.
        #[arg(long, value_parser = flock_cli::bench::vehicle_parser(), conflicts_with = "workload")]
        vehicle: Option<flocking::bench::BenchVehicle>,
        /// Instead of the α-lattice, a workload of the ABM frameworks' boids benchmark
        /// (ABMFrameworksComparison's Flocking/DECLARATION.md), or the Vicsek model at its paper's
        /// density (fixtures/vicsek1995_fig2a_n400.ron): 100 steps timed from a fresh start per
        /// seed, the median printed. The flags of the α-lattice do not apply to it.
        #[arg(long, value_parser = flock_cli::bench::workload_parser())]
        workload: Option<flocking::workload::Workload>,
        /// With --workload: the number of seeds timed (at least 1).
        #[arg(long, default_value_t = 10, requires = "workload", value_parser = clap::value_parser!(u64).range(1..))]
        seeds: u64,
        /// With --workload: this many agents at the workload's density (its box grown to hold them).
        #[arg(long, requires = "workload")]
        scale_to: Option<usize>,
        /// Start even when the estimated memory exceeds what this machine has free, or the start
        /// is too dense to estimate (as `flocking run --no-resource-check`).
        #[arg(long)]
        no_resource_check: bool,
    },
}

/// Exit code of an invalid scenario.
const INVALID: u8 = 2;

/// `flocking bench`: checks the flags, prints the estimate and refuses what does not fit (unless
/// `unchecked`), then times the α-lattice of `config` or the `workload` and prints the report.
fn bench(
    config: &flocking::bench::BenchConfig,
    workload: Option<WorkloadConfig>,
    unchecked: bool,
) -> ExitCode {
    let estimate = match workload {
        Some(workload) => workload.estimate(),
        None => config.check().map(|()| config.estimate()),
    };
    let estimate = match estimate {
        Ok(estimate) => estimate,
        Err(e) => return bench_failed(&e),
    };
    if let Err(e) = flock_cli::resources::announce(&estimate, None, (unchecked, false)) {
        errln!("error: {e}");
        return ExitCode::from(INVALID);
    }
    let report = match workload {
        Some(workload) => workload
            .scenario()
            .and_then(|s| time_seeds(&s, workload.seeds))
            .map(|report| report.to_string()),
        None => flocking::bench::bench(config).map(|report| report.to_string()),
    };
    match report {
        Ok(report) => {
            outln!("{report}");
            ExitCode::SUCCESS
        }
        Err(e) => bench_failed(&e),
    }
}

/// Prints why a benchmark did not run, a flag as the command writes it (`--scale-to`), and
/// returns the exit code: 2 for a refused flag, 1 for memory this machine could not give, 130
/// for Ctrl-C.
fn bench_failed(error: &BenchError) -> ExitCode {
    let message = error.with_flag(|flag, value| format!("--{} {value}", flag.replace('_', "-")));
    match error {
        BenchError::Invalid { .. } => {
            errln!("error: {message}");
            ExitCode::from(INVALID)
        }
        BenchError::Memory(_) => {
            errln!("error: {message}");
            ExitCode::FAILURE
        }
        BenchError::Interrupted => ExitCode::from(INTERRUPTED),
    }
}

fn main() -> ExitCode {
    let command = Cli::parse().command;
    // reading and checking can be interrupted at once: nothing is written yet
    stop_on_ctrl_c();
    let code = dispatch(command);
    // what the command printed did not reach its reader (a full disk behind a redirection)
    if flock_cli::console::stdout_failed() && code == ExitCode::SUCCESS {
        return ExitCode::FAILURE;
    }
    code
}

/// Runs `command` and returns its exit code.
fn dispatch(command: Command) -> ExitCode {
    match command {
        Command::Bench {
            n,
            dim,
            steps,
            algorithm,
            threads,
            warmup,
            shuffled,
            conditions,
            vehicle,
            workload,
            seeds,
            scale_to,
            no_resource_check,
        } => {
            if let Err(code) = use_threads(threads) {
                return code;
            }
            let config = flocking::bench::BenchConfig {
                n,
                dim,
                steps,
                warmup,
                algorithm,
                shuffled,
                conditions: conditions.into(),
                vehicle,
            };
            let workload = workload.map(|workload| WorkloadConfig {
                workload,
                seeds,
                scale_to,
            });
            bench(&config, workload, no_resource_check)
        }
        Command::Plot {
            dir,
            stress_edges,
            reynolds_at,
            outputs,
            times,
            quiet,
        } => {
            if let Err(e) = flock_viz::plot::check_plot_dir(&dir) {
                errln!("error: {e}");
                return ExitCode::from(INVALID);
            }
            let options = FigureOptions {
                reynolds_time: reynolds_at,
                ..FigureOptions::plot(outputs, times, stress_edges)
            };
            match plot(&dir, &options, quiet) {
                Ok(files) => {
                    outln!(
                        "{} in {}",
                        files_count(files.len()),
                        dir.join("figures").display()
                    );
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    errln!("error: {e}");
                    if e.is_refusal() {
                        ExitCode::from(INVALID)
                    } else {
                        ExitCode::FAILURE
                    }
                }
            }
        }
        Command::Figures {
            out,
            quiet,
            no_player,
        } => match flock_cli::figures(std::path::Path::new("fixtures"), &out, quiet, !no_player) {
            Ok(_) => ExitCode::SUCCESS,
            Err(e) => {
                errln!("error: {e}");
                if e.is_refusal() {
                    ExitCode::from(INVALID)
                } else {
                    ExitCode::FAILURE
                }
            }
        },
        Command::Sweep(args) => flock_cli::sweep::main(args, &WRITING),
        Command::Validate { scenario, set } => match load(&scenario, &set) {
            Ok(s) => {
                errln!("{}: valid", scenario.display());
                let resolved = s.clone().resolved();
                out!("{}", resolved.to_ron().unwrap_or_default());
                outln!();
                let estimate = s.estimate_at_start(&Outputs::RUN);
                errln!("{estimate}");
                if let Err(e) = flock_cli::resources::check(&estimate, None, (false, false)) {
                    errln!("warning: {e}");
                    // the stable step and the warnings build the initial net of every agent,
                    // which does not fit either (issue 27)
                    errln!(
                        "warning: the stable step and the start's warnings are not estimated: they need the initial net of every agent"
                    );
                    return ExitCode::SUCCESS;
                }
                if let Some(stable) = flocking::largest_stable_step(&s) {
                    errln!(
                        "step {} against the estimated largest stable step {stable:.3e}",
                        s.step
                    );
                }
                for warning in s.warnings() {
                    errln!("{warning}");
                }
                ExitCode::SUCCESS
            }
            Err(code) => code,
        },
        Command::Run {
            scenario,
            out,
            set,
            force,
            resume,
            trajectory_format,
            checkpoint_every,
            threads,
            no_resource_check,
            plot,
            stress_edges,
            plot_outputs,
            plot_times,
            quiet,
            epsilon1,
            epsilon2,
            settle,
        } => {
            if let Err(code) = use_threads(threads) {
                return code;
            }
            let opened = match (resume, scenario) {
                (Some(dir), _) => resume_directory(&dir, checkpoint_every, no_resource_check),
                (None, Some(scenario)) => {
                    let out = out.unwrap_or_else(|| {
                        PathBuf::from("out").join(scenario.file_stem().unwrap_or_default())
                    });
                    let options = OutputOptions {
                        force,
                        format: trajectory_format,
                        checkpoint_every,
                    };
                    create_directory(&scenario, &set, &out, &options, no_resource_check)
                }
                (None, None) => unreachable!("clap requires a scenario unless --resume is given"),
            };
            let (dir, sim, start) = match opened {
                Ok(opened) => opened,
                Err(code) => return code,
            };
            let criteria = FlockingCriteria {
                epsilon1,
                epsilon2,
                ..FlockingCriteria::default()
            };
            let dir = dir.with_criteria(criteria);
            match execute(sim, dir, start.as_ref(), quiet, settle) {
                Ok(out) if plot => match self::plot(
                    &out,
                    &FigureOptions::plot(plot_outputs, plot_times, stress_edges),
                    quiet,
                ) {
                    Ok(files) => {
                        outln!(
                            "  {} {} in {}",
                            padded("figures"),
                            files_count(files.len()),
                            out.join("figures").display()
                        );
                        ExitCode::SUCCESS
                    }
                    Err(e) => {
                        errln!("error: the run is complete, but its figures failed: {e}");
                        errln!("draw them again with `flocking plot {}`", out.display());
                        if e.is_refusal() {
                            ExitCode::from(INVALID)
                        } else {
                            ExitCode::FAILURE
                        }
                    }
                },
                Ok(_) => ExitCode::SUCCESS,
                Err(code) => code,
            }
        }
    }
}

/// Set once outputs are being written; before, Ctrl-C (or SIGTERM) quits at once.
static WRITING: AtomicBool = AtomicBool::new(false);

/// Exit code of a run stopped by Ctrl-C (128 + SIGINT).
const INTERRUPTED: u8 = 130;

/// Before anything is written (reading, validating, estimating, a benchmark) Ctrl-C quits at
/// once; then the first Ctrl-C requests the library's interrupt ([`flocking::interrupt`]): the
/// run stops cleanly after the current step, or, when that step is still running half a second
/// later, cuts it short and goes back to its last checkpoint; a second one quits at once (the
/// partial directory then still holds whole records and the last checkpoint).
fn stop_on_ctrl_c() {
    let installed = ctrlc::set_handler(|| {
        if !WRITING.load(Ordering::SeqCst) || flocking::interrupt::request() {
            std::process::exit(i32::from(INTERRUPTED));
        }
        errln!(
            "\nstopping after the current step, or within a second if it is long (Ctrl-C again to quit at once)"
        );
    });
    if let Err(e) = installed {
        errln!("warning: Ctrl-C will not stop the run cleanly: {e}");
    }
}

/// A run to start or continue: its directory, its simulation (built before the directory is
/// written, so that a refusal leaves nothing behind) and the checkpoint it continues from.
type Opened = (RunDirectory, DynSimulation, Option<Start>);

/// Loads and checks a scenario, prints its warnings and estimate, refuses it when it does not
/// fit (unless `unchecked`), builds its simulation and starts its output directory.
fn create_directory(
    path: &Path,
    set: &[(String, serde_json::Value)],
    out: &Path,
    options: &OutputOptions,
    unchecked: bool,
) -> Result<Opened, ExitCode> {
    let scenario = load(path, set)?;
    let outputs = Outputs {
        trajectory_csv: Some(options.format == TrajectoryFormat::Csv),
        ..Outputs::RUN
    };
    check_resources(&scenario, &outputs, out, unchecked)?;
    for warning in scenario.warnings() {
        errln!("{warning}");
    }
    let sim = DynSimulation::new(&scenario).map_err(|e| {
        errln!("error: {e}");
        refusal(&e)
    })?;
    WRITING.store(true, Ordering::SeqCst);
    let dir = RunDirectory::create_with(out, &scenario, options).map_err(|e| match e {
        CreateError::Occupied { target } => {
            errln!(
                "error: output directory {} holds an earlier run; choose another --out or pass --force to replace it",
                target.display()
            );
            ExitCode::from(INVALID)
        }
        CreateError::Interrupted { partial, target } => {
            errln!(
                "error: {} holds an interrupted run; continue it with `flocking run --resume {}`, or pass --force to start over",
                partial.display(),
                target.display()
            );
            ExitCode::from(INVALID)
        }
        e @ CreateError::NotADirectory { .. } => {
            errln!("error: {e}");
            ExitCode::from(INVALID)
        }
        CreateError::Dir(e) => {
            errln!("error: {e}");
            ExitCode::from(INVALID)
        }
        CreateError::Io(e) => {
            errln!("error: {e}");
            ExitCode::FAILURE
        }
    })?;
    Ok((dir, sim, None))
}

/// The scenario file at `path` with the values of `--set` (path, value) changed, or the exit code
/// 2 once its error is printed: the file's, at its line and column, or the change's, naming its
/// path (and the paths there are).
fn load(path: &Path, set: &[(String, serde_json::Value)]) -> Result<Scenario, ExitCode> {
    let refuse = |message: String| {
        errln!("error: {message}");
        ExitCode::from(INVALID)
    };
    let scenario = Scenario::load(path).map_err(|e| refuse(e.to_string()))?;
    if set.is_empty() {
        return Ok(scenario);
    }
    scenario
        .with_values(set.iter().cloned())
        .map_err(|e| refuse(format!("--set: {e}")))
}

/// `--set PATH=VALUE`: VALUE read as JSON (a number, a bool, a list), else kept as text, which
/// [`Scenario::with_values`] reads as RON at the enum paths of the conditions
/// (`Bernoulli(p: 0.1)`), as Python's `with_values` does.
fn parse_set(text: &str) -> Result<(String, serde_json::Value), String> {
    let Some((path, value)) = text.split_once('=') else {
        return Err(format!(
            "{text:?}: write PATH=VALUE, e.g. `--set agents=20` or `--set conditions.communication.loss='Bernoulli(p: 0.1)'`"
        ));
    };
    let value = serde_json::from_str(value.trim())
        .unwrap_or_else(|_| serde_json::Value::String(value.trim().to_owned()));
    Ok((path.trim().to_owned(), value))
}

/// Prints the estimate of `scenario` writing `outputs` into `out` and refuses it when it does not
/// fit (unless `unchecked`): before the warnings, which build the initial net of every agent
/// (issue 27); the start's net is counted (in constant memory per agent) only when the estimate
/// without it fits.
fn check_resources(
    scenario: &Scenario,
    outputs: &Outputs,
    out: &Path,
    unchecked: bool,
) -> Result<(), ExitCode> {
    let estimate = scenario.estimate_at_start(outputs);
    flock_cli::resources::announce(&estimate, Some(out), (unchecked, false)).map_err(|e| {
        errln!("error: {e}");
        ExitCode::from(INVALID)
    })
}

/// Reopens an interrupted run directory at its last checkpoint: checks it, its estimate (unless
/// `unchecked`) and the state it continues from, and rebuilds its simulation, all before
/// anything is written (issue 49: a refused resume deleted `DIR.partial`).
fn resume_directory(
    dir: &Path,
    checkpoint_every: u64,
    unchecked: bool,
) -> Result<Opened, ExitCode> {
    let (interrupted, scenario, start) =
        RunDirectory::resume(dir, checkpoint_every).map_err(|e| {
            if let ResumeError::Tidied { .. } = &e {
                outln!("{e}");
                return ExitCode::SUCCESS;
            }
            match &e {
                ResumeError::Nothing {
                    partial,
                    target,
                    complete: false,
                } => errln!(
                    "error: there is no interrupted run at {}: start it with `flocking run SCENARIO --out {}`",
                    partial.display(),
                    target.display()
                ),
                _ => errln!("error: {e}"),
            }
            match e {
                ResumeError::Scenario(_)
                | ResumeError::Nothing { .. }
                | ResumeError::Refused(_)
                | ResumeError::Dir(_) => ExitCode::from(INVALID),
                ResumeError::Tidied { .. } => ExitCode::SUCCESS,
                ResumeError::Io(_) => ExitCode::FAILURE,
            }
        })?;
    let partial = interrupted.partial().to_owned();
    let kept = || {
        errln!(
            "{} is kept as it was; nothing was written",
            partial.display()
        );
    };
    let outputs = Outputs {
        trajectory_csv: Some(!partial.join("trajectory.npy").exists()),
        ..Outputs::RUN
    };
    check_resources(&scenario, &outputs, &partial, unchecked).inspect_err(|_| kept())?;
    let sim =
        DynSimulation::build_with(&scenario, start.as_ref(), &ScenarioProtocol).map_err(|e| {
            errln!(
                "error: the checkpoint in {} cannot be continued: {e}",
                partial.display()
            );
            kept();
            refusal(&e)
        })?;
    WRITING.store(true, Ordering::SeqCst);
    let dir = interrupted.reopen().map_err(|e| {
        errln!("error: {e}");
        ExitCode::FAILURE
    })?;
    match &start {
        Some(start) => outln!(
            "resuming {} at step {} of {}",
            dir.partial().display(),
            start.steps,
            scenario.steps()
        ),
        None => outln!(
            "resuming {}: no checkpoint yet, starting over",
            dir.partial().display()
        ),
    }
    Ok((dir, sim, start))
}

/// The exit code of a simulation that cannot be built: 2 for a value out of its domain, 1 for
/// memory this machine could not give ([`flocking::ScenarioError::is_memory`]).
fn refusal(error: &flocking::ScenarioError) -> ExitCode {
    if error.is_memory() {
        ExitCode::FAILURE
    } else {
        ExitCode::from(INVALID)
    }
}

/// `--settle`: a fraction in [0, 1).
fn parse_settle(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(f) if (0.0..1.0).contains(&f) => Ok(f),
        _ => Err(format!(
            "{text:?}: give the fraction of the duration after which the run has settled, in [0, 1)"
        )),
    }
}

/// Runs into `dir` and reports (settled after `settle` of the duration); on failure keeps what
/// was written, marked incomplete, and returns the exit code.
fn execute(
    sim: DynSimulation,
    dir: RunDirectory,
    start: Option<&Start>,
    quiet: bool,
    settle: f64,
) -> Result<PathBuf, ExitCode> {
    let scenario = &sim.scenario().clone();
    let mut recorder = Progress::for_terminal(dir, scenario, quiet)
        .starting_at(start.map_or(0, |start| start.steps));
    let result = flocking::run_from(sim, start.map(|start| start.initial_energy), &mut recorder);
    let dir = recorder.into_inner();
    let error = match result {
        Ok(summary) => {
            let finished = dir.finish().map_err(|e| {
                errln!("error: {e}");
                ExitCode::FAILURE
            })?;
            let metrics = finished.path.join("metrics.csv");
            let records = read_records(&metrics, summary.agents).map_err(|e| {
                errln!("error: {}: {e}", metrics.display());
                ExitCode::FAILURE
            })?;
            outln!(
                "{}",
                Report {
                    name: &scenario.name,
                    summary: &summary,
                    records: &records,
                    settled_from: settle * scenario.duration,
                }
            );
            // judged on the whole metrics.csv, also after a resume
            if let Some(verdict) = &finished.verdict {
                outln!("  {} {verdict}", padded(verdict.label()));
            }
            outln!("  {} {}", padded("outputs"), finished.path.display());
            return Ok(finished.path);
        }
        Err(error) => error,
    };
    errln!("error: {error}");
    let (why, resumable, code) = match &error {
        // the simulation was built before the run began: its directory is kept as it is
        RunError::Scenario(_) => (error.to_string(), true, ExitCode::from(INVALID)),
        RunError::Numerical(_) => (error.to_string(), false, ExitCode::FAILURE),
        RunError::Record(e) => (format!("writing failed: {e}"), true, ExitCode::FAILURE),
        RunError::Interrupted { .. } => (
            format!("{error} by Ctrl-C"),
            true,
            ExitCode::from(INTERRUPTED),
        ),
    };
    let partial_path = dir.partial().to_owned();
    match dir.keep_incomplete(&why, resumable) {
        Ok(partial) if resumable => errln!(
            "the records so far are kept in {}; continue with `flocking run --resume {}`",
            partial.display(),
            partial.display()
        ),
        Ok(partial) => errln!(
            "the records up to the last good step are kept in {}, marked incomplete",
            partial.display()
        ),
        Err(e) if resumable => errln!(
            "error: cannot mark the run incomplete: {e}\nthe records so far are kept in {}; continue with `flocking run --resume {}`",
            partial_path.display(),
            partial_path.display()
        ),
        Err(e) => errln!("error: cannot mark the run incomplete: {e}"),
    }
    Err(code)
}

/// Sizes rayon's global pool (default: all cores); results are identical for any size.
fn use_threads(threads: Option<usize>) -> Result<(), ExitCode> {
    let Some(threads) = threads else {
        return Ok(());
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global()
        .map_err(|e| {
            errln!("error: cannot start {threads} threads: {e}");
            ExitCode::FAILURE
        })
}

/// Draws the figures of the run in `dir` with `options`, a spinner on stderr while it does unless
/// `quiet` or stderr is not a terminal.
fn plot(
    dir: &Path,
    options: &FigureOptions,
    quiet: bool,
) -> Result<Vec<PathBuf>, flock_viz::PlotError> {
    let _spinner = flock_cli::progress::Spinner::for_terminal(
        &format!(
            "drawing {}",
            options
                .outputs
                .iter()
                .map(|o| o.name())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        quiet,
    );
    plot_run_with(dir, options)
}

/// A time of `--times`: seconds, a finite number.
fn parse_time(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(t) if t.is_finite() => Ok(t),
        _ => Err(format!(
            "{:?} is not a time: give seconds separated by commas, e.g. `0,5,10`",
            text.trim()
        )),
    }
}

/// "1 file", "6 files": the figures a plot wrote.
fn files_count(n: usize) -> String {
    format!("{n} file{}", if n == 1 { "" } else { "s" })
}

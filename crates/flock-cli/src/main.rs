//! `flock`: run flocking scenarios from RON files.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use flock_cli::{Progress, Report, RunDirectory, RunError, Scenario, plot_run, run_scenario};

/// Flocking simulations of Olfati-Saber (TAC 2006) and relatives, from RON scenario files.
#[derive(Debug, Parser)]
#[command(name = "flock", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a scenario and write metrics.csv, trajectory.csv, final.csv and scenario.ron to DIR.
    Run {
        /// The scenario file (.ron).
        scenario: PathBuf,
        /// The output directory (default: `out/<scenario file stem>`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Replace an existing output directory.
        #[arg(long)]
        force: bool,
        /// Worker threads (default: all cores); results are identical for any count.
        #[arg(long)]
        threads: Option<usize>,
        /// Also draw the run's figures into DIR/figures (as `flock plot DIR`).
        #[arg(long)]
        plot: bool,
        /// No progress bar (it is shown only on a terminal, for runs longer than about a second).
        #[arg(long)]
        quiet: bool,
    },
    /// Run every `fixtures/*.ron` (relative to the current directory) into `DIR/<fixture stem>/`,
    /// draw its figures (GIF and trajectory CSVs dropped), and write `DIR/index.html`, a static page
    /// of the papers' figures and final metrics.
    Figures {
        /// The output directory.
        #[arg(long, default_value = "docs/figures")]
        out: PathBuf,
        /// Print nothing but errors.
        #[arg(long)]
        quiet: bool,
    },
    /// Draw the figures of a finished run into DIR/figures: snapshots (SVG, PNG), the metric curves
    /// of TAC 2006 Fig. 18, an animated GIF and a self-contained HTML player.
    Plot {
        /// A run directory written by `flock run`.
        dir: PathBuf,
    },
    /// Check a scenario file and print it with every default filled in.
    Validate {
        /// The scenario file (.ron).
        scenario: PathBuf,
    },
    /// Time a synthetic scenario of n agents on an α-lattice and print agent-steps/s and memory.
    Bench {
        /// The number of agents.
        #[arg(long, default_value_t = 100_000)]
        n: usize,
        /// The dimension, 2 or 3.
        #[arg(long, default_value_t = 2)]
        dim: usize,
        /// Timed steps (metrics recorded every 10).
        #[arg(long, default_value_t = 20)]
        steps: u64,
        /// The algorithm: 1, 2 or 3 (3 adds 1,000 obstacles).
        #[arg(long, default_value = "2")]
        algorithm: flock_cli::bench::BenchAlgorithm,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Untimed steps before the timed ones.
        #[arg(long, default_value_t = 3)]
        warmup: u64,
    },
}

/// Exit code of an invalid scenario.
const INVALID: u8 = 2;

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Bench {
            n,
            dim,
            steps,
            algorithm,
            threads,
            warmup,
        } => {
            if let Err(code) = use_threads(threads) {
                return code;
            }
            let config = flock_cli::bench::BenchConfig {
                n,
                dim,
                steps,
                warmup,
                algorithm,
            };
            match flock_cli::bench::bench(&config) {
                Ok(report) => {
                    println!("{report}");
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(INVALID)
                }
            }
        }
        Command::Plot { dir } => match plot_run(&dir) {
            Ok(files) => {
                println!(
                    "{} figure file(s) in {}",
                    files.len(),
                    dir.join("figures").display()
                );
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Command::Figures { out, quiet } => {
            match flock_cli::figures(std::path::Path::new("fixtures"), &out, quiet) {
                Ok(_) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Command::Validate { scenario } => match Scenario::load(&scenario) {
            Ok(s) => {
                println!("{}: valid", scenario.display());
                print!("{}", s.to_ron().unwrap_or_default());
                println!();
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(INVALID)
            }
        },
        Command::Run {
            scenario,
            out,
            force,
            threads,
            plot,
            quiet,
        } => {
            let loaded = match Scenario::load(&scenario) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(INVALID);
                }
            };
            if let Err(code) = use_threads(threads) {
                return code;
            }
            let out = out.unwrap_or_else(|| {
                PathBuf::from("out").join(scenario.file_stem().unwrap_or_default())
            });
            match execute(&loaded, &out, force, quiet) {
                Ok(()) if plot => match plot_run(&out) {
                    Ok(files) => {
                        println!(
                            "  figures               {} file(s) in {}",
                            files.len(),
                            out.join("figures").display()
                        );
                        ExitCode::SUCCESS
                    }
                    Err(e) => {
                        eprintln!("error: the run is complete, but its figures failed: {e}");
                        ExitCode::FAILURE
                    }
                },
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    match e {
                        RunError::Scenario(_) => ExitCode::from(INVALID),
                        RunError::Record(_) => ExitCode::FAILURE,
                    }
                }
            }
        }
    }
}

fn execute(
    scenario: &Scenario,
    out: &std::path::Path,
    force: bool,
    quiet: bool,
) -> Result<(), RunError<std::io::Error>> {
    let dir = RunDirectory::create(out, scenario, force).map_err(RunError::Record)?;
    let mut recorder = Progress::for_terminal(dir, scenario, quiet);
    let result = run_scenario(scenario, &mut recorder);
    let dir = recorder.into_inner();
    match result {
        Ok(summary) => {
            let target = dir.finish().map_err(RunError::Record)?;
            println!(
                "{}",
                Report {
                    name: &scenario.name,
                    summary: &summary
                }
            );
            println!("  outputs               {}", target.display());
            Ok(())
        }
        Err(e) => {
            dir.abandon();
            Err(e)
        }
    }
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
            eprintln!("error: cannot start {threads} threads: {e}");
            ExitCode::FAILURE
        })
}

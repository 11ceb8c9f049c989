//! `flock`: run flocking scenarios from RON files.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use flock_cli::{Report, RunDirectory, RunError, Scenario, run_scenario};

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
    },
    /// Check a scenario file and print it with every default filled in.
    Validate {
        /// The scenario file (.ron).
        scenario: PathBuf,
    },
}

/// Exit code of an invalid scenario.
const INVALID: u8 = 2;

fn main() -> ExitCode {
    match Cli::parse().command {
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
        } => {
            let loaded = match Scenario::load(&scenario) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(INVALID);
                }
            };
            if let Some(threads) = threads
                && let Err(e) = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build_global()
            {
                eprintln!("error: cannot start {threads} threads: {e}");
                return ExitCode::FAILURE;
            }
            let out = out.unwrap_or_else(|| {
                PathBuf::from("out").join(scenario.file_stem().unwrap_or_default())
            });
            match execute(&loaded, &out, force) {
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
) -> Result<(), RunError<std::io::Error>> {
    let mut dir = RunDirectory::create(out, scenario, force).map_err(RunError::Record)?;
    match run_scenario(scenario, &mut dir) {
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

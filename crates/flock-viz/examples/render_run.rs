//! Renders every figure of a run directory written by `flocking run --out DIR` into `DIR/figures/`:
//! snapshots (TAC 2006 Figs. 10–13; 3D runs also from above), the metric curves (Fig. 18), an
//! animated GIF and an HTML player.
//!
//! ```sh
//! cargo run --release -p flock-viz --example render_run -- DIR [RANGE]
//! ```
//!
//! RANGE is the interaction range r that draws the net's edges (default 8.4 = 1.2 d with the
//! papers' d = 7). Obstacles and the γ-agent are not in a run's CSV files: the `flocking` binary
//! adds them from the scenario.

use std::path::PathBuf;
use std::process::ExitCode;

use flock_viz::{FigureOptions, RunData, write_figures};

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let Some(dir) = args.next().map(PathBuf::from) else {
        eprintln!("usage: render_run DIR [RANGE]");
        return ExitCode::from(2);
    };
    let range = match args.next().map(|r| r.parse::<f64>()) {
        None => 8.4,
        Some(Ok(r)) if r > 0.0 => r,
        Some(_) => {
            eprintln!("RANGE must be a positive number");
            return ExitCode::from(2);
        }
    };
    let run = match RunData::load(&dir) {
        Ok(run) => run,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let name = dir
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let scene = run.scene(range).with_title(name);
    let out = dir.join("figures");
    match write_figures(&scene, Some(&run.metrics), &out, &FigureOptions::default()) {
        Ok(written) => {
            for path in written {
                println!("{}", path.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

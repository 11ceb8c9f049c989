//! The README's library example: runs TAC 2006 Fig. 11 with the `flock` library alone and prints
//! its final connectivity. From the workspace root:
//! `cargo run --release -p flock --example fig11_connectivity`.

use flock::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenario = Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
    let summary = flock::run(&scenario, &mut ())?;
    println!("final connectivity C = {}", summary.metrics.connectivity);
    Ok(())
}

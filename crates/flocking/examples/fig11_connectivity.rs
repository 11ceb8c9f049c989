//! The README's library example: runs TAC 2006 Fig. 11 with the `flocking` library alone and prints
//! its final connectivity. From the workspace root:
//! `cargo run --release -p flocking --example fig11_connectivity`.

use flocking::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenario = Scenario::load("fixtures/tac2006_fig11_alg2_n100.ron")?;
    let summary = flocking::run(&scenario, &mut ())?;
    println!("final connectivity C = {}", summary.metrics.connectivity);
    Ok(())
}

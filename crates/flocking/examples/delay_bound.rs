//! The delay bound τ* = π / (2 λ_max(c₂^α L_a(q) + c₂^γ I)) of a TAC 2006 flock's linearised
//! velocity consensus (`flocking::velocity_consensus_delay_bound`), at the final lattice of the
//! scenario's ideal run (its `conditions` left out). From the workspace root:
//! `cargo run --release -p flocking --example delay_bound -- fixtures/tac2006_fig11_alg2_n100.ron`
//! (the default); `docs/conditions.md` draws it on the delay sweep of Fig. 11.

use flocking::protocols::conditions::Conditions;
use flocking::{Record, Recorder, Scenario, State, velocity_consensus_delay_bound};

/// Keeps the last state recorded.
struct Last(Option<State<'static>>);

impl Recorder for Last {
    type Error = std::convert::Infallible;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        self.0 = Some(record.state.clone().into_owned());
        Ok(())
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1);
    let path = path
        .as_deref()
        .unwrap_or("fixtures/tac2006_fig11_alg2_n100.ron");
    let mut scenario = Scenario::load(path)?;
    scenario.conditions = Conditions::default();
    let mut last = Last(None);
    flocking::run(&scenario, &mut last)?;
    let state = last.0.ok_or("the run recorded nothing")?;
    let tau = velocity_consensus_delay_bound(&scenario, &state.positions)
        .ok_or("no delay bound: not Algorithm 1, 2 or 3")?;
    println!("τ* = {tau:.4} s at t = {} s", scenario.duration);
    Ok(())
}

//! A run of agents numbered at random, which the simulation stores by cell: its records are in
//! original order, and a run resumed from a checkpoint (sorted again from the original order, at
//! another step) records the same bits; under real conditions and on vehicles too (their state
//! checkpointed in original order and moved back by cell on resume), and for Vicsek's particles
//! on a torus.

use flock_graph::{NeighbourSearch, ProximityNet};
use flocking::initial::initial_swarm;
use flocking::{Record, Recorder, Scenario, Start};
use glam::DVec2;

/// 20,000 agents in a Gaussian cloud, numbered at random as drawn; 24 steps recorded every 6, a
/// checkpoint after 12.
const CLOUD: &str = r#"Scenario(
    name: "cloud",
    dim: 2,
    agents: 20000,
    seed: 3,
    algorithm: Algorithm2(
        gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.5]),
        c1: 0.02,
        c2: 0.4,
    ),
    initial: (
        positions: Gaussian(mean: [0.0, 0.0], std: 250.0),
        velocities: Box(min: [-2.0, -2.0], max: [2.0, 2.0]),
    ),
    step: 0.01,
    duration: 0.24,
    record_every: 6,
)"#;

/// Every record as bits (time, metrics, energy, state in the recorded order), and the checkpoint.
#[derive(Default)]
struct Bits {
    records: Vec<Vec<u64>>,
    checkpoint: Option<Start>,
}

impl Recorder for Bits {
    type Error = std::convert::Infallible;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let numbers = [record.t, record.energy]
            .into_iter()
            .chain(record.metrics.reals())
            .chain(record.metrics.extras());
        let state = &record.state;
        let coordinates = state
            .positions
            .iter()
            .chain(state.velocities.iter())
            .copied();
        let failed = state
            .failed
            .iter()
            .flat_map(|f| f.iter().map(|&f| f64::from(f)));
        let vehicles = state.vehicle.iter().copied();
        let diagnostics = record.diagnostics.iter().map(|&(_, x)| x);
        self.records.push(
            numbers
                .chain(coordinates)
                .chain(failed)
                .chain(vehicles)
                .chain(diagnostics)
                .map(f64::to_bits)
                .collect(),
        );
        Ok(())
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        steps == 12
    }

    fn checkpoint(&mut self, start: &Start) -> Result<(), Self::Error> {
        self.checkpoint = Some(start.clone());
        Ok(())
    }
}

/// The cloud under every kind of condition that keeps a state: a delay line with jitter,
/// Gilbert–Elliott loss holding the last value, Ornstein–Uhlenbeck sensing at 50 Hz, per-agent
/// gusts and agents failing at a rate.
const CONDITIONS: &str = r#"    conditions: (
        communication: (
            delay: 0.03,
            jitter: 0.02,
            loss: GilbertElliott(p_fail: 0.3, p_recover: 2.0),
            when_lost: Hold(max_age: 0.1),
        ),
        sensing: (noise: OrnsteinUhlenbeck(sigma_q: 0.05, sigma_p: 0.02, correlation_time: 0.5), rate: 50.0),
        disturbance: (wind: (mean: [0.1, 0.0], gust: 0.2, per_agent: true), process_noise: 0.05),
        faults: (at: [(agent: 3, time: 0.05)], rate: 1.0, mode: Silent),
    ),
)"#;

/// 20,000 Vicsek particles at ρ = 4 on a torus (`fixtures/vicsek1995_fig2a_n400.ron` grown),
/// numbered at random as drawn; 24 steps recorded every 6, a checkpoint after 12.
const VICSEK: &str = r#"Scenario(
    name: "vicsek",
    dim: 2,
    agents: 20000,
    seed: 3,
    algorithm: Vicsek(v0: 0.03, r: 1.0, eta: 2.0),
    domain: PeriodicAtDensity(density: 4.0),
    initial: (
        positions: Domain,
        velocities: Headings(speed: 0.03),
    ),
    step: 1.0,
    duration: 24.0,
    record_every: 6,
)"#;

#[test]
fn records_of_agents_stored_by_cell_are_in_original_order_and_resume_bit_identically() {
    stored_by_cell_records_and_resumes(CLOUD, 8.4);
}

/// Particles on a torus are stored by its cells, ideal and under a delay of two steps, 10 %
/// loss, a communication range and sensing noise (their noise keyed by original index).
#[test]
fn vicsek_particles_stored_by_cell_on_a_torus_resume_bit_identically() {
    stored_by_cell_records_and_resumes(VICSEK, 1.0);
    let vicsek = VICSEK.strip_suffix(')').expect("a scenario");
    let conditions = r#"    conditions: (
        communication: (delay: 2.0, range: Some(1.5), loss: Bernoulli(p: 0.1)),
        sensing: (noise: White(sigma_q: 0.01, sigma_p: 0.001)),
    ),
)"#;
    stored_by_cell_records_and_resumes(&format!("{vicsek}{conditions}"), 1.0);
}

#[test]
fn under_conditions_records_of_agents_stored_by_cell_resume_bit_identically() {
    let cloud = CLOUD.strip_suffix(')').expect("a scenario");
    stored_by_cell_records_and_resumes(&format!("{cloud}{CONDITIONS}"), 8.4);
}

#[test]
fn records_of_unicycles_stored_by_cell_resume_bit_identically() {
    let cloud = CLOUD.strip_suffix(')').expect("a scenario");
    stored_by_cell_records_and_resumes(&format!("{cloud}    vehicle: Unicycle(()),\n)"), 8.4);
}

/// `text`, a run of 20,000 agents at random (interaction range `r`), recorded from its initial
/// state in original order and resumed from its checkpoint after 12 steps to the bits of the
/// rest of the run.
fn stored_by_cell_records_and_resumes(text: &str, r: f64) {
    let scenario = Scenario::parse(text, "cloud.ron").expect("valid");
    let mut whole = Bits::default();
    flocking::run(&scenario, &mut whole).expect("the run");
    assert_eq!(whole.records.len(), 5, "t = 0 and four records");
    // the first record is the initial state as drawn, in its order (the positions: a vehicle
    // starts at the velocity of its equilibrium)
    let start = initial_swarm::<DVec2>(&scenario);
    let drawn: Vec<u64> = start
        .positions
        .iter()
        .flat_map(|v| [v.x, v.y])
        .map(f64::to_bits)
        .collect();
    assert!(
        // after t, the energy, the six reals and the five extras
        whole.records[0][13..13 + drawn.len()] == drawn[..],
        "t = 0 is recorded in original order"
    );
    // the net of the drawn state is scattered in memory: the simulation stores it by cell
    let mut net = ProximityNet::without_distances();
    NeighbourSearch::new().build(&start.positions, r, &mut net);
    assert!(net.is_scattered() && net.graph().directed_edge_count() > 2 * 20_000);
    let checkpoint = whole
        .checkpoint
        .take()
        .expect("a checkpoint after 12 steps");
    let mut resumed = Bits::default();
    flocking::resume(&scenario, Some(&checkpoint), &mut resumed).expect("the resumed run");
    assert_eq!(resumed.records.len(), 2);
    assert!(
        resumed.records[..] == whole.records[3..],
        "records after the checkpoint"
    );
}

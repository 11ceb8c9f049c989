//! A run of agents numbered at random, which the simulation stores by cell: its records are in
//! original order, and a run resumed from a checkpoint (sorted again from the original order, at
//! another step) records the same bits.

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
        self.records
            .push(numbers.chain(coordinates).map(f64::to_bits).collect());
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

#[test]
fn records_of_agents_stored_by_cell_are_in_original_order_and_resume_bit_identically() {
    let scenario = Scenario::parse(CLOUD, "cloud.ron").expect("valid");
    let mut whole = Bits::default();
    flocking::run(&scenario, &mut whole).expect("the run");
    assert_eq!(whole.records.len(), 5, "t = 0 and four records");
    // the first record is the initial state as drawn, in its order
    let start = initial_swarm::<DVec2>(&scenario);
    let drawn: Vec<u64> = start
        .positions
        .iter()
        .chain(&start.velocities)
        .flat_map(|v| [v.x, v.y])
        .map(f64::to_bits)
        .collect();
    assert!(
        // after t, the energy, the six reals and the four extras
        whole.records[0][12..] == drawn[..],
        "t = 0 is recorded in original order"
    );
    // the net of the drawn state is scattered in memory: the simulation stores it by cell
    let mut net = ProximityNet::without_distances();
    NeighbourSearch::new().build(&start.positions, 8.4, &mut net);
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

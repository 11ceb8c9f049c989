//! A local controller written outside the library ([`Controller`], run by [`WithController`]):
//! TAC 2006 Algorithm 2's local form applied to the rows of each agent's [`Perception`] (its own
//! measured state, the states it heard rebuilt as own + relative) follows the built-in run to
//! round-off, ideal and under delay + loss + noise, with the agents stored by cell (so the rows'
//! original order is put back into the simulation's), and a controller of no input does not.

use std::sync::Arc;

use flocking::controller::{Controller, WithController};
use flocking::perception::Perception;
use flocking::protocols::{DynProtocol, Perceived};
use flocking::{DynSimulation, Scenario};
use glam::DVec2;
use serde_json::json;

use crate::common::fixture;

/// The scenario's own protocol applied to the perception rows.
struct Rebuilt(DynProtocol<DVec2>);

impl Controller for Rebuilt {
    fn inputs(&self, perception: &Perception, out: &mut [f64]) {
        let local = self.0.local_form().expect("Algorithm 2 has a local form");
        let v = |rows: &[f64], m: usize| DVec2::new(rows[2 * m], rows[2 * m + 1]);
        for i in 0..perception.agents() {
            let own = Perceived {
                agent: i as u32,
                position: v(&perception.positions, i),
                velocity: v(&perception.velocities, i),
            };
            let heard: Vec<Perceived<DVec2>> = (perception.indptr[i]..perception.indptr[i + 1])
                .map(|m| Perceived {
                    agent: perception.neighbours[m],
                    position: own.position + v(&perception.relative_positions, m),
                    velocity: own.velocity + v(&perception.relative_velocities, m),
                })
                .collect();
            let u = local.local_input(perception.t, &own, &heard);
            out[2 * i..2 * i + 2].copy_from_slice(&[u.x, u.y]);
        }
    }
}

/// No input at all.
struct Idle;

impl Controller for Idle {
    fn inputs(&self, _: &Perception, out: &mut [f64]) {
        out.fill(0.0);
    }
}

/// The largest |Δ| of the positions after `steps` steps of the built-in run and of `controller`.
fn gap<C: Controller + 'static>(scenario: &Scenario, controller: C, steps: usize) -> f64 {
    let mut builtin = DynSimulation::new(scenario).expect("a valid scenario");
    let mut outside =
        DynSimulation::new_with(scenario, &WithController(Arc::new(controller))).expect("valid");
    assert!(
        outside.stored_by_cell(),
        "the test wants the agents stored by cell"
    );
    for _ in 0..steps {
        builtin.step();
        outside.step();
    }
    let (a, b) = (builtin.state(), outside.state());
    a.positions
        .iter()
        .zip(b.positions.iter())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_controller_outside_the_library_follows_the_builtin_to_round_off() {
    // 20,000 agents at Fig. 11's density: numbered at random, they are stored by cell
    let ideal = fixture("tac2006_fig11_alg2_n100")
        .with_values([
            ("duration", json!(0.05)),
            ("agents", json!(20_000)),
            (
                "initial.positions.Gaussian.std",
                json!(50.0 * 200f64.sqrt()),
            ),
        ])
        .expect("a larger flock");
    let conditions = Scenario {
        conditions: ron::from_str(
            "#![enable(implicit_some)] (communication: (delay: 0.03, loss: Bernoulli(p: 0.2)), sensing: (noise: White(sigma_q: 0.02, sigma_p: 0.01)))",
        )
        .expect("valid conditions"),
        ..ideal.clone()
    };
    for scenario in [&ideal, &conditions] {
        let protocol = scenario.protocol::<DVec2>().expect("Algorithm 2");
        let rebuilt = gap(scenario, Rebuilt(protocol), 5);
        assert!(rebuilt < 1e-9, "{rebuilt}");
        let idle = gap(scenario, Idle, 5);
        assert!(idle > 1e-6, "no input moves the agents elsewhere: {idle}");
    }
}

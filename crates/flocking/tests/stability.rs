//! The stable-step estimate of the 2003 protocols and the Tanner law: half of it runs healthy,
//! a step above it is warned about, and (for the 2003 protocols, whose bound is not a worst case)
//! eight times it blows up with the estimate named as the likely cause.

use flocking::{RunError, Scenario, largest_stable_step};

use crate::common::fixture;

/// `name` with its step set to `factor` times the estimate, cut to 20 s.
fn at(name: &str, factor: f64) -> (Scenario, f64) {
    let mut scenario = fixture(name);
    let stable = largest_stable_step(&scenario).expect("an estimate");
    scenario.step = factor * stable;
    scenario.duration = scenario.duration.min(20.0);
    (scenario, stable)
}

#[test]
fn half_the_estimated_step_runs_healthy() {
    for name in [
        "tr2003_fig9_sink_n100",
        "acc2004_fig4_sink_n100",
        "tr2003_fig7_obstacles_n100",
        "tanner2003_fig3_fixed_n10",
    ] {
        let (scenario, _) = at(name, 0.5);
        assert!(scenario.warnings().is_empty(), "{name}");
        flocking::run(&scenario, &mut ()).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn steps_above_the_estimate_are_warned_about() {
    for name in ["tr2003_fig9_sink_n100", "tanner2003_fig3_fixed_n10"] {
        let (scenario, _) = at(name, 1.5);
        let warnings = scenario.warnings();
        assert!(
            warnings.iter().any(|w| w.field == "step"),
            "{name}: {warnings:?}"
        );
    }
}

#[test]
fn eight_times_the_estimate_blows_up_the_2003_protocols() {
    for name in ["tr2003_fig9_sink_n100", "tr2003_fig7_obstacles_n100"] {
        let (scenario, stable) = at(name, 8.0);
        match flocking::run(&scenario, &mut ()) {
            Err(RunError::Numerical(e)) => {
                assert!(e.cause.contains(&format!("{stable:.3e}")), "{name}: {e}");
            }
            other => panic!("{name}: expected a blow-up, got {other:?}"),
        }
    }
}

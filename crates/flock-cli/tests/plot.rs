//! `flocking run --plot` and `flocking plot DIR`: the figures of a run, with its obstacles and γ-agent.

use std::fs;

use crate::common::{flocking, temp_dir};

/// A short Algorithm 3 run in 2D with one ball in the way.
const SCENARIO: &str = r#"Scenario(
    name: "plot_test",
    dim: 2,
    agents: 12,
    seed: 5,
    algorithm: Algorithm3(gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [2.0, 0.0]), c1: 1.0),
    obstacles: [Ball(centre: [30.0, 0.0], radius: 5.0), Cuboid(centre: [20.0, 20.0], half_extents: [3.0, 2.0], rotation: 0.4)],
    initial: (positions: Box(min: [-10.0, -10.0], max: [10.0, 10.0])),
    step: 0.02,
    duration: 2.0,
)
"#;

#[test]
fn run_with_plot_writes_every_figure() {
    let tmp = temp_dir("plot_run");
    fs::write(tmp.path().join("s.ron"), SCENARIO).expect("write the scenario");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o", "--plot"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let figures = tmp.path().join("o/figures");
    for file in [
        "snapshots.svg",
        "snapshots.png",
        "metrics.svg",
        "metrics.png",
        "animation.gif",
        "player.html",
    ] {
        let bytes = fs::read(figures.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert!(bytes.len() > 500, "{file} is only {} bytes", bytes.len());
    }
    let player = fs::read_to_string(figures.join("player.html")).expect("the player");
    assert!(
        player.contains("id=\"play\"") && !player.contains("http"),
        "self-contained player"
    );
    let metrics = fs::read_to_string(figures.join("metrics.svg")).expect("the metric figure");
    assert!(
        metrics.contains("obstacle clearance"),
        "the obstacle column is plotted"
    );
    // plotting again from the run directory gives the same files, byte for byte
    let first = fs::read(figures.join("snapshots.svg")).expect("svg");
    let again = flocking(tmp.path(), &["plot", "o"]);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    assert_eq!(fs::read(figures.join("snapshots.svg")).expect("svg"), first);
}

#[test]
fn plot_of_a_directory_that_is_not_a_run_fails_clearly() {
    let tmp = temp_dir("plot_missing");
    let output = flocking(tmp.path(), &["plot", "nowhere"]);
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("scenario.ron"), "{message}");
}

#[test]
fn a_run_with_an_npy_trajectory_draws_the_same_figures() {
    let tmp = temp_dir("plot_npy");
    fs::write(tmp.path().join("s.ron"), SCENARIO).expect("write the scenario");
    for args in [
        &["run", "s.ron", "--out", "csv", "--plot", "--quiet"][..],
        &[
            "run",
            "s.ron",
            "--out",
            "npy",
            "--plot",
            "--quiet",
            "--trajectory-format",
            "npy",
        ],
    ] {
        let output = flocking(tmp.path(), args);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    for file in ["snapshots.svg", "metrics.svg", "player.html"] {
        let read = |run: &str| fs::read(tmp.path().join(run).join("figures").join(file));
        assert_eq!(read("csv").ok(), read("npy").ok(), "{file}");
    }
}

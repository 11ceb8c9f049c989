//! `flocking run --plot` and `flocking plot DIR`: the figures of a run, with its obstacles and γ-agent.

use std::fs;

use crate::common::{files, flocking, stderr, temp_dir};

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
    assert!(
        !figures.join("reynolds.svg").exists(),
        "the reading of ACC 2004 is for (α, α) runs only"
    );
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

/// A run with faults draws its failed agents as crosses in the snapshots (each panel after the
/// failure says how many) and lists them for the player, which draws them so too.
#[test]
fn failed_agents_are_marked_in_the_snapshots_and_the_player() {
    let tmp = temp_dir("plot_failed");
    let scenario = SCENARIO.replace(
        "    step: 0.02,",
        "    conditions: (faults: (at: [(agent: 3, time: 0.5)], mode: Frozen)),\n    step: 0.02,",
    );
    fs::write(tmp.path().join("s.ron"), scenario).expect("write the scenario");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o", "--plot"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let figures = tmp.path().join("o/figures");
    let svg = fs::read_to_string(figures.join("snapshots.svg")).expect("the snapshots");
    let cross = format!(
        "stroke=\"{}\"",
        flock_viz::style::hex(flock_viz::style::FAILED)
    );
    assert!(svg.contains(&cross), "a failed agent's cross");
    assert!(
        svg.contains("t = 0 s") && !svg.contains("t = 0 s,"),
        "t = 0: none failed yet"
    );
    assert!(
        svg.contains("s, 1 failed (×)"),
        "a later panel counts the failed agent"
    );
    let player = fs::read_to_string(figures.join("player.html")).expect("the player");
    assert!(
        player.contains("\"failed\":[[]"),
        "no agent failed in the first frame"
    );
    assert!(player.contains("[3]"), "agent 3 failed in a later frame");
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

/// A short ACC 2004 (α, α) run with a sink: `flocking plot` adds `reynolds.svg/png`, ACC 2004's
/// reading of one frame as Reynolds's rules, at the time `--reynolds-at` asks; other runs get none.
#[test]
fn plot_draws_the_reynolds_reading_of_an_alpha_alpha_run() {
    const ALPHA_ALPHA: &str = r#"Scenario(
    name: "reynolds_test",
    dim: 2,
    agents: 20,
    seed: 3,
    algorithm: Flocking2003(form: Smooth, c1: 1.0, translation: Some((gamma: Static(position: [0.0, 0.0]), c1: 0.02, c2: 1.0))),
    alpha: (d: 7.0, a: 1.0, b: 5.0),
    initial: (positions: Box(min: [-15.0, -15.0], max: [15.0, 15.0])),
    step: 0.01,
    duration: 2.0,
    record_every: 10,
)
"#;
    let tmp = temp_dir("plot_reynolds");
    fs::write(tmp.path().join("s.ron"), ALPHA_ALPHA).expect("write the scenario");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o", "--quiet"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let output = flocking(tmp.path(), &["plot", "o", "--reynolds-at", "1.5"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let figures = tmp.path().join("o/figures");
    let svg = fs::read_to_string(figures.join("reynolds.svg")).expect("reynolds.svg");
    assert!(svg.contains("t = 1.5 s"), "not drawn at 1.5 s");
    // the counts of the legend are those of metrics.csv at t = 1.5
    let metrics = fs::read_to_string(tmp.path().join("o/metrics.csv")).expect("metrics.csv");
    let header: Vec<&str> = metrics.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = metrics
        .lines()
        .find(|line| line.starts_with("1.5"))
        .expect("a record at 1.5 s")
        .split(',')
        .collect();
    let count = |name: &str| {
        let k = header.iter().position(|h| *h == name).expect(name);
        row[k].parse::<f64>().expect("a count") as usize
    };
    let (towards, away, neutral) = (
        count("stress_towards"),
        count("stress_away"),
        count("stress_neutral"),
    );
    assert_eq!(towards + away + neutral, 20);
    for label in [
        format!("towards the centre ({towards})"),
        format!("away from the centre ({away})"),
        format!("neutral ({neutral})"),
    ] {
        assert!(svg.contains(&label), "the legend lacks {label:?}");
    }
    assert!(
        fs::read(figures.join("reynolds.png"))
            .expect("reynolds.png")
            .len()
            > 500
    );
}

/// A second writer is refused: `plot` takes the run directory's lock, so a `plot` while another
/// process holds it (a resume, another `plot`) exits 2 naming the holder and writes nothing
/// (before, two `plot`s of one run could interleave their updates of the manifest).
#[test]
fn plot_of_a_directory_another_process_writes_is_refused() {
    let tmp = temp_dir("plot_locked");
    fs::write(tmp.path().join("s.ron"), SCENARIO).expect("write the scenario");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let run = tmp.path().join("o");
    let lock = flocking::owned::DirLock::acquire(&run).expect("the test holds the lock");
    let refused = flocking(tmp.path(), &["plot", "o"]);
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    let message = stderr(&refused);
    let holder = format!("process {}", std::process::id());
    assert!(
        message.contains("o is being written by") && message.contains(&holder),
        "{message}"
    );
    assert!(!run.join("figures").exists(), "nothing drawn");
    drop(lock);
    let drawn = flocking(tmp.path(), &["plot", "o"]);
    assert!(drawn.status.success(), "{}", stderr(&drawn));
    assert!(run.join("figures/snapshots.svg").is_file());
}

/// A user's `metrics.svg.tmp` beside the `metrics.svg` flocking drew and settled is the user's,
/// not a write of flocking's cut short: `plot` keeps it and refuses (exit 2, naming the file and
/// the fix).
#[test]
fn a_users_tmp_beside_a_figure_is_kept_and_plot_refuses() {
    let tmp = temp_dir("plot_users_tmp");
    fs::write(tmp.path().join("s.ron"), SCENARIO).expect("write the scenario");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o", "--plot"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let mine = tmp.path().join("o/figures/metrics.svg.tmp");
    fs::write(&mine, "mine\n").expect("a user's file");
    let refused = flocking(tmp.path(), &["plot", "o"]);
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    let message = stderr(&refused);
    assert!(
        message.contains("holds metrics.svg.tmp, which flocking did not write")
            && message.contains("move it"),
        "{message}"
    );
    assert_eq!(fs::read(&mine).expect("kept"), b"mine\n");
    let moved = tmp.path().join("metrics.svg.tmp.mine");
    fs::rename(&mine, &moved).expect("the user moves it away");
    let drawn = flocking(tmp.path(), &["plot", "o"]);
    assert!(drawn.status.success(), "{}", stderr(&drawn));
    assert_eq!(fs::read(&moved).expect("kept"), b"mine\n");
}

/// `--outputs` draws the figures chosen and no other, the same bytes as when all are drawn; the
/// default set is every output (`run --plot` as `plot --outputs snapshots,metrics,gif,player`);
/// `--times` draws the snapshots at those times.
#[test]
fn plot_draws_the_outputs_and_times_chosen() {
    let tmp = temp_dir("plot_outputs");
    fs::write(tmp.path().join("s.ron"), SCENARIO).expect("write the scenario");
    let run = flocking(
        tmp.path(),
        &["run", "s.ron", "--out", "o", "--plot", "--quiet"],
    );
    assert!(run.status.success(), "{}", stderr(&run));
    let all = files(&tmp.path().join("o/figures"));
    let names: Vec<&str> = all.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        [
            "animation.gif",
            "metrics.png",
            "metrics.svg",
            "player.html",
            "snapshots.png",
            "snapshots.svg"
        ]
    );
    let every = flocking(
        tmp.path(),
        &[
            "run",
            "s.ron",
            "--out",
            "every",
            "--plot",
            "--quiet",
            "--plot-outputs",
            "snapshots,metrics,gif,player",
        ],
    );
    assert!(every.status.success(), "{}", stderr(&every));
    assert_eq!(files(&tmp.path().join("every/figures")), all);

    let some = flocking(
        tmp.path(),
        &[
            "run",
            "s.ron",
            "--out",
            "some",
            "--plot",
            "--quiet",
            "--plot-outputs",
            "metrics,gif",
        ],
    );
    assert!(some.status.success(), "{}", stderr(&some));
    let drawn = files(&tmp.path().join("some/figures"));
    let names: Vec<&str> = drawn.keys().map(String::as_str).collect();
    assert_eq!(names, ["animation.gif", "metrics.png", "metrics.svg"]);
    for (name, bytes) in &drawn {
        assert_eq!(bytes, &all[name], "{name}");
    }

    let at = flocking(
        tmp.path(),
        &["plot", "some", "--outputs", "snapshots", "--times", "0,1"],
    );
    assert!(at.status.success(), "{}", stderr(&at));
    let svg = fs::read_to_string(tmp.path().join("some/figures/snapshots.svg")).expect("svg");
    assert!(
        svg.contains("\nt = 1 s\n") && !svg.contains("t = 2"),
        "two panels, at 0 and 1 s"
    );

    let wrong = flocking(tmp.path(), &["plot", "o", "--outputs", "snapshots,movie"]);
    assert_eq!(wrong.status.code(), Some(2));
    assert!(
        stderr(&wrong).contains("\"movie\" is not a figure"),
        "{}",
        stderr(&wrong)
    );
}

/// A snapshot time outside the run is refused, naming it and the run's span, before any figure
/// is drawn (exit 2); `run --plot` keeps the run and says how to draw them again.
#[test]
fn a_snapshot_time_outside_the_run_is_refused() {
    let tmp = temp_dir("plot_times");
    fs::write(tmp.path().join("s.ron"), SCENARIO).expect("write the scenario");
    let run = flocking(
        tmp.path(),
        &[
            "run",
            "s.ron",
            "--out",
            "o",
            "--plot",
            "--quiet",
            "--plot-times",
            "0,50",
        ],
    );
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    let message = stderr(&run);
    assert!(
        message.contains("snapshot time 50 s is outside the run, which spans 0 s to 2 s")
            && message.contains("flocking plot o"),
        "{message}"
    );
    assert!(
        tmp.path().join("o/metrics.csv").is_file(),
        "the run is kept"
    );
    assert!(!tmp.path().join("o/figures").exists(), "nothing drawn");
    for times in ["-1", "2.5"] {
        let plot = flocking(tmp.path(), &["plot", "o", &format!("--times={times}")]);
        assert_eq!(plot.status.code(), Some(2), "{}", stderr(&plot));
        assert!(
            stderr(&plot).contains(&format!("snapshot time {times} s is outside")),
            "{}",
            stderr(&plot)
        );
    }
    let plot = flocking(
        tmp.path(),
        &["plot", "o", "--times", "0,2", "--outputs", "snapshots"],
    );
    assert!(
        plot.status.success(),
        "the run's end is within it: {}",
        stderr(&plot)
    );
    let bad = flocking(tmp.path(), &["plot", "o", "--times", "0,soon"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        stderr(&bad).contains("\"soon\" is not a time"),
        "{}",
        stderr(&bad)
    );
}

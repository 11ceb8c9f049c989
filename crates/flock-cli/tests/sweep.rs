//! `flocking sweep`: the command line of sweeps — a sweep killed with SIGKILL and run again gives the
//! runs.csv of an uninterrupted one, byte for byte; shards merged; phase diagrams drawn; clear
//! errors.

use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{TempDir, fixtures_dir, flocking, stderr};

/// Fig. 11 cut to 30 agents and 20 s (some 10–20 ms a run), over 4 × 2 values × 3 seeds (24 runs).
fn write_sweep(dir: &Path) -> String {
    let text = format!(
        r#"Sweep(
    name: "cli",
    base: Path("{}"),
    set: {{"duration": 20.0, "agents": 30, "initial.positions.std": 12.0}},
    axes: [
        (path: "algorithm.c1", values: Logspace(from: 0.01, to: 0.1, count: 4)),
        (path: "algorithm.c2", values: List([0.4, 1.0])),
    ],
    seeds: 3,
)"#,
        fixtures_dir().join("tac2006_fig11_alg2_n100.ron").display()
    );
    let path = dir.join("sweep.ron");
    fs::write(&path, text).expect("write the sweep");
    path.to_str().expect("UTF-8").to_owned()
}

fn sweep(dir: &Path, args: &[&str]) -> String {
    let mut all = vec!["sweep"];
    all.extend_from_slice(args);
    let output = flocking(dir, &all);
    assert!(
        output.status.success(),
        "flocking {all:?}: {}",
        stderr(&output)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

#[test]
fn a_killed_sweep_resumes_to_the_same_runs_csv() {
    let tmp = TempDir::new("sweep_kill");
    let spec = write_sweep(tmp.path());
    sweep(
        tmp.path(),
        &[&spec, "--out", "whole", "--jobs", "1", "--quiet"],
    );
    let whole = fs::read(tmp.path().join("whole/runs.csv")).expect("runs.csv");
    assert_eq!(String::from_utf8_lossy(&whole).lines().count(), 25);

    let mut child = Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(tmp.path())
        .args(["sweep", &spec, "--out", "killed", "--jobs", "2", "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("flocking sweep starts");
    let rows = tmp.path().join("killed/rows");
    let deadline = Instant::now() + Duration::from_secs(120);
    let done = || fs::read_dir(&rows).map_or(0, |entries| entries.count());
    while done() < 4 && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    let finished = done();
    assert!(
        (4..24).contains(&finished),
        "killed after {finished} of 24 runs: make the runs longer"
    );
    assert!(
        !tmp.path().join("killed/runs.csv").exists(),
        "no runs.csv before the end"
    );

    let report = sweep(
        tmp.path(),
        &[&spec, "--out", "killed", "--jobs", "2", "--quiet"],
    );
    assert!(report.contains("found done"), "{report}");
    assert_eq!(
        fs::read(tmp.path().join("killed/runs.csv")).expect("runs.csv"),
        whole,
        "runs.csv after a SIGKILL and a rerun"
    );
}

#[test]
fn shards_merge_and_phase_diagrams_are_drawn() {
    let tmp = TempDir::new("sweep_shards");
    let spec = write_sweep(tmp.path());
    sweep(tmp.path(), &[&spec, "--out", "all", "--quiet"]);
    for i in 0..3 {
        let shard = format!("{i}/3");
        sweep(
            tmp.path(),
            &[
                &spec,
                "--out",
                &format!("s{i}"),
                "--shard",
                &shard,
                "--quiet",
            ],
        );
    }
    let report = sweep(tmp.path(), &["merge", "--out", "merged", "s0", "s1", "s2"]);
    assert!(report.contains("24 row(s)"), "{report}");
    assert_eq!(
        fs::read(tmp.path().join("merged/runs.csv")).expect("merged"),
        fs::read(tmp.path().join("all/runs.csv")).expect("all")
    );
    let missing = flocking(tmp.path(), &["sweep", "merge", "--out", "m2", "s0", "s2"]);
    assert!(!missing.status.success());
    assert!(
        stderr(&missing).contains("8 of 24 runs are in no shard"),
        "{}",
        stderr(&missing)
    );

    sweep(
        tmp.path(),
        &[
            "plot",
            "all",
            "--x",
            "algorithm.c1",
            "--y",
            "algorithm.c2",
            "--metric",
            "alpha_flock",
            "--out",
            "map.svg",
        ],
    );
    let map = fs::read_to_string(tmp.path().join("map.svg")).expect("map.svg");
    for text in ["algorithm.c1", "algorithm.c2", "alpha_flock (mean)"] {
        assert!(map.contains(text), "{text} missing from the heatmap");
    }
    sweep(
        tmp.path(),
        &[
            "plot",
            "all",
            "--x",
            "algorithm.c1",
            "--metric",
            "cohesion_radius",
            "--log-x",
            "--band",
            "quantiles",
            "--out",
            "line.png",
        ],
    );
    let png = fs::read(tmp.path().join("line.png")).expect("line.png");
    assert_eq!(&png[1..4], b"PNG");

    let bad = flocking(
        tmp.path(),
        &[
            "sweep",
            "plot",
            "all",
            "--x",
            "algorithm.c1",
            "--metric",
            "speed",
        ],
    );
    assert!(!bad.status.success());
    assert!(
        stderr(&bad).contains("\"speed\" is not a column")
            && stderr(&bad).contains("cohesion_radius"),
        "{}",
        stderr(&bad)
    );
}

#[test]
fn bad_sweep_commands_are_clear_errors() {
    let tmp = TempDir::new("sweep_errors_cli");
    let spec = write_sweep(tmp.path());
    let no_out = flocking(tmp.path(), &["sweep", &spec]);
    assert_eq!(no_out.status.code(), Some(2));
    assert!(stderr(&no_out).contains("--out"), "{}", stderr(&no_out));
    let shard = flocking(
        tmp.path(),
        &["sweep", &spec, "--out", "o", "--shard", "3/3"],
    );
    assert!(stderr(&shard).contains("0 ≤ i < N"), "{}", stderr(&shard));
    fs::write(tmp.path().join("bad.ron"), "Sweep(seeds: 2)").expect("write");
    let bad = flocking(tmp.path(), &["sweep", "bad.ron", "--out", "o"]);
    assert!(!bad.status.success());
    assert!(stderr(&bad).contains("bad.ron:1:"), "{}", stderr(&bad));
    sweep(tmp.path(), &[&spec, "--out", "o", "--quiet"]);
    fs::write(
        tmp.path().join("other.ron"),
        fs::read_to_string(&spec)
            .expect("read")
            .replace("seeds: 3", "seeds: 2"),
    )
    .expect("write");
    fs::create_dir(tmp.path().join("empty")).expect("mkdir");
    let not_a_sweep = flocking(
        tmp.path(),
        &[
            "sweep",
            "plot",
            "empty",
            "--x",
            "algorithm.c1",
            "--metric",
            "seed",
        ],
    );
    assert!(
        stderr(&not_a_sweep).contains("is not the output directory of a sweep"),
        "{}",
        stderr(&not_a_sweep)
    );
    let refused = flocking(tmp.path(), &["sweep", "other.ron", "--out", "o"]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("another sweep"),
        "{}",
        stderr(&refused)
    );
}

/// The committed results of the shipped sweeps (`docs/figures/sweeps/<name>/`, read by
/// docs/sweeps.md) are what flocking computes and draws today: Algorithm 3's sweep run again (140
/// runs) gives its runs.csv byte for byte, shard 0 of 20 of Algorithm 2's (20 of its 400 runs)
/// gives the same rows, and every committed diagram is drawn again from the committed runs.csv.
#[test]
fn the_committed_sweeps_are_what_flock_computes_and_draws() {
    let tmp = TempDir::new("sweep_committed");
    let sweeps = fixtures_dir().join("../sweeps");
    let committed = fixtures_dir().join("../docs/figures/sweeps");
    let stale = "stale: run the sweep and its plot commands again (docs/sweeps.md)";

    let alg3 = sweeps.join("alg3_beta_radius.ron");
    sweep(
        tmp.path(),
        &[alg3.to_str().expect("UTF-8"), "--out", "alg3", "--quiet"],
    );
    for file in ["runs.csv", "sweep.ron"] {
        assert!(
            fs::read(tmp.path().join("alg3").join(file)).expect("computed")
                == fs::read(committed.join("alg3_beta_radius").join(file)).expect("committed"),
            "docs/figures/sweeps/alg3_beta_radius/{file} is {stale}"
        );
    }

    let alg2 = sweeps.join("alg2_c1_n.ron");
    sweep(
        tmp.path(),
        &[
            alg2.to_str().expect("UTF-8"),
            "--out",
            "alg2",
            "--shard",
            "0/20",
            "--quiet",
        ],
    );
    let whole = fs::read_to_string(committed.join("alg2_c1_n/runs.csv")).expect("committed");
    let whole: Vec<&str> = whole.lines().collect();
    let shard = fs::read_to_string(tmp.path().join("alg2/runs.csv")).expect("shard");
    let mut shard = shard.lines();
    assert_eq!(shard.next(), Some(whole[0]), "the header");
    let rows: Vec<&str> = shard.collect();
    assert_eq!(rows.len(), 20);
    for row in rows {
        let index: usize = row
            .split(',')
            .next()
            .and_then(|k| k.parse().ok())
            .expect("run");
        assert_eq!(index % 20, 0, "shard 0/20 holds runs 0, 20, 40, …");
        assert!(
            row == whole[index + 1],
            "run {index} of docs/figures/sweeps/alg2_c1_n/runs.csv is {stale}"
        );
    }

    let diagrams = [
        ("alg2_c1_n", "algorithm.c1", "agents", "alpha_flock"),
        (
            "alg3_beta_radius",
            "algorithm.beta.c1",
            "obstacles.0.radius",
            "obstacle_clearance",
        ),
        (
            "alg3_beta_radius",
            "algorithm.beta.c1",
            "obstacles.0.radius",
            "collisions",
        ),
        (
            "alg3_beta_radius",
            "algorithm.beta.c1",
            "obstacles.0.radius",
            "min_distance",
        ),
    ];
    for (name, x, y, metric) in diagrams {
        for ext in ["svg", "png"] {
            let out = tmp.path().join(format!("{name}-{metric}.{ext}"));
            let dir = committed.join(name);
            sweep(
                tmp.path(),
                &[
                    "plot",
                    dir.to_str().expect("UTF-8"),
                    "--x",
                    x,
                    "--y",
                    y,
                    "--metric",
                    metric,
                    "--log-x",
                    "--out",
                    out.to_str().expect("UTF-8"),
                ],
            );
            assert!(
                fs::read(&out).expect("drawn")
                    == fs::read(dir.join(format!("{metric}.{ext}"))).expect("committed"),
                "docs/figures/sweeps/{name}/{metric}.{ext} is {stale}"
            );
        }
    }
}

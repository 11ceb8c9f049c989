//! `flocking bench` through the binary: the report names every measurement (timings not checked).

use std::process::Command;

fn bench(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_flocking"))
        .arg("bench")
        .args(args)
        .output()
        .expect("the flocking binary runs")
}

#[test]
fn bench_reports_throughput_memory_and_threads() {
    let out = bench(&["--n", "500", "--steps", "3"]);
    assert!(out.status.success(), "{out:?}");
    let report = String::from_utf8(out.stdout).expect("UTF-8 report");
    // the estimate of `flocking run` first, then the report
    let (estimate, report) = report.split_once('\n').expect("two parts");
    assert!(
        estimate.starts_with("estimate: 6 steps, 2 records; memory "),
        "{estimate}"
    );
    assert!(
        report.starts_with("flocking bench: Algorithm 2, 2D, n = 500, 3 steps after 3 warm-up"),
        "{report}"
    );
    for field in [
        "threads",
        "agent-steps/s",
        "ns per agent-step",
        "ms per step",
        "ms per plain step",
        "ms per recorded step",
        "peak memory",
        "mean neighbours",
    ] {
        assert!(
            report.lines().any(|l| l.trim_start().starts_with(field)),
            "no `{field}` line in\n{report}"
        );
    }
    if cfg!(target_os = "linux") {
        assert!(report.contains("bytes/agent"), "{report}");
    }
    assert!(!report.contains("agents stored"), "{report}");
}

/// Agents numbered at random are stored by cell when there are enough of them to be scattered in
/// memory (neighbours 4,096 indices apart).
#[test]
fn bench_stores_agents_numbered_at_random_by_cell() {
    let out = bench(&[
        "--n",
        "20000",
        "--steps",
        "2",
        "--warmup",
        "0",
        "--shuffled",
    ]);
    assert!(out.status.success(), "{out:?}");
    let report = String::from_utf8(out.stdout).expect("UTF-8 report");
    assert!(
        report.contains("agents numbered       at random"),
        "{report}"
    );
    assert!(report.contains("agents stored         by cell"), "{report}");
}

#[test]
fn bench_runs_algorithm_3_in_3d_on_one_thread() {
    let out = bench(&[
        "--n",
        "300",
        "--dim",
        "3",
        "--steps",
        "10",
        "--algorithm",
        "3",
        "--threads",
        "1",
        "--warmup",
        "0",
    ]);
    assert!(out.status.success(), "{out:?}");
    let report = String::from_utf8(out.stdout).expect("UTF-8 report");
    assert!(report.contains("Algorithm 3, 3D, n = 300"), "{report}");
    assert!(report.contains("obstacles             1000"), "{report}");
    let threads = report
        .lines()
        .find(|l| l.trim_start().starts_with("threads"))
        .expect("a threads line");
    assert_eq!(threads.split_whitespace().nth(1), Some("1"), "{report}");
    assert!(
        report.contains("(1 steps, metrics and energy included)"),
        "{report}"
    );
}

#[test]
fn bench_refuses_a_bad_dimension() {
    let out = bench(&["--n", "100", "--dim", "4", "--steps", "1"]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("--dim 4: flocking simulates the plane or space")
    );
}

#[test]
fn bench_runs_under_delay_loss_and_sensing_noise() {
    let out = bench(&[
        "--n",
        "400",
        "--steps",
        "3",
        "--delay",
        "0.1",
        "--loss",
        "0.1",
        "--sensing-noise",
        "0.05,0.02",
        "--control-rate",
        "50",
        "--max-acceleration",
        "10",
    ]);
    assert!(out.status.success(), "{out:?}");
    let report = String::from_utf8(out.stdout).expect("UTF-8 report");
    for line in [
        "  conditions            delay 0.1 s (neighbours), loss 0.1 (Bernoulli), \
         sensing noise 0.05 m, 0.02 m/s (white), control at 50 Hz, acceleration ≤ 10 m/s²",
        // a delay line of 0.1 / 0.01 + 1 = 11 states of 32 B (its newest the measured state),
        // the input held by sampled control and the delivered acceleration (16 B each) and a flag
        // (issue 31: white noise keeps no offsets, Bernoulli loss with dropped packets no links)
        "  conditions' state     385 bytes/agent",
        "  agent-steps/s ",
    ] {
        assert!(report.contains(line), "{line}\n{report}");
    }
}

#[test]
fn bench_refuses_invalid_conditions() {
    for (args, message) in [
        (["--loss", "1.5"], "--loss 1.5: is a probability"),
        (["--delay", "0.015"], "--delay 0.015: is not a whole number"),
        (
            ["--control-rate", "30"],
            "--control-rate 30.0: gives a period",
        ),
    ] {
        let out = bench(&[&["--n", "100", "--steps", "1"][..], &args[..]].concat());
        assert_eq!(out.status.code(), Some(2), "{out:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(message), "{stderr}");
    }
    let out = bench(&["--n", "100", "--delayed", "sometimes"]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
}

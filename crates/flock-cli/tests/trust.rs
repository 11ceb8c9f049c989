//! Runs that blow up, are interrupted or are killed keep whole records, say that they are
//! incomplete, and resume to outputs bit-identical with an uninterrupted run; the `.npy`
//! trajectory holds exactly what the CSV one does.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::thread::sleep;
use std::time::{Duration, Instant};

use flocking::health::Fault;
use flocking::run_dir::{Checkpoint, INCOMPLETE_FILE};
use flocking::{Cloud, DynSimulation, Initial, Record, Recorder, RunError, Scenario};

use crate::common::{files, flocking, remove_own_file, stderr, temp_dir, write};

/// Algorithm 2, 60 agents, 12,000 steps recorded every 10: long enough (about a second in a
/// test build) to be interrupted at many points.
pub(crate) const LONG_2D: &str = r#"Scenario(
    name: "long",
    dim: 2,
    agents: 60,
    seed: 3,
    algorithm: Algorithm2(
        gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.5]),
        c1: 0.02,
        c2: 0.4,
    ),
    initial: (
        positions: Box(min: [-35.0, -35.0], max: [35.0, 35.0]),
        velocities: Box(min: [-1.0, -1.0], max: [1.0, 1.0]),
    ),
    step: 0.01,
    duration: 120.0,
    record_every: 10,
)
"#;

/// [`LONG_2D`] under every condition (issue 21): delayed neighbours with jitter, Gilbert–Elliott
/// loss with held packets, Ornstein–Uhlenbeck sensing at 5 Hz, sampled control, clipped and lagged
/// actuation, gusty wind, process noise and faults at a rate. Each draw is keyed by purpose, agent
/// or link and step, and the checkpoint carries the history, the link, noise and lag states.
fn long_conditioned() -> String {
    let text = with_conditions(
        "        communication: (
            delay: 0.1,
            jitter: 0.05,
            delayed: Neighbours,
            range: 10.0,
            loss: GilbertElliott(p_fail: 0.1, p_recover: 0.9),
            when_lost: Hold(max_age: 0.5),
        ),
        sensing: (noise: OrnsteinUhlenbeck(sigma_q: 0.2, sigma_p: 0.05, correlation_time: 2.0), rate: 5.0),
        control: (rate: 20.0),
        actuation: (max_acceleration: 6.0, max_speed: 8.0, lag: 0.5),
        disturbance: (wind: (mean: [0.3, 0.0], gust: 0.2), process_noise: 0.05),
        faults: (rate: 0.002, mode: Silent),
",
    );
    assert_ne!(text, LONG_2D);
    text
}

/// 30 agents with c₁^α = 200 and h = 0.05: far above the stable step, it runs away at step 1.
const BLOW_UP: &str = r#"Scenario(
    dim: 2,
    agents: 30,
    seed: 1,
    algorithm: Algorithm1,
    alpha: (c1: 200.0),
    initial: (positions: Box(min: [0.0, 0.0], max: [20.0, 20.0])),
    step: 0.05,
    duration: 5.0,
)
"#;

fn partial(out: &Path) -> PathBuf {
    flocking::run_dir::partial_path(out)
}

/// Runs `args` to completion, asserting success.
pub(crate) fn complete(dir: &Path, args: &[&str]) {
    let output = flocking(dir, args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

/// A `flocking` process in the background.
pub(crate) fn spawn(dir: &Path, args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the flock binary starts")
}

/// Sends SIGINT to `child`, as Ctrl-C does.
pub(crate) fn ctrl_c(child: &Child) {
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
}

/// Every line of the first `bytes` bytes of a CSV file is whole: it ends with a newline and has
/// the header's field count. Returns the number of data lines.
fn whole_lines(path: &Path, bytes: Option<u64>) -> usize {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let end = bytes.map_or(text.len(), |b| usize::try_from(b).expect("a length"));
    let text = text
        .get(..end)
        .unwrap_or_else(|| panic!("{} is shorter than {end} bytes", path.display()));
    assert!(
        text.ends_with('\n'),
        "{} ends in a cut line",
        path.display()
    );
    let mut lines = text.lines();
    let fields = lines.next().expect("a header").split(',').count();
    lines
        .map(|line| {
            assert_eq!(
                line.split(',').count(),
                fields,
                "{}: cut line {line:?}",
                path.display()
            );
            assert!(
                line.split(',').all(|x| x.parse::<f64>().is_ok()),
                "{}: unreadable line {line:?}",
                path.display()
            );
        })
        .count()
}

/// What a killed or interrupted run leaves: `DIR.partial` with its note, whole records in every
/// file, and a readable checkpoint, if any, that the files reach.
fn check_incomplete(out: &Path, agents: usize) {
    let dir = partial(out);
    let note = fs::read_to_string(dir.join(INCOMPLETE_FILE)).expect("an INCOMPLETE note");
    assert!(note.starts_with("incomplete: "), "{note}");
    assert!(note.contains("flocking run --resume"), "{note}");
    assert!(!out.exists(), "DIR appears only for complete runs");
    let names = files(&dir);
    for name in names.keys() {
        assert!(
            [
                ".flocking",
                ".flocking.lock",
                "INCOMPLETE",
                "INCOMPLETE.tmp",
                "scenario.ron",
                "metrics.csv",
                "trajectory.csv",
                "trajectory.npy",
                "checkpoint.bin",
                "checkpoint.tmp",
            ]
            .contains(&name.as_str()),
            "unexpected file {name}"
        );
    }
    if !names.contains_key("metrics.csv") {
        return;
    }
    // Up to the checkpoint (or the headers, before the first one) every record is whole; a
    // process killed inside a write may leave one cut record after it, which --resume removes.
    let Some(checkpoint) = Checkpoint::read(&dir).expect("a whole checkpoint or none") else {
        return;
    };
    let records = whole_lines(&dir.join("metrics.csv"), Some(checkpoint.metrics_bytes));
    assert_eq!(records as u64, checkpoint.records);
    if names.contains_key("trajectory.csv") {
        let lines = whole_lines(
            &dir.join("trajectory.csv"),
            Some(checkpoint.trajectory_bytes),
        );
        assert_eq!(
            lines,
            records * agents,
            "the trajectory's records up to the checkpoint"
        );
    }
}

#[test]
fn the_health_check_names_the_step_the_agent_and_the_fault() {
    let base = Scenario::parse(LONG_2D, "long.ron").expect("valid");
    let scenario = Scenario {
        agents: 3,
        initial: Initial {
            positions: Cloud::Explicit(vec![vec![0.0, 0.0], vec![7.0, 0.0], vec![0.0, 7.0]]),
            velocities: Cloud::Zero,
        },
        ..base
    };
    let q = [0.0, 0.0, 7.0, 0.0, 0.0, 7.0];
    let sim = DynSimulation::from_state(&scenario, &q, &[0.0; 6], 5).expect("a valid state");
    assert!(sim.check_health().is_ok());
    // r/h = 8.4/0.01 = 840: one step may not cross the interaction range.
    let p = [0.0, 0.0, 0.0, 839.0, 0.0, 841.0];
    let sim = DynSimulation::from_state(&scenario, &q, &p, 9).expect("a valid state");
    let error = sim.check_health().unwrap_err();
    assert_eq!((error.steps, error.fault.agent), (9, 2));
    assert!(
        matches!(error.fault.fault, Fault::Runaway { speed, limit } if speed == 841.0 && (limit - 840.0).abs() < 1e-9),
        "{error}"
    );
    let message = error.to_string();
    assert!(
        message.starts_with("numerical blow-up at step 9 (t = 0.09): agent 2 runs away at speed"),
        "{message}"
    );
    // a state that is not finite is refused before any step, with its agent
    let p = [0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0];
    let error = DynSimulation::from_state(&scenario, &q, &p, 0).unwrap_err();
    assert_eq!(error.field().as_deref(), Some("velocities[1]"), "{error}");
}

#[test]
fn a_blow_up_stops_the_run_with_the_step_agent_and_cause() {
    let scenario = Scenario::parse(BLOW_UP, "blow_up.ron").expect("valid (with a warning)");
    match flocking::run(&scenario, &mut ()) {
        Err(RunError::Numerical(e)) => {
            assert_eq!(e.steps, 1);
            let message = e.to_string();
            assert!(
                message.starts_with("numerical blow-up at step 1 (t = 0.05): agent"),
                "{message}"
            );
            assert!(
                message.contains("Likely cause: the step h = 0.05 exceeds the largest stable step"),
                "{message}"
            );
        }
        other => panic!("expected a numerical error, got {other:?}"),
    }
}

/// Initial speeds beyond what the step resolves (an agent would cross more than r in its first
/// step) are refused up front, naming the field (issue 49: the run stopped at step 0 as a
/// numerical blow-up); the health check still stops a state given whole.
#[test]
fn initial_speeds_beyond_what_the_step_resolves_are_refused_up_front() {
    let text = LONG_2D.replace(
        "velocities: Box(min: [-1.0, -1.0], max: [1.0, 1.0])",
        "velocities: Box(min: [-1.0, -1.0], max: [1.0, 1e6])",
    );
    let error = Scenario::parse(&text, "fast.ron").expect_err("refused");
    assert_eq!(
        error.field().as_deref(),
        Some("initial.velocities"),
        "{error}"
    );
    let valid = Scenario::parse(LONG_2D, "long.ron").expect("valid");
    let mut velocities = vec![0.0; 2 * valid.agents];
    velocities[1] = 1e6;
    let positions = flocking::DynSimulation::new(&valid)
        .expect("built")
        .state()
        .positions
        .into_owned();
    let sim = flocking::DynSimulation::from_state(&valid, &positions, &velocities, 0)
        .expect("a finite state");
    let fault = sim.check_health().expect_err("too fast");
    assert_eq!(fault.steps, 0);
    assert!(
        matches!(fault.fault.fault, Fault::Runaway { .. }),
        "{fault}"
    );
}

#[test]
fn a_blown_up_run_keeps_its_records_marked_failed_and_refuses_to_resume() {
    let tmp = temp_dir("blow_up_cli");
    let file = write(tmp.path(), "blow_up.ron", BLOW_UP);
    let out = tmp.path().join("out");
    let output = flocking(tmp.path(), &["run", &file, "--out", "out", "--quiet"]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let err = stderr(&output);
    assert!(err.contains("warning: `step` = 0.05"), "{err}");
    assert!(err.contains("error: numerical blow-up at step 1"), "{err}");
    assert!(err.contains("marked incomplete"), "{err}");
    assert!(!out.exists());
    let dir = partial(&out);
    let note = fs::read_to_string(dir.join(INCOMPLETE_FILE)).expect("the note");
    assert!(
        note.starts_with("failed: numerical blow-up at step 1"),
        "{note}"
    );
    // t = 0 was recorded whole; nothing of the bad step was.
    assert_eq!(whole_lines(&dir.join("metrics.csv"), None), 1);
    assert_eq!(whole_lines(&dir.join("trajectory.csv"), None), 30);
    let resumed = flocking(tmp.path(), &["run", "--resume", "out"]);
    assert_eq!(resumed.status.code(), Some(2));
    assert!(
        stderr(&resumed).contains("cannot be resumed, it would fail again"),
        "{}",
        stderr(&resumed)
    );
}

#[test]
fn ctrl_c_stops_after_a_step_and_resume_is_bit_identical() {
    let tmp = temp_dir("ctrl_c");
    let file = write(tmp.path(), "long.ron", LONG_2D);
    let clock = Instant::now();
    complete(tmp.path(), &["run", &file, "--out", "whole", "--quiet"]);
    let whole_run = clock.elapsed();
    // Ctrl-C a third of an uninterrupted run's time after the start: past start-up (the handler is
    // installed), before the end; sooner again if a faster run still finished first.
    let mut delay = whole_run / 3;
    let output = loop {
        let _ = fs::remove_dir_all(tmp.path().join("cut"));
        let args = [
            "run",
            &file,
            "--out",
            "cut",
            "--quiet",
            "--checkpoint-every",
            "0",
        ];
        let child = spawn(tmp.path(), &args);
        sleep(delay);
        ctrl_c(&child);
        let output = child.wait_with_output().expect("the run ends");
        if output.status.code() == Some(0) && delay > Duration::from_millis(40) {
            delay /= 4;
            continue;
        }
        break output;
    };
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        output.status.code(),
        Some(130),
        "the run ended before Ctrl-C: {err}"
    );
    assert!(err.contains("interrupted after step"), "{err}");
    let out = tmp.path().join("cut");
    check_incomplete(&out, 60);
    let note = fs::read_to_string(partial(&out).join(INCOMPLETE_FILE)).expect("the note");
    assert!(
        note.starts_with("incomplete: interrupted after step"),
        "{note}"
    );
    let checkpoint = Checkpoint::read(&partial(&out))
        .expect("readable")
        .expect("Ctrl-C keeps a checkpoint even with --checkpoint-every 0");
    assert!(checkpoint.start.steps > 0 && checkpoint.start.steps < 12_000);
    // A new run into the same directory is refused: it would discard the interrupted one.
    let again = flocking(tmp.path(), &["run", &file, "--out", "cut"]);
    assert_eq!(again.status.code(), Some(2));
    assert!(
        stderr(&again).contains("flocking run --resume"),
        "{}",
        stderr(&again)
    );
    complete(tmp.path(), &["run", "--resume", "cut", "--quiet"]);
    assert_eq!(files(&out), files(&tmp.path().join("whole")));
    assert!(!partial(&out).exists());
    let finished = flocking(tmp.path(), &["run", "--resume", "cut"]);
    assert!(
        stderr(&finished).contains("holds a complete run"),
        "{}",
        stderr(&finished)
    );
}

/// Kills runs with SIGKILL at pseudo-random instants, checks what each leaves, resumes, and
/// compares the completed outputs with an uninterrupted run's, which it returns by file name.
fn kill_and_resume(
    test: &str,
    scenario: &str,
    format: &str,
    kills: usize,
) -> std::collections::BTreeMap<String, Vec<u8>> {
    let tmp = temp_dir(test);
    let file = write(tmp.path(), "long.ron", scenario);
    let format_args = ["--trajectory-format", format];
    let mut args = vec!["run", &file, "--out", "whole", "--quiet"];
    args.extend(format_args);
    let clock = Instant::now();
    complete(tmp.path(), &args);
    // Kills land between 1 % and 12 % of an uninterrupted run's time after each (re)start, so
    // that most of them fall mid-run whatever the machine's speed.
    let whole_run = clock.elapsed().as_secs_f64();
    let out = tmp.path().join("cut");
    let mut first = vec![
        "run",
        &file,
        "--out",
        "cut",
        "--quiet",
        "--checkpoint-every",
        "50",
    ];
    first.extend(format_args);
    let resume = [
        "run",
        "--resume",
        "cut",
        "--quiet",
        "--checkpoint-every",
        "50",
    ];
    // A fixed linear congruential sequence of fractions in [0.01, 0.12).
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut delay = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let fraction = 0.01 + 0.11 * ((state >> 11) as f64 / (1u64 << 53) as f64);
        Duration::from_secs_f64(fraction * whole_run)
    };
    let (mut killed, mut early) = (0, 0);
    let mut child = spawn(tmp.path(), &first);
    while killed < kills {
        let started = Instant::now();
        let wait = delay();
        while started.elapsed() < wait && child.try_wait().expect("poll").is_none() {
            sleep(Duration::from_millis(2));
        }
        if child.try_wait().expect("poll").is_some() {
            break;
        }
        child.kill().expect("SIGKILL");
        child.wait().expect("reaped");
        if !partial(&out).exists() {
            // killed while preparing, before `DIR.partial` appeared (it is built under another
            // name and renamed whole): nothing to resume, the user's tree untouched but for
            // that staging directory, which the next run into `DIR` clears (its process is gone)
            assert!(!out.exists(), "DIR appears only for complete runs");
            early += 1;
            assert!(early < 10 * kills, "{early} kills before the run appeared");
            child = spawn(tmp.path(), &first);
            continue;
        }
        killed += 1;
        check_incomplete(&out, 60);
        child = spawn(tmp.path(), &resume);
    }
    let output = child.wait_with_output().expect("the last run ends");
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    eprintln!("{killed} SIGKILLs mid-run, each leaving whole records");
    assert!(killed >= kills / 2, "only {killed} kills landed mid-run");
    let whole = files(&tmp.path().join("whole"));
    assert_eq!(files(&out), whole, "after {killed} kills");
    whole
}

#[test]
fn runs_killed_at_random_instants_resume_to_bit_identical_csv_outputs() {
    kill_and_resume("sigkill_csv", LONG_2D, "csv", 12);
}

#[test]
fn runs_killed_at_random_instants_resume_to_bit_identical_npy_outputs() {
    kill_and_resume("sigkill_npy", LONG_2D, "npy", 6);
}

#[test]
fn runs_under_every_condition_killed_at_random_instants_resume_to_bit_identical_outputs() {
    let whole = kill_and_resume("sigkill_conditions", &long_conditioned(), "csv", 8);
    // the conditions were on: links were lost, information was old, agents failed
    let metrics = String::from_utf8_lossy(&whole["metrics.csv"]).into_owned();
    let mut lines = metrics.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let last: Vec<f64> = lines
        .last()
        .expect("records")
        .split(',')
        .map(|field| field.parse().expect("a number"))
        .collect();
    let column = |name: &str| {
        let k = header.iter().position(|h| *h == name);
        last[k.unwrap_or_else(|| panic!("no {name} in {header:?}"))]
    };
    assert!(column("links_lost") > 0.0, "{header:?} {last:?}");
    assert!(column("information_age") >= 0.1, "{header:?} {last:?}");
    assert!(column("failed") >= 1.0, "{header:?} {last:?}");
}

#[test]
fn a_corrupt_checkpoint_is_refused_with_its_path() {
    let tmp = temp_dir("corrupt_checkpoint");
    let out = tmp.path().join("cut");
    let dir = partial(&out);
    fs::create_dir_all(&dir).expect("mkdir");
    // flocking's partial directory (issue 27: a resume writes only into a marked one)
    fs::write(dir.join(".flocking"), "written by flocking run\n").expect("marker");
    fs::write(dir.join("scenario.ron"), LONG_2D).expect("scenario");
    fs::write(dir.join(INCOMPLETE_FILE), "incomplete: killed\n").expect("note");
    fs::write(dir.join("checkpoint.bin"), b"FLOCKCK2 but cut short").expect("checkpoint");
    let output = flocking(tmp.path(), &["run", "--resume", "cut"]);
    assert_eq!(output.status.code(), Some(1));
    let err = stderr(&output);
    assert!(
        err.contains("checkpoint.bin is not a flock checkpoint"),
        "{err}"
    );
}

/// The records of a `.npy` file: its header's dict and its data as f64.
fn read_npy(path: &Path) -> (String, Vec<f64>) {
    let bytes = fs::read(path).expect("the npy file");
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let len = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
    assert_eq!((10 + len) % 64, 0, "the header is padded to 64 bytes");
    let dict = String::from_utf8(bytes[10..10 + len].to_vec()).expect("an ASCII header");
    assert!(dict.ends_with('\n'));
    let data = bytes[10 + len..]
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect();
    (dict, data)
}

#[test]
fn the_npy_trajectory_holds_exactly_the_csv_trajectory() {
    let tmp = temp_dir("npy");
    let text = LONG_2D.replace("duration: 120.0", "duration: 0.5");
    let file = write(tmp.path(), "short.ron", &text);
    complete(tmp.path(), &["run", &file, "--out", "csv", "--quiet"]);
    complete(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "npy",
            "--quiet",
            "--trajectory-format",
            "npy",
        ],
    );
    let (csv, npy) = (tmp.path().join("csv"), tmp.path().join("npy"));
    for name in ["metrics.csv", "final.csv", "scenario.ron"] {
        assert_eq!(
            fs::read(csv.join(name)).ok(),
            fs::read(npy.join(name)).ok(),
            "{name}"
        );
    }
    assert!(!npy.join("trajectory.csv").exists());
    let (dict, data) = read_npy(&npy.join("trajectory.npy"));
    let (agents, records) = (60, 6);
    assert!(
        dict.starts_with(
            "{'descr': [('t', '<f8'), ('q', '<f8', (60, 2)), ('p', '<f8', (60, 2))], 'fortran_order': False, 'shape': (6,), }"
        ),
        "{dict}"
    );
    assert_eq!(data.len(), records * (1 + 4 * agents));
    let rows: Vec<Vec<f64>> = fs::read_to_string(csv.join("trajectory.csv"))
        .expect("trajectory.csv")
        .lines()
        .skip(1)
        .map(|line| {
            line.split(',')
                .map(|x| x.parse().expect("a number"))
                .collect()
        })
        .collect();
    for (k, record) in data.chunks_exact(1 + 4 * agents).enumerate() {
        let (q, p) = record[1..].split_at(2 * agents);
        for i in 0..agents {
            let row = &rows[k * agents + i];
            assert_eq!(record[0].to_bits(), row[0].to_bits(), "t of record {k}");
            assert_eq!(row[1], i as f64);
            assert_eq!(
                [q[2 * i], q[2 * i + 1], p[2 * i], p[2 * i + 1]],
                row[2..6],
                "agent {i} of record {k}"
            );
        }
    }
}

/// Checks that every recorded value is finite (`min_distance` may be +∞ for a single agent) and
/// that every record names the same diagnostic columns as the first.
struct Finite {
    columns: Option<Vec<&'static str>>,
    agents: usize,
}

impl Recorder for Finite {
    type Error = std::convert::Infallible;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let m = &record.metrics;
        let values = [
            m.connectivity,
            m.giant_component,
            m.cohesion_radius,
            m.deviation_energy,
            m.velocity_mismatch,
            record.energy,
        ];
        assert!(
            values.iter().all(|x| x.is_finite()),
            "t = {}: {values:?}",
            record.t
        );
        assert!(m.min_distance.is_finite() || self.agents < 2);
        let names: Vec<&'static str> = record.diagnostics.iter().map(|&(name, _)| name).collect();
        let columns = self.columns.get_or_insert_with(|| names.clone());
        assert_eq!(*columns, names, "the diagnostic columns of every record");
        assert!(
            record
                .diagnostics
                .iter()
                .all(|(name, x)| x.is_finite()
                    || (*name == "min_linked_distance" && self.agents < 2)),
            "{:?}",
            record.diagnostics
        );
        Ok(())
    }
}

/// Every input the fuzzer found (`fuzz/regressions/`) is now rejected with a message naming a
/// field, or runs (cut to 20 steps) recording only finite values in the declared columns.
#[test]
fn the_fuzzers_findings_are_rejected_or_run_finite() {
    let dir = crate::common::fixtures_dir().join("../fuzz/regressions");
    let mut paths: Vec<PathBuf> = fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "ron"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 10, "{} findings", paths.len());
    for path in paths {
        let text = fs::read_to_string(&path).expect("a finding");
        let scenario = match Scenario::parse(&text, "finding.ron") {
            Err(e) => {
                assert!(e.field().is_some(), "{}: {e}", path.display());
                continue;
            }
            Ok(scenario) => scenario,
        };
        let short = Scenario {
            duration: scenario.duration.min(20.0 * scenario.step),
            ..scenario
        };
        let mut finite = Finite {
            columns: None,
            agents: short.agents,
        };
        match flocking::run(&short, &mut finite) {
            Ok(_) | Err(RunError::Numerical(_)) => {}
            Err(e) => panic!("{}: {e}", path.display()),
        }
    }
}

/// A short run (2D, 20 agents, 400 steps recorded every 10) for the ownership tests.
pub(crate) const SHORT_2D: &str = r#"Scenario(
    name: "short",
    dim: 2,
    agents: 20,
    seed: 5,
    algorithm: Algorithm2(
        gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.5]),
        c1: 0.02,
        c2: 0.4,
    ),
    initial: (positions: Box(min: [-15.0, -15.0], max: [15.0, 15.0])),
    step: 0.01,
    duration: 4.0,
    record_every: 10,
)
"#;

/// Asserts that `output` exited with code 2 and that its stderr holds every one of `words`.
pub(crate) fn refused(output: &std::process::Output, words: &[&str]) {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(2), "{err}");
    for word in words {
        assert!(err.contains(word), "{word:?} missing from: {err}");
    }
}

#[test]
fn issue_20_force_never_replaces_a_users_directory() {
    let tmp = temp_dir("force_user_dir");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    let d = tmp.path().join("d");
    fs::create_dir(&d).expect("mkdir");
    fs::write(d.join("thesis.tex"), "x\n").expect("a user's file");
    let output = flocking(tmp.path(), &["run", &file, "--out", "d", "--force"]);
    refused(
        &output,
        &["d holds thesis.tex, which flocking did not write"],
    );
    assert_eq!(fs::read(d.join("thesis.tex")).expect("kept"), b"x\n");
    assert!(!partial(&d).exists());
    // A user's file added to a run directory protects it too.
    complete(tmp.path(), &["run", &file, "--out", "r", "--quiet"]);
    fs::write(tmp.path().join("r/notes.txt"), "mine\n").expect("a user's file");
    let output = flocking(tmp.path(), &["run", &file, "--out", "r", "--force"]);
    refused(&output, &["holds notes.txt"]);
    assert_eq!(
        fs::read(tmp.path().join("r/notes.txt")).expect("kept"),
        b"mine\n"
    );
    // ...and a run directory of flocking's alone is replaced, once the user takes their file.
    remove_own_file(tmp.path(), &tmp.path().join("r/notes.txt"), b"mine\n");
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--force", "--quiet"],
    );
}

#[test]
fn issue_20_force_never_replaces_the_working_directory_or_its_parents() {
    let tmp = temp_dir("force_cwd");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    // p/c and p look like flocking's run directories, and are still refused.
    let c = tmp.path().join("p/c");
    complete(tmp.path(), &["run", &file, "--out", "p/c", "--quiet"]);
    for dir in [tmp.path().join("p"), c.clone()] {
        fs::write(dir.join(".flocking"), "written by flocking run\n").expect("marker");
    }
    let before = files(&c);
    for out in [".", "..", c.parent().and_then(Path::to_str).expect("UTF-8")] {
        let output = flocking(&c, &["run", &file, "--out", out, "--force"]);
        refused(
            &output,
            &[
                "the working directory or one of its parents",
                "flocking never replaces it",
            ],
        );
        assert_eq!(files(&c), before, "--out {out}");
    }
    // The default output of a scenario named `..ron` is `out/.`, the directory of every run.
    let dots = write(tmp.path(), "..ron", SHORT_2D);
    complete(
        tmp.path(),
        &["run", &file, "--out", "out/earlier", "--quiet"],
    );
    let earlier = files(&tmp.path().join("out/earlier"));
    let output = flocking(tmp.path(), &["run", &dots, "--force"]);
    refused(&output, &["holds earlier, which flocking did not write"]);
    assert_eq!(files(&tmp.path().join("out/earlier")), earlier);
}

/// A tmpfs of `size` mounted at `dir` (as root), unmounted when dropped; `None` (with the
/// reason printed) where this process cannot mount.
struct Tmpfs(PathBuf);

impl Tmpfs {
    fn mount(dir: &Path, size: &str) -> Option<Self> {
        fs::create_dir_all(dir).expect("mkdir");
        let status = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(dir)
            .stderr(Stdio::null())
            .status();
        if status.is_ok_and(|s| s.success()) {
            Some(Self(dir.to_owned()))
        } else {
            eprintln!("SKIPPED: cannot mount a tmpfs (needs root): the test checks nothing here");
            None
        }
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

#[test]
fn issue_20_force_never_replaces_a_mount_point() {
    let tmp = temp_dir("force_mount");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    let Some(_mount) = Tmpfs::mount(&tmp.path().join("m"), "1m") else {
        return;
    };
    let m = tmp.path().join("m");
    fs::write(m.join(".flocking"), "written by flocking run\n").expect("marker");
    fs::write(m.join("metrics.csv"), "t\n").expect("a file");
    let before = files(&m);
    let output = flocking(tmp.path(), &["run", &file, "--out", "m", "--force"]);
    refused(&output, &["m is a mount point"]);
    assert_eq!(files(&m), before);
}

/// Waits until `path` exists (or the child exits), polling.
fn wait_for(path: &Path, child: &mut Child) {
    while !path.exists() {
        assert!(
            child.try_wait().expect("poll").is_none(),
            "the run ended before {} appeared",
            path.display()
        );
        sleep(Duration::from_millis(2));
    }
}

#[test]
fn issue_20_a_directory_appearing_during_the_run_is_kept_and_the_run_stays_resumable() {
    let tmp = temp_dir("appearing");
    let file = write(tmp.path(), "long.ron", LONG_2D);
    complete(tmp.path(), &["run", &file, "--out", "whole", "--quiet"]);
    let out = tmp.path().join("cut");
    let mut child = spawn(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "cut",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    wait_for(&partial(&out).join("checkpoint.bin"), &mut child);
    fs::create_dir(&out).expect("mkdir");
    fs::write(out.join("thesis.tex"), "x\n").expect("a user's file");
    let output = child.wait_with_output().expect("the run ends");
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains("appeared during the run"), "{err}");
    assert!(err.contains("flocking run --resume"), "{err}");
    assert_eq!(fs::read(out.join("thesis.tex")).expect("kept"), b"x\n");
    fs::rename(&out, tmp.path().join("moved")).expect("the user moves it away");
    complete(tmp.path(), &["run", "--resume", "cut", "--quiet"]);
    assert_eq!(files(&out), files(&tmp.path().join("whole")));
    // An empty directory appearing is kept too (only a `DIR` empty from the start is replaced):
    // the finishing rename refuses any existing `DIR` (RENAME_NOREPLACE), so that nothing
    // appearing between the last check and the rename is replaced either.
    let out = tmp.path().join("cut2");
    let mut child = spawn(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "cut2",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    wait_for(&partial(&out).join("checkpoint.bin"), &mut child);
    fs::create_dir(&out).expect("an empty directory appears");
    let output = child.wait_with_output().expect("the run ends");
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains("appeared during the run"), "{err}");
    assert!(out.is_dir() && fs::read_dir(&out).expect("ls").next().is_none());
    fs::remove_dir(&out).expect("the user removes it");
    complete(tmp.path(), &["run", "--resume", "cut2", "--quiet"]);
    assert_eq!(files(&out), files(&tmp.path().join("whole")));
    // An empty `DIR` that was there from the start is the run's to fill.
    let empty = tmp.path().join("empty");
    fs::create_dir(&empty).expect("mkdir");
    complete(tmp.path(), &["run", &file, "--out", "empty", "--quiet"]);
    assert_eq!(files(&empty), files(&tmp.path().join("whole")));
}

#[test]
fn issue_20_a_second_writer_is_refused_with_the_first_ones_pid() {
    let tmp = temp_dir("two_writers");
    let file = write(tmp.path(), "long.ron", LONG_2D);
    complete(tmp.path(), &["run", &file, "--out", "whole", "--quiet"]);
    let out = tmp.path().join("cut");
    let mut child = spawn(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "cut",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    let pid = format!("process {}", child.id());
    wait_for(&partial(&out).join("checkpoint.bin"), &mut child);
    let resumed = flocking(tmp.path(), &["run", "--resume", "cut"]);
    refused(
        &resumed,
        &["cut.partial is being written by", &pid, "started"],
    );
    let forced = flocking(tmp.path(), &["run", &file, "--out", "cut", "--force"]);
    refused(&forced, &["is being written by", &pid]);
    let output = child.wait_with_output().expect("the first run ends");
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(files(&out), files(&tmp.path().join("whole")));
    // A killed writer's lock goes with it: the next one takes over.
    let mut child = spawn(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "again",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    wait_for(
        &partial(&tmp.path().join("again")).join("checkpoint.bin"),
        &mut child,
    );
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    complete(tmp.path(), &["run", "--resume", "again", "--quiet"]);
    assert_eq!(
        files(&tmp.path().join("again")),
        files(&tmp.path().join("whole"))
    );
}

#[test]
fn issue_20_resume_refuses_an_edited_scenario_naming_the_field() {
    let tmp = temp_dir("edited_scenario");
    let file = write(tmp.path(), "long.ron", LONG_2D);
    let out = tmp.path().join("cut");
    let mut child = spawn(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "cut",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    wait_for(&partial(&out).join("checkpoint.bin"), &mut child);
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    let scenario = partial(&out).join("scenario.ron");
    let text = fs::read_to_string(&scenario).expect("scenario");
    let edited = text.replacen("c1: 0.02", "c1: 0.05", 1);
    assert_ne!(edited, text, "the resolved scenario writes c1: 0.02");
    fs::write(&scenario, &edited).expect("edit");
    let before = files(&partial(&out));
    let output = flocking(tmp.path(), &["run", "--resume", "cut"]);
    refused(&output, &["scenario.ron was edited", "algorithm.c1"]);
    let mut after = files(&partial(&out));
    after.remove(".flocking.lock");
    let mut before = before;
    before.remove(".flocking.lock");
    assert_eq!(after, before, "the refused resume changes nothing");
}

/// `dir`'s checkpoint rewritten with the magic `magic` (and its hash recomputed): the checkpoint
/// an older flocking would have written of the same state.
fn remagic_checkpoint(dir: &Path, magic: &[u8; 8]) {
    let path = dir.join("checkpoint.bin");
    let mut bytes = fs::read(&path).expect("a checkpoint");
    bytes.truncate(bytes.len() - 8);
    bytes[..8].copy_from_slice(magic);
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    bytes.extend_from_slice(&hash.to_le_bytes());
    fs::write(&path, bytes).expect("rewritten");
}

/// Runs `text` (as `name`) in `dir` until its first checkpoint, kills it, rewrites the
/// checkpoint with the older format's `magic`, and resumes it. A resume that `refuses` must name
/// `words` and change nothing; otherwise it must end the run with the bytes of an uninterrupted
/// one.
fn resume_from_older_checkpoint(
    dir: &Path,
    name: &str,
    text: &str,
    magic: &[u8; 8],
    refuses: Option<&[&str]>,
) {
    let file = write(dir, &format!("{name}.ron"), text);
    let out = dir.join(name);
    let args = [
        "run",
        &file,
        "--out",
        name,
        "--quiet",
        "--checkpoint-every",
        "50",
    ];
    let mut child = spawn(dir, &args);
    wait_for(&partial(&out).join("checkpoint.bin"), &mut child);
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    remagic_checkpoint(&partial(&out), magic);
    let mut before = files(&partial(&out));
    let output = flocking(dir, &["run", "--resume", name]);
    if let Some(words) = refuses {
        refused(&output, words);
        let mut after = files(&partial(&out));
        after.remove(".flocking.lock");
        before.remove(".flocking.lock");
        assert_eq!(after, before, "the refused resume changes nothing");
    } else {
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        assert!(!partial(&out).exists());
        let whole = format!("{name}_whole");
        complete(dir, &["run", &file, "--out", &whole, "--quiet"]);
        for f in ["metrics.csv", "trajectory.csv", "final.csv"] {
            assert!(
                fs::read(out.join(f)).expect("resumed")
                    == fs::read(dir.join(&whole).join(f)).expect("whole"),
                "{f} of the resumed run {name} differs from the uninterrupted run's"
            );
        }
    }
}

/// Resumes `long_conditioned()` (every condition) and `accepted` from checkpoints rewritten
/// with an older format's `magic`: the first refused, naming `why`, the second resumed bit for
/// bit ([`resume_from_older_checkpoint`]).
fn older_checkpoint(name: &str, magic: &[u8; 8], why: &[&str], accepted: &str) {
    let tmp = temp_dir(name);
    let dir = tmp.path();
    resume_from_older_checkpoint(dir, "refused", &long_conditioned(), magic, Some(why));
    resume_from_older_checkpoint(dir, "accepted", accepted, magic, None);
}

/// `LONG_2D` with `conditions` (the lines inside `conditions: ( … )`).
fn with_conditions(conditions: &str) -> String {
    LONG_2D.replacen(
        "    record_every: 10,\n",
        &format!("    record_every: 10,\n    conditions: (\n{conditions}    ),\n"),
        1,
    )
}

/// Issue 31: the random draws moved from ChaCha8 to Philox4x32-10, so a checkpoint of the older
/// format (`FLOCKCK3`) of a run that draws at random cannot continue bit for bit: its resume is
/// refused, naming why and the fix, and changes nothing; a run without random draws resumes
/// from it.
#[test]
fn issue_31_a_checkpoint_of_chacha8_draws_is_refused_for_a_random_run_only() {
    let why = ["ChaCha8", "Philox4x32-10", "start the run again"];
    older_checkpoint("chacha8_checkpoint", b"FLOCKCK3", &why, LONG_2D);
}

/// The normal draws moved from Box–Muller to the ziggurat, so a checkpoint of the older format
/// (`FLOCKCK4`) of a run that draws normals (sensing noise, gusts, process noise) cannot continue
/// bit for bit: its resume is refused, naming why and the fix, and changes nothing. A run whose
/// draws are all uniforms drawn as then (symmetric Bernoulli loss, random failures) resumes from
/// it to the bytes of the uninterrupted run.
#[test]
fn a_checkpoint_of_box_muller_normals_is_refused_for_a_run_that_draws_normals_only() {
    let uniforms = with_conditions(
        "        communication: (delay: 0.1, loss: Bernoulli(p: 0.2), symmetric: true),
        faults: (rate: 0.002, mode: Removed),
",
    );
    let why = ["Box–Muller", "ziggurat", "start the run again"];
    older_checkpoint("box_muller_checkpoint", b"FLOCKCK4", &why, &uniforms);
}

/// A receiver's links now draw their loss and jitter from the receiver's shared Philox blocks,
/// so a checkpoint of the older format (`FLOCKCK5`, a block per link) of a run that draws per
/// link (jitter, loss that is not symmetric) cannot continue bit for bit: its resume is refused,
/// naming why and the fix, and changes nothing. A run whose draws are per agent or per pair
/// (sensing noise, symmetric loss, random failures) resumes from it to the bytes of the
/// uninterrupted run.
#[test]
fn a_checkpoint_of_a_block_per_link_is_refused_for_a_run_that_draws_per_link_only() {
    let per_agent = with_conditions(
        "        communication: (delay: 0.1, loss: Bernoulli(p: 0.2), symmetric: true),
        sensing: (noise: White(sigma_q: 0.1, sigma_p: 0.05)),
        faults: (rate: 0.002, mode: Removed),
",
    );
    let why = ["a block of its own", "shared blocks", "start the run again"];
    older_checkpoint("block_per_link_checkpoint", b"FLOCKCK5", &why, &per_agent);
}

/// A file of the test's own that fills the filesystem of its directory but `pages` pages; it
/// is created new (never a file that was there) and removed when dropped, only if the path still
/// names that very file (its device and inode).
struct Filler {
    path: PathBuf,
    identity: (u64, u64),
}

impl Filler {
    fn new(dir: &Path, pages: u64) -> Self {
        use std::io::Write as _;
        use std::os::unix::fs::MetadataExt as _;
        let path = dir.join("filler");
        let mut file = fs::File::create_new(&path).expect("a new filler file");
        let page = vec![0u8; 4096];
        while file.write_all(&page).is_ok() {}
        let metadata = file.metadata().expect("metadata");
        file.set_len(metadata.len().saturating_sub(pages * 4096))
            .expect("free pages");
        Self {
            path,
            identity: (metadata.dev(), metadata.ino()),
        }
    }
}

impl Drop for Filler {
    fn drop(&mut self) {
        use std::os::unix::fs::MetadataExt as _;
        let ours = fs::symlink_metadata(&self.path)
            .is_ok_and(|m| m.is_file() && (m.dev(), m.ino()) == self.identity);
        if ours {
            let _ = fs::remove_file(&self.path);
        }
    }
}

#[test]
fn issue_20_a_full_disk_at_any_phase_keeps_the_run_resumable() {
    let tmp = temp_dir("full_disk");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(tmp.path(), &["run", &file, "--out", "whole", "--quiet"]);
    let whole = files(&tmp.path().join("whole"));
    let bytes: u64 = whole.values().map(|b| b.len() as u64).sum();
    let disk = tmp.path().join("disk");
    let Some(_mount) = Tmpfs::mount(&disk, "4m") else {
        return;
    };
    fs::write(disk.join("thesis.tex"), "x\n").expect("a user's file");
    // The resource check refuses a full disk before writing anything, with the figures...
    let filler = Filler::new(&disk, 0);
    let refused = flocking(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            disk.join("refused").to_str().expect("UTF-8"),
            "--quiet",
        ],
    );
    drop(filler); // frees the space
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    assert!(
        stderr(&refused).contains("of disk but 0 B is free"),
        "{}",
        stderr(&refused)
    );
    assert!(!disk.join("refused").exists() && !disk.join("refused.partial").exists());
    // ...and with it overridden, every write phase may meet the full disk.
    let mut failures = 0;
    // From no free page to enough for every file (each file takes whole pages).
    for pages in 0..=bytes / 4096 + 12 {
        let out = disk.join(format!("run{pages}"));
        let out_arg = out.to_str().expect("UTF-8");
        let filler = Filler::new(&disk, pages);
        let output = flocking(
            tmp.path(),
            &[
                "run",
                &file,
                "--out",
                out_arg,
                "--quiet",
                "--checkpoint-every",
                "40",
                "--no-resource-check",
            ],
        );
        drop(filler); // frees the space
        let err = stderr(&output);
        assert_eq!(fs::read(disk.join("thesis.tex")).expect("kept"), b"x\n");
        match output.status.code() {
            Some(0) => {}
            Some(1) => {
                failures += 1;
                assert!(
                    err.contains("No space left on device") && err.contains("cannot "),
                    "{err}"
                );
                if partial(&out).exists() {
                    assert!(err.contains("flocking run --resume"), "{err}");
                    complete(tmp.path(), &["run", "--resume", out_arg, "--quiet"]);
                } else {
                    assert!(!out.exists(), "{pages} pages: {err}");
                    complete(tmp.path(), &["run", &file, "--out", out_arg, "--quiet"]);
                }
            }
            code => panic!("{pages} free pages: exit {code:?}: {err}"),
        }
        let written = files(&out);
        assert_eq!(
            written.keys().collect::<Vec<_>>(),
            whole.keys().collect::<Vec<_>>(),
            "{pages} free pages: {err}"
        );
        assert!(written == whole, "{pages} free pages: {err}");
        // the finished run is flocking's, and removable as such (its marker checked first)
        flocking::owned::remove(&out, flocking::owned::Kind::Run).expect("a run of flocking's");
    }
    assert!(failures > 3, "only {failures} runs hit the full disk");
}

#[test]
fn issue_20_a_stopped_sweep_exits_130_as_a_stopped_run() {
    let tmp = temp_dir("sweep_stopped");
    write(tmp.path(), "long.ron", LONG_2D);
    let sweep = write(
        tmp.path(),
        "sweep.ron",
        r#"Sweep(name: "stopped", base: Path("long.ron"), axes: [], seeds: 40)"#,
    );
    let mut child = spawn(
        tmp.path(),
        &["sweep", &sweep, "--out", "sw", "--jobs", "1", "--quiet"],
    );
    wait_for(&tmp.path().join("sw/sweep.ron"), &mut child);
    ctrl_c(&child);
    let output = child.wait_with_output().expect("the sweep ends");
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{err}");
    assert!(err.contains("the same command resumes"), "{err}");
}

/// `flocking sweep plot sw` of the fraction of α-flocks over the seeds of [`seeds_sweep`].
pub(crate) const PLOT_SEEDS: [&str; 7] = [
    "sweep",
    "plot",
    "sw",
    "--x",
    "seed",
    "--metric",
    "alpha_flock",
];

/// A sweep of `seeds` runs of `base` (a file in the same directory), no axes.
pub(crate) fn seeds_sweep(dir: &Path, base: &str, seeds: usize) -> String {
    write(
        dir,
        "sweep.ron",
        &format!(r#"Sweep(name: "seeds", base: Path("{base}"), axes: [], seeds: {seeds})"#),
    )
}

#[test]
fn issue_20_sweep_and_merge_never_replace_a_users_files() {
    let tmp = temp_dir("sweep_user_dir");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    let mine = tmp.path().join("mine");
    fs::create_dir(&mine).expect("mkdir");
    fs::write(mine.join("runs.csv"), "my,own\n1,2\n").expect("a user's file");
    let before = files(&mine);
    let output = flocking(tmp.path(), &["sweep", &sweep, "--out", "mine", "--quiet"]);
    refused(
        &output,
        &["mine holds runs.csv, which flocking did not write"],
    );
    assert_eq!(files(&mine), before);
    // a run directory of flocking's is not a sweep's
    complete(tmp.path(), &["run", "short.ron", "--out", "r", "--quiet"]);
    let run = files(&tmp.path().join("r"));
    let output = flocking(tmp.path(), &["sweep", &sweep, "--out", "r", "--quiet"]);
    refused(
        &output,
        &["r is a run directory of flocking's, not a sweep's output directory"],
    );
    assert_eq!(files(&tmp.path().join("r")), run);
    // a sweep's directory is marked, unlocked when done, and the same command resumes it
    complete(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    let sw = tmp.path().join("sw");
    assert_eq!(
        fs::read_to_string(sw.join(".flocking")).expect("marker"),
        "written by flocking sweep\n"
    );
    assert!(!sw.join(".flocking.lock").exists());
    let runs = fs::read(sw.join("runs.csv")).expect("runs.csv");
    let again = flocking(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    assert_eq!(again.status.code(), Some(0), "{}", stderr(&again));
    assert!(String::from_utf8_lossy(&again.stdout).contains("2 found done"));
    assert_eq!(fs::read(sw.join("runs.csv")).expect("runs.csv"), runs);
    // merge: into a user's directory refused, into a new one done
    let output = flocking(tmp.path(), &["sweep", "merge", "--out", "mine", "sw"]);
    refused(
        &output,
        &["mine holds runs.csv, which flocking did not write"],
    );
    assert_eq!(files(&mine), before);
    complete(tmp.path(), &["sweep", "merge", "--out", "merged", "sw"]);
    assert_eq!(
        fs::read(tmp.path().join("merged/runs.csv")).expect("merged"),
        runs
    );
}

#[test]
fn issue_20_a_kept_run_never_replaces_a_users_directory() {
    let tmp = temp_dir("sweep_keep_user");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 1);
    let args = ["sweep", &sweep, "--out", "sw", "--keep-runs", "--quiet"];
    complete(tmp.path(), &args);
    let sw = tmp.path().join("sw");
    let id = fs::read_dir(sw.join("runs"))
        .expect("runs/")
        .next()
        .expect("one run")
        .expect("entry")
        .file_name();
    let run = sw.join("runs").join(&id);
    // the run's row is lost, and a user's file is in its directory: it is run again, and refused
    let id = id.to_string_lossy();
    for row in fs::read_dir(sw.join("rows")).expect("rows/") {
        let row = row.expect("entry").path();
        let name = row
            .file_name()
            .expect("a name")
            .to_string_lossy()
            .into_owned();
        assert!(
            name.ends_with(&format!("-{id}.csv")),
            "{name}: not the row of run {id}"
        );
        remove_own_file(tmp.path(), &row, b"");
    }
    fs::write(run.join("thesis.tex"), "x\n").expect("a user's file");
    let output = flocking(tmp.path(), &args);
    let err = stderr(&output);
    assert!(
        err.contains("holds thesis.tex, which flocking did not write"),
        "{err}"
    );
    assert_eq!(fs::read(run.join("thesis.tex")).expect("kept"), b"x\n");
    assert!(run.join("metrics.csv").is_file(), "the earlier run is kept");
}

#[test]
fn issue_20_a_second_sweep_writer_is_refused_with_the_first_ones_pid() {
    let tmp = temp_dir("two_sweeps");
    write(tmp.path(), "long.ron", LONG_2D);
    let sweep = seeds_sweep(tmp.path(), "long.ron", 2);
    let args = [
        "sweep",
        &sweep,
        "--out",
        "sw",
        "--keep-runs",
        "--jobs",
        "1",
        "--quiet",
    ];
    let mut child = spawn(tmp.path(), &args);
    let pid = format!("process {}", child.id());
    wait_for(&tmp.path().join("sw/runs"), &mut child);
    let second = flocking(tmp.path(), &args);
    refused(&second, &["sw is being written by", &pid, "started"]);
    let merged = flocking(tmp.path(), &["sweep", "merge", "--out", "sw", "sw"]);
    refused(&merged, &["sw is being written by", &pid]);
    let output = child.wait_with_output().expect("the first sweep ends");
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{err}");
    assert!(!err.contains("run 0") && !err.contains("run 1"), "{err}");
    let runs = fs::read_to_string(tmp.path().join("sw/runs.csv")).expect("runs.csv");
    assert_eq!(runs.lines().count(), 3, "{runs}");
    // no failure recorded: the error column, the last, is empty in every row
    assert!(runs.lines().skip(1).all(|row| row.ends_with(',')), "{runs}");
    assert!(!tmp.path().join("sw/.flocking.lock").exists());
}

#[test]
fn issue_20_figures_never_replaces_a_users_directory() {
    let tmp = temp_dir("figures_user_dir");
    let fixtures = tmp.path().join("fixtures");
    fs::create_dir(&fixtures).expect("mkdir");
    write(&fixtures, "short.ron", SHORT_2D);
    // a gallery of flocking's is marked, and replaced
    complete(tmp.path(), &["figures", "--out", "g", "--quiet"]);
    complete(tmp.path(), &["figures", "--out", "g", "--quiet"]);
    assert_eq!(
        fs::read_to_string(tmp.path().join("g/.flocking")).expect("marker"),
        "written by flocking figures\n"
    );
    assert!(tmp.path().join("g/short/figures/metrics.svg").is_file());
    // a user's file in G/<stem>, or a user's G/<stem>: refused, untouched
    let stem = tmp.path().join("g/short");
    fs::write(stem.join("thesis.tex"), "x\n").expect("a user's file");
    let before = files(&stem);
    let output = flocking(tmp.path(), &["figures", "--out", "g", "--quiet"]);
    refused(
        &output,
        &["short: g/short holds thesis.tex, which flocking did not write"],
    );
    assert_eq!(files(&stem), before);
    remove_own_file(
        tmp.path(),
        &stem.join(".flocking"),
        b"written by flocking run\n",
    );
    let before = files(&stem);
    let output = flocking(tmp.path(), &["figures", "--out", "g", "--quiet"]);
    refused(&output, &["g/short holds"]);
    assert_eq!(files(&stem), before);
    // a user's G: refused before anything is written
    let mine = tmp.path().join("mine");
    fs::create_dir(&mine).expect("mkdir");
    fs::write(mine.join("short"), "mine\n").expect("a user's file");
    let output = flocking(tmp.path(), &["figures", "--out", "mine", "--quiet"]);
    refused(&output, &["mine holds short, which flocking did not write"]);
    assert_eq!(
        fs::read_dir(&mine).expect("ls").count(),
        1,
        "nothing written"
    );
    // no fixtures: a usage error
    let output = flocking(&fixtures, &["figures", "--out", "g", "--quiet"]);
    refused(&output, &["no fixtures"]);
}

#[test]
fn issue_20_plot_never_overwrites_a_file_flocking_did_not_write() {
    let tmp = temp_dir("plot_user_files");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    // `flocking plot`: bad input is exit 2
    let output = flocking(tmp.path(), &["plot", "nowhere"]);
    refused(&output, &["nowhere is not a directory"]);
    fs::create_dir(tmp.path().join("empty")).expect("mkdir");
    let output = flocking(tmp.path(), &["plot", "empty"]);
    refused(&output, &["empty is not a complete run directory"]);
    // a run directory without flocking's marker whose figures/ may be a user's
    complete(tmp.path(), &["run", &file, "--out", "r", "--quiet"]);
    complete(tmp.path(), &["plot", "r"]);
    complete(tmp.path(), &["plot", "r"]);
    remove_own_file(
        tmp.path(),
        &tmp.path().join("r/.flocking"),
        b"written by flocking run\n",
    );
    fs::write(tmp.path().join("r/figures/metrics.svg"), "mine\n").expect("a user's figure");
    let output = flocking(tmp.path(), &["plot", "r"]);
    refused(&output, &["r holds figures, which flocking did not write"]);
    assert_eq!(
        fs::read(tmp.path().join("r/figures/metrics.svg")).expect("kept"),
        b"mine\n"
    );
    // `flocking sweep plot --out`: a user's file is refused, the sweep's own replaced
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    complete(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    let plot = PLOT_SEEDS;
    complete(tmp.path(), &plot);
    complete(tmp.path(), &plot);
    assert!(tmp.path().join("sw/alpha_flock.svg").is_file());
    fs::write(tmp.path().join("mine.svg"), "mine\n").expect("a user's file");
    let mut args = plot.to_vec();
    args.extend(["--out", "mine.svg"]);
    let output = flocking(tmp.path(), &args);
    refused(&output, &["holds mine.svg, which flocking did not write"]);
    assert_eq!(
        fs::read(tmp.path().join("mine.svg")).expect("kept"),
        b"mine\n"
    );
    let mut args = plot.to_vec();
    args.extend(["--out", "new.csv"]);
    complete(tmp.path(), &args);
    assert!(tmp.path().join("new.csv").is_file());
    // a sweep plot of a directory that is not a sweep's: exit 2
    let output = flocking(
        tmp.path(),
        &[
            "sweep",
            "plot",
            "r",
            "--x",
            "seed",
            "--metric",
            "alpha_flock",
        ],
    );
    refused(&output, &["is not the output directory of a sweep"]);
}

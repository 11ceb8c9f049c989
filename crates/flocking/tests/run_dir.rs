//! Run directories written by [`RunDirectory`] and read back by [`read_run`]: the same numbers,
//! whatever the trajectory's format, with a header named by the protocol's diagnostics.

use std::cell::RefCell;

use flocking::run_dir::{METRICS_HEADER, OutputOptions, TrajectoryFormat};
use flocking::{DynSimulation, Record, Recorder, RunDirectory, Scenario, State, read_run};

use crate::common::{TempDir, fixture, temp_dir};

/// `fixtures/{name}.ron` cut to `duration` seconds.
fn short(name: &str, duration: f64) -> Scenario {
    let mut scenario = fixture(name);
    scenario.duration = duration;
    scenario
}

/// Every record's metrics row, as the library hands it to recorders.
struct Rows<'a>(RunDirectory, &'a RefCell<Vec<Vec<f64>>>);

impl Recorder for Rows<'_> {
    type Error = std::io::Error;

    fn record(&mut self, record: &Record<'_>) -> Result<(), Self::Error> {
        let m = &record.metrics;
        let mut row = vec![record.t];
        row.extend(m.reals());
        row.push(m.collisions as f64);
        row.push(record.energy);
        row.extend(m.extras());
        row.push(m.components as f64);
        row.extend(record.diagnostics.iter().map(|&(_, v)| v));
        self.1.borrow_mut().push(row);
        self.0.record(record)
    }
}

/// Runs `scenario` into `dir/name` in `format`; returns the rows recorded.
fn write(
    scenario: &Scenario,
    dir: &TempDir,
    name: &str,
    format: TrajectoryFormat,
) -> Vec<Vec<f64>> {
    let options = OutputOptions {
        format,
        ..OutputOptions::default()
    };
    let out = dir.path().join(name);
    let rows = RefCell::new(Vec::new());
    let directory = RunDirectory::create_with(&out, scenario, &options).expect("a new directory");
    let mut recorder = Rows(directory, &rows);
    flocking::run(scenario, &mut recorder).expect("the run");
    recorder.0.finish().expect("the directory completes");
    rows.into_inner()
}

#[test]
fn runs_read_back_as_recorded_from_csv_and_npy() {
    let tmp = temp_dir("run_dir_round_trip");
    let scenario = short("tac2006_fig14_split_rejoin_n150", 1.0);
    let rows = write(&scenario, &tmp, "csv", TrajectoryFormat::Csv);
    write(&scenario, &tmp, "npy", TrajectoryFormat::Npy);
    let csv = read_run(&tmp.path().join("csv")).expect("the CSV run reads back");
    let npy = read_run(&tmp.path().join("npy")).expect("the .npy run reads back");
    assert_eq!(csv.scenario, scenario);
    // the header: the common metrics, then the names Algorithm 3's diagnostics give (the obstacles,
    // then the γ-tracking errors)
    let names: Vec<&str> = csv.metrics.iter().map(|(name, _)| name.as_str()).collect();
    let expected: Vec<&str> = METRICS_HEADER
        .split(',')
        .chain([
            "obstacle_clearance",
            "inside_obstacles",
            "gamma_position_error",
            "gamma_velocity_error",
        ])
        .collect();
    assert_eq!(names, expected);
    // every number as recorded (shortest round-trip decimals read back to the same bits)
    for (k, row) in rows.iter().enumerate() {
        for (c, value) in row.iter().enumerate() {
            assert_eq!(
                csv.metrics[c].1[k].to_bits(),
                value.to_bits(),
                "row {k}, {}",
                names[c]
            );
        }
    }
    assert_eq!(csv.metrics, npy.metrics);
    assert_eq!(csv.trajectory, npy.trajectory);
    let trajectory = &csv.trajectory;
    assert_eq!((trajectory.dim, trajectory.agents), (2, 150));
    assert_eq!(trajectory.frames(), rows.len());
    // the last frame is the state of the simulation run as long
    let mut sim = DynSimulation::new(&scenario).expect("valid");
    while sim.steps() < scenario.steps() {
        sim.step();
    }
    let State {
        positions,
        velocities,
        ..
    } = sim.state();
    let last = trajectory.frames() - 1;
    assert_eq!(trajectory.positions_at(last), &positions[..]);
    assert_eq!(trajectory.velocities_at(last), &velocities[..]);
}

#[test]
fn the_header_names_the_diagnostics_of_each_protocol() {
    let tmp = temp_dir("run_dir_headers");
    for (name, extra) in [
        (
            "tac2006_fig11_alg2_n100",
            ",gamma_position_error,gamma_velocity_error",
        ),
        (
            "tanner2003_fig3_fixed_n10",
            ",velocity_disagreement,min_linked_distance",
        ),
        (
            "tr2003_fig7_obstacles_n100",
            ",defect_factor,normalised_defect_factor,structural_energy,translational_energy,\
             gamma_position_error,gamma_velocity_error,stress_towards,stress_away,stress_neutral,\
             obstacle_clearance,inside_obstacles",
        ),
    ] {
        write(&short(name, 0.1), &tmp, name, TrajectoryFormat::Csv);
        let text = std::fs::read_to_string(tmp.path().join(name).join("metrics.csv"))
            .expect("metrics.csv");
        assert_eq!(
            text.lines().next(),
            Some(format!("{METRICS_HEADER}{extra}").as_str()),
            "{name}"
        );
    }
}

#[test]
fn a_record_naming_other_columns_is_refused() {
    let tmp = temp_dir("run_dir_drift");
    let scenario = short("tac2006_fig11_alg2_n100", 0.1);
    let mut dir =
        RunDirectory::create(&tmp.path().join("out"), &scenario, false).expect("a new directory");
    let sim = DynSimulation::new(&scenario).expect("valid");
    let observation = sim.observe();
    let record = |diagnostics: &'static [(&'static str, f64)]| Record {
        t: sim.time(),
        steps: sim.steps(),
        metrics: observation.metrics,
        energy: observation.energy,
        state: sim.state(),
        diagnostics,
    };
    dir.record(&record(&[("a", 1.0)]))
        .expect("the first record names the columns");
    dir.record(&record(&[("a", 2.0)]))
        .expect("the same columns");
    let error = dir.record(&record(&[("b", 1.0)])).unwrap_err();
    assert!(error.to_string().contains("diagnostic columns"), "{error}");
    dir.abandon();
}

/// A run `out` killed after its `checkpoint` of the scenario `text` (empty records): its
/// `DIR.partial` as a run leaves it, marked, with its note; returns `out`.
fn interrupted_run(out: &std::path::Path, text: &str, checkpoint: &[u8]) -> std::path::PathBuf {
    let partial = flocking::run_dir::partial_path(out);
    std::fs::create_dir(&partial).expect("mkdir");
    std::fs::write(partial.join(".flocking"), "written by flocking run\n").expect("marker");
    std::fs::write(partial.join("scenario.ron"), format!("{text}\n")).expect("scenario");
    std::fs::write(partial.join("INCOMPLETE"), "incomplete: killed\n").expect("note");
    std::fs::write(partial.join("metrics.csv"), "").expect("metrics");
    std::fs::write(partial.join("trajectory.csv"), "").expect("trajectory");
    std::fs::write(partial.join("checkpoint.bin"), checkpoint).expect("the checkpoint");
    out.to_owned()
}

/// The bytes of a checkpoint with the header words `words` (dim, agents, steps, energy bits,
/// records, metrics bytes, trajectory bytes; the scenario's length is added), the state
/// `state`, the scenario `scenario`, and a valid FNV-1a hash: a forged checkpoint.
fn forged_checkpoint(words: [u64; 7], state: &[f64], scenario: &str) -> Vec<u8> {
    let mut bytes = b"FLOCKCK2".to_vec();
    for word in words.into_iter().chain([scenario.len() as u64]) {
        bytes.extend_from_slice(&word.to_le_bytes());
    }
    for x in state {
        bytes.extend_from_slice(&x.to_le_bytes());
    }
    bytes.extend_from_slice(scenario.as_bytes());
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    bytes.extend_from_slice(&hash.to_le_bytes());
    bytes
}

/// Issue 27: every field of a checkpoint read back is checked as user input. A forged file with
/// a valid hash (`dim = 1, agents = 2⁶³` panicked; `steps = u64::MAX` was accepted, and the run
/// stopped at t = 105 of 300 judged "α-flocking: yes") is refused, naming the field.
#[test]
fn issue_27_a_forged_checkpoint_is_refused_not_trusted() {
    let tmp = temp_dir("forged_checkpoint");
    let mut scenario = fixture("tac2006_fig11_alg2_n100");
    scenario.agents = 2;
    scenario.duration = 1.0;
    let text = scenario.to_ron().expect("RON");
    let state = [0.0; 8];
    let h = 1.0_f64.to_bits();
    let cases: [([u64; 7], &[f64], &str); 4] = [
        (
            [1, 1 << 63, 0, h, 0, 0, 0],
            &[],
            "its dimension is 1, not 2 or 3",
        ),
        (
            [2, 1 << 62, 0, h, 0, 0, 0],
            &[],
            "holds 4611686018427387904 agents",
        ),
        (
            [2, 2, u64::MAX, h, 0, 0, 0],
            &state,
            "past the scenario's last step",
        ),
        (
            [2, 2, 10, h, u64::MAX, 0, 0],
            &state,
            "counts 18446744073709551615 records",
        ),
    ];
    for (k, (words, state, message)) in cases.into_iter().enumerate() {
        let out = interrupted_run(
            &tmp.path().join(format!("r{k}")),
            &text,
            &forged_checkpoint(words, state, &text),
        );
        let Err(error) = RunDirectory::resume(&out, 1000) else {
            panic!("case {k}: a forged checkpoint was resumed");
        };
        assert!(error.to_string().contains(message), "case {k}: {error}");
    }
}

/// Issue 27: a run killed while preparing leaves `DIR.partial.new-<pid>` marked without its note;
/// the next run into `DIR` removes it once that process is gone, and keeps the one of a live
/// process, an unmarked one (not known to be flocking's, even empty) and a directory of the
/// user's with the same prefix.
#[test]
fn issue_27_a_run_killed_while_preparing_leaves_nothing_behind() {
    let tmp = temp_dir("stale_staging");
    let out = tmp.path().join("out");
    let staging = |suffix: &str| tmp.path().join(format!("out.partial.new-{suffix}"));
    let dead = u32::MAX - 1;
    let (empty, marked, live, user) = (
        staging(&dead.to_string()),
        staging(&(dead - 1).to_string()),
        staging("1"), // init: alive
        staging("notes"),
    );
    for dir in [&empty, &marked, &live, &user] {
        std::fs::create_dir(dir).expect("a staging directory");
    }
    flocking::owned::mark(&marked, flocking::owned::Kind::Run).expect("marked");
    std::fs::write(user.join("mine.txt"), "the user's").expect("a user file");
    let mut scenario = fixture("tac2006_fig12_alg1_n40");
    scenario.duration = 2.0 * scenario.step;
    let dir = RunDirectory::create(&out, &scenario, false).expect("the run starts");
    dir.abandon();
    assert!(!marked.exists(), "the dead run's staging is removed");
    assert!(empty.is_dir(), "an unmarked directory is kept, even empty");
    assert!(live.is_dir(), "a live process's staging is kept");
    assert_eq!(
        std::fs::read_to_string(user.join("mine.txt")).expect("kept"),
        "the user's"
    );
}

/// The fuzz directory's files of `dir` (`fuzz/corpus/<target>` or `fuzz/regressions`) whose names
/// end with `suffix`, sorted.
fn fuzz_files(dir: &str, suffix: &str) -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz")
        .join(dir);
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.to_string_lossy().ends_with(suffix))
        .collect();
    paths.sort();
    paths
}

/// The fuzz target `checkpoint`'s seeds (real checkpoints) parse, and its regressions (forged
/// checkpoints with a valid hash, issue 27) are refused — by the parser when a field is out of
/// its range, by the resume when the checkpoint does not fit its run — never a panic.
#[test]
fn the_checkpoint_fuzz_corpus_and_regressions_are_read_or_refused() {
    use flocking::run_dir::Checkpoint;
    let seeds = fuzz_files("corpus/checkpoint", ".bin");
    assert!(!seeds.is_empty());
    for path in seeds {
        let bytes = std::fs::read(&path).expect("a seed");
        let checkpoint =
            Checkpoint::parse(&bytes, &path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(
            checkpoint.start.positions.len(),
            checkpoint.start.velocities.len()
        );
    }
    let regressions = fuzz_files("regressions", ".bin");
    assert!(regressions.len() >= 4, "{} regressions", regressions.len());
    let tmp = temp_dir("fuzz_checkpoints");
    let mut scenario = fixture("tac2006_fig11_alg2_n100");
    scenario.agents = 2;
    scenario.duration = 1.0;
    let text = scenario.to_ron().expect("RON");
    for (k, path) in regressions.iter().enumerate() {
        let bytes = std::fs::read(path).expect("a regression");
        if let Err(error) = Checkpoint::parse(&bytes, path) {
            assert!(
                error.to_string().contains("is not a flock checkpoint"),
                "{error}"
            );
            continue;
        }
        let out = interrupted_run(&tmp.path().join(format!("r{k}")), &text, &bytes);
        assert!(
            RunDirectory::resume(&out, 1000).is_err(),
            "{}: a forged checkpoint was resumed",
            path.display()
        );
    }
}

/// The fuzz target `read_records`'s seeds (a byte for the number of agents, then a run's
/// `metrics.csv`) read back every record.
#[test]
fn the_read_records_fuzz_corpus_reads_back() {
    let seeds = fuzz_files("corpus/read_records", ".csv");
    assert!(!seeds.is_empty());
    let tmp = temp_dir("fuzz_records");
    for path in seeds {
        let bytes = std::fs::read(&path).expect("a seed");
        let (&agents, text) = bytes.split_first().expect("not empty");
        let metrics = tmp.path().join("metrics.csv");
        std::fs::write(&metrics, text).expect("written");
        let records = flocking::run_dir::read_records(&metrics, usize::from(agents))
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let rows = text.iter().filter(|&&b| b == b'\n').count() - 1;
        assert_eq!(records.len(), rows, "{}", path.display());
    }
}

/// Issue 28: a failed agent is marked in the trajectory and `final.csv`, not only counted in
/// `metrics.csv`. Agents fail at random (rate 0.5/s) and two at given times, `Removed`: at
/// every record of the CSV and the `.npy` trajectory, the marked agents are exactly as many as
/// `metrics.csv`'s `failed`, a mark never clears, a marked `Removed` agent stands still with
/// velocity 0, and `final.csv` ends with the last record's marks. Without faults the files have
/// no such column.
#[test]
fn failed_agents_are_marked_in_the_trajectory_and_the_final_state() {
    let tmp = temp_dir("run_dir_failed_marks");
    let base = short("tac2006_fig11_alg2_n100", 2.0);
    let scenario = base
        .clone()
        .with_values([(
            "conditions.faults",
            flocking::serde_json::json!({
                "at": [{"agent": 7, "time": 0.5}, {"agent": 42, "time": 1.2}],
                "rate": 0.5,
                "mode": "Removed",
            }),
        )])
        .expect("faults");
    write(&scenario, &tmp, "csv", TrajectoryFormat::Csv);
    write(&scenario, &tmp, "npy", TrajectoryFormat::Npy);
    let csv = read_run(&tmp.path().join("csv")).expect("the CSV run reads back");
    let npy = read_run(&tmp.path().join("npy")).expect("the .npy run reads back");
    assert_eq!(csv.trajectory, npy.trajectory);
    let trajectory = &csv.trajectory;
    let counted = &csv
        .metrics
        .iter()
        .find(|(name, _)| name == "failed")
        .expect("metrics.csv counts the failed agents")
        .1;
    let frames = trajectory.frames();
    assert_eq!(counted.len(), frames);
    let mut before = vec![false; trajectory.agents];
    for (k, &count) in counted.iter().enumerate() {
        let marks = trajectory
            .failed_at(k)
            .expect("the trajectory marks failures");
        let marked = marks.iter().filter(|&&f| f).count();
        assert_eq!(marked as f64, count, "record {k}");
        for (i, (&now, &was)) in marks.iter().zip(&before).enumerate() {
            assert!(now || !was, "agent {i}'s mark cleared at record {k}");
            if was {
                let p = &trajectory.velocities_at(k)[2 * i..2 * i + 2];
                assert_eq!(p, [0.0, 0.0], "removed agent {i} moves at record {k}");
                assert_eq!(
                    trajectory.positions_at(k)[2 * i..2 * i + 2],
                    trajectory.positions_at(k - 1)[2 * i..2 * i + 2],
                    "removed agent {i} moved at record {k}"
                );
            }
        }
        before = marks.to_vec();
    }
    let last = trajectory.failed_at(frames - 1).expect("marks");
    // both scheduled failures and at least one random one (rate 0.5/s, 100 agents, 2 s)
    assert!(last[7] && last[42], "{last:?}");
    assert!(counted[frames - 1] >= 3.0, "{}", counted[frames - 1]);
    let final_csv = std::fs::read_to_string(tmp.path().join("csv/final.csv")).expect("final.csv");
    let mut lines = final_csv.lines();
    assert_eq!(lines.next(), Some("id,x,y,vx,vy,failed"));
    let final_marks: Vec<bool> = lines
        .map(|line| line.rsplit(',').next() == Some("1"))
        .collect();
    assert_eq!(final_marks, last);
    // a scenario without faults: no column, nothing marked
    write(&base, &tmp, "ideal", TrajectoryFormat::Csv);
    let ideal = read_run(&tmp.path().join("ideal")).expect("reads back");
    assert!(ideal.trajectory.failed.is_empty());
    assert_eq!(ideal.trajectory.failed_at(0), None);
    let header = std::fs::read_to_string(tmp.path().join("ideal/trajectory.csv")).expect("csv");
    assert!(header.starts_with("t,id,x,y,vx,vy\n"), "{}", &header[..40]);
}

/// Issue 51 (the storage moved into `flocking::storage`, the checkpoint's FNV-1a became the `fnv`
/// crate's): a run directory that flocking 1f9075e (the last version before) wrote and that was
/// interrupted by Ctrl-C after step 11,001 of 30,000 (`tests/data/interrupted_by_1f9075e`: an
/// Algorithm 2 run under every condition, its checkpoint holding the delay line, the channel and
/// the faults, at that step) resumes here and finishes with the bytes of the same run written
/// whole by this version.
#[test]
fn issue_51_a_run_interrupted_by_the_flocking_before_resumes_to_the_same_bytes() {
    use flocking::ScenarioProtocol;
    let tmp = temp_dir("older_run");
    let data =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/interrupted_by_1f9075e");
    let (resumed, partial) = (tmp.path().join("run"), tmp.path().join("run.partial"));
    std::fs::create_dir(&partial).expect("mkdir");
    for entry in std::fs::read_dir(&data).expect("the older run") {
        let path = entry.expect("an entry").path();
        std::fs::copy(&path, partial.join(path.file_name().expect("a name"))).expect("copied");
    }
    let (interrupted, scenario, start) = RunDirectory::resume(&resumed, 500).expect("resumable");
    let start = start.expect("its checkpoint");
    assert_eq!(start.steps, 11_001);
    assert!(
        !start.conditions.is_empty(),
        "the conditions' state is kept"
    );
    let sim = DynSimulation::build_with(&scenario, Some(&start), &ScenarioProtocol)
        .expect("the checkpoint continues");
    let mut dir = interrupted.reopen().expect("reopened");
    flocking::run_from(sim, Some(start.initial_energy), &mut dir).expect("the rest of the run");
    dir.finish().expect("finished");
    let whole = tmp.path().join("whole");
    let options = OutputOptions {
        checkpoint_every: 500,
        ..OutputOptions::default()
    };
    let mut dir = RunDirectory::create_with(&whole, &scenario, &options).expect("a new run");
    flocking::run(&scenario, &mut dir).expect("the whole run");
    dir.finish().expect("finished");
    for name in [
        "metrics.csv",
        "trajectory.csv",
        "final.csv",
        "flocking.txt",
        "scenario.ron",
    ] {
        let read = |dir: &std::path::Path| std::fs::read(dir.join(name)).expect("a run's file");
        assert!(read(&resumed) == read(&whole), "{name} differs");
    }
}

/// Issue 53: reading a directory that is not a run says so, and what to give instead; a path
/// that is no directory says that.
#[test]
fn a_directory_that_is_not_a_run_is_named_as_such() {
    let dir = temp_dir("not-a-run");
    let error = flocking::read_run(dir.path()).expect_err("no run there");
    let text = error.to_string();
    assert!(
        text.contains("not a run directory: it holds no scenario.ron"),
        "{text}"
    );
    assert!(
        text.starts_with(&dir.path().display().to_string()),
        "{text}"
    );
    let missing = flocking::read_run(&dir.path().join("nowhere")).expect_err("nothing there");
    assert!(
        missing.to_string().contains("no such directory"),
        "{missing}"
    );
}

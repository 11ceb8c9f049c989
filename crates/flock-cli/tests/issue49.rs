//! Issue 49, "Never lose a user's data, round three": a refused resume keeps every byte of the
//! interrupted run, Ctrl-C stops every long loop within 2 s, `bench` has `run`'s guards, and the
//! errors of the models and vehicles name the field at fault with exit code 2.

use std::cell::Cell;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::thread::sleep;
use std::time::{Duration, Instant};

use flocking::run_dir::{Checkpoint, INCOMPLETE_FILE, OutputOptions, partial_path};
use flocking::{DynSimulation, Record, Recorder, RunDirectory, Scenario, ScenarioProtocol, Start};

use crate::common::{files, flocking, flocking_under_4_gib, stderr, temp_dir, write};
use crate::trust::{SHORT_2D, ctrl_c, refused, spawn};

/// Hands every record and checkpoint to the run directory, and asks the run to stop once
/// `stop_after` steps are taken, as Ctrl-C does.
struct StopAfter {
    dir: RunDirectory,
    steps: Cell<u64>,
    stop_after: u64,
}

impl Recorder for StopAfter {
    type Error = std::io::Error;

    fn record(&mut self, record: &Record<'_>) -> std::io::Result<()> {
        self.dir.record(record)
    }

    fn wants_checkpoint(&self, steps: u64) -> bool {
        self.dir.wants_checkpoint(steps)
    }

    fn checkpoint(&mut self, start: &Start) -> std::io::Result<()> {
        self.dir.checkpoint(start)
    }

    fn stop_requested(&self) -> bool {
        self.steps.set(self.steps.get() + 1);
        self.steps.get() >= self.stop_after
    }
}

/// The run of `text` into `tmp/name`, stopped after 25 steps with a checkpoint (as Ctrl-C
/// stops it): its `DIR.partial`.
fn interrupted(tmp: &Path, name: &str, text: &str) -> PathBuf {
    let scenario: Scenario = text.parse().expect("a scenario");
    let out = tmp.join(name);
    let options = OutputOptions {
        checkpoint_every: 10,
        ..OutputOptions::default()
    };
    let mut recorder = StopAfter {
        dir: RunDirectory::create_with(&out, &scenario, &options).expect("created"),
        steps: Cell::new(0),
        stop_after: 25,
    };
    let error = flocking::run(&scenario, &mut recorder).expect_err("stopped");
    assert!(error.to_string().contains("after step 25"), "{error}");
    recorder
        .dir
        .keep_incomplete(&format!("{error} by Ctrl-C"), true)
        .expect("kept")
}

/// The checkpoint of `partial` changed by `forge` and written back with its hash made to match,
/// as a forged or damaged file may be.
fn forge(partial: &Path, forge: impl FnOnce(&mut Start)) {
    let mut checkpoint = Checkpoint::read(partial)
        .expect("readable")
        .expect("a checkpoint");
    forge(&mut checkpoint.start);
    checkpoint.write(partial).expect("written back");
}

/// The size and a checksum of every file of `dir` (not its subdirectories), by name.
fn checksums(dir: &Path) -> std::collections::BTreeMap<String, (usize, u64)> {
    use std::hash::{DefaultHasher, Hash, Hasher};
    files(dir)
        .into_iter()
        .map(|(name, bytes)| {
            let mut hasher = DefaultHasher::new();
            bytes.hash(&mut hasher);
            (name, (bytes.len(), hasher.finish()))
        })
        .collect()
}

/// SHORT_2D's agents on the unicycles of `fixtures/unicycle_alg2_n50.ron`.
fn unicycles() -> String {
    SHORT_2D.replace(
        "    step: 0.01,",
        "    vehicle: Unicycle(()),\n    step: 0.01,",
    )
}

/// SHORT_2D under a communication delay of 0.05 s.
fn delayed() -> String {
    SHORT_2D.replace(
        "    step: 0.01,",
        "    conditions: (communication: (delay: 0.05)),\n    step: 0.01,",
    )
}

/// Issue 49, finding 1: a resume refused for any reason — a checkpoint whose hash matches but
/// whose state is NaN, infinite, 10³⁰⁰ or outside the box, whose vehicle state is not finite,
/// whose conditions' state does not read, or records cut short, an edited scenario — leaves
/// every byte of `DIR.partial` as it was (the refused resume deleted it, 16–34 MB of records).
#[test]
fn issue_49_a_refused_resume_keeps_every_byte_of_the_interrupted_run() {
    let tmp = temp_dir("refused_resume");
    type Forgery = Box<dyn Fn(&Path)>;
    let cases: Vec<(&str, String, Forgery, &str)> = vec![
        (
            "nan",
            SHORT_2D.to_owned(),
            Box::new(|p| forge(p, |s| s.positions[3] = f64::NAN)),
            "positions[1]",
        ),
        (
            "infinite",
            SHORT_2D.to_owned(),
            Box::new(|p| forge(p, |s| s.velocities[0] = f64::INFINITY)),
            "velocities[0]",
        ),
        (
            "huge",
            SHORT_2D.to_owned(),
            Box::new(|p| forge(p, |s| s.positions[0] = 1e300)),
            "positions[0]",
        ),
        (
            "vehicle",
            unicycles(),
            Box::new(|p| forge(p, |s| s.vehicle[4] = f64::NAN)),
            "vehicle[4]",
        ),
        (
            "conditions",
            delayed(),
            Box::new(|p| forge(p, |s| s.conditions = "(not a state".to_owned())),
            "no readable state of the conditions",
        ),
        (
            "delay_line",
            delayed(),
            Box::new(|p| {
                forge(p, |s| {
                    s.conditions = s.conditions.replacen("history:[([", "history:[([NaN,", 1);
                    // one value replaced, not added: the first number after it goes
                    let at = s.conditions.find("[NaN,").expect("forged") + 5;
                    let end = at + s.conditions[at..].find(',').expect("a number");
                    s.conditions.replace_range(at..=end, "");
                });
            }),
            "conditions_state.history",
        ),
        (
            "cut_records",
            SHORT_2D.to_owned(),
            Box::new(|p| {
                // the header and the first record kept, the records after them cut
                let metrics = fs::read(p.join("metrics.csv")).expect("metrics");
                let second = metrics
                    .iter()
                    .enumerate()
                    .filter(|&(_, &b)| b == b'\n')
                    .nth(1);
                let end = second.expect("two lines").0 + 1;
                fs::write(p.join("metrics.csv"), &metrics[..end]).expect("cut");
            }),
            "is shorter than its checkpoint says",
        ),
        (
            "edited",
            SHORT_2D.to_owned(),
            Box::new(|p| {
                let text = fs::read_to_string(p.join("scenario.ron")).expect("scenario");
                fs::write(p.join("scenario.ron"), text.replace("c1: 0.02", "c1: 0.03"))
                    .expect("edited");
            }),
            "was edited after the run started",
        ),
    ];
    for (name, text, damage, says) in cases {
        let partial = interrupted(tmp.path(), name, &text);
        damage(&partial);
        let before = checksums(&partial);
        let output = flocking(tmp.path(), &["run", "--resume", name]);
        refused(&output, &[says]);
        assert_eq!(checksums(&partial), before, "{name}: every byte kept");
        assert!(!tmp.path().join(name).exists(), "{name}");
    }
}

/// Issue 49, finding 1: the library refuses the state as the command does, before anything is
/// written, and the checkpoint of a whole run resumes.
#[test]
fn issue_49_a_checkpoint_state_is_checked_as_a_start() {
    let scenario: Scenario = SHORT_2D.parse().expect("a scenario");
    let sim = DynSimulation::new(&scenario).expect("built");
    let start = sim.start(sim.energy());
    assert!(start.check(&scenario).is_ok());
    let refused = |change: &dyn Fn(&mut Start)| {
        let mut forged = start.clone();
        change(&mut forged);
        DynSimulation::build_with(&scenario, Some(&forged), &ScenarioProtocol)
            .expect_err("refused")
            .field()
    };
    // a start within ±10⁹ reaches at most 10⁹ + steps · r: 10⁹ + 8.4 after one step
    let beyond = |s: &mut Start| {
        s.steps = 1;
        s.positions[0] = 1e9 + 9.0;
    };
    let within = |s: &mut Start| {
        s.steps = 1;
        s.positions[0] = 1e9 + 8.0;
    };
    assert_eq!(refused(&beyond).as_deref(), Some("positions[0]"));
    let mut far = start.clone();
    within(&mut far);
    assert!(far.check(&scenario).is_ok());
    // a speed above r/h = 840 is one no run keeps
    assert_eq!(
        refused(&|s| s.velocities[2] = 841.0).as_deref(),
        Some("velocities[1]")
    );
    let mut fast = start.clone();
    fast.velocities[2] = 839.0;
    assert!(fast.check(&scenario).is_ok());
}

/// Sends SIGINT to `child` once `started` holds (polled), and returns its output and how long it
/// took to end after the signal.
fn interrupt(
    child: std::process::Child,
    started: impl Fn() -> bool,
) -> (std::process::Output, Duration) {
    let waited = Instant::now();
    while !started() {
        assert!(waited.elapsed() < Duration::from_secs(120), "never started");
        sleep(Duration::from_millis(50));
    }
    // well inside the step that takes seconds
    sleep(Duration::from_millis(1500));
    let signalled = Instant::now();
    ctrl_c(&child);
    let output = child.wait_with_output().expect("it ends");
    (output, signalled.elapsed())
}

/// A run of `agents` of `algorithm` (in a box of side `side`), its `vehicle`, over 1 s of steps
/// of 0.1 s, checkpointed at every step.
fn long_steps(algorithm: &str, agents: usize, side: f64, vehicle: &str) -> String {
    format!(
        r#"Scenario(
    name: "long_steps",
    dim: 2,
    agents: {agents},
    seed: 2,
    algorithm: {algorithm},
    vehicle: {vehicle},
    initial: (positions: Box(min: [0.0, 0.0], max: [{side}, {side}])),
    step: 0.1,
    duration: 1.0,
)
"#
    )
}

/// Issue 49, finding 2: Ctrl-C stops a step of an all-pairs model (Cucker–Smale without a cutoff,
/// 50,000 agents: seconds a step) within 2 s, with exit code 130, leaving a resumable run; and a
/// vehicle's ten million inner steps a step the same way (the run torn inside the step goes
/// back to its last checkpoint). Before, the first Ctrl-C did nothing for tens of seconds.
#[test]
fn issue_49_ctrl_c_stops_a_long_step_within_2_s() {
    let tmp = temp_dir("ctrl_c_long_step");
    let cases = [
        (
            "pairs",
            long_steps("CuckerSmale(beta: 0.25)", 50_000, 1e5, "PointMass"),
        ),
        (
            "inner",
            long_steps(
                "Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.01, c2: 0.2)",
                50,
                50.0,
                "Unicycle((inner_step: 1e-8))",
            ),
        ),
    ];
    for (name, text) in cases {
        let file = write(tmp.path(), &format!("{name}.ron"), &text);
        let child = spawn(
            tmp.path(),
            &[
                "run",
                &file,
                "--out",
                name,
                "--quiet",
                "--checkpoint-every",
                "1",
            ],
        );
        let partial = partial_path(&tmp.path().join(name));
        // started once its first record is on the disk
        let metrics = partial.join("metrics.csv");
        let (output, took) = interrupt(child, || {
            fs::read_to_string(&metrics).is_ok_and(|m| m.lines().count() >= 2)
        });
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(130), "{name}: {err}");
        assert!(took < Duration::from_secs(2), "{name}: {took:?}, {err}");
        let note = fs::read_to_string(partial.join(INCOMPLETE_FILE)).expect("the note");
        assert!(
            note.contains("Resume: flocking run --resume"),
            "{name}: {note}"
        );
        // resumable: the directory and its checkpoint pass every check of a resume, and the
        // run's simulation is rebuilt from it (nothing written)
        let (_, scenario, start) = RunDirectory::resume(&partial, 1).expect("resumable");
        DynSimulation::build_with(&scenario, start.as_ref(), &ScenarioProtocol)
            .expect("its simulation rebuilt");
    }
}

/// Issue 49, finding 2: `flocking bench` quits at once on Ctrl-C (it writes nothing), also inside
/// a workload of every pair in range.
#[test]
fn issue_49_ctrl_c_stops_a_benchmark_at_once() {
    let tmp = temp_dir("ctrl_c_bench");
    let child = spawn(
        tmp.path(),
        &[
            "bench",
            "--n",
            "2000000",
            "--steps",
            "100000",
            "--no-resource-check",
        ],
    );
    let started = Instant::now();
    let (output, took) = interrupt(child, || started.elapsed() > Duration::from_secs(1));
    assert_eq!(output.status.code(), Some(130), "{}", stderr(&output));
    assert!(took < Duration::from_secs(2), "{took:?}");
}

/// Issue 49, finding 2: an inner step of 10⁻³⁰⁰ s validated and never ended; the work of a step
/// is now bounded (agents × inner steps, pairs of an all-pairs model) by what the estimate counts.
#[test]
fn issue_49_the_work_of_one_step_is_bounded() {
    let tmp = temp_dir("work_bound");
    for (text, field) in [
        (
            long_steps(
                "Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.01, c2: 0.2)",
                50,
                50.0,
                "Unicycle((inner_step: 1e-300))",
            ),
            "`vehicle.inner_step` = 1e-300",
        ),
        (
            long_steps(
                "Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.01, c2: 0.2)",
                1000,
                500.0,
                "Unicycle((inner_step: 1e-8))",
            ),
            "1000 agents × 1e7 inner steps",
        ),
        (
            long_steps("CuckerSmale(beta: 0.25)", 100_000, 1e5, "PointMass"),
            "give algorithm.cutoff",
        ),
    ] {
        let file = write(tmp.path(), "s.ron", &text);
        let output = flocking(tmp.path(), &["validate", &file]);
        refused(&output, &[field]);
    }
}

/// Issue 49, finding 3: `flocking bench` has `run`'s guards: its estimate is printed and checked
/// (exit 2 when it does not fit), an allocation that cannot be had with `--no-resource-check` is
/// an error (exit 1) instead of an abort (exit 134), flags that do not apply to a workload and
/// counts out of range are refused naming the flag.
#[test]
fn issue_49_bench_has_the_guards_of_run() {
    let tmp = temp_dir("bench_guards");
    let delay = "bench --n 100 --delay 1000000 --steps 2";
    let output = flocking_under_4_gib(tmp.path(), delay);
    refused(
        &output,
        &[
            "of memory but",
            "the delay line of conditions.communication.delay",
        ],
    );
    let output = flocking_under_4_gib(tmp.path(), &format!("{delay} --no-resource-check"));
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(
        err.contains("which this machine cannot allocate") && err.contains("a shorter delay"),
        "{err}"
    );
    assert!(
        !err.contains("panicked") && !err.contains("memory allocation"),
        "{err}"
    );
    for (args, says) in [
        (
            &["--workload", "vicsek", "--dim", "3"][..],
            "'--workload <WORKLOAD>' cannot be used with '--dim <DIM>'",
        ),
        (
            &["--workload", "vicsek", "--delay", "0.1"][..],
            "cannot be used with '--delay <SECONDS>'",
        ),
        (
            &["--workload", "boids-small", "--vehicle", "unicycle"][..],
            "cannot be used with '--vehicle <VEHICLE>'",
        ),
        (&["--workload", "vicsek", "--seeds", "0"][..], "--seeds"),
        (
            &["--workload", "vicsek", "--scale-to", "0"][..],
            "--scale-to 0",
        ),
        (&["--steps", "1e15"][..], "--steps"),
        (
            &["--n", "10", "--steps", "1000000000000000"][..],
            "--steps 1000000000000000",
        ),
        (
            &["--n", "10", "--warmup", "1000000000000"][..],
            "--warmup 1000000000000",
        ),
        (&["--n", "1"][..], "--n 1"),
    ] {
        let output = flocking(tmp.path(), &[&["bench"][..], args].concat());
        refused(&output, &[says]);
    }
}

/// Issue 49, finding 6: a delay line that does not fit, started with `--no-resource-check`, is an
/// error naming the delay line (exit 1), not an abort with a backtrace.
#[test]
fn issue_49_a_delay_line_that_cannot_be_had_is_an_error() {
    let tmp = temp_dir("delay_line");
    let text = SHORT_2D.replace(
        "    step: 0.01,",
        "    conditions: (communication: (delay: 1000000.0)),\n    step: 0.01,",
    );
    write(tmp.path(), "s.ron", &text);
    let output = flocking_under_4_gib(tmp.path(), "run s.ron --out r --no-resource-check");
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(
        err.contains("`conditions.communication.delay` = 1000000.0")
            && err.contains("which this machine cannot allocate"),
        "{err}"
    );
    assert!(
        !err.contains("panicked") && !err.contains("memory allocation"),
        "{err}"
    );
    assert!(!tmp.path().join("r.partial").exists() && !tmp.path().join("r").exists());
}

/// Issue 49, finding 4: a run written with `--trajectory-format npy` reads back with its vehicle's
/// columns named as the CSV names them (they were `s1` … `s11`).
#[test]
fn issue_49_an_npy_trajectory_reads_back_its_vehicle_columns_by_name() {
    let tmp = temp_dir("npy_names");
    let file = write(
        tmp.path(),
        "u.ron",
        &unicycles().replace("duration: 4.0", "duration: 0.1"),
    );
    for format in ["csv", "npy"] {
        let output = flocking(
            tmp.path(),
            &[
                "run",
                &file,
                "--out",
                format,
                "--trajectory-format",
                format,
                "--quiet",
            ],
        );
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    }
    let read = |dir: &str| flocking::read_run(&tmp.path().join(dir)).expect("read back");
    let (csv, npy) = (read("csv"), read("npy"));
    assert_eq!(
        npy.trajectory.vehicle_columns,
        ["heading", "speed", "turn_rate"]
    );
    assert_eq!(npy.trajectory, csv.trajectory);
}

/// Issue 49, finding 5: settings the run would stop at its first step as a "numerical blow-up"
/// are refused by `validate` (exit 2) with the real reason and the field at fault.
#[test]
fn issue_49_the_velocity_models_are_refused_up_front_with_the_real_reason() {
    let tmp = temp_dir("up_front");
    let fixture = |name: &str| {
        fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../fixtures/{name}.ron")),
        )
        .expect("a fixture")
    };
    let vicsek = fixture("vicsek1995_fig2a_n400");
    let couzin = fixture("couzin2002_torus_n100");
    let cucker = fixture("cucker_smale2007_n50");
    let quadrotor = fixture("crazyflie_alg2_3d_n50");
    for (text, words) in [
        (
            vicsek.replace("Vicsek(v0: 0.03, r: 1.0,", "Vicsek(v0: 2.0, r: 1.0,"),
            &[
                "`algorithm.v0` = 2.0",
                "farther than its interaction range r = 1",
            ][..],
        ),
        (
            couzin.replace("Couzin(", "Couzin(speed: 300.0, "),
            &["`algorithm.speed` = 300.0"][..],
        ),
        (
            cucker.replace(
                "CuckerSmale(beta: 0.25)",
                "CuckerSmale(beta: 0.25, cutoff: 0.01)",
            ),
            &["`initial.velocities`", "algorithm.cutoff"][..],
        ),
        (
            cucker.replace(
                "CuckerSmale(beta: 0.25)",
                "CuckerSmale(beta: 0.25, cutoff: -1.0)",
            ),
            &["`algorithm.cutoff` = -1.0"][..],
        ),
        (
            vicsek.replace(
                "PeriodicAtDensity(density: 4.0)",
                "PeriodicAtDensity(density: 1e-17)",
            ),
            &["`domain.density` = 1e-17", "beyond the 1e9"][..],
        ),
        (
            quadrotor.replace(
                "vehicle: Quadrotor(())",
                "vehicle: Quadrotor((mass: 1e-300))",
            ),
            &["`vehicle.mass` = 1e-300", "position loop"][..],
        ),
    ] {
        let file = write(tmp.path(), "s.ron", &text);
        let output = flocking(tmp.path(), &["validate", &file]);
        refused(&output, words);
        assert!(
            !stderr(&output).contains("algorithm.range"),
            "{}",
            stderr(&output)
        );
    }
    // the missing cutoff under a perception condition: named as the fix, once
    let text = cucker.replace(
        "    integrator: Rk4,\n",
        "    conditions: (communication: (delay: 0.1)),\n",
    );
    let file = write(tmp.path(), "s.ron", &text);
    let output = flocking(tmp.path(), &["validate", &file]);
    refused(
        &output,
        &["set algorithm.cutoff", "`conditions.communication`"],
    );
    assert_eq!(
        stderr(&output).matches("conditions.communication").count(),
        1,
        "{}",
        stderr(&output)
    );
}

/// Issue 49, finding 5: a sweep's value `Quadrotor(())` is the vehicle of default parameters, as
/// a scenario file writes it (it was refused as `{"Quadrotor":null}`).
#[test]
fn issue_49_a_sweep_takes_a_vehicle_of_its_defaults() {
    let tmp = temp_dir("sweep_unit");
    let base = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/crazyflie_alg2_3d_n50.ron")
        .canonicalize()
        .expect("the fixture");
    let sweep = write(
        tmp.path(),
        "q.sweep.ron",
        &format!(
            r#"Sweep(
    base: Path({:?}),
    set: {{"duration": 0.1}},
    axes: [(path: "vehicle", values: List([Quadrotor(()), PointMass]))],
    seeds: 1,
)"#,
            base.display().to_string()
        ),
    );
    let output = flocking(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let runs = fs::read_to_string(tmp.path().join("sw/runs.csv")).expect("runs.csv");
    assert_eq!(runs.lines().count(), 3, "{runs}");
}

/// Issue 49, finding 5: a manifest that is not flocking's (a FIFO, 100 MB) is a refusal, exit code
/// 2, not an I/O failure (exit code 1).
#[test]
fn issue_49_a_manifest_that_is_not_flockings_is_refused_with_exit_code_2() {
    let tmp = temp_dir("manifest");
    let file = write(
        tmp.path(),
        "s.ron",
        &SHORT_2D.replace("duration: 4.0", "duration: 0.1"),
    );
    for (name, damage) in [("fifo", "mkfifo"), ("large", "truncate -s 100M")] {
        let output = flocking(tmp.path(), &["run", &file, "--out", name, "--quiet"]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        let manifest = tmp.path().join(name).join(".flocking.manifest");
        fs::remove_file(&manifest).expect("flocking's manifest");
        let status = Command::new("sh")
            .arg("-c")
            .arg(format!("{damage} '{}'", manifest.display()))
            .status()
            .expect("sh runs");
        assert!(status.success());
        let before = checksums(&tmp.path().join(name));
        let output = flocking(tmp.path(), &["run", &file, "--out", name, "--force"]);
        refused(&output, &["is not a manifest flocking wrote"]);
        let output = flocking(tmp.path(), &["plot", name]);
        refused(&output, &["is not a manifest flocking wrote"]);
        assert_eq!(checksums(&tmp.path().join(name)), before, "{name}");
    }
}

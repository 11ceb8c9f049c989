//! Parameter sweeps ([`flocking::sweep`]): the runs and their ids, Linspace and Logspace, bad sweep
//! files, failing runs recorded, and `runs.csv` the same bytes whatever the workers, the shards
//! and the interruptions.

use std::fs;
use std::sync::atomic::AtomicBool;

use flocking::metrics::FlockMetrics;
use flocking::serde_json::json;
use flocking::sweep::store::{self, RUNS_FILE};
use flocking::sweep::{
    ExecuteOptions, ParameterLabel, Shard, Sweep, SweepError, Values, execute, metric_label,
};

use crate::common::temp_dir;

/// Fig. 11 cut to 20 agents and 2 s, over c₁ × two agent counts × 2 seeds (12 runs), one value
/// of c₁ so large that the run blows up.
const SWEEP: &str = r#"Sweep(
    name: "tiny",
    base: Path("../../fixtures/tac2006_fig11_alg2_n100.ron"),
    set: {"duration": 2.0, "initial.positions.std": 10.0},
    axes: [
        (path: "algorithm.c1", values: List([0.02, 0.03, 1e8])),
        (path: "agents", values: List([10, 20])),
    ],
    seeds: 2,
)"#;

fn tiny() -> Sweep {
    SWEEP.parse().unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn runs_are_the_product_of_the_axes_with_seeds_innermost_and_stable_ids() {
    let sweep = tiny();
    let runs = sweep.runs();
    assert_eq!(runs.len(), 3 * 2 * 2);
    let key: Vec<(f64, u64, u64)> = runs
        .iter()
        .map(|r| {
            (
                r.values[0].as_f64().expect("a number"),
                r.values[1].as_u64().expect("an integer"),
                r.seed,
            )
        })
        .collect();
    assert_eq!(
        key[..5],
        [
            (0.02, 10, 0),
            (0.02, 10, 1),
            (0.02, 20, 0),
            (0.02, 20, 1),
            (0.03, 10, 0)
        ]
    );
    assert!(runs.iter().enumerate().all(|(k, r)| r.index == k));
    let ids: Vec<String> = runs.iter().map(|r| r.id(&sweep.axes)).collect();
    let mut unique = ids.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), ids.len(), "one id per run");
    // the id is of the values, not of the position: reversing an axis moves runs, not ids
    let mut reversed = sweep.clone();
    reversed.axes[1].values = Values::List(vec![json!(20), json!(10)]);
    let moved = reversed.runs()[0].id(&reversed.axes);
    assert_eq!(moved, ids[2], "(0.02, 20, seed 0) keeps its id");
}

#[test]
fn linspace_and_logspace_include_both_ends() {
    let lin = Values::Linspace {
        from: 0.0,
        to: 1.0,
        count: 5,
    };
    assert_eq!(lin.expand(), [0.0, 0.25, 0.5, 0.75, 1.0].map(|x| json!(x)));
    let log = Values::Logspace {
        from: 0.01,
        to: 1.0,
        count: 3,
    };
    let values: Vec<f64> = log
        .expand()
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect();
    assert_eq!((values[0], values[2]), (0.01, 1.0));
    approx::assert_relative_eq!(values[1], 0.1, max_relative = 1e-14);
    let one = Values::Linspace {
        from: 3.0,
        to: 9.0,
        count: 1,
    };
    assert_eq!(one.expand(), [json!(3.0)]);
}

#[test]
fn bad_sweep_files_are_refused_with_the_field_or_the_line() {
    let placed = |text: &str| text.parse::<Sweep>().expect_err("refused");
    let error = |text: &str| placed(text).problem().clone();
    let e = error(&SWEEP.replace("seeds: 2", "seeds: 0"));
    assert!(
        matches!(&e, SweepError::Invalid { field, .. } if field == "seeds"),
        "{e}"
    );
    let e = error(&SWEEP.replace("path: \"agents\"", "path: \"agnets\""));
    assert!(
        matches!(&e, SweepError::Invalid { field, why } if field == "axes[1].path" && why.contains("`agents`")),
        "{e}"
    );
    let e = error(&SWEEP.replace("List([10, 20])", "List([])"));
    assert!(
        matches!(&e, SweepError::Invalid { field, .. } if field == "axes[1].values"),
        "{e}"
    );
    let e = error(&SWEEP.replace("List([10, 20])", "Logspace(from: 0.0, to: 1.0, count: 3)"));
    assert!(
        matches!(&e, SweepError::Invalid { field, .. } if field == "axes[1].values"),
        "{e}"
    );
    for settle in ["1.0", "-0.1", "NaN"] {
        let e = error(&SWEEP.replace("seeds: 2", &format!("seeds: 2, settle: {settle}")));
        assert!(
            matches!(&e, SweepError::Invalid { field, why } if field == "settle" && why.contains("[0, 1)")),
            "{e}"
        );
    }
    let e = error(&SWEEP.replace("seeds: 2", "seeds: 2, sedes: 3"));
    assert!(matches!(&e, SweepError::Syntax { line: 9, .. }), "{e}");
    let e = error(&SWEEP.replace("\"duration\": 2.0", "\"duration\": -2.0"));
    assert!(
        matches!(&e, SweepError::Base(b) if b.field().as_deref() == Some("duration")),
        "{e}"
    );
}

#[test]
fn duplicate_and_set_axes_are_refused_at_their_line() {
    let duplicate = SWEEP.replace(
        "(path: \"agents\", values: List([10, 20])),",
        "(path: \"agents\", values: List([10, 20])),\n        (path: \"agents\", values: List([30])),",
    );
    let e = duplicate.parse::<Sweep>().expect_err("refused");
    assert!(e.to_string().starts_with("<string>:8:10:"), "{e}");
    assert!(e.to_string().contains("already the path of axes[1]"), "{e}");
    let overlap = SWEEP.replace("\"duration\": 2.0,", "\"duration\": 2.0, \"agents\": 20,");
    let e = overlap.parse::<Sweep>().expect_err("refused");
    assert!(e.to_string().contains("also in `set`"), "{e}");
    assert!(
        matches!(
            &e,
            SweepError::At {
                line: 7,
                col: 10,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn an_invalid_run_is_refused_before_any_run_with_its_values_and_line() {
    let e = SWEEP
        .replace("List([0.02, 0.03, 1e8])", "List([0.02, 0.0])")
        .parse::<Sweep>()
        .expect_err("c1 = 0 is refused");
    let text = e.to_string();
    assert!(
        text.starts_with("<string>:6:32:"),
        "the values of axes[0]: {text}"
    );
    assert!(
        text.contains("run 4 (algorithm.c1 = 0.0, agents = 10, seed = 0)")
            && text.contains("`algorithm.c1`"),
        "{text}"
    );
}

#[test]
fn huge_grids_and_seed_counts_are_refused_without_allocating() {
    for (from, to) in [
        ("seeds: 2", "seeds: 18446744073709551615"),
        (
            "List([10, 20])",
            "Linspace(from: 10.0, to: 20.0, count: 10000000000000)",
        ),
        ("seeds: 2", "seeds: 300000"),
    ] {
        let e = SWEEP
            .replace(from, to)
            .parse::<Sweep>()
            .expect_err("refused");
        assert!(e.to_string().contains("1000000"), "{e}");
    }
}

/// Runs the sweep into `dir` with `jobs` workers (and a shard) and returns `runs.csv`.
fn sweep_into(sweep: &Sweep, dir: &std::path::Path, jobs: usize, shard: Option<Shard>) -> String {
    let options = ExecuteOptions {
        jobs,
        shard,
        keep_runs: false,
    };
    execute(sweep, dir, &options, &|| false, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
    fs::read_to_string(dir.join(RUNS_FILE)).expect("runs.csv")
}

#[test]
fn failing_runs_are_rows_with_their_error_and_the_sweep_goes_on() {
    let tmp = temp_dir("sweep_errors");
    let sweep = tiny();
    let text = sweep_into(&sweep, tmp.path(), 2, None);
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .expect("a header")
        .iter()
        .map(str::to_owned)
        .collect();
    assert_eq!(
        header,
        [
            "run",
            "id",
            "algorithm.c1",
            "agents",
            "seed",
            "connectivity",
            "giant_component",
            "cohesion_radius",
            "deviation_energy",
            "velocity_mismatch",
            "min_distance",
            "collisions",
            "connected_from",
            "alpha_flock",
            "strict_alpha_flock",
            "obstacle_clearance",
            "inside_obstacles",
            "settled_min_distance",
            "settled_collisions",
            "polarisation",
            "milling",
            "nearest_neighbour_mean",
            "settled_polarisation",
            "settled_milling",
            "settled_largest_group",
            "gamma_position_error",
            "gamma_velocity_error",
            "verdict",
            "error"
        ]
    );
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.expect("a row")).collect();
    assert_eq!(rows.len(), 12);
    for row in &rows {
        let (c1, error) = (&row[2], &row[row.len() - 1]);
        match c1 {
            "0.02" => assert!(error.is_empty() && !row[5].is_empty(), "{row:?}"),
            "0.03" => assert!(error.is_empty(), "{row:?}"),
            _ => assert!(
                error.contains("blow-up") || error.contains("blow"),
                "{row:?}"
            ),
        }
    }
    let times = fs::read_to_string(tmp.path().join(store::TIMES_FILE)).expect("times.csv");
    assert_eq!(times.lines().count(), 13);
}

#[test]
fn runs_csv_is_the_same_bytes_for_any_workers_shards_and_interruptions() {
    let sweep = tiny();
    let tmp = temp_dir("sweep_identity");
    let one = sweep_into(&sweep, &tmp.path().join("one"), 1, None);
    let two = sweep_into(&sweep, &tmp.path().join("two"), 2, None);
    assert_eq!(one, two, "--jobs 1 and --jobs 2");
    let shards: Vec<std::path::PathBuf> = (0..3)
        .map(|i| {
            let dir = tmp.path().join(format!("shard{i}"));
            sweep_into(&sweep, &dir, 1, Some(Shard { index: i, count: 3 }));
            dir
        })
        .collect();
    let merged = tmp.path().join("merged");
    assert_eq!(store::merge(&merged, &shards).expect("merged"), 12);
    assert_eq!(
        fs::read_to_string(merged.join(RUNS_FILE)).expect("runs.csv"),
        one
    );
    let missing =
        store::merge(&tmp.path().join("partial"), &shards[..2]).expect_err("a shard is missing");
    assert!(missing.to_string().contains("4 of 12 runs"), "{missing}");
    // a sweep stopped after some runs, then the same call again
    let resumed = tmp.path().join("resumed");
    let stop = AtomicBool::new(false);
    let options = ExecuteOptions::default();
    let count = std::sync::atomic::AtomicUsize::new(0);
    let stopped = execute(
        &sweep,
        &resumed,
        &options,
        &|| stop.load(std::sync::atomic::Ordering::SeqCst),
        &|_| {
            if count.fetch_add(1, std::sync::atomic::Ordering::SeqCst) == 4 {
                stop.store(true, std::sync::atomic::Ordering::SeqCst);
            }
        },
    )
    .expect("stopped cleanly");
    assert!(stopped.stopped && stopped.ran == 5, "{stopped:?}");
    let again = execute(&sweep, &resumed, &options, &|| false, &|_| {}).expect("resumed");
    assert_eq!((again.skipped, again.ran, again.stopped), (5, 7, false));
    assert_eq!(
        fs::read_to_string(resumed.join(RUNS_FILE)).expect("runs.csv"),
        one
    );
    // a directory of another sweep is refused
    let other = Sweep {
        seeds: 3,
        ..sweep.clone()
    };
    let refused = execute(&other, &resumed, &options, &|| false, &|_| {});
    assert!(refused.is_err_and(|e| e.to_string().contains("another sweep")));
}

#[test]
fn keep_runs_writes_each_run_directory() {
    let tmp = temp_dir("sweep_keep");
    let sweep = Sweep {
        axes: Vec::new(),
        seeds: 2,
        ..tiny()
    };
    let options = ExecuteOptions {
        jobs: 2,
        shard: None,
        keep_runs: true,
    };
    execute(&sweep, tmp.path(), &options, &|| false, &|_| {}).expect("runs");
    for run in sweep.runs() {
        let dir = tmp.path().join(store::RUNS_DIR).join(run.id(&sweep.axes));
        assert!(dir.join("metrics.csv").is_file(), "{}", dir.display());
    }
}

/// The sweeps shipped in `sweeps/` load, their axes name parameters of their scenarios, and their
/// grids are the ones `docs/sweeps.md` reads.
#[test]
fn the_shipped_sweeps_load() {
    let dir = crate::common::fixtures_dir().join("../sweeps");
    let alg2 = Sweep::load(dir.join("alg2_c1_n.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((alg2.runs().len(), alg2.seeds), (5 * 4 * 20, 20));
    let alg3 = Sweep::load(dir.join("alg3_beta_radius.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((alg3.runs().len(), alg3.seeds), (7 * 4 * 5, 5));
    for run in [&alg3.runs()[0], &alg3.runs()[139]] {
        let scenario = alg3.scenario(run).unwrap_or_else(|e| panic!("{e}"));
        assert!(scenario.algorithm.uses_obstacles());
    }
    let last = alg3.scenario(&alg3.runs()[139]).expect("valid");
    assert_eq!(
        last.value("obstacles.0.radius").expect("a path"),
        json!(40.0)
    );
    assert_eq!(
        last.value("algorithm.beta.c1").expect("a path"),
        json!(1000.0)
    );
    // the robustness sweeps of docs/conditions.md: the last run of each at its grid's far corner
    let corner = |file: &str, count: usize, paths: [(&str, f64); 2]| {
        let sweep = Sweep::load(dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            (sweep.runs().len(), sweep.seeds),
            (count * 10, 10),
            "{file}"
        );
        let last = sweep
            .scenario(&sweep.runs()[count * 10 - 1])
            .expect("valid");
        for (path, value) in paths {
            assert_eq!(last.value(path).expect("a path"), json!(value), "{file}");
        }
        last
    };
    let fig11 = corner(
        "tac2006_fig11_delay_loss.ron",
        11 * 4,
        [
            ("conditions.communication.delay", 0.8),
            ("conditions.communication.loss.Bernoulli.p", 0.5),
        ],
    );
    assert_eq!(fig11.agents, 100);
    let fig14 = corner(
        "tac2006_fig14_noise_amax.ron",
        5 * 5,
        [
            ("conditions.sensing.noise.White.sigma_q", 3.0),
            ("conditions.actuation.max_acceleration", 100.0),
        ],
    );
    assert!(fig14.algorithm.uses_obstacles());
    // CDS Fig. 7–8: the action-function sweep sets a, b and c₃ on every run, the older one pins
    // the report's Fig. 4 pair a = 1, b = 5
    let fig7 = Sweep::load(dir.join("tr2003_fig7_repulsion.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((fig7.runs().len(), fig7.seeds), (2 * 8 * 4 * 5, 5));
    let last = fig7.scenario(&fig7.runs()[319]).expect("valid");
    for (path, value) in [
        ("alpha.a", 4.0),
        ("alpha.b", 120.0),
        ("algorithm.avoidance.c3", 30.0),
    ] {
        assert_eq!(last.value(path).expect("a path"), json!(value), "{path}");
    }
    let older =
        Sweep::load(dir.join("tr2003_fig7_collisions.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((older.runs().len(), older.seeds), (6 * 3 * 2, 2));
    for run in older.runs() {
        let scenario = older.scenario(&run).expect("valid");
        assert_eq!(scenario.value("alpha.a").expect("a path"), json!(1.0));
        assert_eq!(scenario.value("alpha.b").expect("a path"), json!(5.0));
    }
}

/// The column `name` of a CSV text, as numbers.
fn numbers(text: &str, name: &str) -> Vec<f64> {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let k = reader
        .headers()
        .expect("a header")
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    reader
        .records()
        .map(|r| r.expect("a row")[k].parse().expect("a number"))
        .collect()
}

/// The least distance and the most collisions of a kept run's `metrics.csv` at t ≥ `from`.
fn closest_in(metrics: &str, from: f64) -> (f64, f64) {
    let t = numbers(metrics, "t");
    let pick = |name: &str| -> Vec<f64> {
        numbers(metrics, name)
            .into_iter()
            .zip(&t)
            .filter(|(_, t)| **t >= from)
            .map(|(x, _)| x)
            .collect()
    };
    (
        pick("min_distance")
            .into_iter()
            .fold(f64::INFINITY, f64::min),
        pick("collisions").into_iter().fold(0.0, f64::max),
    )
}

/// A random start puts agents close together; the settled columns are the closest approach from
/// `settle` × the duration on, the whole-run columns from t = 0, both read back independently
/// from each kept run's metrics.csv.
#[test]
fn settled_columns_are_the_closest_approach_after_the_settle_fraction() {
    let tmp = temp_dir("sweep_settled");
    for (settle, dir) in [(None, "default"), (Some(0.5), "half")] {
        let text = match settle {
            None => SWEEP.to_owned(),
            Some(f) => SWEEP.replace("seeds: 2", &format!("seeds: 2, settle: {f}")),
        };
        let sweep: Sweep = text
            .replace("List([0.02, 0.03, 1e8])", "List([0.02])")
            .parse()
            .unwrap_or_else(|e| panic!("{e}"));
        let settle = settle.unwrap_or(0.25);
        assert_eq!(sweep.settle, settle);
        let out = tmp.path().join(dir);
        let options = ExecuteOptions {
            jobs: 2,
            shard: None,
            keep_runs: true,
        };
        execute(&sweep, &out, &options, &|| false, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
        let runs = fs::read_to_string(out.join(RUNS_FILE)).expect("runs.csv");
        let ids: Vec<String> = csv::Reader::from_reader(runs.as_bytes())
            .records()
            .map(|r| r.expect("a row")[1].to_owned())
            .collect();
        let columns = [
            "min_distance",
            "collisions",
            "settled_min_distance",
            "settled_collisions",
        ]
        .map(|name| numbers(&runs, name));
        for (k, id) in ids.iter().enumerate() {
            let metrics =
                fs::read_to_string(out.join(store::RUNS_DIR).join(id).join("metrics.csv"))
                    .expect("metrics.csv");
            let duration = sweep.base_scenario().expect("valid").duration;
            let whole = closest_in(&metrics, f64::NEG_INFINITY);
            let settled = closest_in(&metrics, settle * duration);
            assert_eq!(
                (columns[0][k], columns[1][k]),
                whole,
                "run {k}: the whole run"
            );
            assert_eq!((columns[2][k], columns[3][k]), settled, "run {k}: settled");
            assert!(settled.0 >= whole.0 && settled.1 <= whole.1, "run {k}");
        }
        assert!(
            columns[0] != columns[2],
            "the random start comes closer than the settled flock"
        );
    }
}

/// Figures name parameters by what they are in the scenario's algorithm, and metrics by name and
/// symbol; unknown ones by themselves.
#[test]
fn labels_name_parameters_by_algorithm_and_columns_by_metric() {
    let dir = crate::common::fixtures_dir().join("../sweeps");
    let alg3 = Sweep::load(dir.join("alg3_beta_radius.ron")).unwrap_or_else(|e| panic!("{e}"));
    let base = alg3.base_scenario().expect("valid");
    let axis =
        |scenario: &flocking::Scenario, path: &str| ParameterLabel::of(scenario, path).axis();
    assert_eq!(axis(&base, "algorithm.beta.c1"), "β gain c₁^β");
    assert_eq!(axis(&base, "algorithm.c1"), "navigational gain c₁^γ");
    assert_eq!(axis(&base, "obstacles.0.radius"), "ball radius (m)");
    assert_eq!(
        ParameterLabel::of(&base, "obstacles.0.radius").short(),
        "ball radius"
    );
    let sink = crate::common::fixture("tr2003_fig9_sink_n100");
    assert_eq!(axis(&sink, "algorithm.c1"), "consensus gain c₁");
    assert_eq!(axis(&sink, "no.such.path"), "no.such.path");
    assert_eq!(metric_label("alpha_flock"), "fraction α-flocking");
    assert_eq!(
        metric_label("settled_collisions"),
        "most colliding pairs after settling"
    );
    assert_eq!(
        metric_label(FlockMetrics::REAL_COLUMNS[2]),
        "cohesion radius R"
    );
}

/// Fig. 16's obstacles (two balls, so the base has `obstacles.0.radius`), as a sweep over whole
/// lists of them (docs/sweeps.md: "even whole RON values"): `List([Ball(…)])` once lost the
/// variant's name and no run could read it.
const OBSTACLE_SWEEP: &str = r#"Sweep(
    base: Path("../../fixtures/tac2006_fig16_squeeze_n150.ron"),
    set: {"duration": 1.0, "agents": 10},
    axes: [
        (path: "obstacles", values: List([
            [Ball(centre: [150.0, 0.0], radius: 12.0)],
            [Ball(centre: [160.0, 5.0], radius: 3.0), Ball(centre: [200.0, 0.0], radius: 15.0)],
        ])),
        (path: "obstacles.0.radius", values: List([4.0])),
    ],
    seeds: 1,
)"#;

#[test]
fn whole_ron_values_in_an_axis_keep_their_variants() {
    let sweep: Sweep = OBSTACLE_SWEEP.parse().unwrap_or_else(|e| panic!("{e}"));
    let runs = sweep.runs();
    assert_eq!(runs.len(), 2);
    let obstacles = |k: usize| {
        sweep
            .scenario(&runs[k])
            .unwrap_or_else(|e| panic!("{e}"))
            .value("obstacles")
            .expect("a field")
    };
    assert_eq!(
        obstacles(0),
        json!([{"Ball": {"centre": [150.0, 0.0], "radius": 4.0}}])
    );
    assert_eq!(
        obstacles(1),
        json!([
            {"Ball": {"centre": [160.0, 5.0], "radius": 4.0}},
            {"Ball": {"centre": [200.0, 0.0], "radius": 15.0}}
        ])
    );
    // The ids differ, and the sweep written to `sweep.ron` reads back the same.
    assert_ne!(runs[0].id(&sweep.axes), runs[1].id(&sweep.axes));
    let ron = sweep.to_ron().expect("serializes");
    let back: Sweep = ron.parse().unwrap_or_else(|e| panic!("{e}\n{ron}"));
    assert_eq!(back, sweep);
    // One element of a list, by its index.
    let one: Sweep = OBSTACLE_SWEEP
        .replace("(path: \"obstacles.0.radius\", values: List([4.0])),", "")
        .replace("path: \"obstacles\"", "path: \"obstacles.0\"")
        .replace(
            "[Ball(centre: [150.0, 0.0], radius: 12.0)]",
            "Ball(centre: [150.0, 0.0], radius: 12.0)",
        )
        .replace(
            "[Ball(centre: [160.0, 5.0], radius: 3.0), Ball(centre: [200.0, 0.0], radius: 15.0)]",
            "Ball(centre: [160.0, 5.0], radius: 3.0)",
        )
        .parse()
        .unwrap_or_else(|e| panic!("{e}"));
    // A unit variant by its name.
    let integrators: Sweep = SWEEP
        .replace(
            "(path: \"agents\", values: List([10, 20])),",
            "(path: \"integrator\", values: List([Rk4, SymplecticEuler])),",
        )
        .parse()
        .unwrap_or_else(|e| panic!("{e}"));
    let run = &integrators.runs()[0];
    assert_eq!(run.values[1], json!("Rk4"));
    let scenario = integrators.scenario(run).expect("valid");
    assert_eq!(scenario.value("integrator").expect("a field"), json!("Rk4"));
    let scenario = one.scenario(&one.runs()[1]).expect("valid");
    assert_eq!(
        scenario.value("obstacles.0").expect("a field"),
        json!({"Ball": {"centre": [160.0, 5.0], "radius": 3.0}})
    );
}

#[test]
fn an_invalid_whole_value_is_refused_at_its_line_and_column() {
    for (from, to, why) in [
        (
            "radius: 3.0)",
            "radius: -3.0)",
            "`obstacles[0].radius` is -3.0",
        ),
        (
            "Ball(centre: [160.0, 5.0]",
            "Bal(centre: [160.0, 5.0]",
            "Bal",
        ),
    ] {
        let e = OBSTACLE_SWEEP
            .replace(from, to)
            .replace("(path: \"obstacles.0.radius\", values: List([4.0])),", "")
            .parse::<Sweep>()
            .expect_err("refused");
        let text = e.to_string();
        assert!(text.starts_with("<string>:5:29:"), "{text}");
        assert!(
            text.contains("run 1 (obstacles = ") && text.contains(why),
            "{text}"
        );
    }
}

#[test]
fn a_checked_sweep_reads_back_without_checking_every_run_again() {
    let sweep = tiny();
    let ron = sweep.to_ron().expect("serializes");
    assert_eq!(Sweep::parse_checked(&ron, "sweep.ron"), Ok(sweep.clone()));
    // An invalid run is refused by `parse`, left to its row by `parse_checked`…
    let invalid = ron.replace("100000000.0", "-1.0");
    assert_ne!(invalid, ron);
    assert!(invalid.parse::<Sweep>().is_err());
    assert!(Sweep::parse_checked(&invalid, "sweep.ron").is_ok());
    // …but the counts, the axes and the base are still checked.
    let huge = ron.replace("seeds: 2", "seeds: 18446744073709551615");
    let e = Sweep::parse_checked(&huge, "sweep.ron").expect_err("refused");
    assert!(e.to_string().contains("1000000"), "{e}");
    let e = Sweep::parse_checked(SWEEP, "sweep.ron").expect_err("a path base");
    assert!(e.to_string().contains("base"), "{e}");
}

//! `docs/outputs.md` lists exactly the columns the writers write: every fixture cut to two steps,
//! and a 3D scenario with every condition on, are run into run directories, a tiny sweep into a
//! sweep directory, and the headers they get are compared with the page's tables, file by file.
//! A column added to a writer without its line on the page (or a line left for a column no
//! writer writes) fails here.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

use flocking::sweep::store::{RUNS_FILE, TIMES_FILE};
use flocking::sweep::{ExecuteOptions, Sweep, execute};
use flocking::{RunDirectory, Scenario};

use crate::common::{fixture_paths, stem, temp_dir};

/// The page's column names per `### \`file\`` heading: the first cell of each row of its tables
/// of columns (those whose header cell is `column`), each name in backquotes (a cell may list
/// several: `` `x`, `y`, `z` ``).
fn documented() -> BTreeMap<String, BTreeSet<String>> {
    let page =
        fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/outputs.md"))
            .expect("docs/outputs.md");
    let mut files: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut current: Option<String> = None;
    // whether the lines read are the rows of a table of columns (its header cell `column`)
    let mut columns_table = false;
    for line in page.lines() {
        if let Some(heading) = line.strip_prefix("### ") {
            current = heading
                .strip_prefix('`')
                .and_then(|h| h.strip_suffix('`'))
                .map(str::to_owned);
            continue;
        }
        let Some(file) = &current else { continue };
        let Some(row) = line.strip_prefix("| ") else {
            columns_table = false;
            continue;
        };
        let cell = row.split(" | ").next().unwrap_or_default();
        if cell == "column" {
            columns_table = true;
        }
        if !columns_table || cell == "column" || cell.starts_with("---") {
            continue;
        }
        for name in cell.split(", ") {
            let name = name
                .strip_prefix('`')
                .and_then(|n| n.strip_suffix('`'))
                .unwrap_or_else(|| panic!("{file}: the column cell {cell:?} is not `name`s"));
            files
                .entry(file.clone())
                .or_default()
                .insert(name.to_owned());
        }
    }
    files
}

/// The header (first line) of the CSV file at `path`, split at commas.
fn header(path: &Path) -> Vec<String> {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let first = text.lines().next().unwrap_or_default();
    first.split(',').map(str::to_owned).collect()
}

/// `scenario` run for two steps, each recorded, into `out`.
fn run_into(mut scenario: Scenario, out: &Path) {
    scenario.duration = 2.0 * scenario.step;
    scenario.record_every = 1;
    scenario.snapshots = Some(vec![0.0]);
    let mut directory = RunDirectory::create(out, &scenario, false)
        .unwrap_or_else(|e| panic!("{}: {e}", scenario.name));
    flocking::run(&scenario, &mut directory).unwrap_or_else(|e| panic!("{}: {e}", scenario.name));
    directory.finish().expect("the directory completes");
}

/// Algorithm 2 in 3D with every condition that adds a column.
const EVERY_CONDITION: &str = r#"Scenario(
    name: "every_condition",
    dim: 3,
    agents: 8,
    algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0, 0.0]), c1: 0.05, c2: 0.4),
    initial: (positions: Gaussian(mean: [0.0, 0.0, 0.0], std: 5.0)),
    step: 0.01,
    duration: 1.0,
    conditions: (
        communication: (delay: 0.01, loss: Bernoulli(p: 0.1)),
        sensing: (rate: 50.0),
        actuation: (max_acceleration: 2.0, max_speed: 3.0),
        faults: (at: [(agent: 0, time: 0.0)], mode: Removed),
    ),
)"#;

#[test]
fn the_outputs_page_lists_exactly_the_columns_the_writers_write() {
    let tmp = temp_dir("outputs_columns");
    let mut written: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut add = |file: &str, names: Vec<String>| {
        written.entry(file.to_owned()).or_default().extend(names);
    };
    let mut scenarios: Vec<Scenario> = fixture_paths()
        .iter()
        .map(|path| Scenario::load(path).unwrap_or_else(|e| panic!("{}: {e}", stem(path))))
        .collect();
    scenarios.push(Scenario::parse(EVERY_CONDITION, "every_condition.ron").expect("valid"));
    // the fixed wings in 3D (the fixtures fly them in the plane)
    let mut wings_3d = fixture_paths()
        .iter()
        .find(|path| stem(path) == "fixed_wing_alg2_n30")
        .map(|path| Scenario::load(path).expect("the fixed-wing fixture"))
        .expect("fixtures/fixed_wing_alg2_n30.ron");
    wings_3d = wings_3d
        .with_values([
            ("dim", flocking::serde_json::json!(3)),
            (
                "algorithm.gamma.ConstantVelocity.position",
                flocking::serde_json::json!([0.0, 0.0, 0.0]),
            ),
            (
                "algorithm.gamma.ConstantVelocity.velocity",
                flocking::serde_json::json!([25.0, 0.0, 0.0]),
            ),
            (
                "initial.positions.Gaussian.mean",
                flocking::serde_json::json!([0.0, 0.0, 0.0]),
            ),
            (
                "initial.velocities.Box.min",
                flocking::serde_json::json!([20.0, -3.0, -1.0]),
            ),
            (
                "initial.velocities.Box.max",
                flocking::serde_json::json!([25.0, 3.0, 1.0]),
            ),
            ("name", flocking::serde_json::json!("fixed_wing_3d")),
        ])
        .expect("the fixed wings in 3D");
    scenarios.push(wings_3d);
    for scenario in scenarios {
        let out = tmp.path().join(&scenario.name);
        run_into(scenario, &out);
        for file in ["metrics.csv", "trajectory.csv", "final.csv"] {
            add(file, header(&out.join(file)));
        }
    }

    let sweep: Sweep = r#"Sweep(
        name: "one_axis",
        base: Path("../../fixtures/consensus_cycle_n20.ron"),
        set: {"duration": 0.02},
        axes: [(path: "algorithm.gain", values: List([1.0]))],
        seeds: 1,
    )"#
    .parse()
    .unwrap_or_else(|e| panic!("{e}"));
    let dir = tmp.path().join("sweep");
    let options = ExecuteOptions {
        jobs: 1,
        shard: None,
        keep_runs: false,
    };
    execute(&sweep, &dir, &options, &|| false, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
    // an axis column is named by its path: the page's `<axis path>`
    let axes: Vec<&str> = sweep.axes.iter().map(|a| a.path.as_str()).collect();
    let runs = header(&dir.join(RUNS_FILE))
        .into_iter()
        .map(|c| {
            if axes.contains(&c.as_str()) {
                "<axis path>".to_owned()
            } else {
                c
            }
        })
        .collect();
    add(RUNS_FILE, runs);
    add(TIMES_FILE, header(&dir.join(TIMES_FILE)));

    let documented = documented();
    for (file, names) in &written {
        let listed = documented
            .get(file)
            .unwrap_or_else(|| panic!("docs/outputs.md has no section `### \\`{file}\\``"));
        let missing: Vec<_> = names.difference(listed).collect();
        let stale: Vec<_> = listed.difference(names).collect();
        assert!(
            missing.is_empty() && stale.is_empty(),
            "docs/outputs.md, {file}: written but not listed {missing:?}; listed but not written {stale:?}"
        );
    }
    let undocumented_files: Vec<_> = documented
        .keys()
        .filter(|f| f.ends_with(".csv") && !written.contains_key(*f))
        .collect();
    assert!(
        undocumented_files.is_empty(),
        "docs/outputs.md has tables of files no writer wrote here: {undocumented_files:?}"
    );
}

/// Issue 49: when every agent has been removed by faults, a record's metrics are undefined and
/// `metrics.csv` writes them as `NaN` (and the distances to a nearest agent as `inf`), which
/// docs/outputs.md did not say. The page's paragraph on it names every column that is then
/// `NaN` or `inf`, and no other.
#[test]
fn issue_49_the_outputs_page_says_which_columns_an_empty_flock_leaves_nan() {
    let tmp = temp_dir("outputs_empty_flock");
    let scenario = Scenario::parse(
        r#"Scenario(
    name: "all_removed",
    dim: 2,
    agents: 3,
    algorithm: Algorithm2(gamma: Static(position: [0.0, 0.0]), c1: 0.05, c2: 0.4),
    initial: (positions: Box(min: [-5.0, -5.0], max: [5.0, 5.0])),
    step: 0.01,
    duration: 1.0,
    conditions: (faults: (at: [(agent: 0, time: 0.0), (agent: 1, time: 0.0), (agent: 2, time: 0.0)])),
)"#,
        "all_removed.ron",
    )
    .expect("valid");
    let out = tmp.path().join("all_removed");
    run_into(scenario, &out);
    let text = fs::read_to_string(out.join("metrics.csv")).expect("metrics.csv");
    let mut lines = text.lines();
    let names: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let last: Vec<&str> = lines.last().expect("a row").split(',').collect();
    let with = |value: &str| -> BTreeSet<&str> {
        names
            .iter()
            .zip(&last)
            .filter(|(_, v)| **v == value)
            .map(|(n, _)| *n)
            .collect()
    };
    let (nan, inf) = (with("NaN"), with("inf"));
    assert!(nan.contains("connectivity") && inf.contains("min_distance"));
    let page =
        fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/outputs.md"))
            .expect("docs/outputs.md");
    let paragraph = page
        .split("\n\n")
        .find(|p| p.contains("every agent has been removed"))
        .expect("docs/outputs.md says what a record without agents holds");
    let named = |marker: &str| -> BTreeSet<&str> {
        let part = paragraph
            .split(marker)
            .nth(1)
            .and_then(|rest| rest.split(';').next())
            .unwrap_or_else(|| panic!("the paragraph has no {marker:?}: {paragraph}"));
        part.split('`')
            .skip(1)
            .step_by(2)
            .filter(|n| names.contains(n))
            .collect()
    };
    assert_eq!(named("written `NaN`:"), nan, "{paragraph}");
    assert_eq!(named("written `inf`:"), inf, "{paragraph}");
}

//! The summary `flocking run` prints: the least distance and the most colliding pairs over the
//! whole run and after it has settled (`--settle`), read back independently from metrics.csv.

use std::fs;

use flocking::serde_json::json;

use flock_cli::summary::{LABEL_WIDTH, measure, padded};

use crate::common::{csv_column, fixture, flocking, stderr, temp_dir};

/// The column `name` of a metrics.csv, as numbers.
fn column(metrics: &str, name: &str) -> Vec<f64> {
    csv_column(metrics, name)
        .iter()
        .map(|v| v.parse().expect("a number"))
        .collect()
}

#[test]
fn the_summary_gives_the_closest_approach_over_the_run_and_after_settling() {
    let tmp = temp_dir("summary_settle");
    let scenario = fixture("tac2006_fig11_alg2_n100")
        .with_values([
            ("agents", json!(30)),
            ("duration", json!(20.0)),
            ("initial.positions.std", json!(8.0)),
        ])
        .expect("valid");
    let path = tmp.path().join("scenario.ron");
    fs::write(&path, scenario.to_ron().expect("RON")).expect("write");
    let output = flocking(
        tmp.path(),
        &[
            "run",
            "scenario.ron",
            "--out",
            "run",
            "--settle",
            "0.5",
            "--quiet",
        ],
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let summary = String::from_utf8_lossy(&output.stdout);

    let metrics = fs::read_to_string(tmp.path().join("run/metrics.csv")).expect("metrics.csv");
    let (t, distance, pairs) = (
        column(&metrics, "t"),
        column(&metrics, "min_distance"),
        column(&metrics, "collisions"),
    );
    let from = 0.5 * scenario.duration;
    let after = |values: &[f64], settled: bool| -> Vec<f64> {
        values
            .iter()
            .zip(&t)
            .filter(|(_, t)| !settled || **t >= from)
            .map(|(x, _)| *x)
            .collect()
    };
    let least = |settled| {
        after(&distance, settled)
            .into_iter()
            .fold(f64::INFINITY, f64::min)
    };
    let most = |settled| after(&pairs, settled).into_iter().fold(0.0, f64::max);
    let expected = [
        format!(
            "  {} {} m over the run, {} m after settling (t ≥ {from} s)",
            padded("least distance"),
            measure(least(false)),
            measure(least(true))
        ),
        format!(
            "  {} {} over the run, {} after settling",
            padded("most colliding pairs"),
            most(false),
            most(true)
        ),
    ];
    for line in &expected {
        assert!(
            summary.lines().any(|l| l == line),
            "{line:?} not in\n{summary}"
        );
    }
    assert!(
        least(false) < least(true),
        "the start comes closer than the settled flock: {summary}"
    );
    // the net's edge set stops changing at one of the records
    let topology = summary
        .lines()
        .find_map(|l| l.strip_prefix(&format!("  {} from t = ", padded("topology invariant"))))
        .unwrap_or_else(|| panic!("no topology line in\n{summary}"));
    let from = topology.split(' ').next().expect("a time");
    assert!(
        t.iter().any(|t| format!("{t:.2}") == from),
        "{from} is not a record's time: {summary}"
    );

    let bad = flocking(
        tmp.path(),
        &["run", "scenario.ron", "--out", "o", "--settle", "1"],
    );
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("[0, 1)"), "{}", stderr(&bad));
}

/// The summary of a short Fig. 11 run, its wall time left out: one label column of 27 characters
/// (as a terminal shows them: the tilde of K̃ takes none), every measure with 4 significant
/// digits and its unit (snapshot `snapshots/lib__summary__the_summary_is_one_aligned_table.snap`).
#[test]
fn the_summary_is_one_aligned_table() {
    let tmp = temp_dir("summary_table");
    let scenario = fixture("tac2006_fig11_alg2_n100")
        .with_values([("agents", json!(30)), ("duration", json!(10.0))])
        .expect("valid");
    fs::write(tmp.path().join("s.ron"), scenario.to_ron().expect("RON")).expect("write");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o", "--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let summary = String::from_utf8_lossy(&output.stdout);
    // from the header on (the estimate before it is the warnings' business)
    let lines: Vec<&str> = summary
        .lines()
        .skip_while(|l| !l.starts_with("flocking run: "))
        .filter(|l| !l.starts_with("  wall time"))
        .collect();
    assert!(lines.len() > 10, "{summary}");
    for line in &lines[1..] {
        // the columns a terminal shows: combining marks take none
        let columns: Vec<char> = line
            .chars()
            .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
            .collect();
        let value = 2 + LABEL_WIDTH + 1;
        assert!(
            columns.len() > value
                && columns[..2] == [' ', ' ']
                && columns[2] != ' '
                && columns[value - 1] == ' '
                && columns[value] != ' ',
            "the value of {line:?} does not start at column {}",
            value + 1
        );
    }
    insta::assert_snapshot!(lines.join("\n"));
}

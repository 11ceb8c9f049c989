//! Agents driven onto one point (TAC 2006 Fig. 11 with c₁^γ raised from 0.02 to 0.5): the run
//! warns at the first record where two agents are closer than 10⁻³ d, naming the pair and the
//! time, and its summary counts the merged agents — each checked against the trajectory by brute
//! force, and not warned at the fixture's own gain.

use std::collections::BTreeMap;
use std::fs;

use crate::common::{TempDir, fixture, flocking, stderr, temp_dir};

/// The records of `trajectory.csv`: time → positions in id order.
fn frames(text: &str) -> BTreeMap<String, Vec<(f64, f64)>> {
    let mut frames: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let x: f64 = fields[2].parse().expect("x");
        let y: f64 = fields[3].parse().expect("y");
        frames.entry(fields[0].to_owned()).or_default().push((x, y));
    }
    frames
}

/// Every pair (i < j) closer than `tolerance`, by brute force.
fn close_pairs(q: &[(f64, f64)], tolerance: f64) -> Vec<(usize, usize, f64)> {
    let mut pairs = Vec::new();
    for i in 0..q.len() {
        for j in i + 1..q.len() {
            let distance = (q[i].0 - q[j].0).hypot(q[i].1 - q[j].1);
            if distance < tolerance {
                pairs.push((i, j, distance));
            }
        }
    }
    pairs
}

/// Runs Fig. 11 for 20 s with navigational gain `c1`; returns the stderr, the stdout and the
/// trajectory.
fn run_fig11(tmp: &TempDir, c1: f64) -> (String, String, String) {
    let mut scenario = fixture("tac2006_fig11_alg2_n100");
    scenario = scenario
        .with_values([
            ("algorithm.c1", flocking::serde_json::json!(c1)),
            ("duration", flocking::serde_json::json!(20.0)),
        ])
        .unwrap_or_else(|e| panic!("{e}"));
    let text = scenario.to_ron().expect("the scenario serialises");
    fs::write(tmp.path().join("s.ron"), text).expect("write the scenario");
    let output = flocking(tmp.path(), &["run", "s.ron", "--out", "o", "--quiet"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let trajectory = fs::read_to_string(tmp.path().join("o/trajectory.csv")).expect("trajectory");
    (
        stderr(&output),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        trajectory,
    )
}

#[test]
fn merged_agents_are_warned_at_the_first_record_and_counted() {
    let tmp = temp_dir("merging_strong_gain");
    let (err, out, trajectory) = run_fig11(&tmp, 0.5);
    let tolerance = 1e-3 * 7.0;
    let frames = frames(&trajectory);
    let mut times: Vec<(f64, &String)> =
        frames.keys().map(|t| (t.parse().expect("t"), t)).collect();
    times.sort_by(|a, b| a.0.total_cmp(&b.0));
    // the first record with a pair closer than the tolerance, by brute force
    let (k, first) = times
        .iter()
        .enumerate()
        .find(|(_, (_, t))| !close_pairs(&frames[*t], tolerance).is_empty())
        .expect("c₁ = 0.5 drives agents onto each other within 20 s");
    let pairs = close_pairs(&frames[first.1], tolerance);
    let (i, j, _) = pairs
        .iter()
        .copied()
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .expect("a pair");
    assert!(k > 0, "no pair is merged at the start");
    let warnings: Vec<&str> = err.lines().filter(|l| l.contains("merged at")).collect();
    assert_eq!(warnings.len(), 1, "one warning, at the first merge:\n{err}");
    assert!(
        warnings[0].starts_with(&format!(
            "warning: agents {i} and {j} merged at t = {} ",
            first.1
        )),
        "expected agents {i} and {j} at t = {}:\n{err}",
        first.1
    );
    // the final state's merged agents and the points they share, by brute force (union–find)
    let last = &frames[times.last().expect("records").1];
    let mut group: Vec<usize> = (0..last.len()).collect();
    fn root(group: &mut [usize], mut i: usize) -> usize {
        while group[i] != i {
            group[i] = group[group[i]];
            i = group[i];
        }
        i
    }
    for (i, j, _) in close_pairs(last, tolerance) {
        let (a, b) = (root(&mut group, i), root(&mut group, j));
        group[a.max(b)] = a.min(b);
    }
    let mut sizes: BTreeMap<usize, usize> = BTreeMap::new();
    for i in 0..last.len() {
        *sizes.entry(root(&mut group, i)).or_default() += 1;
    }
    let merged: Vec<usize> = sizes.values().copied().filter(|&s| s > 1).collect();
    let expected = format!(
        "  {} {} agent(s) on {} point(s)   (closer than 10⁻³ d",
        flock_cli::summary::padded("merged agents"),
        merged.iter().sum::<usize>(),
        merged.len()
    );
    assert!(!merged.is_empty(), "{out}");
    assert!(out.contains(&expected), "expected `{expected}` in\n{out}");
}

#[test]
fn the_fixture_gain_merges_no_agents() {
    let tmp = temp_dir("merging_fixture_gain");
    let (err, out, trajectory) = run_fig11(&tmp, 0.02);
    assert!(!err.contains("merged"), "{err}");
    assert!(!out.contains("merged agents"), "{out}");
    for q in frames(&trajectory).values() {
        assert!(close_pairs(q, 7e-3).is_empty());
    }
}

//! The HTML player in a real browser: short runs of TAC 2006 Figs. 11 (2D) and 13 (3D) plotted by
//! `flocking run --plot`, their `player.html` driven in headless Chromium by `tests/browser/player.mjs`
//! (no console errors, agents drawn where the data puts them, merged agents ringed with their
//! count, play/pause, scrub, speed, edges, zoom and the 3D view selector). The screenshots are kept in `target/browser-artifacts/`.
//!
//! Needs `/usr/bin/chromium` (or `$FLOCK_CHROMIUM`), `node` and `npm ci --prefix tests/browser`,
//! so the tests are `#[ignore]`d: `scripts/test` counts them as ignored, and `.ci/run` (which
//! installs the tools) runs them with `cargo test -p flock-cli --test lib browser -- --ignored`,
//! where a missing tool fails them. See `docs/figures.md`.

use flocking::serde_json::{Value, json};
use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use crate::common::{fixture, temp_dir};

/// The simulated time of the short runs: 101 recorded frames, 0.2 s apart.
const DURATION: f64 = 20.0;

/// The workspace's root directory.
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .nth(2)
        .expect("crates/flock-cli is two levels below the workspace")
        .to_path_buf()
}

/// `$CARGO_TARGET_DIR` (relative to the workspace) if set, else the workspace's `target/`.
fn target_dir() -> PathBuf {
    match env::var_os("CARGO_TARGET_DIR") {
        Some(dir) if !dir.is_empty() => workspace().join(dir),
        _ => workspace().join("target"),
    }
}

/// What the browser test needs and is missing, as messages.
fn missing_tools() -> Vec<String> {
    let mut missing = Vec::new();
    let chromium = env::var_os("FLOCK_CHROMIUM")
        .filter(|path| !path.is_empty())
        .map_or_else(|| PathBuf::from("/usr/bin/chromium"), PathBuf::from);
    if !chromium.is_file() {
        missing.push(format!(
            "no Chromium at {} (apt-get install chromium, or set FLOCK_CHROMIUM)",
            chromium.display()
        ));
    }
    let node = Command::new("node").arg("--version").output();
    if !node.is_ok_and(|output| output.status.success()) {
        missing.push("no `node` on the PATH".to_owned());
    }
    let playwright = workspace().join("tests/browser/node_modules/playwright-core/package.json");
    if !playwright.is_file() {
        missing.push("no playwright-core (run `npm ci --prefix tests/browser`)".to_owned());
    }
    missing
}

/// Plots a short run of `fixtures/{name}.ron`, with the scenario values `changes`, and checks its
/// player in headless Chromium (`mode` is `2d` or `3d`), keeping the screenshot as
/// `target/browser-artifacts/{artefact}`; returns the script's JSON summary.
fn check_player(name: &str, changes: &[(&str, Value)], mode: &str, artefact: &str) -> Value {
    let missing = missing_tools();
    if !missing.is_empty() {
        panic!(
            "the {mode} player's browser test cannot run: {}",
            missing.join("; ")
        );
    }

    let tmp = temp_dir(&format!("browser_{mode}"));
    let mut scenario = fixture(name)
        .with_values(changes.iter().cloned())
        .expect("valid changes");
    scenario.duration = DURATION;
    assert_eq!(scenario.validate(), Ok(()));
    let text = scenario.to_ron().expect("the scenario serialises");
    fs::write(tmp.path().join("s.ron"), text).expect("write the scenario");
    let run = Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(tmp.path())
        .args(["run", "s.ron", "--out", "o", "--plot", "--quiet"])
        .output()
        .expect("flocking runs");
    assert!(
        run.status.success(),
        "flocking run --plot: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let player = tmp.path().join("o/figures/player.html");
    assert!(player.is_file(), "no {}", player.display());

    let artefacts = target_dir().join("browser-artifacts");
    fs::create_dir_all(&artefacts).expect("create the artefact directory");
    let screenshot = artefacts.join(artefact);
    let _ = fs::remove_file(&screenshot);
    let started = Instant::now();
    let output = Command::new("node")
        .current_dir(workspace())
        .arg("tests/browser/player.mjs")
        .arg(&player)
        .arg(&screenshot)
        .arg(mode)
        .output()
        .expect("node runs");
    let seconds = started.elapsed().as_secs_f64();
    assert!(
        output.status.success(),
        "the {mode} player failed in Chromium ({seconds:.1} s):\n{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    let png = fs::read(&screenshot).unwrap_or_else(|e| panic!("{}: {e}", screenshot.display()));
    assert!(
        png.starts_with(b"\x89PNG\r\n\x1a\n"),
        "{} is not a PNG",
        screenshot.display()
    );
    println!("{}", String::from_utf8_lossy(&output.stdout).trim_end());
    println!(
        "the {mode} player passed in Chromium in {seconds:.1} s; screenshot: {}",
        screenshot.display()
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    let summary = &stdout[stdout.find('{').expect("a JSON summary")..];
    flocking::serde_json::from_str(summary).expect("the summary is JSON")
}

#[test]
#[ignore = "needs headless Chromium, node and playwright-core; .ci/run runs it with --ignored (docs/figures.md)"]
fn player_2d_works_in_headless_chromium() {
    check_player("tac2006_fig11_alg2_n100", &[], "2d", "player-2d.png");
}

/// Agents 5 and 40 fail (frozen) at t = 4 s: from then on the page draws each as a cross at its
/// position and counts them in `#time`, and draws the others as before.
#[test]
#[ignore = "needs headless Chromium, node and playwright-core; .ci/run runs it with --ignored (docs/figures.md)"]
fn player_with_failed_agents_works_in_headless_chromium() {
    let faults = json!({"faults": {"at": [{"agent": 5, "time": 4.0}, {"agent": 40, "time": 4.0}], "mode": "Frozen"}});
    let changes = [("conditions", faults)];
    check_player(
        "tac2006_fig11_alg2_n100",
        &changes,
        "2d",
        "player-failed.png",
    );
}

#[test]
#[ignore = "needs headless Chromium, node and playwright-core; .ci/run runs it with --ignored (docs/figures.md)"]
fn player_3d_works_in_headless_chromium() {
    check_player("tac2006_fig13_alg2_3d_n50", &[], "3d", "player-3d.png");
}

/// Agents that start at the same point with the same velocity feel the same forces (the σ-norm
/// gradient between them vanishes) and stay merged: agents 55 and 56, and 77, 78 and 79, of
/// Fig. 11's hundred on a 7 m grid, all moving as the γ-agent does. The page rings each merged point and writes its
/// count beside it, in every frame checked.
#[test]
#[ignore = "needs headless Chromium, node and playwright-core; .ci/run runs it with --ignored (docs/figures.md)"]
fn player_rings_merged_agents_in_headless_chromium() {
    let grid = |k: usize| vec![7.0 * (k % 10) as f64, 7.0 * (k / 10) as f64];
    let twin = |k: usize| match k {
        56 => 55,
        78 | 79 => 77,
        k => k,
    };
    let positions: Vec<Vec<f64>> = (0..100).map(|k| grid(twin(k))).collect();
    let velocities = vec![vec![1.0, 0.5]; 100];
    let initial =
        json!({"positions": {"Explicit": positions}, "velocities": {"Explicit": velocities}});
    let summary = check_player(
        "tac2006_fig11_alg2_n100",
        &[("initial", initial)],
        "2d",
        "player-merged.png",
    );
    assert_eq!(
        summary["checks"]["merged_points"],
        json!([2, 2, 2]),
        "two merged points in the first, middle and last frames: {summary}"
    );
}

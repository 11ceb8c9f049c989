//! `flocking figures`: every fixture run and drawn, with a static `index.html`; and `flocking run --quiet`.

use std::fs;
use std::process::Command;

use flock_cli::figures;

use crate::common::{files, temp_dir};

/// A tiny 2D scenario: 8 agents for 0.5 s.
const TINY: &str = r#"Scenario(
    name: "tac2006_fig99_tiny",
    description: "Algorithm 2, n = 8, 2D: a tiny test flock <with> markup & such",
    dim: 2,
    agents: 8,
    seed: 3,
    algorithm: Algorithm2(gamma: ConstantVelocity(position: [0.0, 0.0], velocity: [1.0, 0.0]), c1: 1.0, c2: 2.0),
    initial: (positions: Box(min: [-5.0, -5.0], max: [5.0, 5.0])),
    step: 0.01,
    duration: 0.5,
    record_every: 5,
)
"#;

#[test]
fn figures_writes_an_offline_index_of_every_fixture() {
    let tmp = temp_dir("figures_cmd");
    let fixtures = tmp.path().join("fixtures");
    fs::create_dir_all(&fixtures).expect("create fixtures/");
    fs::write(fixtures.join("tac2006_fig99_tiny.ron"), TINY).expect("write the scenario");
    fs::write(fixtures.join("notes.txt"), "not a scenario").expect("write a non-fixture");
    let out = tmp.path().join("site");

    let entries = figures(&fixtures, &out, true, true).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(entries.len(), 1);
    assert_eq!(entries[0].reference, "Olfati-Saber, TAC 2006, Fig. 99");

    let index = fs::read_to_string(out.join("index.html")).expect("index.html");
    assert!(index.contains("tac2006_fig99_tiny"), "{index}");
    assert!(index.contains("TAC 2006, Fig. 99"), "{index}");
    assert!(
        index.contains("&lt;with&gt; markup &amp; such"),
        "escaped description"
    );
    assert!(index.contains("giant component"), "the metric table");
    assert!(!index.contains("http"), "no network reference");

    let images: Vec<&str> = index
        .split("<img src=\"")
        .skip(1)
        .map(|rest| rest.split('"').next().expect("a closing quote"))
        .collect();
    assert!(
        images.contains(&"tac2006_fig99_tiny/figures/snapshots.png")
            && images.contains(&"tac2006_fig99_tiny/figures/metrics.png"),
        "{images:?}"
    );
    for image in images {
        let len = fs::metadata(out.join(image))
            .unwrap_or_else(|e| panic!("{image}: {e}"))
            .len();
        assert!(len > 0, "{image} is empty");
    }

    let run = out.join("tac2006_fig99_tiny");
    assert!(run.join("scenario.ron").is_file() && run.join("metrics.csv").is_file());
    assert!(run.join("figures/player.html").is_file());
    assert!(!run.join("trajectory.csv").exists() && !run.join("final.csv").exists());
    assert!(!run.join("figures/animation.gif").exists());

    // A second call replaces the runs in place.
    figures(&fixtures, &out, true, true).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn figures_without_fixtures_is_a_clear_error() {
    let tmp = temp_dir("figures_none");
    let err = figures(
        &tmp.path().join("fixtures"),
        &tmp.path().join("o"),
        true,
        true,
    )
    .expect_err("no fixtures directory");
    assert!(err.to_string().contains("no fixtures"), "{err}");
    let output = Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(tmp.path())
        .args(["figures", "--out", "o", "--quiet"])
        .output()
        .expect("flocking runs");
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("no fixtures"));
}

#[test]
fn run_quiet_is_accepted_and_writes_the_same_files() {
    let tmp = temp_dir("run_quiet");
    fs::write(tmp.path().join("s.ron"), TINY).expect("write the scenario");
    let flocking = |args: &[&str]| {
        let output = Command::new(env!("CARGO_BIN_EXE_flocking"))
            .current_dir(tmp.path())
            .args(args)
            .output()
            .expect("flocking runs");
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
    };
    flocking(&["run", "s.ron", "--out", "a"]);
    flocking(&["run", "s.ron", "--out", "b", "--quiet"]);
    for file in ["metrics.csv", "trajectory.csv", "final.csv", "scenario.ron"] {
        let a = fs::read(tmp.path().join("a").join(file)).expect("a");
        let b = fs::read(tmp.path().join("b").join(file)).expect("b");
        assert!(a == b, "{file} differs with --quiet");
    }
}

/// The gallery committed in `docs/figures` (`flocking figures --out docs/figures --no-player`) cannot
/// go stale silently: every fixture is run and drawn again, and every file the gallery keeps —
/// each fixture's run files and figures, the function plots and the page — must equal the
/// committed one byte for byte. After changing a fixture, the drawing or the metrics, regenerate
/// the gallery with that command.
///
/// The same runs check TAC 2006 Theorem 5 on every 2D fixture that ends as a lattice at rest
/// (CDS Fig. 9, TAC Figs. 10, 11, 14, 16, ACC Fig. 4): an α-lattice's net is planar, so it has at
/// most 3n − 6 edges and no two of its edges cross.
#[test]
fn the_committed_gallery_is_what_flock_figures_draws() {
    let committed = crate::common::fixtures_dir().join("../docs/figures");
    let tmp = temp_dir("figures_gallery");
    let out = tmp.path().join("gallery");
    let entries = figures(&crate::common::fixtures_dir(), &out, true, false)
        .unwrap_or_else(|e| panic!("{e}"));

    // every file drawn is the committed one; the directories of the fixtures and the function
    // plots hold nothing else (the top holds other pictures of the docs too)
    let mut dirs: Vec<(String, bool)> = entries
        .iter()
        .flat_map(|e| {
            [
                (e.stem.clone(), true),
                (format!("{}/figures", e.stem), true),
            ]
        })
        .collect();
    dirs.extend([(String::new(), false), ("functions".to_owned(), true)]);
    let mut differences = Vec::new();
    for (dir, whole) in &dirs {
        let drawn = files(&out.join(dir));
        let kept = files(&committed.join(dir));
        let path = |name: &str| {
            if dir.is_empty() {
                name.to_owned()
            } else {
                format!("{dir}/{name}")
            }
        };
        for (name, bytes) in &drawn {
            match kept.get(name) {
                None => differences.push(format!("{} (drawn, not committed)", path(name))),
                Some(k) if k != bytes => differences.push(format!(
                    "{} (drawn {} bytes, committed {} bytes{})",
                    path(name),
                    bytes.len(),
                    k.len(),
                    first_difference(bytes, k)
                )),
                Some(_) => {}
            }
        }
        if *whole {
            for name in kept.keys().filter(|n| !drawn.contains_key(*n)) {
                differences.push(format!("{} (committed, no longer drawn)", path(name)));
            }
        }
    }
    assert!(
        differences.is_empty(),
        "docs/figures is stale, {} file(s) differ:\n  {}\nregenerate it with \
         `cargo run --release -p flock-cli -- figures --out docs/figures --no-player`",
        differences.len(),
        differences.join("\n  ")
    );
    assert_eq!(entries.len(), crate::common::fixture_paths().len());

    let lattices = [
        "tr2003_fig9_sink_n100",
        "tac2006_fig10_alg2_n150",
        "tac2006_fig11_alg2_n100",
        "tac2006_fig14_split_rejoin_n150",
        "tac2006_fig16_squeeze_n150",
        "acc2004_fig4_sink_n100",
    ];
    for stem in lattices {
        let entry = entries
            .iter()
            .find(|e| e.stem == stem)
            .unwrap_or_else(|| panic!("no fixture {stem}"));
        let lattice = &entry.summary.lattice;
        let n = entry.summary.agents;
        eprintln!(
            "{stem}: {} edges (3n − 6 = {}), {:?} crossings, K̃ = {:.1e}",
            lattice.edges,
            3 * n - 6,
            lattice.crossings,
            entry.summary.metrics.velocity_mismatch
        );
        assert!(
            lattice.edges <= 3 * n - 6,
            "{stem}: {} edges",
            lattice.edges
        );
        assert_eq!(lattice.crossings, Some(0), "{stem}");
        assert!(
            entry.summary.metrics.velocity_mismatch < 1e-2,
            "{stem}: not at rest"
        );
    }
}

/// Where two versions of a file first differ: `, first at line L: "drawn" against "committed"`
/// for text, `, first at byte B` otherwise.
fn first_difference(drawn: &[u8], committed: &[u8]) -> String {
    if let (Ok(a), Ok(b)) = (std::str::from_utf8(drawn), std::str::from_utf8(committed)) {
        let cut = |s: &str| s.chars().take(80).collect::<String>();
        let mut lines = a.lines().zip(b.lines()).enumerate();
        return match lines.find(|(_, (x, y))| x != y) {
            Some((k, (x, y))) => format!(
                ", first at line {}: {:?} against {:?}",
                k + 1,
                cut(x),
                cut(y)
            ),
            None => ", one is a prefix of the other".to_owned(),
        };
    }
    let at = drawn
        .iter()
        .zip(committed)
        .position(|(a, b)| a != b)
        .unwrap_or(drawn.len().min(committed.len()));
    format!(", first at byte {at}")
}

#[test]
fn a_stale_file_is_named_with_where_it_differs() {
    assert_eq!(
        first_difference(b"a\nb\nc", b"a\nB\nc"),
        ", first at line 2: \"b\" against \"B\""
    );
    assert_eq!(
        first_difference(&[0, 1, 2, 0xff], &[0, 1, 3, 0xff]),
        ", first at byte 2"
    );
}

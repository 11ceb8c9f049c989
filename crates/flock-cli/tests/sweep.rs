//! `flocking sweep`: the command line of sweeps — a sweep killed with SIGKILL and run again gives the
//! runs.csv of an uninterrupted one, byte for byte; shards merged; phase diagrams drawn; clear
//! errors.

use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{csv_column, fixtures_dir, flocking, flocking_under_4_gib, stderr, temp_dir};

/// Fig. 11 cut to 30 agents and 20 s (some 10–20 ms a run), over 4 × 2 values × 3 seeds (24 runs).
fn write_sweep(dir: &Path) -> String {
    let text = format!(
        r#"Sweep(
    name: "cli",
    base: Path("{}"),
    set: {{"duration": 20.0, "agents": 30, "initial.positions.std": 12.0}},
    axes: [
        (path: "algorithm.c1", values: Logspace(from: 0.01, to: 0.1, count: 4)),
        (path: "algorithm.c2", values: List([0.4, 1.0])),
    ],
    seeds: 3,
)"#,
        fixtures_dir().join("tac2006_fig11_alg2_n100.ron").display()
    );
    let path = dir.join("sweep.ron");
    fs::write(&path, text).expect("write the sweep");
    path.to_str().expect("UTF-8").to_owned()
}

fn sweep(dir: &Path, args: &[&str]) -> String {
    let mut all = vec!["sweep"];
    all.extend_from_slice(args);
    let output = flocking(dir, &all);
    assert!(
        output.status.success(),
        "flocking {all:?}: {}",
        stderr(&output)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The estimate counts the runs this command will run: a shard's, less those found done (a
/// Slurm task of 1 run in 4 estimated all of them, and a finished sweep minutes of work).
#[test]
fn the_estimate_counts_only_the_runs_left_in_this_share() {
    let tmp = temp_dir("sweep_estimate");
    let spec = write_sweep(tmp.path());
    let shard = sweep(
        tmp.path(),
        &[
            &spec, "--out", "s", "--shard", "1/4", "--jobs", "1", "--quiet",
        ],
    );
    assert!(shard.contains("estimate: 6 runs of"), "{shard}");
    let again = sweep(
        tmp.path(),
        &[
            &spec, "--out", "s", "--shard", "1/4", "--jobs", "1", "--quiet",
        ],
    );
    assert!(again.contains("estimate: nothing left to run"), "{again}");
    assert!(!again.contains("runs of"), "{again}");
}

/// `flocking sweep` under a 4 GiB limit, on `jobs` workers, of a sweep of Fig. 11's fixture with
/// `agents` for 1 s over one `axis`: refused (exit 2) before its directory exists; its stdout
/// and stderr.
fn refused_fig11_sweep(name: &str, agents: &str, axis: &str, jobs: usize) -> (String, String) {
    let tmp = temp_dir(&format!("sweep_{name}"));
    let text = format!(
        r#"Sweep(
    name: "{name}",
    base: Path("{}"),
    set: {{"duration": 1.0, "agents": {agents}}},
    axes: [{axis}],
    seeds: 1,
)"#,
        fixtures_dir().join("tac2006_fig11_alg2_n100.ron").display()
    );
    fs::write(tmp.path().join(format!("{name}.ron")), text).expect("write the sweep");
    let command = format!("sweep {name}.ron --out s --jobs {jobs} --quiet");
    let output = flocking_under_4_gib(tmp.path(), &command);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{err}");
    assert!(!tmp.path().join("s").exists());
    (String::from_utf8_lossy(&output.stdout).into_owned(), err)
}

/// Each run's start is counted: a sweep whose one cell packs 12,000 agents into a cloud of
/// σ = 5 cm (each sees all the others: 7.2·10⁷ edges) needs the memory of that crowd, and under a
/// 4 GiB limit is refused before its directory exists, where its worker would have been killed.
#[test]
fn a_sweep_with_a_crowded_cell_is_estimated_by_it() {
    let (said, err) = refused_fig11_sweep(
        "crowd",
        "12000",
        r#"(path: "initial.positions.std", values: List([500.0, 0.05]))"#,
        1,
    );
    assert!(
        err.contains("a run needs about 7.9 GB of memory but"),
        "{err}"
    );
    assert!(
        said.contains("2 runs of") && said.contains("mean degree 11999.0"),
        "{said}"
    );
}

/// Runs whose memory is mostly their delay line are refused naming the delay as the fix, with
/// two workers too (the delay lines of both counted against the memory of both).
#[test]
fn a_sweep_of_long_delays_names_the_delay_line() {
    let (_, err) = refused_fig11_sweep(
        "delays",
        "8",
        r#"(path: "conditions.communication.delay", values: List([2e5, 3e5]))"#,
        2,
    );
    // 3·10⁷ slots of 8 agents' states, 32 bytes each, and of their own 80 bytes: 10.1 GB for
    // each of the two workers
    assert!(
        err.contains("a run needs about 20.2 GB of memory but")
            && err.contains("20.2 GB of it the delay line of conditions.communication.delay")
            && err.contains("a shorter delay"),
        "{err}"
    );
}

#[test]
fn a_killed_sweep_resumes_to_the_same_runs_csv() {
    let tmp = temp_dir("sweep_kill");
    let spec = write_sweep(tmp.path());
    sweep(
        tmp.path(),
        &[&spec, "--out", "whole", "--jobs", "1", "--quiet"],
    );
    let whole = fs::read(tmp.path().join("whole/runs.csv")).expect("runs.csv");
    assert_eq!(String::from_utf8_lossy(&whole).lines().count(), 25);

    let mut child = Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(tmp.path())
        .args(["sweep", &spec, "--out", "killed", "--jobs", "2", "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("flocking sweep starts");
    let rows = tmp.path().join("killed/rows");
    let deadline = Instant::now() + Duration::from_secs(120);
    let done = || fs::read_dir(&rows).map_or(0, |entries| entries.count());
    while done() < 4 && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    let finished = done();
    assert!(
        (4..24).contains(&finished),
        "killed after {finished} of 24 runs: make the runs longer"
    );
    assert!(
        !tmp.path().join("killed/runs.csv").exists(),
        "no runs.csv before the end"
    );

    let report = sweep(
        tmp.path(),
        &[&spec, "--out", "killed", "--jobs", "2", "--quiet"],
    );
    assert!(report.contains("found done"), "{report}");
    assert_eq!(
        fs::read(tmp.path().join("killed/runs.csv")).expect("runs.csv"),
        whole,
        "runs.csv after a SIGKILL and a rerun"
    );
}

#[test]
fn shards_merge_and_phase_diagrams_are_drawn() {
    let tmp = temp_dir("sweep_shards");
    let spec = write_sweep(tmp.path());
    sweep(tmp.path(), &[&spec, "--out", "all", "--quiet"]);
    for i in 0..3 {
        let shard = format!("{i}/3");
        sweep(
            tmp.path(),
            &[
                &spec,
                "--out",
                &format!("s{i}"),
                "--shard",
                &shard,
                "--quiet",
            ],
        );
    }
    let report = sweep(tmp.path(), &["merge", "--out", "merged", "s0", "s1", "s2"]);
    assert!(report.contains("24 row(s)"), "{report}");
    assert_eq!(
        fs::read(tmp.path().join("merged/runs.csv")).expect("merged"),
        fs::read(tmp.path().join("all/runs.csv")).expect("all")
    );
    let missing = flocking(tmp.path(), &["sweep", "merge", "--out", "m2", "s0", "s2"]);
    assert!(!missing.status.success());
    assert!(
        stderr(&missing).contains("8 of 24 runs are in no shard"),
        "{}",
        stderr(&missing)
    );

    sweep(
        tmp.path(),
        &[
            "plot",
            "all",
            "--x",
            "algorithm.c1",
            "--y",
            "algorithm.c2",
            "--metric",
            "alpha_flock",
            "--out",
            "map.svg",
        ],
    );
    let map = fs::read_to_string(tmp.path().join("map.svg")).expect("map.svg");
    for text in [
        "navigational gain c₁^γ",
        "navigational damping gain c₂^γ",
        "fraction α-flocking: mean over 3 seeds",
    ] {
        assert!(map.contains(text), "{text} missing from the heatmap");
    }
    sweep(
        tmp.path(),
        &[
            "plot",
            "all",
            "--x",
            "algorithm.c1",
            "--metric",
            "cohesion_radius",
            "--log-x",
            "--band",
            "quantiles",
            "--out",
            "line.png",
        ],
    );
    let png = fs::read(tmp.path().join("line.png")).expect("line.png");
    assert_eq!(&png[1..4], b"PNG");

    let bad = flocking(
        tmp.path(),
        &[
            "sweep",
            "plot",
            "all",
            "--x",
            "algorithm.c1",
            "--metric",
            "speed",
        ],
    );
    assert!(!bad.status.success());
    assert!(
        stderr(&bad).contains("\"speed\" is not a metric")
            && stderr(&bad).contains("cohesion_radius"),
        "{}",
        stderr(&bad)
    );
}

#[test]
fn bad_sweep_commands_are_clear_errors() {
    let tmp = temp_dir("sweep_errors_cli");
    let spec = write_sweep(tmp.path());
    let no_out = flocking(tmp.path(), &["sweep", &spec]);
    assert_eq!(no_out.status.code(), Some(2));
    assert!(stderr(&no_out).contains("--out"), "{}", stderr(&no_out));
    let shard = flocking(
        tmp.path(),
        &["sweep", &spec, "--out", "o", "--shard", "3/3"],
    );
    assert!(stderr(&shard).contains("0 ≤ i < N"), "{}", stderr(&shard));
    fs::write(tmp.path().join("bad.ron"), "Sweep(seeds: 2)").expect("write");
    let bad = flocking(tmp.path(), &["sweep", "bad.ron", "--out", "o"]);
    assert!(!bad.status.success());
    assert!(stderr(&bad).contains("bad.ron:1:"), "{}", stderr(&bad));
    sweep(tmp.path(), &[&spec, "--out", "o", "--quiet"]);
    fs::write(
        tmp.path().join("other.ron"),
        fs::read_to_string(&spec)
            .expect("read")
            .replace("seeds: 3", "seeds: 2"),
    )
    .expect("write");
    fs::create_dir(tmp.path().join("empty")).expect("mkdir");
    let not_a_sweep = flocking(
        tmp.path(),
        &[
            "sweep",
            "plot",
            "empty",
            "--x",
            "algorithm.c1",
            "--metric",
            "seed",
        ],
    );
    assert!(
        stderr(&not_a_sweep).contains("is not the output directory of a sweep"),
        "{}",
        stderr(&not_a_sweep)
    );
    let refused = flocking(tmp.path(), &["sweep", "other.ron", "--out", "o"]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("another sweep"),
        "{}",
        stderr(&refused)
    );
}

/// The committed results of the shipped sweeps (`docs/figures/sweeps/<name>/`, read by
/// docs/sweeps.md) are what flocking computes and draws today: Algorithm 3's sweep run again (140
/// runs) gives its runs.csv byte for byte, shard 0 of 20 of Algorithm 2's (20 of its 400 runs)
/// gives the same rows, and every committed diagram is drawn again from the committed runs.csv.
#[test]
fn the_committed_sweeps_are_what_flock_computes_and_draws() {
    let tmp = temp_dir("sweep_committed");
    let sweeps = fixtures_dir().join("../sweeps");
    let committed = fixtures_dir().join("../docs/figures/sweeps");
    let stale = "stale: run the sweep and its plot commands again (docs/sweeps.md)";

    let alg3 = sweeps.join("alg3_beta_radius.ron");
    sweep(
        tmp.path(),
        &[alg3.to_str().expect("UTF-8"), "--out", "alg3", "--quiet"],
    );
    for file in ["runs.csv", "sweep.ron"] {
        assert!(
            fs::read(tmp.path().join("alg3").join(file)).expect("computed")
                == fs::read(committed.join("alg3_beta_radius").join(file)).expect("committed"),
            "docs/figures/sweeps/alg3_beta_radius/{file} is {stale}"
        );
    }

    let alg2 = sweeps.join("alg2_c1_n.ron");
    sweep(
        tmp.path(),
        &[
            alg2.to_str().expect("UTF-8"),
            "--out",
            "alg2",
            "--shard",
            "0/20",
            "--quiet",
        ],
    );
    let whole = fs::read_to_string(committed.join("alg2_c1_n/runs.csv")).expect("committed");
    let whole: Vec<&str> = whole.lines().collect();
    let shard = fs::read_to_string(tmp.path().join("alg2/runs.csv")).expect("shard");
    let mut shard = shard.lines();
    assert_eq!(shard.next(), Some(whole[0]), "the header");
    let rows: Vec<&str> = shard.collect();
    assert_eq!(rows.len(), 20);
    for row in rows {
        let index: usize = row
            .split(',')
            .next()
            .and_then(|k| k.parse().ok())
            .expect("run");
        assert_eq!(index % 20, 0, "shard 0/20 holds runs 0, 20, 40, …");
        assert!(
            row == whole[index + 1],
            "run {index} of docs/figures/sweeps/alg2_c1_n/runs.csv is {stale}"
        );
    }

    // every plot command of docs/sweeps.md that draws into the committed files, run from the
    // repository's root as written (and its SVG twin, the same command with `.svg`), but drawing
    // into the test's directory, compared with the committed file
    let root = fixtures_dir().join("..");
    let doc = fs::read_to_string(root.join("docs/sweeps.md")).expect("docs/sweeps.md");
    let mut drawn = 0;
    for line in doc
        .lines()
        .filter(|l| l.starts_with("flocking sweep plot docs/figures/sweeps/"))
    {
        let mut words = shlex::split(line).unwrap_or_else(|| panic!("a shell line: {line}"));
        let out = words.iter().position(|w| w == "--out").expect("--out") + 1;
        let Some(file) = words[out]
            .strip_prefix("docs/figures/sweeps/")
            .map(Path::new)
        else {
            continue;
        };
        let file = committed.join(file);
        for ext in ["png", "svg"] {
            let into = tmp.path().join(format!("drawn-{drawn}.{ext}"));
            words[out] = into.to_str().expect("UTF-8").to_owned();
            let args: Vec<&str> = words[1..].iter().map(String::as_str).collect();
            let output = flocking(&root, &args);
            assert!(output.status.success(), "{line}: {}", stderr(&output));
            let file = file.with_extension(ext);
            assert!(
                fs::read(&into).expect("drawn") == fs::read(&file).expect("committed"),
                "{} is {stale}",
                file.display()
            );
            drawn += 1;
        }
    }
    let committed_diagrams: usize = fs::read_dir(&committed)
        .expect("committed")
        .map(|sweep| {
            fs::read_dir(sweep.expect("a sweep").path())
                .expect("committed")
                .filter(|e| {
                    e.as_ref()
                        .expect("entry")
                        .path()
                        .extension()
                        .is_some_and(|x| x == "svg" || x == "png")
                })
                .count()
        })
        .sum();
    assert_eq!(
        committed_diagrams, drawn,
        "every committed diagram is drawn"
    );
}

/// The committed `runs.csv` of Algorithm 2's sweep: its column `name` as text, row by row.
fn committed_column(name: &str) -> Vec<String> {
    let path = fixtures_dir().join("../docs/figures/sweeps/alg2_c1_n/runs.csv");
    csv_column(&fs::read_to_string(path).expect("runs.csv"), name)
}

/// `flocking sweep plot DIR --x algorithm.c1 --metric METRIC`, then `extra`, then `--out OUT`.
fn plot_args<'a>(dir: &'a str, metric: &'a str, extra: &[&'a str], out: &'a str) -> Vec<&'a str> {
    let mut args = vec![
        "sweep",
        "plot",
        dir,
        "--x",
        "algorithm.c1",
        "--metric",
        metric,
    ];
    args.extend_from_slice(extra);
    args.extend(["--out", out]);
    args
}

/// The rows of a `flocking sweep plot --out X.csv` table: (panel, x, runs, mean).
fn table(path: &Path) -> Vec<(String, f64, usize, f64)> {
    let mut reader = csv::Reader::from_path(path).expect("the table");
    reader
        .records()
        .map(|r| {
            let r = r.expect("a row");
            (
                r[0].to_owned(),
                r[1].parse().expect("x"),
                r[3].parse().expect("runs"),
                r[4].parse().expect("mean"),
            )
        })
        .collect()
}

/// `flocking sweep plot` of the committed Algorithm 2 sweep (c₁^γ × n × 20 seeds) along c₁^γ:
/// with `--where agents=N` each point is the mean over the 20 runs of that n only, with
/// `--facet agents` one panel per n holds the same means, and without either the 80 runs are
/// pooled and the title and a warning say so — each checked against means computed here from
/// runs.csv.
#[test]
fn plot_where_and_facet_draw_only_the_runs_they_name() {
    let tmp = temp_dir("sweep_where");
    let dir = fixtures_dir().join("../docs/figures/sweeps/alg2_c1_n");
    let dir = dir.to_str().expect("UTF-8");
    let (c1, agents, radius) = (
        committed_column("algorithm.c1"),
        committed_column("agents"),
        committed_column("cohesion_radius"),
    );
    let seeds = committed_column("seed")
        .into_iter()
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    let mut ns = agents.clone();
    ns.sort_by_key(|n| n.parse::<u64>().expect("an integer"));
    ns.dedup();
    let mean = |keep: &dyn Fn(usize) -> bool| {
        let selected: Vec<f64> = (0..radius.len())
            .filter(|&k| keep(k))
            .map(|k| radius[k].parse::<f64>().expect("a number"))
            .collect();
        (
            selected.len(),
            selected.iter().sum::<f64>() / selected.len() as f64,
        )
    };
    let plot = |extra: &[&str], out: &str| {
        let args = plot_args(dir, "cohesion_radius", extra, out);
        let output = flocking(tmp.path(), &args);
        assert!(output.status.success(), "{args:?}: {}", stderr(&output));
        stderr(&output)
    };

    let warning = plot(&[], "pooled.csv");
    assert!(
        warning.contains("pools")
            && warning.contains("--where agents=")
            && warning.contains("--facet agents"),
        "{warning}"
    );
    plot(&["--facet", "agents"], "facet.csv");
    let facet = table(&tmp.path().join("facet.csv"));
    let pooled = table(&tmp.path().join("pooled.csv"));
    for n in &ns {
        // one file per n: `--out` never replaces a file outside a directory of flocking's
        let out = format!("where-{n}.csv");
        assert!(plot(&["--where", &format!("agents={n}")], &out).is_empty());
        let fixed = table(&tmp.path().join(&out));
        let panel: Vec<_> = facet
            .iter()
            .filter(|r| r.0 == format!("n = {n}"))
            .cloned()
            .collect();
        assert_eq!(panel.len(), fixed.len(), "n = {n}: one panel row per c₁");
        for ((_, x, runs, m), (_, px, pruns, pm)) in fixed.iter().zip(&panel) {
            let (count, expected) =
                mean(&|k| agents[k] == *n && c1[k].parse::<f64>().expect("c1") == *x);
            assert_eq!(*runs, count, "n = {n}, c₁ = {x}: only the runs of this n");
            assert_eq!(count, seeds);
            approx::assert_relative_eq!(*m, expected, max_relative = 1e-14);
            assert_eq!((px, pruns, pm), (x, runs, m), "the panel n = {n}");
        }
    }
    for (_, x, runs, m) in &pooled {
        let (count, expected) = mean(&|k| c1[k].parse::<f64>().expect("c1") == *x);
        assert_eq!((*runs, count), (ns.len() * seeds, ns.len() * seeds));
        approx::assert_relative_eq!(*m, expected, max_relative = 1e-14);
    }

    let list = ns.join(", ");
    plot(&[], "pooled.svg");
    plot(&["--where", &format!("agents={}", ns[1])], "where.svg");
    let pooled = fs::read_to_string(tmp.path().join("pooled.svg")).expect("svg");
    let title = format!(
        "cohesion radius R: mean over {} runs pooled over n ∈ {{{list}}} × {seeds} seeds",
        ns.len() * seeds
    );
    assert!(pooled.contains(&title), "{title}");
    let fixed = fs::read_to_string(tmp.path().join("where.svg")).expect("svg");
    let title = format!("cohesion radius R: mean over {seeds} seeds, n = {}", ns[1]);
    assert!(fixed.contains(&title), "{title}");
    assert!(fixed.contains("navigational gain c₁^γ"));
}

/// `--bound X --bound-label TEXT` draws one labelled vertical line in the bound's colour, on a
/// line (here c₁^γ = 0.05, between the grid's 0.02 and 0.063) and on a heatmap; a bound outside
/// the x values drawn is an error that says their range, and a label without a bound is refused.
#[test]
fn plot_bound_draws_a_labelled_vertical_line_within_the_grid() {
    let tmp = temp_dir("sweep_bound");
    let dir = fixtures_dir().join("../docs/figures/sweeps/alg2_c1_n");
    let dir = dir.to_str().expect("UTF-8");
    let bound = ["--bound", "0.05", "--bound-label", "c₁ bound (test)"];
    let line = [&["--where", "agents=50"][..], &bound[..]].concat();
    let heatmap = [&["--y", "agents", "--log-x"][..], &bound[..]].concat();
    for (extra, out) in [(line, "line.svg"), (heatmap, "heatmap.svg")] {
        let args = plot_args(dir, "alpha_flock", &extra, out);
        let output = flocking(tmp.path(), &args);
        assert!(output.status.success(), "{args:?}: {}", stderr(&output));
        let svg = fs::read_to_string(tmp.path().join(out)).expect("svg");
        assert_eq!(
            svg.matches("c₁ bound (test)").count(),
            1,
            "{out}: one label"
        );
        assert_eq!(
            svg.matches("stroke=\"#D62728\"").count(),
            1,
            "{out}: one line"
        );
    }
    let args = plot_args(
        dir,
        "alpha_flock",
        &["--where", "agents=50", "--bound", "5"],
        "far.svg",
    );
    let output = flocking(tmp.path(), &args);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("the bound 5 is outside the x values drawn, 0.002 to 0.2"),
        "{}",
        stderr(&output)
    );
    assert!(!tmp.path().join("far.svg").exists());
    let args = plot_args(dir, "alpha_flock", &["--bound-label", "alone"], "alone.svg");
    assert_eq!(flocking(tmp.path(), &args).status.code(), Some(2));
}

#[test]
fn bad_where_and_facet_are_clear_errors() {
    let tmp = temp_dir("sweep_bad_where");
    let dir = fixtures_dir().join("../docs/figures/sweeps/alg2_c1_n");
    let dir = dir.to_str().expect("UTF-8");
    let mut ns = committed_column("agents");
    ns.sort_by_key(|n| n.parse::<u64>().expect("an integer"));
    ns.dedup();
    let failing = |extra: &[&str]| {
        let args = plot_args(dir, "alpha_flock", extra, "never.svg");
        let output = flocking(tmp.path(), &args);
        assert_eq!(
            output.status.code(),
            Some(2),
            "{args:?}: {}",
            stderr(&output)
        );
        assert!(!tmp.path().join("never.svg").exists());
        stderr(&output)
    };
    let e = failing(&["--where", "agents=60"]);
    assert!(
        e.contains("no run has agents = 60")
            && e.contains(&format!("its values are {}", ns.join(", "))),
        "{e}"
    );
    let e = failing(&["--where", "agnets=50"]);
    assert!(
        e.contains("\"agnets\" is not an axis") && e.contains("algorithm.c1, agents"),
        "{e}"
    );
    let e = failing(&["--where", "algorithm.c1=0.2"]);
    assert!(e.contains("drawn or fixed already"), "{e}");
    let e = failing(&["--where", "agents=50", "--where", "agents=25"]);
    assert!(e.contains("drawn or fixed already"), "{e}");
    let e = failing(&["--facet", "algorithm.c1"]);
    assert!(e.contains("--facet algorithm.c1"), "{e}");
    let e = failing(&["--where", "agents"]);
    assert!(e.contains("AXIS=VALUE"), "{e}");
    // a column that is not a measure is bad input, not a failed plot (issue 28: exit 1 before)
    for metric in ["error", "id", "seed"] {
        let args = plot_args(dir, metric, &[], "never.svg");
        let output = flocking(tmp.path(), &args);
        let e = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{metric}: {e}");
        assert!(
            e.contains("is not a metric") && e.contains("alpha_flock"),
            "{e}"
        );
    }
    // a number matches as a number: 50.0 is the 50 of runs.csv
    let output = flocking(
        tmp.path(),
        &plot_args(dir, "alpha_flock", &["--where", "agents=50.0"], "ok.csv"),
    );
    assert!(output.status.success(), "{}", stderr(&output));
}

/// `--series` and `--reference` refuse what they cannot draw with exit code 2, naming the
/// value and the fix, and write nothing: a reference file without the header `series,label,x,y`,
/// a series that is not a value of the axis, a value that is not a number, a reference series
/// without `--series` or `--facet`, and series over a heatmap.
#[test]
fn bad_series_and_references_are_clear_errors() {
    let tmp = temp_dir("sweep_bad_reference");
    let dir = fixtures_dir().join("../docs/figures/sweeps/vicsek1995_fig2a");
    let dir = dir.to_str().expect("UTF-8");
    let failing = |extra: &[&str], reference: &str| {
        fs::write(tmp.path().join("paper.csv"), reference).expect("written");
        let mut args = vec![
            "sweep",
            "plot",
            dir,
            "--x",
            "algorithm.eta",
            "--metric",
            "settled_polarisation",
            "--reference",
            "paper.csv",
            "--out",
            "never.svg",
        ];
        args.extend_from_slice(extra);
        let output = flocking(tmp.path(), &args);
        assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
        assert!(!tmp.path().join("never.svg").exists());
        stderr(&output)
    };
    let series = ["--series", "agents"];
    let e = failing(&series, "n,eta,va\n40,3,0.5\n");
    assert!(
        e.contains("\"n,eta,va\"") && e.contains("give series,label,x,y"),
        "{e}"
    );
    let e = failing(&series, "# a comment\nseries,label,x,y\n41,paper,3,0.5\n");
    assert!(
        e.contains("paper.csv line") && e.contains("\"41\" is not a value of agents"),
        "{e}"
    );
    assert!(e.contains("40, 100, 400, 4000"), "{e}");
    let e = failing(&series, "series,label,x,y\n40,paper,three,0.5\n");
    assert!(e.contains("\"three\" is not a finite number"), "{e}");
    let e = failing(&[], "series,label,x,y\n40,paper,3,0.5\n");
    assert!(e.contains("needs --series or --facet"), "{e}");
    let e = failing(
        &["--series", "agents", "--y", "agents"],
        "series,label,x,y\n,border,3,40\n",
    );
    assert!(e.contains("--series agents"), "{e}");
    // the same file with a series the axis has draws
    fs::write(
        tmp.path().join("paper.csv"),
        "series,label,x,y\n40,paper,3,0.5\n,N = 10000,2.4,0.5\n",
    )
    .expect("written");
    let output = flocking(
        tmp.path(),
        &[
            "sweep",
            "plot",
            dir,
            "--x",
            "algorithm.eta",
            "--series",
            "agents",
            "--metric",
            "settled_polarisation",
            "--reference",
            "paper.csv",
            "--out",
            "ok.svg",
        ],
    );
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(tmp.path().join("ok.svg").is_file());
}

/// Issue 53: an axis of names (here `vehicle`) is drawn as categories in the sweep's order, fixed
/// by the name a title shows; a mistyped metric or axis is refused with the nearest names.
#[test]
fn categorical_axes_are_drawn_and_typos_get_the_nearest_name() {
    let tmp = temp_dir("sweep_categories");
    let sweep_dir = fixtures_dir().join("../docs/figures/sweeps/crazyflie_rate_delay");
    let dir = sweep_dir.to_str().expect("UTF-8");
    let table = sweep(
        tmp.path(),
        &[
            "plot",
            dir,
            "--x",
            "vehicle",
            "--where",
            "conditions.control.rate=100",
            "--where",
            "conditions.communication.delay=0.4",
            "--metric",
            "alpha_flock",
            "--out",
            "vehicle.csv",
        ],
    );
    assert!(table.contains("vehicle.csv"), "{table}");
    let table = fs::read_to_string(tmp.path().join("vehicle.csv")).expect("vehicle.csv");
    let rows: Vec<&str> = table.lines().collect();
    assert_eq!(rows[0], "panel,x,y,runs,mean,low,high");
    assert!(
        rows[1].starts_with(",Quadrotor(inner_step: 0.001),,3,"),
        "{table}"
    );
    assert!(rows[2].starts_with(",PointMass,,3,"), "{table}");
    assert_eq!(rows.len(), 3, "{table}");
    // fixed by the name the figure shows
    sweep(
        tmp.path(),
        &[
            "plot",
            dir,
            "--x",
            "conditions.communication.delay",
            "--y",
            "conditions.control.rate",
            "--where",
            "vehicle=Quadrotor(inner_step: 0.001)",
            "--metric",
            "velocity_mismatch",
            "--log-colour",
            "--out",
            "quadrotor.svg",
        ],
    );
    let map = fs::read_to_string(tmp.path().join("quadrotor.svg")).expect("quadrotor.svg");
    assert!(map.contains("vehicle = Quadrotor(inner_step: 0.001)"));
    for (flag, typo, nearest) in [
        (
            "--metric",
            "velocity_mismatsh",
            "did you mean velocity_mismatch?",
        ),
        ("--x", "vehicles", "did you mean vehicle?"),
    ] {
        let mut args = vec![
            "sweep",
            "plot",
            dir,
            "--x",
            "vehicle",
            "--metric",
            "alpha_flock",
        ];
        let at = args.iter().position(|a| *a == flag).expect("flag") + 1;
        args[at] = typo;
        let bad = flocking(tmp.path(), &args);
        assert_eq!(bad.status.code(), Some(2));
        assert!(stderr(&bad).contains(nearest), "{}", stderr(&bad));
    }
    let far = flocking(
        tmp.path(),
        &["sweep", "plot", dir, "--x", "vehicle", "--metric", "zzz"],
    );
    assert!(!stderr(&far).contains("did you mean"), "{}", stderr(&far));
}

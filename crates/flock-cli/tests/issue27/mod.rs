//! Issue 27, "Never lose a user's file, round two": ownership at every depth, no write through a
//! link flocking did not create, resumes and sweeps that refuse what is not flocking's, `--out`
//! checked before the first step.

use std::fs;
use std::path::Path;

use crate::common::{
    files, flocking, flocking_under_4_gib, remove_own_empty_dir, remove_own_file, remove_own_link,
    stderr, temp_dir, write,
};
use crate::trust::{PLOT_SEEDS, SHORT_2D, complete, refused, seeds_sweep};

mod saved_over;
mod sweeps;

/// The one kept run directory of the sweep in `sw`.
fn kept_run(sw: &Path) -> std::path::PathBuf {
    let entry = fs::read_dir(sw.join("runs"))
        .expect("runs/")
        .next()
        .expect("one run")
        .expect("entry");
    entry.path()
}

#[test]
fn issue_27_force_refuses_a_users_file_at_any_depth_of_a_run() {
    let tmp = temp_dir("force_depth");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--plot", "--quiet"],
    );
    let figures = tmp.path().join("r/figures");
    fs::write(figures.join("annotated_for_paper.svg"), "mine\n").expect("a user's figure");
    let output = flocking(tmp.path(), &["run", &file, "--out", "r", "--force"]);
    refused(
        &output,
        &["r holds figures/annotated_for_paper.svg, which flocking did not write"],
    );
    assert_eq!(
        fs::read(figures.join("annotated_for_paper.svg")).expect("kept"),
        b"mine\n"
    );
    remove_own_file(
        tmp.path(),
        &figures.join("annotated_for_paper.svg"),
        b"mine\n",
    );
    // a user's directory inside figures/
    fs::create_dir(figures.join("mine")).expect("mkdir");
    fs::write(figures.join("mine/notes.txt"), "notes\n").expect("a user's note");
    let before = files(&figures);
    let output = flocking(tmp.path(), &["run", &file, "--out", "r", "--force"]);
    refused(
        &output,
        &["r holds figures/mine, which flocking did not write"],
    );
    assert_eq!(
        fs::read(figures.join("mine/notes.txt")).expect("kept"),
        b"notes\n"
    );
    assert_eq!(files(&figures), before);
    assert!(!tmp.path().join("r.partial").exists());
    // a link in place of one of flocking's files is not flocking's either
    remove_own_file(tmp.path(), &figures.join("mine/notes.txt"), b"notes\n");
    remove_own_empty_dir(tmp.path(), &figures.join("mine"));
    fs::write(tmp.path().join("thesis.tex"), "x\n").expect("a user's file");
    std::os::unix::fs::symlink("../thesis.tex", tmp.path().join("r/final.csv.link"))
        .expect("a link");
    let output = flocking(tmp.path(), &["run", &file, "--out", "r", "--force"]);
    refused(&output, &["r holds final.csv.link"]);
    remove_own_link(
        tmp.path(),
        &tmp.path().join("r/final.csv.link"),
        Path::new("../thesis.tex"),
    );
    // flocking's own run directory, figures and all, is replaced
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--force", "--quiet"],
    );
    assert_eq!(
        fs::read(tmp.path().join("thesis.tex")).expect("kept"),
        b"x\n"
    );
}

#[test]
fn issue_27_a_kept_run_and_a_gallery_refuse_a_users_file_in_figures() {
    let tmp = temp_dir("depth_sweep_gallery");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 1);
    let args = ["sweep", &sweep, "--out", "sw", "--keep-runs", "--quiet"];
    complete(tmp.path(), &args);
    let sw = tmp.path().join("sw");
    let run = kept_run(&sw);
    complete(tmp.path(), &["plot", run.to_str().expect("UTF-8")]);
    fs::create_dir(run.join("figures/mine")).expect("mkdir");
    fs::write(run.join("figures/mine/notes.txt"), "notes\n").expect("a user's note");
    // the run's row is lost: it is run again, and its directory refused
    for row in fs::read_dir(sw.join("rows")).expect("rows/") {
        remove_own_file(tmp.path(), &row.expect("entry").path(), b"");
    }
    let output = flocking(tmp.path(), &args);
    let err = stderr(&output);
    assert!(
        err.contains("holds figures/mine, which flocking did not write"),
        "{err}"
    );
    assert_eq!(
        fs::read(run.join("figures/mine/notes.txt")).expect("kept"),
        b"notes\n"
    );
    assert!(
        run.join("figures/metrics.svg").is_file(),
        "the earlier run is kept"
    );

    // `flocking figures --out g` over g/<fixture>/figures/notes.txt
    let fixtures = tmp.path().join("fixtures");
    fs::create_dir(&fixtures).expect("mkdir");
    write(&fixtures, "short.ron", SHORT_2D);
    complete(
        tmp.path(),
        &["figures", "--out", "g", "--quiet", "--no-player"],
    );
    let figures = tmp.path().join("g/short/figures");
    fs::write(figures.join("notes.txt"), "notes\n").expect("a user's note");
    let before = files(&figures);
    let output = flocking(tmp.path(), &["figures", "--out", "g", "--quiet"]);
    refused(
        &output,
        &["g/short holds figures/notes.txt, which flocking did not write"],
    );
    assert_eq!(files(&figures), before);
}

#[test]
fn issue_27_plot_never_writes_through_a_link() {
    let tmp = temp_dir("plot_link");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(tmp.path(), &["run", &file, "--out", "r2", "--quiet"]);
    let mine = tmp.path().join("mine");
    fs::create_dir(&mine).expect("mkdir");
    fs::write(mine.join("metrics.svg"), "mine\n").expect("a user's figure");
    std::os::unix::fs::symlink(&mine, tmp.path().join("r2/figures")).expect("a link");
    let output = flocking(tmp.path(), &["plot", "r2"]);
    refused(&output, &["r2 holds figures, which flocking did not write"]);
    assert_eq!(files(&mine).len(), 1);
    assert_eq!(fs::read(mine.join("metrics.svg")).expect("kept"), b"mine\n");
    // a link in place of one figure
    remove_own_link(tmp.path(), &tmp.path().join("r2/figures"), &mine);
    fs::create_dir(tmp.path().join("r2/figures")).expect("mkdir");
    std::os::unix::fs::symlink(
        mine.join("metrics.svg"),
        tmp.path().join("r2/figures/metrics.svg"),
    )
    .expect("a link");
    let output = flocking(tmp.path(), &["plot", "r2"]);
    refused(&output, &["r2 holds figures/metrics.svg"]);
    assert_eq!(fs::read(mine.join("metrics.svg")).expect("kept"), b"mine\n");
    // the library refuses it too (for every caller of `write_figures`)
    let error = flocking::owned::write_no_follow(&tmp.path().join("r2/figures/metrics.svg"), b"x")
        .expect_err("refused");
    assert!(error.to_string().contains("is a link"), "{error}");
    assert_eq!(fs::read(mine.join("metrics.svg")).expect("kept"), b"mine\n");
}

/// A user's directory `x.partial` that looks like an interrupted run: its note, its scenario, a
/// `metrics.csv` and a `trajectory.csv` that is a link to a user's file.
fn users_partial(tmp: &Path) -> std::path::PathBuf {
    let partial = tmp.join("x.partial");
    fs::create_dir(&partial).expect("mkdir");
    fs::write(partial.join("INCOMPLETE"), "incomplete: my notes\n").expect("a note");
    fs::write(partial.join("scenario.ron"), SHORT_2D).expect("a scenario");
    fs::write(partial.join("metrics.csv"), "my,own\n1,2\n").expect("a user's table");
    fs::write(tmp.join("data.csv"), "precious\n").expect("a user's file");
    std::os::unix::fs::symlink("../data.csv", partial.join("trajectory.csv")).expect("a link");
    partial
}

#[test]
fn issue_27_resume_refuses_a_directory_flocking_did_not_write() {
    let tmp = temp_dir("resume_foreign");
    let partial = users_partial(tmp.path());
    let before = files(&partial);
    for arg in ["x", "x.partial"] {
        let output = flocking(tmp.path(), &["run", "--resume", arg]);
        refused(
            &output,
            &["x.partial has no .flocking marker", "never writes into it"],
        );
        assert_eq!(files(&partial), before);
        assert_eq!(
            fs::read(tmp.path().join("data.csv")).expect("kept"),
            b"precious\n"
        );
    }
    // with a marker, the link is still not flocking's
    fs::write(partial.join(".flocking"), "written by flocking run\n").expect("a marker");
    let output = flocking(tmp.path(), &["run", "--resume", "x"]);
    refused(
        &output,
        &["x.partial holds trajectory.csv, which flocking did not write"],
    );
    assert_eq!(
        fs::read(tmp.path().join("data.csv")).expect("kept"),
        b"precious\n"
    );
    assert_eq!(
        fs::read(partial.join("metrics.csv")).expect("kept"),
        b"my,own\n1,2\n"
    );
    // `--resume /` and a user's directory are not "a complete run"
    let mine = tmp.path().join("mine");
    fs::create_dir(&mine).expect("mkdir");
    for dir in ["/", "mine"] {
        let output = flocking(tmp.path(), &["run", "--resume", dir]);
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{err}");
        assert!(!err.contains("holds a complete run"), "{dir}: {err}");
        assert!(err.contains("no interrupted run"), "{dir}: {err}");
    }
}

/// Issue 27: an `INCOMPLETE` that is a FIFO is refused at once, not read (which would hang).
#[test]
fn issue_27_resume_of_a_fifo_note_does_not_hang() {
    let tmp = temp_dir("resume_fifo");
    let partial = tmp.path().join("x.partial");
    fs::create_dir(&partial).expect("mkdir");
    fs::write(partial.join(".flocking"), "written by flocking run\n").expect("a marker");
    fs::write(partial.join("scenario.ron"), SHORT_2D).expect("a scenario");
    let made = std::process::Command::new("mkfifo")
        .arg(partial.join("INCOMPLETE"))
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let started = std::time::Instant::now();
    let output = flocking(tmp.path(), &["run", "--resume", "x"]);
    assert!(started.elapsed() < std::time::Duration::from_secs(20));
    refused(
        &output,
        &["x.partial holds INCOMPLETE, which flocking did not write"],
    );
}

#[test]
fn issue_27_a_users_copy_of_a_sweep_and_its_own_files_are_never_written() {
    let tmp = temp_dir("sweep_copy");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    complete(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    // a copy of the sweep without the marker, with an edited runs.csv
    let copy = tmp.path().join("copy");
    fs::create_dir(&copy).expect("mkdir");
    fs::copy(tmp.path().join("sw/sweep.ron"), copy.join("sweep.ron")).expect("copied");
    fs::write(copy.join("runs.csv"), "my,edited\n1,2\n").expect("a user's table");
    let before = files(&copy);
    let output = flocking(tmp.path(), &["sweep", &sweep, "--out", "copy", "--quiet"]);
    refused(&output, &["copy holds", "which flocking did not write"]);
    assert_eq!(files(&copy), before);
    // `sweep plot --out` never replaces the sweep's own files
    let own = files(&tmp.path().join("sw"));
    for name in [
        "sw/sweep.ron",
        "sw/runs.csv",
        "sw/times.csv",
        "sw/.flocking",
    ] {
        let output = flocking(tmp.path(), &[&PLOT_SEEDS[..], &["--out", name]].concat());
        refused(
            &output,
            &[name, "is one of the files of a sweep's output directory"],
        );
        assert_eq!(files(&tmp.path().join("sw")), own, "{name}");
    }
}

#[test]
fn issue_27_out_with_a_trailing_slash_just_works() {
    let tmp = temp_dir("trailing_slash");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(tmp.path(), &["run", &file, "--out", "newdir/", "--quiet"]);
    let out = tmp.path().join("newdir");
    assert!(out.join("metrics.csv").is_file() && out.join("flocking.txt").is_file());
    assert!(!out.join(".partial").exists() && !tmp.path().join("newdir.partial").exists());
    // and replaced with --force the same way
    complete(
        tmp.path(),
        &["run", &file, "--out", "newdir/", "--force", "--quiet"],
    );
    assert!(!out.join(".partial").exists() && out.join("metrics.csv").is_file());
}

#[test]
fn issue_27_an_out_that_is_not_a_directory_is_refused_before_the_run() {
    let tmp = temp_dir("out_not_dir");
    let file = write(tmp.path(), "s.ron", crate::trust::LONG_2D);
    fs::write(tmp.path().join("f"), "mine\n").expect("a user's file");
    std::os::unix::fs::symlink("nowhere", tmp.path().join("dangling")).expect("a link");
    let made = std::process::Command::new("mkfifo")
        .arg(tmp.path().join("fifo"))
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let cases = [
        ("f", "is a file"),
        ("fifo", "is a FIFO"),
        ("dangling", "is a dangling link"),
        ("/dev/null", "is a device"),
    ];
    for (out, what) in cases {
        for force in [false, true] {
            let mut args = vec!["run", &file, "--out", out];
            if force {
                args.push("--force");
            }
            let started = std::time::Instant::now();
            let output = flocking(tmp.path(), &args);
            refused(
                &output,
                &[&format!("output directory {out} {what}, not a directory")],
            );
            // refused at once, not after the run (about a second here)
            assert!(started.elapsed() < std::time::Duration::from_secs(5));
            assert!(!Path::new(&format!("{out}.partial")).exists());
        }
    }
    assert!(!Path::new("/dev/null.partial").exists());
    assert_eq!(fs::read(tmp.path().join("f")).expect("kept"), b"mine\n");
    let names: Vec<String> = fs::read_dir(tmp.path())
        .expect("ls")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 4, "nothing else written: {names:?}");
}

#[test]
fn issue_27_two_runs_into_one_directory_one_wins_the_other_is_refused() {
    let tmp = temp_dir("two_runs");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    for trial in 0..6 {
        let out = format!("d{trial}");
        let args = ["run", &file, "--out", &out, "--quiet"];
        let children = [
            crate::trust::spawn(tmp.path(), &args),
            crate::trust::spawn(tmp.path(), &args),
        ];
        let outputs: Vec<_> = children
            .into_iter()
            .map(|c| c.wait_with_output().expect("a run ends"))
            .collect();
        let mut codes: Vec<_> = outputs.iter().map(|o| o.status.code()).collect();
        codes.sort_unstable();
        let errs: Vec<String> = outputs.iter().map(stderr).collect();
        assert_eq!(codes, [Some(0), Some(2)], "trial {trial}: {errs:?}");
        for err in &errs {
            assert!(!err.contains("os error"), "trial {trial}: {err}");
        }
        assert!(tmp.path().join(&out).join("flocking.txt").is_file());
        // nothing but the run and the scenario
        let left: Vec<String> = fs::read_dir(tmp.path())
            .expect("ls")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .filter(|name| name.starts_with(&out))
            .collect();
        assert_eq!(left, std::slice::from_ref(&out), "trial {trial}");
    }
}

#[test]
fn issue_27_a_forced_run_interrupted_is_resumable() {
    let tmp = temp_dir("force_resume");
    let file = write(tmp.path(), "long.ron", crate::trust::LONG_2D);
    complete(tmp.path(), &["run", &file, "--out", "whole", "--quiet"]);
    complete(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "d",
            "--quiet",
            "--checkpoint-every",
            "7000",
        ],
    );
    let d = tmp.path().join("d");
    let mut child = crate::trust::spawn(
        tmp.path(),
        &[
            "run",
            &file,
            "--out",
            "d",
            "--force",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    let checkpoint = tmp.path().join("d.partial/checkpoint.bin");
    while !checkpoint.exists() {
        assert!(child.try_wait().expect("poll").is_none(), "the run ended");
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    assert!(
        d.join("metrics.csv").is_file(),
        "the earlier run is kept meanwhile"
    );
    complete(tmp.path(), &["run", "--resume", "d", "--quiet"]);
    assert!(!tmp.path().join("d.partial").exists());
    assert_eq!(files(&d), files(&tmp.path().join("whole")));
}

/// A run killed right after its final rename (a double SIGTERM) leaves `DIR` with its
/// checkpoint and `INCOMPLETE` note: `--resume` finishes the tidying, and says so.
#[test]
fn issue_27_a_run_killed_after_its_final_rename_is_tidied_by_resume() {
    let tmp = temp_dir("after_rename");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(tmp.path(), &["run", &file, "--out", "d", "--quiet"]);
    let d = tmp.path().join("d");
    let whole = files(&d);
    fs::write(d.join("INCOMPLETE"), "incomplete: killed\n").expect("the note left");
    fs::write(d.join("checkpoint.bin"), "FLOCKCK2").expect("the checkpoint left");
    let output = flocking(tmp.path(), &["run", "--resume", "d"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let said = String::from_utf8_lossy(&output.stdout);
    assert!(
        said.contains("holds a complete run whose finishing was cut short"),
        "{said}"
    );
    assert_eq!(files(&d), whole);
    // a user's directory with such names is not touched
    let mine = tmp.path().join("mine");
    fs::create_dir(&mine).expect("mkdir");
    for name in ["INCOMPLETE", "final.csv", "flocking.txt", "checkpoint.bin"] {
        fs::write(mine.join(name), "mine\n").expect("a user's file");
    }
    let before = files(&mine);
    let output = flocking(tmp.path(), &["run", "--resume", "mine"]);
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert_eq!(files(&mine), before);
}

/// Issue 27: with every agent removed by faults, the metrics are undefined: the summary and
/// `flocking.txt` say so (they said "C 1.0000 (0 component(s))" and "strict: yes").
#[test]
fn issue_27_the_metrics_of_an_empty_flock_are_undefined() {
    let tmp = temp_dir("empty_flock");
    let text = SHORT_2D.replace(
        "    record_every: 10,\n",
        "    record_every: 10,\n    conditions: (faults: (at: [(agent: 0, time: 0.5), (agent: 1, time: 0.5), (agent: 2, time: 0.5)], mode: Removed)),\n",
    );
    let text = text.replace("agents: 20", "agents: 3");
    assert_ne!(text, SHORT_2D);
    let file = write(tmp.path(), "empty.ron", &text);
    let output = flocking(tmp.path(), &["run", &file, "--out", "r", "--quiet"]);
    let out = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        out.contains(&format!(
            "{} undefined: no agent is left",
            flock_cli::summary::padded("metrics")
        )),
        "{out}"
    );
    assert!(!out.contains("connectivity C"), "{out}");
    assert!(!out.contains("strict: yes"), "{out}");
    let verdict = fs::read_to_string(tmp.path().join("r/flocking.txt")).expect("flocking.txt");
    assert!(
        verdict.contains("undefined, strict: undefined"),
        "{verdict}"
    );
}

/// Issue 27: a run made with Python's `controls=f` records it in its directory; `flocking run
/// --resume` cannot supply `f` and refuses it, untouched, rather than finish it with the
/// scenario's protocol (neither run).
#[test]
fn issue_27_a_run_with_python_controls_is_not_resumed_without_them() {
    use flocking::{RunDirectory, Scenario};
    let tmp = temp_dir("controls_resume");
    let scenario: Scenario = SHORT_2D.parse().expect("a scenario");
    let out = tmp.path().join("x");
    let mut dir = RunDirectory::create(&out, &scenario, false).expect("created");
    dir.record_controls("Python controls=__main__.f")
        .expect("recorded");
    let partial = dir
        .keep_incomplete("interrupted by Ctrl-C", true)
        .expect("kept");
    assert_eq!(
        fs::read_to_string(partial.join("controls.txt")).expect("the record"),
        "inputs from Python controls=__main__.f\n"
    );
    let before = files(&partial);
    let output = flocking(tmp.path(), &["run", "--resume", "x"]);
    refused(
        &output,
        &[
            "was made with Python controls=__main__.f",
            "flocking.resume(\"",
        ],
    );
    assert_eq!(files(&partial), before, "nothing written");
    // the library refuses the other mismatch too, and resumes with the controls given
    let error = RunDirectory::resume_with_controls(&out, 1000, None).expect_err("refused");
    assert!(error.to_string().contains("neither run"), "{error}");
    let (resumed, _, _) =
        RunDirectory::resume_with_controls(&out, 1000, Some("Python controls=__main__.f"))
            .expect("resumed with its controls");
    let resumed = resumed.reopen().expect("reopened");
    assert_eq!(resumed.controls(), Some("Python controls=__main__.f"));
    drop(resumed);
    let plain = tmp.path().join("plain");
    let dir = RunDirectory::create(&plain, &scenario, false).expect("created");
    dir.keep_incomplete("interrupted by Ctrl-C", true)
        .expect("kept");
    let error = RunDirectory::resume_with_controls(&plain, 1000, Some("Python controls=g"))
        .expect_err("refused");
    assert!(
        error
            .to_string()
            .contains("made with the scenario's protocol"),
        "{error}"
    );
}

/// Issue 27: output that cannot be written (`> /dev/full`) is a failure, not exit 0.
#[test]
fn issue_27_validate_into_a_full_device_fails() {
    let tmp = temp_dir("dev_full");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    let full = fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(tmp.path())
        .args(["validate", &file])
        .stdout(full)
        .output()
        .expect("the flocking binary runs");
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains("writing to standard output"), "{err}");
}

/// Issue 27: a file given as a merge shard is a refusal (exit 2) naming it, not an I/O error.
#[test]
fn issue_27_a_file_given_as_a_merge_shard_is_refused() {
    let tmp = temp_dir("merge_file");
    fs::write(tmp.path().join("notes.txt"), "mine\n").expect("a user's file");
    let output = flocking(tmp.path(), &["sweep", "merge", "--out", "m", "notes.txt"]);
    refused(
        &output,
        &["notes.txt is not the output directory of a sweep"],
    );
    assert!(!tmp.path().join("m").exists());
}

/// Issue 27: the resource estimate is checked before anything large is built, and counts an
/// address-space limit (`ulimit -v`): 10⁸ agents under a 4 GiB limit are refused with the
/// estimate (exit 2), where the warnings' initial net aborted the process.
#[test]
fn issue_27_the_estimate_is_checked_first_and_counts_ulimit() {
    let tmp = temp_dir("ulimit");
    let text = SHORT_2D.replace("agents: 20", "agents: 100000000");
    let file = write(tmp.path(), "big.ron", &text);
    let output = flocking_under_4_gib(tmp.path(), &format!("run {file} --out o"));
    refused(
        &output,
        &["a run needs about 51.0 GB of memory but", "is available"],
    );
    assert!(!tmp.path().join("o").exists() && !tmp.path().join("o.partial").exists());
}

/// The estimate counts the start's net: 12,000 agents within 5 m of each other (r = 8.4) hold
/// 7.2·10⁷ edges, some 7.9 GB, where the lattice's 6 neighbours each would fit in 25 MB. Under a
/// 4 GiB limit the crowd is refused with its estimate (exit 2) before anything is written, where
/// it would have started and been killed.
#[test]
fn a_crowd_is_estimated_from_its_start_and_refused_before_it_starts() {
    let tmp = temp_dir("crowd");
    let crowd = SHORT_2D.replace("agents: 20", "agents: 12000").replace(
        "[-15.0, -15.0], max: [15.0, 15.0]",
        "[0.0, 0.0], max: [5.0, 5.0]",
    );
    let file = write(tmp.path(), "crowd.ron", &crowd);
    let output = flocking_under_4_gib(tmp.path(), &format!("run {file} --out o"));
    refused(
        &output,
        &["a run needs about 7.9 GB of memory but", "is available"],
    );
    let said = String::from_utf8_lossy(&output.stdout);
    assert!(
        said.contains("start's net of mean degree 11999.0"),
        "{said}"
    );
    assert!(!tmp.path().join("o").exists() && !tmp.path().join("o.partial").exists());
    // 70,000 agents in 1 m²: 4.9·10⁹ pairs to test each step, refused before any test
    let packed = crowd
        .replace("agents: 12000", "agents: 70000")
        .replace("max: [5.0, 5.0]", "max: [1.0, 1.0]");
    let file = write(tmp.path(), "packed.ron", &packed);
    let output = flocking(tmp.path(), &["run", &file, "--out", "p"]);
    refused(
        &output,
        &["the start is too dense to estimate", "fewer agents"],
    );
    assert!(!tmp.path().join("p").exists() && !tmp.path().join("p.partial").exists());
}

/// Issue 27: the gallery's `index.html` and `functions/` are never written through a link.
#[test]
fn issue_27_the_gallery_never_writes_through_a_link() {
    let tmp = temp_dir("gallery_link");
    let fixtures = tmp.path().join("fixtures");
    fs::create_dir(&fixtures).expect("mkdir");
    write(&fixtures, "short.ron", SHORT_2D);
    complete(
        tmp.path(),
        &["figures", "--out", "g", "--quiet", "--no-player"],
    );
    fs::write(tmp.path().join("page.html"), "mine\n").expect("a user's page");
    remove_own_file(
        tmp.path(),
        &tmp.path().join("g/index.html"),
        b"<!DOCTYPE html>",
    );
    std::os::unix::fs::symlink("../page.html", tmp.path().join("g/index.html")).expect("a link");
    let output = flocking(
        tmp.path(),
        &["figures", "--out", "g", "--quiet", "--no-player"],
    );
    // refused before anything is written
    refused(
        &output,
        &["g holds index.html, which flocking did not write"],
    );
    assert_eq!(
        fs::read(tmp.path().join("page.html")).expect("kept"),
        b"mine\n"
    );
}

/// Issue 27: `flocking validate` of a scenario that does not fit says so and skips what would
/// build the initial net of every agent (it aborted under `ulimit -v`).
#[test]
fn issue_27_validate_of_a_scenario_that_does_not_fit_does_not_abort() {
    let tmp = temp_dir("validate_ulimit");
    let text = SHORT_2D.replace("agents: 20", "agents: 100000000");
    let file = write(tmp.path(), "big.ron", &text);
    let output = flocking_under_4_gib(tmp.path(), &format!("validate {file}"));
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(0), "{err}");
    assert!(
        err.contains("warning: a run needs about 51.0 GB of memory"),
        "{err}"
    );
    assert!(
        err.contains("the start's warnings are not estimated"),
        "{err}"
    );
}

/// A run of `LONG_2D` into `tmp/d`, killed (SIGKILL) once it has written its first checkpoint.
fn killed_at_first_checkpoint(tmp: &Path, file: &str) {
    let mut child = crate::trust::spawn(
        tmp,
        &[
            "run",
            file,
            "--out",
            "d",
            "--quiet",
            "--checkpoint-every",
            "50",
        ],
    );
    let checkpoint = tmp.join("d.partial/checkpoint.bin");
    while !checkpoint.exists() {
        assert!(child.try_wait().expect("poll").is_none(), "the run ended");
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
}

/// Issue 27: the manifest stays right across a SIGKILL and a resume: the resumed run records
/// the very manifest of the uninterrupted one (its files are the same, byte for byte), and
/// `--force` then replaces it.
#[test]
fn issue_27_a_run_killed_and_resumed_records_the_uninterrupted_runs_manifest() {
    let tmp = temp_dir("manifest_resume");
    let file = write(tmp.path(), "long.ron", crate::trust::LONG_2D);
    complete(tmp.path(), &["run", &file, "--out", "whole", "--quiet"]);
    killed_at_first_checkpoint(tmp.path(), &file);
    complete(tmp.path(), &["run", "--resume", "d", "--quiet"]);
    let manifest = |dir: &str| {
        fs::read_to_string(tmp.path().join(dir).join(".flocking.manifest")).expect("a manifest")
    };
    assert_eq!(manifest("d"), manifest("whole"));
    for name in ["metrics.csv", "trajectory.csv", "final.csv", "scenario.ron"] {
        assert!(
            manifest("d")
                .lines()
                .any(|line| line.ends_with(&format!(" {name}")))
        );
    }
    complete(
        tmp.path(),
        &["run", &file, "--out", "d", "--force", "--quiet"],
    );
}

/// Issue 27, errors that name no path: a resume of a run whose `metrics.csv` is gone said only
/// "No such file or directory (os error 2)" (exit 1); it names the file and the fix (exit 2).
#[test]
fn issue_27_a_resume_without_its_records_names_the_missing_file() {
    let tmp = temp_dir("resume_missing");
    let file = write(tmp.path(), "long.ron", crate::trust::LONG_2D);
    killed_at_first_checkpoint(tmp.path(), &file);
    let metrics = tmp.path().join("d.partial/metrics.csv");
    let text = fs::read(&metrics).expect("the records");
    remove_own_file(tmp.path(), &metrics, &text);
    let output = flocking(tmp.path(), &["run", "--resume", "d"]);
    refused(
        &output,
        &[
            "d.partial has no metrics.csv",
            "start it over with `flocking run SCENARIO --out d --force`",
        ],
    );
    assert!(!stderr(&output).contains("os error"));
}

/// Issue 27: `sweep plot --out` into a directory that does not exist said "cannot create
/// zz/yy.svg: No such file or directory (os error 2)"; it names the directory and the fix.
#[test]
fn issue_27_a_figure_into_a_missing_directory_names_it() {
    let tmp = temp_dir("plot_missing_dir");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    complete(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    let output = flocking(
        tmp.path(),
        &[&PLOT_SEEDS[..], &["--out", "zz/yy.svg"]].concat(),
    );
    let err = stderr(&output);
    assert_ne!(output.status.code(), Some(0), "{err}");
    assert!(
        err.contains("cannot create zz/yy.svg: the directory zz does not exist; create it"),
        "{err}"
    );
    assert!(!tmp.path().join("zz").exists());
}

/// Issue 27: a disk too small for the outputs is named ("0 B is free there" said not where).
#[test]
fn issue_27_a_disk_too_small_is_named() {
    let tmp = temp_dir("disk_named");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    let output = flocking(tmp.path(), &["run", &file, "--out", "/proc/x"]);
    refused(&output, &["0 B is free for /proc/x"]);
}

/// `flocking sweep plot --out FILE` inside a sweep's directory judges an existing `FILE` by its
/// content, not by its name: the sweep's directory keeps a manifest of the plots flocking drew
/// there, so a plot is replaced by the next one, while a user's file put there under any name,
/// or a plot the user edited, is refused (exit 2, kept); a sweep directory of an older flocking
/// (no manifest) replaces a plot by its name, as before. Before, any file of a marked directory
/// but the reserved names was replaced.
#[test]
fn issue_27_sweep_plot_in_a_sweep_directory_replaces_only_its_own_plots() {
    let tmp = temp_dir("sweep_plot_manifest");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    complete(tmp.path(), &["sweep", &sweep, "--out", "sw", "--quiet"]);
    let plot = |out: &str| flocking(tmp.path(), &[&PLOT_SEEDS[..], &["--out", out]].concat());
    let sw = tmp.path().join("sw");
    // the user's own file in the sweep's directory, under a name a plot could take
    fs::write(sw.join("mine.svg"), "mine\n").expect("a user's file");
    refused(
        &plot("sw/mine.svg"),
        &["sw holds mine.svg, which flocking did not write"],
    );
    assert_eq!(fs::read(sw.join("mine.svg")).expect("kept"), b"mine\n");
    // flocking's plot is replaced by the next one
    assert!(plot("sw/seed.svg").status.success());
    assert!(plot("sw/seed.svg").status.success());
    // a plot the user edited is theirs
    fs::write(sw.join("seed.svg"), "annotated\n").expect("an edited plot");
    refused(
        &plot("sw/seed.svg"),
        &["sw holds seed.svg, which is not the file flocking wrote there"],
    );
    assert_eq!(fs::read(sw.join("seed.svg")).expect("kept"), b"annotated\n");
    // a directory of an older flocking (no manifest): a plot replaced by its name, as before
    let manifest = sw.join(".flocking.manifest");
    let recorded = fs::read(&manifest).expect("the sweep keeps a manifest");
    assert!(String::from_utf8_lossy(&recorded).contains("seed.svg"));
    remove_own_file(tmp.path(), &manifest, &recorded);
    fs::write(sw.join("old.svg"), "an older flocking's plot\n").expect("an old plot");
    assert!(plot("sw/old.svg").status.success());
    assert!(
        !manifest.exists(),
        "no manifest is made up for an older directory"
    );
}

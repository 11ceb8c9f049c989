//! Issue 27 in sweeps: a full disk retried, a refused kept run, a seed axis, a stray row file.

use super::*;

/// The bytes a directory's files take on a tmpfs (whole pages), at any depth.
fn pages(dir: &Path) -> u64 {
    fs::read_dir(dir)
        .expect("ls")
        .map(|e| e.expect("entry").path())
        .map(|path| {
            if path.is_dir() {
                pages(&path) + 4096
            } else {
                fs::metadata(&path).expect("a file").len().div_ceil(4096) * 4096
            }
        })
        .sum()
}

/// A tmpfs of `bytes` mounted at `dir` (as root), unmounted when dropped; `None` where this
/// process cannot mount.
struct Tmpfs(std::path::PathBuf);

impl Tmpfs {
    fn mount(dir: &Path, bytes: u64) -> Option<Self> {
        fs::create_dir_all(dir).expect("mkdir");
        let status = std::process::Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={bytes}"), "tmpfs"])
            .arg(dir)
            .stderr(std::process::Stdio::null())
            .status();
        if status.is_ok_and(|s| s.success()) {
            Some(Self(dir.to_owned()))
        } else {
            eprintln!("SKIPPED: cannot mount a tmpfs (needs root): the test checks nothing here");
            None
        }
    }

    fn grow(&self, bytes: u64) {
        let status = std::process::Command::new("mount")
            .args(["-o", &format!("remount,size={bytes}")])
            .arg(&self.0)
            .status()
            .expect("mount runs");
        assert!(status.success());
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = std::process::Command::new("umount").arg(&self.0).status();
    }
}

/// The rows of a `runs.csv` (its lines but the header).
fn rows(sw: &Path) -> Vec<String> {
    fs::read_to_string(sw.join("runs.csv"))
        .expect("runs.csv")
        .lines()
        .skip(1)
        .map(str::to_owned)
        .collect()
}

/// Issue 27: a kept run that cannot be written (a full disk) is not a result: it has no row, the
/// sweep exits 1, and the same command makes it once there is room.
#[test]
fn issue_27_a_full_disk_in_a_sweep_is_retried_not_recorded() {
    let tmp = temp_dir("sweep_full_disk");
    write(tmp.path(), "short.ron", SHORT_2D);
    // one kept run's size, measured
    let one = seeds_sweep(tmp.path(), "short.ron", 1);
    complete(
        tmp.path(),
        &["sweep", &one, "--out", "one", "--keep-runs", "--quiet"],
    );
    let run = pages(&kept_run(&tmp.path().join("one")));
    let sweep = seeds_sweep(tmp.path(), "short.ron", 4);
    let Some(disk) = Tmpfs::mount(&tmp.path().join("sw"), run * 3 / 2 + 64 * 1024) else {
        return;
    };
    let args = [
        "sweep",
        &sweep,
        "--out",
        "sw",
        "--keep-runs",
        "--jobs",
        "1",
        "--no-resource-check",
        "--quiet",
    ];
    let output = flocking(tmp.path(), &args);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains("could not be written"), "{err}");
    assert!(err.contains("No space left on device"), "{err}");
    let first = rows(&tmp.path().join("sw"));
    assert!(!first.is_empty() && first.len() < 4, "{first:?}");
    assert!(
        first.iter().all(|row| row.ends_with(',')),
        "no error row: {first:?}"
    );
    // room again: the same command makes the missing runs, and only them
    disk.grow(64 * 1024 * 1024);
    let output = flocking(tmp.path(), &args);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let all = rows(&tmp.path().join("sw"));
    assert_eq!(all.len(), 4, "{all:?}");
    assert!(all.iter().all(|row| row.ends_with(',')), "{all:?}");
    assert!(
        first.iter().all(|row| all.contains(row)),
        "{first:?} kept in {all:?}"
    );
}

/// Issue 27: a kept run refused for a user's file in its directory has no row either.
#[test]
fn issue_27_a_kept_run_refused_has_no_row_and_the_sweep_fails() {
    let tmp = temp_dir("sweep_keep_refused");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    let args = ["sweep", &sweep, "--out", "sw", "--keep-runs", "--quiet"];
    complete(tmp.path(), &args);
    // run 0's row is lost, and a user's file is in its directory
    let id = flocking::sweep::Sweep::load(&sweep)
        .expect("a sweep")
        .runs()[0]
        .id(&[]);
    let row = tmp.path().join(format!("sw/rows/00000000-{id}.csv"));
    remove_own_file(tmp.path(), &row, b"0,");
    let mine = tmp.path().join("sw/runs").join(&id);
    fs::write(mine.join("thesis.tex"), "x\n").expect("a user's file");
    let output = flocking(tmp.path(), &args);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(
        err.contains("holds thesis.tex, which flocking did not write"),
        "{err}"
    );
    assert_eq!(rows(&tmp.path().join("sw")).len(), 1);
    remove_own_file(tmp.path(), &mine.join("thesis.tex"), b"x\n");
    complete(tmp.path(), &args);
    assert_eq!(rows(&tmp.path().join("sw")).len(), 2);
}

#[test]
fn issue_27_a_seed_axis_is_refused_at_its_line() {
    let tmp = temp_dir("seed_axis");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = write(
        tmp.path(),
        "sweep.ron",
        "Sweep(\n    base: Path(\"short.ron\"),\n    axes: [\n        (path: \"seed\", values: List([1, 2, 3])),\n    ],\n    seeds: 2,\n)\n",
    );
    let output = flocking(tmp.path(), &["sweep", &sweep, "--out", "sw"]);
    refused(&output, &["sweep.ron:4:", "`seed` is given by `seeds`"]);
    assert!(!tmp.path().join("sw").exists());
}

#[test]
fn issue_27_a_stray_row_file_adds_no_row() {
    let tmp = temp_dir("stray_row");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 2);
    let args = ["sweep", &sweep, "--out", "sw", "--quiet"];
    complete(tmp.path(), &args);
    let sw = tmp.path().join("sw");
    let before = fs::read(sw.join("runs.csv")).expect("runs.csv");
    let stray = "99,ffff,0,1,1,1,0,0,1,0,0,true,true,,,1,0,\n0.1\n";
    fs::write(sw.join("rows/00000099-ffff.csv"), stray).expect("a stray row");
    fs::write(sw.join("rows/00000001-ffff.csv"), stray).expect("a stray row");
    complete(tmp.path(), &args);
    assert_eq!(fs::read(sw.join("runs.csv")).expect("runs.csv"), before);
}

//! Issue 27: a file the user saved over one of flocking's own names is never replaced (runs,
//! plots, the gallery, kept runs), and a run without a manifest is judged by its names.

use super::*;

/// Saves `mine` over the file `path` of flocking's, returning what flocking wrote there.
fn save_over(path: &Path, mine: &[u8]) -> Vec<u8> {
    let flockings = fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_ne!(flockings, mine, "the user's file differs from flocking's");
    fs::write(path, mine).expect("the user's file saved over flocking's");
    flockings
}

/// Issue 27, ownership by content: a file the user saved over one of a run's own names, at its
/// top (`final.csv`, edited by hand) or in its `figures/` (an annotated `metrics.svg`), is the
/// user's: `run --force` refuses, naming it, and nothing is touched. The same file put back as
/// flocking wrote it is flocking's again.
#[test]
fn issue_27_force_refuses_a_file_the_user_saved_over_a_runs_own_name() {
    let tmp = temp_dir("force_content");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--plot", "--quiet"],
    );
    let r = tmp.path().join("r");
    for (name, mine) in [
        // the same length as flocking's: only the content tells them apart
        ("final.csv", None),
        (
            "figures/metrics.svg",
            Some(&b"<svg>annotated for the paper</svg>\n"[..]),
        ),
    ] {
        let path = r.join(name);
        let mine = mine.map_or_else(
            || {
                let mut edited = fs::read(&path).expect("final.csv");
                let last = edited.len() - 2;
                edited[last] = if edited[last] == b'1' { b'2' } else { b'1' };
                edited
            },
            <[u8]>::to_vec,
        );
        let flockings = save_over(&path, &mine);
        let before = files(&r);
        let output = flocking(tmp.path(), &["run", &file, "--out", "r", "--force"]);
        refused(
            &output,
            &[&format!(
                "r holds {name}, which is not the file flocking wrote there"
            )],
        );
        assert_eq!(fs::read(&path).expect("kept"), mine);
        assert_eq!(files(&r), before);
        assert!(!tmp.path().join("r.partial").exists());
        fs::write(&path, &flockings).expect("flocking's file put back");
    }
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--force", "--quiet"],
    );
}

/// Issue 27: `flocking plot` never replaces a figure the user saved over flocking's, nor one
/// flocking never drew there (a 2D run has no `views.svg`), also in a gallery's fixture
/// (`g/short/figures`, two levels down).
#[test]
fn issue_27_plot_refuses_a_figure_the_user_saved_over_flockings() {
    let tmp = temp_dir("plot_content");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--plot", "--quiet"],
    );
    let figures = tmp.path().join("r/figures");
    let mine = b"<svg>annotated</svg>\n";
    let flockings = save_over(&figures.join("metrics.svg"), mine);
    let before = files(&figures);
    refused(
        &flocking(tmp.path(), &["plot", "r"]),
        &["r holds figures/metrics.svg, which is not the file flocking wrote there"],
    );
    assert_eq!(files(&figures), before);
    fs::write(figures.join("metrics.svg"), &flockings).expect("put back");
    // a file of a figure's name that flocking never drew
    fs::write(figures.join("views.svg"), mine).expect("a user's figure");
    refused(
        &flocking(tmp.path(), &["plot", "r"]),
        &["r holds figures/views.svg, which is not the file flocking wrote there"],
    );
    remove_own_file(tmp.path(), &figures.join("views.svg"), mine);
    complete(tmp.path(), &["plot", "r"]);
    assert_eq!(
        fs::read(figures.join("metrics.svg")).expect("redrawn"),
        flockings
    );

    let fixtures = tmp.path().join("fixtures");
    fs::create_dir(&fixtures).expect("mkdir");
    write(&fixtures, "short.ron", SHORT_2D);
    complete(
        tmp.path(),
        &["figures", "--out", "g", "--quiet", "--no-player"],
    );
    let figures = tmp.path().join("g/short/figures");
    save_over(&figures.join("snapshots.svg"), mine);
    refused(
        &flocking(tmp.path(), &["plot", "g/short"]),
        &["g/short holds figures/snapshots.svg, which is not the file flocking wrote there"],
    );
    assert_eq!(fs::read(figures.join("snapshots.svg")).expect("kept"), mine);
}

/// Issue 27: `flocking figures --out g` refuses a file the user saved over one of the gallery's
/// own, at every depth — its page (`g/index.html`), a function plot (`g/functions/…`), a
/// fixture's record (`g/short/flocking.txt`), a fixture's figure (`g/short/figures/…`) — before
/// anything is written.
#[test]
fn issue_27_figures_refuses_a_file_the_user_saved_over_the_gallerys() {
    let tmp = temp_dir("gallery_content");
    let fixtures = tmp.path().join("fixtures");
    fs::create_dir(&fixtures).expect("mkdir");
    write(&fixtures, "short.ron", SHORT_2D);
    let args = ["figures", "--out", "g", "--quiet", "--no-player"];
    complete(tmp.path(), &args);
    let g = tmp.path().join("g");
    let function = fs::read_dir(g.join("functions"))
        .expect("functions/")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .find(|name| name.ends_with(".svg"))
        .expect("a function plot");
    let cases = [
        ("g", "index.html".to_owned()),
        ("g", format!("functions/{function}")),
        ("g/short", "flocking.txt".to_owned()),
        ("g/short", "figures/metrics.svg".to_owned()),
    ];
    for (dir, name) in cases {
        let path = tmp.path().join(dir).join(&name);
        let mine = b"mine, with my notes\n";
        let flockings = save_over(&path, mine);
        let before = [
            files(&g),
            files(&g.join("short")),
            files(&g.join("short/figures")),
        ];
        refused(
            &flocking(tmp.path(), &args),
            &[&format!(
                "{dir} holds {name}, which is not the file flocking wrote there"
            )],
        );
        let after = [
            files(&g),
            files(&g.join("short")),
            files(&g.join("short/figures")),
        ];
        assert!(before == after, "{dir}/{name}: nothing is touched");
        fs::write(&path, &flockings).expect("put back");
    }
    complete(tmp.path(), &args);
}

/// Issue 27: `sweep --keep-runs` never replaces a kept run whose files the user saved over
/// (`runs/<id>/final.csv`, `runs/<id>/figures/metrics.svg`): the run gets no row, the sweep
/// exits 1, and the same command makes it once the file is moved.
#[test]
fn issue_27_a_kept_run_is_not_replaced_over_a_file_the_user_saved() {
    let tmp = temp_dir("sweep_content");
    write(tmp.path(), "short.ron", SHORT_2D);
    let sweep = seeds_sweep(tmp.path(), "short.ron", 1);
    let args = ["sweep", &sweep, "--out", "sw", "--keep-runs", "--quiet"];
    complete(tmp.path(), &args);
    let sw = tmp.path().join("sw");
    let run = kept_run(&sw);
    complete(tmp.path(), &["plot", run.to_str().expect("UTF-8")]);
    for name in ["final.csv", "figures/metrics.svg"] {
        let path = run.join(name);
        let mine = b"mine\n";
        let flockings = save_over(&path, mine);
        // the run's row is lost: it is run again, and its directory refused
        for row in fs::read_dir(sw.join("rows")).expect("rows/") {
            remove_own_file(tmp.path(), &row.expect("entry").path(), b"");
        }
        let output = flocking(tmp.path(), &args);
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{err}");
        assert!(
            err.contains(&format!(
                "holds {name}, which is not the file flocking wrote there"
            )),
            "{err}"
        );
        assert_eq!(fs::read(&path).expect("kept"), mine);
        fs::write(&path, &flockings).expect("put back");
        complete(tmp.path(), &args);
        assert!(
            !run.join("figures").exists(),
            "the run made again, as the sweep keeps it"
        );
        complete(tmp.path(), &["plot", run.to_str().expect("UTF-8")]);
    }
}

/// Issue 27: a run directory of an older flocking has no manifest; its files are recognised by
/// their names, as that version did, and `--force` replaces it.
#[test]
fn issue_27_a_run_without_a_manifest_is_judged_by_names() {
    let tmp = temp_dir("no_manifest");
    let file = write(tmp.path(), "s.ron", SHORT_2D);
    complete(tmp.path(), &["run", &file, "--out", "r", "--quiet"]);
    let manifest = tmp.path().join("r/.flocking.manifest");
    let text = fs::read(&manifest).expect("a finished run has a manifest");
    assert!(text.starts_with(b"flocking manifest 1\n"));
    remove_own_file(tmp.path(), &manifest, b"flocking manifest 1\n");
    save_over(&tmp.path().join("r/final.csv"), b"edited\n");
    complete(
        tmp.path(),
        &["run", &file, "--out", "r", "--force", "--quiet"],
    );
    assert_eq!(fs::read(&manifest).expect("recorded again"), text);
}

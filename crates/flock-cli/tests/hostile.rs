//! The corpus of hostile inputs in `tests/hostile/` (its `manifest.tsv`: the command, the exit code
//! and a substring of the message): each is refused with its code and message, without a panic
//! or a signal, and leaves nothing behind.

use crate::common::{flocking, stderr, temp_dir};

#[test]
fn every_hostile_input_is_refused_cleanly_and_leaves_nothing() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/hostile");
    let manifest = std::fs::read_to_string(dir.join("manifest.tsv")).expect("the manifest");
    let cases: Vec<&str> = manifest
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .collect();
    assert!(cases.len() >= 10, "{manifest}");
    for case in cases {
        let tmp = temp_dir("hostile");
        let fields: Vec<&str> = case.split('\t').collect();
        let [command, code, message] = fields[..] else {
            panic!("a manifest line is `args<TAB>code<TAB>message`: {case}");
        };
        let out = tmp.path().join("out");
        let args: Vec<String> = command
            .split(' ')
            .map(|a| {
                a.replace("{dir}", &dir.display().to_string())
                    .replace("{out}", &out.display().to_string())
            })
            .collect();
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let output = flocking(tmp.path(), &args);
        let err = stderr(&output);
        assert_eq!(
            output.status.code().map(|c| c.to_string()).as_deref(),
            Some(code),
            "{case}: {err}"
        );
        assert!(err.contains(message), "{case}: {err}");
        assert!(!err.contains("panicked"), "{case}: {err}");
        let left: Vec<_> = std::fs::read_dir(tmp.path())
            .expect("the temp dir")
            .collect();
        assert!(left.is_empty(), "{case}: left {left:?}");
    }
}

/// Issue 20: "SIGTERM and Ctrl-C work at every phase, including reading and validating". A sweep
/// of 10⁶ runs spends seconds checking every run's scenario before it writes anything; SIGINT
/// and SIGTERM (the `ctrlc` crate's `termination` feature) then quit at once with 130, and the
/// output directory is never created.
#[test]
fn issue_20_sigint_and_sigterm_stop_the_validation_of_a_large_sweep() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};

    let tmp = temp_dir("validation_signal");
    let fixture = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/tac2006_fig11_alg2_n100.ron");
    let sweep = crate::common::write(
        tmp.path(),
        "big.sweep.ron",
        &format!(
            r#"Sweep(
    base: Path({:?}),
    axes: [(path: "algorithm.c1", values: Linspace(from: 0.01, to: 0.05, count: 1000000))],
    seeds: 1,
)"#,
            fixture.display().to_string()
        ),
    );
    for signal in ["-INT", "-TERM"] {
        let out = tmp.path().join("out");
        let mut child = Command::new(env!("CARGO_BIN_EXE_flocking"))
            .current_dir(tmp.path())
            .args(["sweep", &sweep, "--out", "out"])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the flocking binary runs");
        std::thread::sleep(Duration::from_millis(800));
        assert!(
            child.try_wait().expect("waits").is_none(),
            "the sweep ended before {signal}: make it larger"
        );
        let sent = Instant::now();
        let signalled = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(signalled.success());
        let status = loop {
            if let Some(status) = child.try_wait().expect("waits") {
                break status;
            }
            if sent.elapsed() > Duration::from_secs(5) {
                let _ = child.kill();
                panic!("{signal}: still validating 5 s after the signal");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        assert_eq!(status.code(), Some(130), "{signal}");
        assert!(
            !out.exists(),
            "{signal}: nothing is written while validating"
        );
        let names: Vec<_> = std::fs::read_dir(tmp.path())
            .expect("lists")
            .map(|e| e.expect("an entry").file_name())
            .collect();
        assert_eq!(names, ["big.sweep.ron"], "{signal}: nothing left behind");
    }
}

//! Every command writing to a closed pipe (`flocking validate X.ron | head -1`, or a reader that
//! has gone before the first byte) exits quietly with its own exit code: no panic, no message,
//! and a run still writes its outputs whole.

use std::io::Read;
use std::path::Path;
use std::process::{Child, Command, Stdio};

use crate::common::{files, fixtures_dir, flocking, temp_dir, write};
use crate::errors::TINY_2D;

/// `flocking args` started in `dir`, its standard output and standard error piped to us.
fn piped(dir: &Path, args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_flocking"))
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the flocking binary starts")
}

/// Runs `flocking args` in `dir` with standard output and standard error pipes whose readers
/// close at once, and returns its exit code.
fn into_closed_pipes(dir: &Path, args: &[&str]) -> Option<i32> {
    let mut child = piped(dir, args);
    drop(child.stdout.take());
    drop(child.stderr.take());
    child.wait().expect("it ends").code()
}

/// `head -1`: standard output closed after its first line; standard error kept and read.
fn into_head(dir: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let mut child = piped(dir, args);
    let mut stdout = child.stdout.take().expect("a pipe");
    let mut first = Vec::new();
    let mut byte = [0u8; 1];
    while stdout.read(&mut byte).expect("readable") == 1 && byte[0] != b'\n' {
        first.push(byte[0]);
    }
    drop(stdout);
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .expect("a pipe")
        .read_to_string(&mut stderr)
        .expect("readable");
    let code = child.wait().expect("it ends").code();
    (code, String::from_utf8_lossy(&first).into_owned(), stderr)
}

#[test]
fn validate_into_head_prints_one_line_and_exits_quietly() {
    let tmp = temp_dir("pipe_validate");
    let fixture = fixtures_dir().join("tac2006_fig11_alg2_n100.ron");
    let fixture = fixture.to_str().expect("UTF-8");
    let (code, first, stderr) = into_head(tmp.path(), &["validate", fixture]);
    assert_eq!(code, Some(0), "{stderr}");
    // the scenario on stdout, the messages on stderr (issue 53)
    assert_eq!(first, "#![enable(implicit_some)]");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!stderr.contains("Broken pipe"), "{stderr}");
}

#[test]
fn every_command_into_closed_pipes_keeps_its_exit_code() {
    let tmp = temp_dir("pipe_commands");
    let scenario = write(tmp.path(), "tiny.ron", TINY_2D);
    for (args, expected) in [
        (vec!["validate", scenario.as_str()], 0),
        (vec!["validate", "missing.ron"], 2),
        (vec!["--help"], 0),
        (vec!["--version"], 0),
        (vec!["run", scenario.as_str(), "--out", "piped"], 0),
        (
            vec!["bench", "--n", "200", "--steps", "2", "--warmup", "1"],
            0,
        ),
    ] {
        assert_eq!(
            into_closed_pipes(tmp.path(), &args),
            Some(expected),
            "flocking {args:?}"
        );
    }
    // the run wrote its outputs whole, as without the pipes
    let output = flocking(tmp.path(), &["run", &scenario, "--out", "plain", "--quiet"]);
    assert_eq!(output.status.code(), Some(0));
    let (piped, plain) = (
        files(&tmp.path().join("piped")),
        files(&tmp.path().join("plain")),
    );
    assert_eq!(
        piped.keys().collect::<Vec<_>>(),
        plain.keys().collect::<Vec<_>>()
    );
    assert_eq!(piped["metrics.csv"], plain["metrics.csv"]);
}

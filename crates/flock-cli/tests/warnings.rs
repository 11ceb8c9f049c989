//! The warnings before a run on the command line (issue 53): `flocking validate` and
//! `flocking run` print each of the scenario's warnings once, on stderr, naming the field and the
//! fix; a scenario without any prints none.

use std::fs;

use crate::common::{fixtures_dir, flocking, stderr, temp_dir, write};

/// TAC 2006 Fig. 11 (its γ-agent at 1.12 m/s, initial speeds up to 2.8 m/s) put on TurtleBot3
/// unicycles of 0.22 m/s, cut to `duration`.
fn fig11_on_unicycles(duration: &str) -> String {
    let text = fs::read_to_string(fixtures_dir().join("tac2006_fig11_alg2_n100.ron"))
        .expect("the fixture");
    let text = text
        .replacen(
            "    initial: (",
            "    vehicle: Unicycle(()),\n    initial: (",
            1,
        )
        .replacen("duration: 100.0", &format!("duration: {duration}"), 1);
    assert!(
        text.contains("Unicycle") && text.contains(duration),
        "{text}"
    );
    text
}

#[test]
fn validate_and_run_print_the_warnings_on_stderr_once_each() {
    let tmp = temp_dir("before_the_run");
    let file = write(tmp.path(), "unicycles.ron", &fig11_on_unicycles("0.1"));
    let validate = flocking(tmp.path(), &["validate", &file]);
    let run = flocking(tmp.path(), &["run", &file, "--out", "o", "--quiet"]);
    for (command, output) in [("validate", &validate), ("run", &run)] {
        let err = stderr(output);
        assert_eq!(output.status.code(), Some(0), "{command}: {err}");
        for (field, fix) in [
            ("algorithm.gamma.velocity", "slower than 0.22"),
            ("initial.velocities", "Headings(speed: 0.22)"),
        ] {
            let lines: Vec<&str> = err
                .lines()
                .filter(|l| l.starts_with(&format!("warning: `{field}`")))
                .collect();
            assert_eq!(lines.len(), 1, "{command}, {field}: {err}");
            assert!(lines[0].contains(fix), "{command}: {}", lines[0]);
        }
        let out = String::from_utf8_lossy(&output.stdout);
        assert!(
            !out.contains("warning: "),
            "{command}: warnings on stdout: {out}"
        );
    }

    // the fixture on point masses warns of nothing
    let fixture = fixtures_dir().join("tac2006_fig11_alg2_n100.ron");
    let output = flocking(tmp.path(), &["validate", fixture.to_str().expect("UTF-8")]);
    assert_eq!(output.status.code(), Some(0));
    assert!(
        !stderr(&output).contains("warning: "),
        "{}",
        stderr(&output)
    );
}

//! The corpus of hostile inputs in `tests/hostile/` (its `manifest.tsv`: the command, the exit code
//! and a substring of the message): each is refused with its code and message, without a panic
//! or a signal, and leaves nothing behind.

use crate::common::{TempDir, flocking, stderr};

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
        let tmp = TempDir::new("hostile");
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

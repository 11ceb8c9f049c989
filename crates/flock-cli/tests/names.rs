//! The distribution is `flocking` (the binary, the Python module, the umbrella crate): `flock` is
//! util-linux's lock command, and taken on PyPI and crates.io. No file of the repository may still
//! run the old command, import the old module or use the old crate.

use std::fs;
use std::path::{Path, PathBuf};

/// The files of the workspace worth reading: text, outside build outputs and dependencies.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let entries = fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("a directory entry").path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        if path.is_dir() {
            if !matches!(
                name,
                "target" | ".git" | "node_modules" | "corpus" | "artifacts"
            ) && !name.starts_with('.')
            {
                files(&path, out);
            }
        } else if !matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("png" | "gif" | "ttf" | "npy" | "bin" | "svg" | "csv" | "lock")
        ) {
            out.push(path);
        }
    }
}

/// Whether `c` can continue a name (so `flock` followed by it is another word).
fn name_char(c: Option<char>) -> bool {
    c.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '-')
}

/// The old names in `text`, as (line, what).
fn old_names(text: &str) -> Vec<(usize, String)> {
    const SUBCOMMANDS: [&str; 7] = ["run", "validate", "sweep", "figures", "plot", "bench", "--"];
    let mut found = Vec::new();
    for (k, line) in text.lines().enumerate() {
        for (at, _) in line.match_indices("flock") {
            let before = line[..at].chars().next_back();
            let rest = &line[at + "flock".len()..];
            let after = rest.chars().next();
            let binary_path = line[..at].ends_with("release/") || line[..at].ends_with("debug/");
            if name_char(before)
                || name_char(after)
                || before == Some('.')
                || (before == Some('/') && !binary_path)
            {
                continue;
            }
            let article = line[..at].split_whitespace().next_back().is_some_and(|w| {
                matches!(
                    w.to_ascii_lowercase().as_str(),
                    "a" | "the" | "one" | "whole" | "each"
                )
            });
            let head = line[..at].trim_end();
            let what = if rest.starts_with("::") {
                Some("the crate path `flock::`")
            } else if head.ends_with("import") || head.ends_with("from") {
                Some("the Python module `flock`")
            } else if rest.starts_with('.')
                && rest[1..].starts_with(|c: char| c.is_ascii_alphabetic())
                && !rest.starts_with(".workspace")
            {
                Some("the Python module `flock.`")
            } else if binary_path {
                Some("the binary target/…/flock")
            } else if rest.starts_with(' ')
                && !article
                && SUBCOMMANDS.iter().any(|s| {
                    rest[1..]
                        .strip_prefix(s)
                        .is_some_and(|tail| *s == "--" || !name_char(tail.chars().next()))
                })
            {
                Some("the command `flock`")
            } else if line[..at].ends_with("CARGO_BIN_EXE_") {
                Some("the binary flock")
            } else {
                None
            };
            if let Some(what) = what {
                found.push((k + 1, what.to_owned()));
            }
        }
    }
    found
}

#[test]
fn no_file_runs_imports_or_uses_the_old_name() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut paths = Vec::new();
    files(&root, &mut paths);
    assert!(
        paths.len() > 100,
        "the workspace has its files: {}",
        paths.len()
    );
    let mut offences = Vec::new();
    for path in &paths {
        let Ok(text) = fs::read_to_string(path) else {
            continue;
        };
        if path.ends_with("crates/flock-cli/tests/names.rs") {
            continue; // the old names, as examples of what is refused
        }
        for (line, what) in old_names(&text) {
            offences.push(format!("{}:{line}: {what}", path.display()));
        }
    }
    assert!(offences.is_empty(), "old names:\n{}", offences.join("\n"));
}

#[test]
fn the_old_names_are_recognised() {
    for (text, expected) in [
        ("flock run s.ron --out o", "the command `flock`"),
        ("$ flock sweep plot out/alg2", "the command `flock`"),
        ("import flock\n", "the Python module `flock`"),
        ("from flock import run", "the Python module `flock`"),
        ("r = flock.run(s)", "the Python module `flock.`"),
        ("use flock::Scenario;", "the crate path `flock::`"),
        (
            "target/release/flock --version",
            "the binary target/…/flock",
        ),
    ] {
        let found = old_names(text);
        assert_eq!(found.len(), 1, "{text}: {found:?}");
        assert_eq!(found[0].1, expected, "{text}");
    }
    for fine in [
        "flocking run s.ron",
        "import flocking",
        "flocking.run(s)",
        "use flock_math::Vector;",
        "cargo run -p flock-cli",
        "the flock runs past the ball",
        "a flock splits",
        "self.flock.alpha",
        "target/release/flocking",
        "flock.workspace = true",
    ] {
        assert_eq!(old_names(fine), [], "{fine}");
    }
}

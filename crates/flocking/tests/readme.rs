//! The README's "Use it as a library" example is `examples/fig11_connectivity.rs`, word for
//! word (CI compiles the examples; the crate's documentation example runs the same calls on
//! Fig. 11 and checks that it ends connected).

use std::path::Path;

/// The workspace's root directory.
fn workspace() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The Rust code block of the README's section `heading`.
fn readme_block(heading: &str) -> String {
    let readme = std::fs::read_to_string(workspace().join("README.md")).expect("the README");
    let section = &readme[readme.find(heading).expect("the section")..];
    let start = section.find("```rust\n").expect("a Rust block") + "```rust\n".len();
    let end = start + section[start..].find("```").expect("the end of the block");
    section[start..end].to_owned()
}

#[test]
fn the_readme_library_example_is_the_example_program() {
    let program = include_str!("../examples/fig11_connectivity.rs");
    let code: String = program
        .lines()
        .skip_while(|line| line.starts_with("//!") || line.is_empty())
        .map(|line| format!("{line}\n"))
        .collect();
    assert_eq!(readme_block("## Use it as a library"), code);
    assert!(code.lines().count() <= 10, "{code}");
}

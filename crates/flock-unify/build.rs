//! Empty: a build script makes Cargo resolve this crate's build-dependencies (syn, for the
//! features of the proc-macros' syn).

fn main() {}

//! Nothing to call: this crate only asks for the features the `flocking` binary and the Python
//! wheel would otherwise enable apart on the dependencies they share, so that both builds reuse
//! one compilation of them. Its `Cargo.toml` says which features and why.

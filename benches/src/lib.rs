//! Criterion benchmarks of flocking's hot kernels, in `benches/kernels.rs`: neighbour search, the
//! forces of Algorithm 2, a symplectic Euler step and the flocking metrics, on the synthetic
//! α-lattices of `flocking bench` (`flock_cli::bench::scenario`).
//!
//! Run them with `cargo bench -p flock-benches`; `cargo test --benches` runs each once.

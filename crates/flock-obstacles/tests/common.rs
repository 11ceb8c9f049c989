//! Deterministic sample points and velocities, and vector comparison.

use flock_math::Vector;

/// `n^DIM` points on a regular grid of half-width `half_width` around `centre`, shifted off the
/// grid's symmetry (so that no point falls exactly on a centre or boundary).
pub fn grid<V: Vector>(centre: V, half_width: f64, n: usize) -> impl Iterator<Item = V> {
    let step = 2.0 * half_width / n as f64;
    (0..n.pow(V::DIM as u32)).map(move |index| {
        V::from_fn(|axis| {
            let i = (index / n.pow(axis as u32)) % n;
            centre.coord(axis) - half_width + (i as f64 + 0.5) * step + 0.013 * (axis + 1) as f64
        })
    })
}

/// A velocity in `[−2, 2)^DIM` that looks random, from the golden-ratio sequence.
pub fn velocity<V: Vector>(index: usize) -> V {
    V::from_fn(|axis| {
        let x = ((index * 37 + axis * 101 + 1) as f64 * 0.618_033_988_749_895).fract();
        4.0 * x - 2.0
    })
}

/// The unit vector along the first axis.
pub fn first_axis<V: Vector>() -> V {
    V::from_fn(|axis| if axis == 0 { 1.0 } else { 0.0 })
}

/// Asserts `‖actual − expected‖ ≤ tolerance`.
#[track_caller]
pub fn assert_close<V: Vector>(actual: V, expected: V, tolerance: f64) {
    let error = (actual - expected).length();
    assert!(
        error <= tolerance,
        "{actual:?} != {expected:?} (error {error:e} > {tolerance:e})"
    );
}

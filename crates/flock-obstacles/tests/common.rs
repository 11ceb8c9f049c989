//! Deterministic sample points and velocities, and vector comparison.

use flock_math::Vector;
use flock_obstacles::ObstacleSpec;

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

/// A small deterministic generator (SplitMix64), so that the tests need no `rand`.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// Uniform in `[0, 1)`.
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[low, high)`.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next_f64()
    }

    /// Uniform in the cube of half-width `half_width` about `centre`.
    pub fn point<V: Vector>(&mut self, centre: V, half_width: f64) -> V {
        centre + V::from_fn(|_| self.uniform(-half_width, half_width))
    }

    /// A uniformly random unit vector.
    pub fn direction<V: Vector>(&mut self) -> V {
        loop {
            let v = V::from_fn(|_| self.uniform(-1.0, 1.0));
            let length = v.length();
            if length > 0.1 && length <= 1.0 {
                return v / length;
            }
        }
    }
}

/// The coordinates of `v` as a scenario writes them.
pub fn coords<V: Vector>(v: V) -> Vec<f64> {
    (0..V::DIM).map(|k| v.coord(k)).collect()
}

/// `V` from the first `V::DIM` of `values`.
pub fn vector<V: Vector>(values: [f64; 3]) -> V {
    V::from_fn(|k| values[k])
}

/// The rotation of a cuboid spec as `V::DIM` unit vectors: the world directions of the box's axes,
/// computed independently of parry (a 2D rotation matrix; Rodrigues' formula in 3D).
pub fn box_axes<V: Vector>(rotation: &[f64]) -> Vec<V> {
    if V::DIM == 2 {
        let angle = rotation.first().copied().unwrap_or(0.0);
        let (sin, cos) = angle.sin_cos();
        vec![vector([cos, sin, 0.0]), vector([-sin, cos, 0.0])]
    } else {
        let r = if rotation.is_empty() {
            [0.0; 3]
        } else {
            [rotation[0], rotation[1], rotation[2]]
        };
        let angle = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let k = if angle > 0.0 {
            r.map(|x| x / angle)
        } else {
            [0.0, 0.0, 1.0]
        };
        let (sin, cos) = angle.sin_cos();
        (0..3)
            .map(|axis| {
                let e = [0, 1, 2].map(|j| if j == axis { 1.0 } else { 0.0 });
                let k_cross_e = [
                    k[1] * e[2] - k[2] * e[1],
                    k[2] * e[0] - k[0] * e[2],
                    k[0] * e[1] - k[1] * e[0],
                ];
                let k_dot_e = k[axis];
                vector(
                    [0, 1, 2]
                        .map(|j| e[j] * cos + k_cross_e[j] * sin + k[j] * k_dot_e * (1.0 - cos)),
                )
            })
            .collect()
    }
}

/// Points in convex position: on an ellipse (2D, `n` points) or an ellipsoid (3D, a Fibonacci
/// lattice of `n` points), scaled by `size` and shifted to `centre`.
pub fn convex_points<V: Vector>(centre: V, size: f64, n: usize) -> Vec<V> {
    (0..n)
        .map(|i| {
            let i = i as f64;
            if V::DIM == 2 {
                let t = 2.0 * core::f64::consts::PI * (i + 0.3) / n as f64;
                centre + vector::<V>([1.3 * t.cos(), 0.8 * t.sin(), 0.0]) * size
            } else {
                let z = 1.0 - 2.0 * (i + 0.5) / n as f64;
                let r = (1.0 - z * z).sqrt();
                let t = i * 2.399_963_229_728_653;
                centre + vector::<V>([1.3 * r * t.cos(), 0.8 * r * t.sin(), z]) * size
            }
        })
        .collect()
}

/// One obstacle of each kind the dimension supports, near the origin, size about 1–3.
pub fn catalogue<V: Vector>() -> Vec<(&'static str, ObstacleSpec)> {
    let c = |x: [f64; 3]| coords(vector::<V>(x));
    let rotation = if V::DIM == 2 {
        vec![0.6]
    } else {
        vec![0.3, -0.5, 0.7]
    };
    vec![
        (
            "ball",
            ObstacleSpec::Ball {
                centre: c([1.0, -0.5, 0.25]),
                radius: 1.5,
            },
        ),
        (
            "wall",
            ObstacleSpec::Wall {
                point: c([0.5, 0.0, -0.5]),
                normal: c([1.0, 2.0, -2.0]),
            },
        ),
        (
            "cuboid",
            ObstacleSpec::Cuboid {
                centre: c([0.5, 0.25, -0.5]),
                half_extents: c([1.5, 0.75, 1.0]),
                rotation,
            },
        ),
        (
            "convex hull",
            ObstacleSpec::ConvexHull {
                points: convex_points::<V>(vector([0.2, -0.3, 0.1]), 1.5, 9)
                    .into_iter()
                    .map(coords)
                    .collect(),
            },
        ),
        (
            "capsule",
            ObstacleSpec::Capsule {
                a: c([-1.0, -0.5, 0.5]),
                b: c([1.5, 0.5, -0.5]),
                radius: 0.6,
            },
        ),
        (
            "segment",
            ObstacleSpec::Segment {
                a: c([-1.0, 0.5, -0.5]),
                b: c([1.0, -1.0, 1.0]),
            },
        ),
        (
            "triangle",
            ObstacleSpec::Triangle {
                a: c([-1.0, -1.0, 0.5]),
                b: c([1.5, -0.5, -0.5]),
                c: c([0.0, 1.5, 0.25]),
            },
        ),
    ]
}

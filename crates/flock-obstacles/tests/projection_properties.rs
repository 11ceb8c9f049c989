//! Property tests of the β-agent's projection, for random obstacles of every kind in 2D and 3D,
//! against points of the obstacle sampled independently of parry (from the spec's own
//! parametrisation: centre and radius, box axes by Rodrigues' formula, convex combinations).
//!
//! For an α-agent at q outside the obstacle K:
//! - q̂ is on the boundary: |signed_distance(q̂)| ≤ η;
//! - q̂ is the closest point: `distance` = ‖q − q̂‖ = signed_distance(q), no sample x ∈ K is nearer
//!   than ‖q − q̂‖ − η, and the projection's variational inequality (q − q̂) · (x − q̂) ≤ 0 holds
//!   for every sample within η (‖q − q̂‖ + ‖x − q̂‖) (what a q̂ off the true projection by η allows);
//! - the normal is the unit vector from q̂ to q, within 2η / ‖q − q̂‖ (its angle when q̂ is off by η).
//!
//! For a point inside a solid obstacle (sampled strictly inside): `inside` is reported,
//! signed_distance(q) = −‖q − q̂‖ < 0, q̂ is on the boundary, and no sampled boundary point is
//! nearer than q̂ (where the boundary has a parametrisation: balls, walls, boxes, capsules). The
//! vertices of segments and 3D triangles, which are the obstacle, are inside.
//!
//! η = 1e-9 (1 + L), L the largest coordinate magnitude involved: obstacles lie within 5 + 4 of the
//! origin and queries within 15, and the closed forms and parry's projections round to a few ulp
//! of L; the 1e-9 relative bound is the obstacles' own plane tolerance (hull faces, flat tests),
//! and leaves room for the relative stopping test of parry's GJK on convex hulls.

use flock_math::Vector;
use flock_obstacles::{Obstacle, ObstacleSpec, Space};
use glam::{DVec2, DVec3};
use proptest::prelude::*;

use crate::common::{Rng, box_axes, coords, vector};

/// The relative tolerance η / (1 + L) of the module's notes.
const RELATIVE: f64 = 1e-9;

/// The kinds of obstacle, as in [`ObstacleSpec`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Ball,
    Wall,
    Cuboid,
    ConvexHull,
    Capsule,
    Segment,
    Triangle,
}

/// The random numbers an obstacle is made from; each kind uses the ones it needs.
#[derive(Clone, Debug)]
struct Raw {
    /// Points a, b, c (and a centre) in [−5, 5]³.
    points: [[f64; 3]; 3],
    /// Half extents in [0.2, 4].
    extents: [f64; 3],
    /// A radius in [0.2, 4].
    radius: f64,
    /// A 2D angle (the first entry) or a 3D axis-angle vector, in [−π, π]³.
    rotation: [f64; 3],
    /// Directions of the hull's points on an ellipsoid (raw, in [−1, 1]³), 4 to 12 of them.
    hull: Vec<[f64; 3]>,
    /// Seeds the sampling of the obstacle.
    seed: u64,
    /// Query points in [−15, 15]³.
    queries: Vec<[f64; 3]>,
}

fn raw() -> impl Strategy<Value = Raw> {
    let point = |half: f64| prop::array::uniform3(-half..half);
    (
        prop::array::uniform3(point(5.0)),
        prop::array::uniform3(0.2..4.0f64),
        0.2..4.0f64,
        point(core::f64::consts::PI),
        prop::collection::vec(point(1.0), 4..=12),
        any::<u64>(),
        prop::collection::vec(point(15.0), 24),
    )
        .prop_map(
            |(points, extents, radius, rotation, hull, seed, queries)| Raw {
                points,
                extents,
                radius,
                rotation,
                hull,
                seed,
                queries,
            },
        )
}

/// An obstacle with points sampled from its own description.
struct Sampled<V> {
    spec: ObstacleSpec,
    /// Points of the obstacle: boundary, interior and extreme points.
    members: Vec<V>,
    /// Points strictly inside (empty for zero-thickness obstacles).
    interior: Vec<V>,
    /// Points of the boundary, where it has a parametrisation (else empty).
    boundary: Vec<V>,
    /// Points that are the obstacle itself and so are inside (vertices of thin obstacles).
    on: Vec<V>,
}

/// `x` with its component along the unit vector `u` removed, normalised (or `None` when tiny).
fn orthogonal<V: Vector>(x: V, u: V) -> Option<V> {
    let y = x - u * u.dot(x);
    (y.length() > 0.1).then(|| y.normalize_or_zero())
}

/// Random convex weights bounded away from 0 (so that the combination is well inside).
fn weights(rng: &mut Rng, n: usize, low: f64) -> Vec<f64> {
    let w: Vec<f64> = (0..n).map(|_| rng.uniform(low, 1.0)).collect();
    let total: f64 = w.iter().sum();
    w.into_iter().map(|x| x / total).collect()
}

fn combination<V: Vector>(points: &[V], w: &[f64]) -> V {
    points
        .iter()
        .zip(w)
        .fold(V::ZERO, |acc, (&x, &wi)| acc + x * wi)
}

/// The obstacle of `kind` made from `raw`, with its samples; `None` when `raw` makes a degenerate
/// one (a flat triangle or hull), which proptest then skips.
fn sample<V: Space>(kind: Kind, raw: &Raw) -> Option<Sampled<V>> {
    let mut rng = Rng::new(raw.seed);
    let [a, b, c] = raw.points.map(vector::<V>);
    let (mut members, mut interior, mut boundary, mut on) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let spec = match kind {
        Kind::Ball => {
            for _ in 0..400 {
                let (dir, s) = (rng.direction::<V>(), rng.uniform(0.0, 0.95));
                boundary.push(a + dir * raw.radius);
                interior.push(a + dir * (raw.radius * s));
            }
            ObstacleSpec::Ball {
                centre: coords(a),
                radius: raw.radius,
            }
        }
        Kind::Wall => {
            let normal = (b - a).normalize_or_zero();
            if normal == V::ZERO {
                return None;
            }
            for _ in 0..400 {
                let Some(tangent) = orthogonal(rng.direction::<V>(), normal) else {
                    continue;
                };
                let along = a + tangent * rng.uniform(0.0, 20.0);
                boundary.push(along);
                interior.push(along - normal * rng.uniform(0.05, 5.0));
            }
            ObstacleSpec::Wall {
                point: coords(a),
                normal: coords(b - a),
            }
        }
        Kind::Cuboid => {
            let rotation = if V::DIM == 2 {
                vec![raw.rotation[0]]
            } else {
                raw.rotation.to_vec()
            };
            let axes = box_axes::<V>(&rotation);
            let half = vector::<V>(raw.extents);
            let corner =
                |s: &[f64]| (0..V::DIM).fold(a, |acc, k| acc + axes[k] * (s[k] * half.coord(k)));
            for _ in 0..400 {
                let mut s = [0.0; 3].map(|_: f64| rng.uniform(-1.0, 1.0));
                interior.push(corner(&s.map(|x| 0.95 * x)));
                let face = (rng.next_f64() * V::DIM as f64) as usize;
                s[face] = if rng.next_f64() < 0.5 { -1.0 } else { 1.0 };
                boundary.push(corner(&s));
            }
            for index in 0..1 << V::DIM {
                let s = [0, 1, 2].map(|k| if index >> k & 1 == 1 { 1.0 } else { -1.0 });
                members.push(corner(&s));
            }
            ObstacleSpec::Cuboid {
                centre: coords(a),
                half_extents: coords(half),
                rotation,
            }
        }
        Kind::ConvexHull => {
            // On an ellipsoid: every point is a vertex of the hull.
            let points: Vec<V> = raw
                .hull
                .iter()
                .filter_map(|x| {
                    let dir = vector::<V>(*x).normalize_or_zero();
                    (dir != V::ZERO).then(|| a + V::from_fn(|k| dir.coord(k) * raw.extents[k]))
                })
                .collect();
            if points.len() <= V::DIM {
                return None;
            }
            members.extend(&points);
            for _ in 0..400 {
                let w = weights(&mut rng, points.len(), 0.0);
                members.push(combination(&points, &w));
                let (i, j) = (
                    (rng.next_f64() * points.len() as f64) as usize,
                    (rng.next_f64() * points.len() as f64) as usize,
                );
                let t = rng.next_f64();
                members.push(points[i] + (points[j] - points[i]) * t);
                let w = weights(&mut rng, points.len(), 0.5);
                interior.push(combination(&points, &w));
            }
            ObstacleSpec::ConvexHull {
                points: points.into_iter().map(coords).collect(),
            }
        }
        Kind::Capsule => {
            let axis = (b - a).normalize_or_zero();
            for _ in 0..400 {
                let t = rng.next_f64();
                let dir = rng.direction::<V>();
                interior.push(a + (b - a) * t + dir * (raw.radius * rng.uniform(0.0, 0.95)));
                // The side (directions across the axis) and the two caps (outward half-spheres).
                if let Some(across) = orthogonal(dir, axis) {
                    boundary.push(a + (b - a) * t + across * raw.radius);
                }
                let end = if dir.dot(axis) <= 0.0 { a } else { b };
                boundary.push(end + dir * raw.radius);
            }
            ObstacleSpec::Capsule {
                a: coords(a),
                b: coords(b),
                radius: raw.radius,
            }
        }
        Kind::Segment => {
            if (b - a).length() < 0.1 {
                return None;
            }
            members.extend((0..=200).map(|i| a + (b - a) * (f64::from(i) / 200.0)));
            on.extend([a, b]);
            ObstacleSpec::Segment {
                a: coords(a),
                b: coords(b),
            }
        }
        Kind::Triangle => {
            let vertices = [a, b, c];
            members.extend(vertices);
            for _ in 0..400 {
                let w = weights(&mut rng, 3, 0.0);
                members.push(combination(&vertices, &w));
                let (i, t) = ((rng.next_f64() * 3.0) as usize, rng.next_f64());
                members.push(vertices[i] + (vertices[(i + 1) % 3] - vertices[i]) * t);
                if V::DIM == 2 {
                    let w = weights(&mut rng, 3, 0.5);
                    interior.push(combination(&vertices, &w));
                }
            }
            if V::DIM == 3 {
                on.extend(vertices);
            }
            ObstacleSpec::Triangle {
                a: coords(a),
                b: coords(b),
                c: coords(c),
            }
        }
    };
    members.extend(&interior);
    members.extend(&boundary);
    Some(Sampled {
        spec,
        members,
        interior,
        boundary,
        on,
    })
}

/// η for points up to `scale` from the origin.
fn eta(scale: f64) -> f64 {
    RELATIVE * (1.0 + scale)
}

fn check<V: Space>(kind: Kind, raw: &Raw) -> Result<(), TestCaseError> {
    let Some(sampled) = sample::<V>(kind, raw) else {
        return Err(TestCaseError::reject("degenerate"));
    };
    // Flat triangles and hulls are refused: not a case of this property.
    let Ok(obstacle) = V::obstacle(&sampled.spec) else {
        return Err(TestCaseError::reject("refused"));
    };
    let largest = |points: &[V]| points.iter().map(|x| x.length()).fold(0.0, f64::max);
    let scale = largest(&sampled.members)
        .max(largest(&sampled.boundary))
        .max(15.0 * 3f64.sqrt());
    let eta = eta(scale);
    let p = V::from_fn(|k| [0.3, -1.1, 0.7][k]);

    for q in raw.queries.iter().map(|&x| vector::<V>(x)) {
        let beta = obstacle.beta_agent(q, p);
        let to_q = q - beta.position;
        let distance = to_q.length();
        prop_assert!(
            (beta.distance - distance).abs() <= eta,
            "distance {} != ‖q − q̂‖ = {distance}",
            beta.distance
        );
        let on_boundary = obstacle.signed_distance(beta.position);
        prop_assert!(
            on_boundary.abs() <= eta,
            "q̂ = {:?} off the boundary by {on_boundary:e}",
            beta.position
        );
        prop_assert!(
            (beta.normal.length() - 1.0).abs() <= 1e-12,
            "normal {:?}",
            beta.normal
        );
        if beta.inside {
            prop_assert!(obstacle.signed_distance(q) <= 0.0);
            continue;
        }
        prop_assert!((obstacle.signed_distance(q) - distance).abs() <= eta);
        for &x in &sampled.members {
            let (to_x, gap) = (x - beta.position, (q - x).length());
            prop_assert!(
                gap >= distance - eta,
                "q = {q:?}: member {x:?} at {gap} nearer than q̂ = {:?} at {distance}",
                beta.position
            );
            let slack = eta * (distance + to_x.length());
            prop_assert!(
                to_q.dot(to_x) <= slack,
                "q = {q:?}: (q − q̂)·(x − q̂) = {:e} > {slack:e} for x = {x:?}",
                to_q.dot(to_x)
            );
        }
        if distance > 1e3 * eta {
            let error = (beta.normal - to_q / distance).length();
            prop_assert!(
                error <= 2.0 * eta / distance + 1e-12,
                "normal {:?} off q − q̂ by {error:e}",
                beta.normal
            );
        }
    }

    for &q in &sampled.interior {
        let beta = obstacle.beta_agent(q, p);
        prop_assert!(beta.inside, "q = {q:?} inside is not reported");
        let depth = (q - beta.position).length();
        prop_assert!((obstacle.signed_distance(q) + depth).abs() <= eta);
        prop_assert!(obstacle.signed_distance(beta.position).abs() <= eta);
        for &y in &sampled.boundary {
            prop_assert!(
                (q - y).length() >= depth - eta,
                "inside q = {q:?}: boundary point {y:?} nearer than q̂ = {:?}",
                beta.position
            );
        }
    }
    for &q in &sampled.on {
        let beta = obstacle.beta_agent(q, p);
        prop_assert!(
            beta.inside && beta.distance <= eta,
            "q = {q:?} on the obstacle: {beta:?}"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn ball_2d(raw in raw()) { check::<DVec2>(Kind::Ball, &raw)?; }
    #[test]
    fn ball_3d(raw in raw()) { check::<DVec3>(Kind::Ball, &raw)?; }
    #[test]
    fn wall_2d(raw in raw()) { check::<DVec2>(Kind::Wall, &raw)?; }
    #[test]
    fn wall_3d(raw in raw()) { check::<DVec3>(Kind::Wall, &raw)?; }
    #[test]
    fn cuboid_2d(raw in raw()) { check::<DVec2>(Kind::Cuboid, &raw)?; }
    #[test]
    fn cuboid_3d(raw in raw()) { check::<DVec3>(Kind::Cuboid, &raw)?; }
    #[test]
    fn convex_hull_2d(raw in raw()) { check::<DVec2>(Kind::ConvexHull, &raw)?; }
    #[test]
    fn convex_hull_3d(raw in raw()) { check::<DVec3>(Kind::ConvexHull, &raw)?; }
    #[test]
    fn capsule_2d(raw in raw()) { check::<DVec2>(Kind::Capsule, &raw)?; }
    #[test]
    fn capsule_3d(raw in raw()) { check::<DVec3>(Kind::Capsule, &raw)?; }
    #[test]
    fn segment_2d(raw in raw()) { check::<DVec2>(Kind::Segment, &raw)?; }
    #[test]
    fn segment_3d(raw in raw()) { check::<DVec3>(Kind::Segment, &raw)?; }
    #[test]
    fn triangle_2d(raw in raw()) { check::<DVec2>(Kind::Triangle, &raw)?; }
    #[test]
    fn triangle_3d(raw in raw()) { check::<DVec3>(Kind::Triangle, &raw)?; }
}

/// Regression: parry's `ConvexPolygon::from_convex_hull` dropped a vertex whose edges turn by less
/// than about 1.7e-4 rad, so the polygon was smaller than the hull: the vertex (5, −1e-4) was
/// outside its own obstacle, and the β-agent of (5, −1) was 1e-4 too far.
#[test]
fn nearly_collinear_hull_vertex_is_kept_2d() {
    let points = [
        [0.0, 0.0],
        [5.0, -1e-4],
        [10.0, 0.0],
        [10.0, 10.0],
        [0.0, 10.0],
    ];
    let hull = DVec2::obstacle(&ObstacleSpec::ConvexHull {
        points: points.iter().map(|x| x.to_vec()).collect(),
    })
    .unwrap();
    let vertex = hull.beta_agent(DVec2::new(5.0, -1e-4), DVec2::ZERO);
    assert!(vertex.inside && vertex.distance < 1e-15, "{vertex:?}");
    let below = hull.beta_agent(DVec2::new(5.0, -1.0), DVec2::ZERO);
    assert!(
        (below.position - DVec2::new(5.0, -1e-4)).length() < 1e-15,
        "{below:?}"
    );
    assert!((below.distance - 0.9999).abs() < 1e-15);
}

/// Regression: parry's `ConvexPolyhedron` merges adjacent triangles whose normals differ by less
/// than about 1.7e-4 rad into one face with the normal of one of them; the face planes were read
/// from it, so inside this thin tetrahedron q̂ (the foot on the nearest face plane) was 1e-5 off
/// the boundary and the depth wrong. The planes are now the hull's triangles'.
#[test]
fn nearly_coplanar_hull_faces_keep_their_planes_3d() {
    let extents = DVec3::new(
        1.426_114_046_118_602_8,
        1.164_850_896_026_705_4,
        2.983_576_808_214_324,
    );
    let directions = [
        [
            -0.799_766_249_316_006_5,
            0.595_753_599_944_686_1,
            0.073_247_879_808_086_09,
        ],
        [
            -0.125_135_899_074_627_2,
            0.133_351_696_323_964_07,
            0.742_374_203_392_044_6,
        ],
        [
            -0.907_675_553_082_432,
            0.833_473_308_827_062_9,
            -0.035_921_663_596_910_96,
        ],
        [
            0.307_581_668_709_141_1,
            0.363_448_602_838_273_96,
            0.240_358_576_089_500_3,
        ],
    ];
    let points: Vec<DVec3> = directions
        .iter()
        .map(|&x| DVec3::from_array(x).normalize() * extents)
        .collect();
    let hull = DVec3::obstacle(&ObstacleSpec::ConvexHull {
        points: points.iter().map(|&x| coords(x)).collect(),
    })
    .unwrap();
    // Inside, well within the plate: q̂ is on the boundary, and no vertex is nearer than the depth.
    let q = (points[0] + points[1] + points[2] + points[3]) * 0.25;
    let beta = hull.beta_agent(q, DVec3::ZERO);
    assert!(beta.inside);
    assert!(
        hull.signed_distance(beta.position).abs() < 1e-12,
        "{beta:?}"
    );
    // Outside: q̂ is on the boundary too.
    let beta = hull.beta_agent(DVec3::ZERO, DVec3::ZERO);
    assert!(!beta.inside);
    assert!(
        hull.signed_distance(beta.position).abs() < 1e-12,
        "{beta:?}"
    );
}

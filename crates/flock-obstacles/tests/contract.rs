//! The β-agent contract for every shape of the catalogue, in 2D and 3D: unit outward normals,
//! velocities tangent to the boundary and equal to the time derivative of `q̂`, and each feature
//! (face, edge, vertex, curved) met.

use std::collections::BTreeMap;

use approx::assert_abs_diff_eq;
use flock_obstacles::{BetaAgent, Obstacle, Space};
use glam::{DVec2, DVec3};

use crate::common::{Rng, catalogue};

/// The feature a β-agent reports, read from `μ` and the velocity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Feature {
    /// `μ = 1`: a flat face.
    Face,
    /// `μ = 0`, `p̂ ≠ 0`: an edge (3D) — the component along it survives.
    Edge,
    /// `μ = 0`, `p̂ = 0`: a vertex.
    Vertex,
    /// `μ` strictly between 0 and 1 (outside a curved boundary) or above 1 (inside one).
    Curved,
}

fn feature<V: Space>(beta: &BetaAgent<V>) -> Feature {
    if beta.mu == 1.0 {
        Feature::Face
    } else if beta.mu == 0.0 && beta.velocity == V::ZERO {
        Feature::Vertex
    } else if beta.mu == 0.0 {
        Feature::Edge
    } else {
        Feature::Curved
    }
}

/// The features each shape must show on random points around it.
fn expected_features(name: &str, dim: usize) -> Vec<Feature> {
    use Feature::{Curved, Edge, Face, Vertex};
    match (name, dim) {
        ("ball", _) => vec![Curved],
        ("wall", _) => vec![Face],
        ("cuboid" | "convex hull", 2) | ("triangle", 2) => vec![Face, Vertex],
        ("cuboid" | "convex hull" | "triangle", 3) => vec![Face, Edge, Vertex],
        ("capsule", 2) => vec![Face, Curved],
        ("capsule", 3) => vec![Curved],
        ("segment", 2) => vec![Face, Vertex],
        ("segment", 3) => vec![Edge, Vertex],
        _ => unreachable!("{name}"),
    }
}

/// Zero-thickness shapes: both sides are boundary, and the inside is the shape itself.
fn is_thin(name: &str, dim: usize) -> bool {
    name == "segment" || (name == "triangle" && dim == 3)
}

fn check_contract<V: Space>() {
    let mut rng = Rng::new(V::DIM as u64);
    let h = 1e-6;
    for (name, spec) in catalogue::<V>() {
        let obstacle = V::obstacle(&spec).unwrap();
        let mut seen = BTreeMap::new();
        let (mut compared, mut kinks, mut inside) = (0, 0, 0);
        for _ in 0..3000 {
            let q = rng.point(V::ZERO, 3.0);
            let p = rng.point(V::ZERO, 1.0);
            let beta = obstacle.beta_agent(q, p);
            *seen.entry(feature(&beta)).or_insert(0) += 1;
            inside += usize::from(beta.inside);

            // The normal: unit, along q − q̂ outside, pointing out of the obstacle.
            assert_abs_diff_eq!(beta.normal.length(), 1.0, epsilon = 1e-12);
            assert_abs_diff_eq!(beta.distance, (beta.position - q).length(), epsilon = 1e-12);
            if !beta.inside {
                assert_abs_diff_eq!(
                    beta.normal.dot(q - beta.position),
                    beta.distance,
                    epsilon = 1e-10
                );
            }
            let eps = 1e-6;
            assert!(
                obstacle.signed_distance(beta.position + beta.normal * eps) > 0.0,
                "{name}: q̂ + ε a is not outside, q = {q:?}"
            );
            // Inwards along −a is inside for a smooth point of a solid; at an edge or a vertex −a
            // may leave a sharp corner.
            if !is_thin(name, V::DIM) && beta.mu != 0.0 {
                assert!(
                    obstacle.signed_distance(beta.position - beta.normal * eps) < 0.0,
                    "{name}: q̂ − ε a is not inside, q = {q:?}"
                );
            }
            assert_eq!(
                obstacle.signed_distance(q),
                if beta.inside {
                    -beta.distance
                } else {
                    beta.distance
                }
            );

            // The velocity: tangent, and the derivative of q̂ where q̂ is smooth along p.
            assert!(
                beta.velocity.dot(beta.normal).abs() <= 1e-12 * (1.0 + beta.mu),
                "{name}: p̂ · a = {:e} at q = {q:?}",
                beta.velocity.dot(beta.normal)
            );
            let ahead = obstacle.beta_agent(q + p * h, p).position;
            let behind = obstacle.beta_agent(q - p * h, p).position;
            let forward = (ahead - beta.position) / h;
            let backward = (beta.position - behind) / h;
            if (forward - backward).length() > 1e-5 {
                kinks += 1;
                continue;
            }
            let central = (ahead - behind) / (2.0 * h);
            assert!(
                (beta.velocity - central).length() < 1e-5,
                "{name}: velocity {:?} != derivative {central:?} at q = {q:?}, p = {p:?} ({:?}, μ = {})",
                beta.velocity,
                feature(&beta),
                beta.mu
            );
            compared += 1;
        }
        assert!(kinks < 30, "{name}: {kinks} kinks");
        assert!(compared > 2900, "{name}: {compared} compared");
        if !is_thin(name, V::DIM) {
            assert!(inside > 40, "{name}: {inside} inside");
        }
        for expected in expected_features(name, V::DIM) {
            assert!(
                seen.get(&expected).copied().unwrap_or(0) >= 20,
                "{name}: {expected:?} met {seen:?}"
            );
        }
    }
}

#[test]
fn contract_2d() {
    check_contract::<DVec2>();
}

#[test]
fn contract_3d() {
    check_contract::<DVec3>();
}

/// An α-agent inside is reported with the closest boundary point, not projected out silently:
/// inside points of every solid shape have `inside`, a negative signed distance, and `q̂` on the
/// boundary (`q̂ ± ε a` on either side).
fn check_inside_reported<V: Space>() {
    for (name, spec) in catalogue::<V>() {
        if is_thin(name, V::DIM) || name == "wall" {
            continue;
        }
        let obstacle = V::obstacle(&spec).unwrap();
        let (min, max) = obstacle.aabb().unwrap();
        let centre = (min + max) * 0.5;
        let beta = obstacle.beta_agent(centre, V::ZERO);
        assert!(beta.inside, "{name}");
        assert!(beta.distance > 0.1, "{name}: {}", beta.distance);
        assert!(obstacle.signed_distance(centre) < -0.1, "{name}");
    }
}

#[test]
fn inside_reported_2d() {
    check_inside_reported::<DVec2>();
}

#[test]
fn inside_reported_3d() {
    check_inside_reported::<DVec3>();
}

/// The bounding box contains the boundary points found from every direction.
fn check_aabb<V: Space>() {
    let mut rng = Rng::new(11);
    for (name, spec) in catalogue::<V>() {
        let obstacle = V::obstacle(&spec).unwrap();
        let Some((min, max)) = obstacle.aabb() else {
            assert_eq!(name, "wall");
            continue;
        };
        for _ in 0..500 {
            let q = rng.direction::<V>() * 50.0;
            let position = obstacle.beta_agent(q, V::ZERO).position;
            for k in 0..V::DIM {
                assert!(
                    min.coord(k) - 1e-12 <= position.coord(k)
                        && position.coord(k) <= max.coord(k) + 1e-12,
                    "{name}: {position:?} outside {min:?}..{max:?}"
                );
            }
        }
    }
}

#[test]
fn aabb_2d() {
    check_aabb::<DVec2>();
}

#[test]
fn aabb_3d() {
    check_aabb::<DVec3>();
}

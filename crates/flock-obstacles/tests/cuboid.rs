//! β-agents on boxes, rotated or not, against the closed form computed independently of parry: in
//! the box's frame (axes from a rotation matrix / Rodrigues' formula), `q̂` clamps `q` to the box
//! outside and moves it to the nearest face inside; `p̂` keeps the components of `p` along the axes
//! that are not clamped.

use flock_math::Vector;
use flock_obstacles::{Obstacle, ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::common::{Rng, assert_close, box_axes, coords, vector};

/// The expected β-agent of `(q, p)`: position, normal, velocity, distance, inside.
fn closed_form<V: Vector>(
    centre: V,
    half_extents: V,
    axes: &[V],
    q: V,
    p: V,
) -> (V, V, V, f64, bool) {
    let local: Vec<f64> = axes.iter().map(|&e| e.dot(q - centre)).collect();
    let h: Vec<f64> = (0..V::DIM).map(|k| half_extents.coord(k)).collect();
    let world = |l: &[f64]| axes.iter().zip(l).fold(centre, |acc, (&e, &x)| acc + e * x);
    let clamped: Vec<bool> = (0..V::DIM).map(|k| local[k].abs() > h[k]).collect();
    if clamped.iter().any(|&c| c) {
        let position = world(
            &(0..V::DIM)
                .map(|k| local[k].clamp(-h[k], h[k]))
                .collect::<Vec<_>>(),
        );
        let distance = (q - position).length();
        let velocity = (0..V::DIM)
            .filter(|&k| !clamped[k])
            .fold(V::ZERO, |acc, k| acc + axes[k] * axes[k].dot(p));
        return (
            position,
            (q - position) / distance,
            velocity,
            distance,
            false,
        );
    }
    let axis = (0..V::DIM)
        .min_by(|&i, &j| (h[i] - local[i].abs()).total_cmp(&(h[j] - local[j].abs())))
        .unwrap();
    let sign = if local[axis] < 0.0 { -1.0 } else { 1.0 };
    let mut on_face = local.clone();
    on_face[axis] = sign * h[axis];
    let normal = axes[axis] * sign;
    (
        world(&on_face),
        normal,
        p - normal * normal.dot(p),
        h[axis] - local[axis].abs(),
        true,
    )
}

fn check_closed_form<V: Space>() {
    let rotations: Vec<Vec<f64>> = if V::DIM == 2 {
        vec![vec![], vec![0.6], vec![-2.5]]
    } else {
        vec![
            vec![],
            vec![0.3, -0.5, 0.7],
            vec![0.0, 0.0, 1.2],
            vec![2.0, 1.0, -0.5],
        ]
    };
    let mut rng = Rng::new(7);
    for rotation in rotations {
        let centre = vector::<V>([0.5, 0.25, -0.5]);
        let half_extents = vector::<V>([1.5, 0.75, 1.0]);
        let spec = ObstacleSpec::Cuboid {
            centre: coords(centre),
            half_extents: coords(half_extents),
            rotation: rotation.clone(),
        };
        let cuboid = V::obstacle(&spec).unwrap();
        let axes = box_axes::<V>(&rotation);
        let (mut inside, mut corners) = (0, 0);
        for _ in 0..2000 {
            let q = rng.point(centre, 2.5);
            let p = rng.point(V::ZERO, 1.0);
            let beta = cuboid.beta_agent(q, p);
            let (position, normal, velocity, distance, is_inside) =
                closed_form(centre, half_extents, &axes, q, p);
            assert_eq!(beta.inside, is_inside, "q = {q:?}, rotation {rotation:?}");
            assert_close(beta.position, position, 1e-12);
            assert_close(beta.normal, normal, 1e-12);
            assert_close(beta.velocity, velocity, 1e-12);
            assert!((beta.distance - distance).abs() < 1e-12);
            inside += usize::from(is_inside);
            corners += usize::from(velocity == V::ZERO);
        }
        assert!(
            inside > 30 && corners > 50,
            "{inside} inside, {corners} at corners"
        );
    }
}

#[test]
fn closed_form_2d() {
    check_closed_form::<DVec2>();
}

#[test]
fn closed_form_3d() {
    check_closed_form::<DVec3>();
}

/// The box is closed: an α-agent on a face is inside and its own β-agent, with that face's normal.
fn check_agent_on_face<V: Space>() {
    let cuboid = V::obstacle(&ObstacleSpec::Cuboid {
        centre: vec![0.0; V::DIM],
        half_extents: coords(vector::<V>([1.0, 2.0, 3.0])),
        rotation: vec![],
    })
    .unwrap();
    let q = vector::<V>([0.25, -2.0, 0.5]);
    let beta = cuboid.beta_agent(q, V::ZERO);
    assert!(beta.inside);
    assert_eq!(beta.position, q);
    assert_eq!(beta.normal, vector::<V>([0.0, -1.0, 0.0]));
    assert_eq!(beta.distance, 0.0);
}

#[test]
fn agent_on_face_2d() {
    check_agent_on_face::<DVec2>();
}

#[test]
fn agent_on_face_3d() {
    check_agent_on_face::<DVec3>();
}

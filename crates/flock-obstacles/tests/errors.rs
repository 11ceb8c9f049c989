//! Constructors refuse what does not define a convex obstacle, with messages that name the field,
//! its value and the fix.

use core::fmt::Debug;

use flock_math::Vector;
use flock_obstacles::{Obstacle, Obstacle2d, Obstacle3d, ObstacleError};
use glam::{DVec2, DVec3};

/// `(x, y)` or `(x, y, z)` as the messages write it.
fn ron<V: Vector>(v: V) -> String {
    let coordinates: Vec<String> = (0..V::DIM).map(|k| format!("{:?}", v.coord(k))).collect();
    format!("({})", coordinates.join(", "))
}

fn check_radius<V: Vector, O: Obstacle<V> + Debug>() {
    for radius in [0.0, -1.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let error = O::ball(V::ZERO, radius).unwrap_err();
        assert!(
            matches!(error, ObstacleError::InvalidRadius { radius: r } if r.to_bits() == radius.to_bits()),
            "{error:?}"
        );
        assert_eq!(
            error.to_string(),
            format!(
                "ball `radius` is {radius:?}, but it must be a finite number > 0: \
                 give the ball a positive radius"
            )
        );
    }
    assert!(O::ball(V::ZERO, f64::MIN_POSITIVE).is_ok());
}

#[test]
fn radius_2d() {
    check_radius::<DVec2, Obstacle2d>();
}

#[test]
fn radius_3d() {
    check_radius::<DVec3, Obstacle3d>();
}

fn check_centre<V: Vector, O: Obstacle<V> + Debug>() {
    let centre = V::from_fn(|axis| if axis == 1 { f64::NAN } else { 1.0 });
    let error = O::ball(centre, 1.0).unwrap_err();
    assert!(
        matches!(&error, ObstacleError::NonFinitePoint { field: "centre", point } if point.len() == V::DIM),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        format!(
            "obstacle `centre` is {}, but every coordinate must be finite: \
             replace the NaN or infinite coordinate",
            ron(centre)
        )
    );
    assert!(error.to_string().contains("(1.0, NaN"));
}

#[test]
fn centre_2d() {
    check_centre::<DVec2, Obstacle2d>();
}

#[test]
fn centre_3d() {
    check_centre::<DVec3, Obstacle3d>();
}

fn check_normal<V: Vector, O: Obstacle<V> + Debug>() {
    let last = |x: f64| V::from_fn(|axis| if axis + 1 == V::DIM { x } else { 0.0 });
    for normal in [V::ZERO, last(f64::NAN), last(f64::INFINITY), last(1e-300)] {
        let error = O::wall(V::ZERO, normal).unwrap_err();
        assert!(
            matches!(&error, ObstacleError::InvalidNormal { normal: n } if n.len() == V::DIM),
            "{error:?}"
        );
        assert_eq!(
            error.to_string(),
            format!(
                "wall `outward_normal` is {}, but it must be finite and non-zero: give a vector \
                 pointing out of the wall towards the agents, e.g. (0.0, 1.0) for a floor",
                ron(normal)
            )
        );
    }
    assert!(O::wall(V::ZERO, last(1e-100)).is_ok());
}

#[test]
fn normal_2d() {
    check_normal::<DVec2, Obstacle2d>();
}

#[test]
fn normal_3d() {
    check_normal::<DVec3, Obstacle3d>();
}

fn check_point<V: Vector, O: Obstacle<V> + Debug>() {
    let point = V::from_fn(|axis| if axis == 0 { f64::NEG_INFINITY } else { 0.5 });
    let error = O::wall(point, first_normal::<V>()).unwrap_err();
    assert!(
        matches!(&error, ObstacleError::NonFinitePoint { field: "point", .. }),
        "{error:?}"
    );
    assert!(
        error
            .to_string()
            .starts_with(&format!("obstacle `point` is {}", ron(point))),
        "{error}"
    );
    assert!(
        error
            .to_string()
            .starts_with("obstacle `point` is (-inf, 0.5")
    );
}

fn first_normal<V: Vector>() -> V {
    V::from_fn(|axis| if axis == 0 { 1.0 } else { 0.0 })
}

#[test]
fn point_2d() {
    check_point::<DVec2, Obstacle2d>();
}

#[test]
fn point_3d() {
    check_point::<DVec3, Obstacle3d>();
}

#[test]
fn is_a_std_error() {
    let error: Box<dyn std::error::Error> = Box::new(ObstacleError::InvalidRadius { radius: 0.0 });
    assert!(error.to_string().starts_with("ball `radius` is 0.0"));
}

//! Descriptions that do not define a non-degenerate convex obstacle are refused, with messages
//! that name the field, its value, why, and the fix.

use flock_math::Vector;
use flock_obstacles::{
    Obstacle, Obstacle2d, Obstacle3d, ObstacleError, ObstacleField, ObstacleSpec, Space,
};
use glam::{DVec2, DVec3};

use crate::common::{catalogue, coords, vector};

/// The error `spec` gives in dimension `V::DIM`.
fn refused<V: Space>(spec: ObstacleSpec) -> ObstacleError {
    V::obstacle(&spec).unwrap_err()
}

/// `(x, y)` or `(x, y, z)` as the messages write it.
fn ron<V: Vector>(v: V) -> String {
    let coordinates: Vec<String> = (0..V::DIM).map(|k| format!("{:?}", v.coord(k))).collect();
    format!("({})", coordinates.join(", "))
}

#[track_caller]
fn assert_error(error: &ObstacleError, field: &str, message: &str) {
    assert_eq!(error.field(), field, "{error:?}");
    assert_eq!(error.to_string(), message, "{error:?}");
}

fn check_radius<V: Space>() {
    for radius in [0.0, -1.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let message = format!(
            "`radius` is {radius:?}, but it must be a finite number > 0: \
             give the obstacle a positive radius"
        );
        let ball = refused::<V>(ObstacleSpec::Ball {
            centre: vec![0.0; V::DIM],
            radius,
        });
        assert!(
            matches!(ball, ObstacleError::InvalidRadius { radius: r } if r.to_bits() == radius.to_bits()),
            "{ball:?}"
        );
        assert_error(&ball, "radius", &message);
        let capsule = refused::<V>(ObstacleSpec::Capsule {
            a: vec![0.0; V::DIM],
            b: vec![1.0; V::DIM],
            radius,
        });
        assert_error(&capsule, "radius", &message);
    }
    assert!(V::Obstacle::ball(V::ZERO, f64::MIN_POSITIVE).is_ok());
}

#[test]
fn radius_2d() {
    check_radius::<DVec2>();
}

#[test]
fn radius_3d() {
    check_radius::<DVec3>();
}

fn check_non_finite_points<V: Space>() {
    let bad = V::from_fn(|axis| if axis == 1 { f64::NAN } else { 1.0 });
    let message = |field: &str| {
        format!(
            "`{field}` is {}, but every coordinate must be finite: \
             replace the NaN or infinite coordinate",
            ron(bad)
        )
    };
    let (good, one) = (vec![0.0; V::DIM], vec![1.0; V::DIM]);
    let cases = [
        (
            "centre",
            ObstacleSpec::Ball {
                centre: coords(bad),
                radius: 1.0,
            },
        ),
        (
            "point",
            ObstacleSpec::Wall {
                point: coords(bad),
                normal: one.clone(),
            },
        ),
        (
            "centre",
            ObstacleSpec::Cuboid {
                centre: coords(bad),
                half_extents: one.clone(),
                rotation: vec![],
            },
        ),
        (
            "b",
            ObstacleSpec::Capsule {
                a: good.clone(),
                b: coords(bad),
                radius: 1.0,
            },
        ),
        (
            "a",
            ObstacleSpec::Segment {
                a: coords(bad),
                b: good.clone(),
            },
        ),
        (
            "c",
            ObstacleSpec::Triangle {
                a: good.clone(),
                b: one.clone(),
                c: coords(bad),
            },
        ),
    ];
    for (field, spec) in cases {
        let error = refused::<V>(spec);
        assert!(
            matches!(&error, ObstacleError::NonFinitePoint { point, .. } if point.len() == V::DIM),
            "{error:?}"
        );
        assert_error(&error, field, &message(field));
    }
    let mut points = hull_points::<V>();
    points[2] = coords(bad);
    assert_error(
        &refused::<V>(ObstacleSpec::ConvexHull { points }),
        "points[2]",
        &message("points[2]"),
    );
    assert!(message("x").contains("(1.0, NaN"));
}

#[test]
fn non_finite_points_2d() {
    check_non_finite_points::<DVec2>();
}

#[test]
fn non_finite_points_3d() {
    check_non_finite_points::<DVec3>();
}

fn check_wrong_dimension<V: Space>() {
    let other = if V::DIM == 2 { 3 } else { 2 };
    let example = if V::DIM == 2 {
        "(0.0, 0.0)"
    } else {
        "(0.0, 0.0, 0.0)"
    };
    let message = |field: &str, len: usize| {
        format!(
            "`{field}` has {len} coordinate{}, but the scenario is {}D: give exactly {} numbers, \
             e.g. {example}",
            if len == 1 { "" } else { "s" },
            V::DIM,
            V::DIM
        )
    };
    let ball = refused::<V>(ObstacleSpec::Ball {
        centre: vec![0.0; other],
        radius: 1.0,
    });
    assert_eq!(
        ball,
        ObstacleError::WrongDimension {
            field: "centre".to_owned(),
            len: other,
            dim: V::DIM
        }
    );
    assert_error(&ball, "centre", &message("centre", other));
    let wall = refused::<V>(ObstacleSpec::Wall {
        point: vec![0.0; V::DIM],
        normal: vec![1.0],
    });
    assert_error(&wall, "normal", &message("normal", 1));
    let cuboid = refused::<V>(ObstacleSpec::Cuboid {
        centre: vec![0.0; V::DIM],
        half_extents: vec![1.0; other],
        rotation: vec![],
    });
    assert_error(&cuboid, "half_extents", &message("half_extents", other));
    let mut points = hull_points::<V>();
    points[3].push(0.0);
    assert_error(
        &refused::<V>(ObstacleSpec::ConvexHull { points }),
        "points[3]",
        &message("points[3]", V::DIM + 1),
    );
}

#[test]
fn wrong_dimension_2d() {
    check_wrong_dimension::<DVec2>();
}

#[test]
fn wrong_dimension_3d() {
    check_wrong_dimension::<DVec3>();
}

fn check_normal<V: Space>() {
    let last = |x: f64| V::from_fn(|axis| if axis + 1 == V::DIM { x } else { 0.0 });
    let floor = if V::DIM == 2 {
        "(0.0, 1.0)"
    } else {
        "(0.0, 0.0, 1.0)"
    };
    for normal in [V::ZERO, last(f64::NAN), last(f64::INFINITY), last(1e-300)] {
        let error = refused::<V>(ObstacleSpec::Wall {
            point: vec![0.0; V::DIM],
            normal: coords(normal),
        });
        assert!(
            matches!(&error, ObstacleError::InvalidNormal { normal: n } if n.len() == V::DIM),
            "{error:?}"
        );
        assert_error(
            &error,
            "normal",
            &format!(
                "`normal` is {}, but it must be finite and non-zero: give a vector pointing out \
                 of the wall towards the agents, e.g. {floor} for a floor",
                ron(normal)
            ),
        );
    }
    assert!(V::Obstacle::wall(V::ZERO, last(1e-100)).is_ok());
}

#[test]
fn normal_2d() {
    check_normal::<DVec2>();
}

#[test]
fn normal_3d() {
    check_normal::<DVec3>();
}

fn check_half_extents<V: Space>() {
    for bad in [0.0, -2.0, f64::NAN, f64::INFINITY] {
        let error = refused::<V>(ObstacleSpec::Cuboid {
            centre: vec![0.0; V::DIM],
            half_extents: coords(V::from_fn(|axis| if axis == 1 { bad } else { 1.0 })),
            rotation: vec![],
        });
        assert_error(
            &error,
            "half_extents[1]",
            &format!(
                "`half_extents[1]` is {bad:?}, but every half extent must be a finite number > 0: \
                 give the box a positive half-width along axis 1"
            ),
        );
    }
}

#[test]
fn half_extents_2d() {
    check_half_extents::<DVec2>();
}

#[test]
fn half_extents_3d() {
    check_half_extents::<DVec3>();
}

fn cuboid_with_rotation(rotation: Vec<f64>, dim: usize) -> ObstacleSpec {
    ObstacleSpec::Cuboid {
        centre: vec![0.0; dim],
        half_extents: vec![1.0; dim],
        rotation,
    }
}

#[test]
fn rotation_2d() {
    let hint = "a 2D rotation is one finite angle in radians: give e.g. (0.5,) or 0.5, or leave \
                `rotation` out for none";
    for (rotation, text) in [
        (vec![0.1, 0.2], "(0.1, 0.2)"),
        (vec![f64::NAN], "(NaN,)"),
        (vec![0.0, 0.0, 1.0], "(0.0, 0.0, 1.0)"),
    ] {
        let error = refused::<DVec2>(cuboid_with_rotation(rotation, 2));
        assert_error(
            &error,
            "rotation",
            &format!("`rotation` is {text}, but {hint}"),
        );
    }
    for rotation in [vec![], vec![0.7]] {
        assert!(DVec2::obstacle(&cuboid_with_rotation(rotation, 2)).is_ok());
    }
}

#[test]
fn rotation_3d() {
    let hint = "a 3D rotation is an axis-angle vector of 3 finite numbers (the unit axis times the \
                angle in radians): give e.g. (0.0, 0.0, 0.5) for 0.5 rad about z, or leave \
                `rotation` out for none";
    for (rotation, text) in [
        (vec![0.5], "(0.5,)"),
        (vec![0.0, f64::INFINITY, 0.0], "(0.0, inf, 0.0)"),
        (vec![1.0, 2.0], "(1.0, 2.0)"),
    ] {
        let error = refused::<DVec3>(cuboid_with_rotation(rotation, 3));
        assert_error(
            &error,
            "rotation",
            &format!("`rotation` is {text}, but {hint}"),
        );
    }
    for rotation in [vec![], vec![0.0; 3], vec![0.1, -0.2, 3.0]] {
        assert!(DVec3::obstacle(&cuboid_with_rotation(rotation, 3)).is_ok());
    }
}

/// `DIM + 2` points in convex position.
fn hull_points<V: Space>() -> Vec<Vec<f64>> {
    let ObstacleSpec::ConvexHull { points } = catalogue::<V>().remove(3).1 else {
        unreachable!("the catalogue's fourth shape is a convex hull")
    };
    points
}

fn check_hull<V: Space>() {
    let (polygon, flat, thin) = if V::DIM == 2 {
        ("polygon", "line", "Segment")
    } else {
        ("polyhedron", "plane", "Triangle")
    };
    let points = hull_points::<V>();
    assert!(
        V::obstacle(&ObstacleSpec::ConvexHull {
            points: points.clone()
        })
        .is_ok()
    );

    // Too few.
    let few = points[..V::DIM].to_vec();
    assert_error(
        &refused::<V>(ObstacleSpec::ConvexHull { points: few }),
        "points",
        &format!(
            "`points` has {} points, but a convex {polygon} needs at least {} points not all on one \
             {flat}: add points",
            V::DIM,
            V::DIM + 1
        ),
    );
    assert_error(
        &refused::<V>(ObstacleSpec::ConvexHull { points: vec![] }),
        "points",
        &format!(
            "`points` has 0 points, but a convex {polygon} needs at least {} points not all on one \
             {flat}: add points",
            V::DIM + 1
        ),
    );

    // Flat: all on the line / plane of the first coordinates, plus repeated points.
    let flat_points: Vec<Vec<f64>> = (0..8)
        .map(|i| {
            let t = i as f64;
            coords(
                vector::<V>([t, 2.0 * t - 1.0, 0.0])
                    + vector::<V>([0.0, 0.0, 1.0]) * ((i % 3) as f64),
            )
        })
        .map(|mut x| {
            x[V::DIM - 1] = if V::DIM == 2 { 2.0 * x[0] - 1.0 } else { 0.5 };
            x
        })
        .collect();
    assert_error(
        &refused::<V>(ObstacleSpec::ConvexHull {
            points: flat_points,
        }),
        "points",
        &format!(
            "`points` all lie on one {flat}, so their convex hull is flat: a convex {polygon} needs \
             {} points not on one {flat} (a zero-thickness wall is a `{thin}`)",
            V::DIM + 1
        ),
    );
    assert!(matches!(
        refused::<V>(ObstacleSpec::ConvexHull {
            points: vec![vec![1.0; V::DIM]; 6]
        }),
        ObstacleError::FlatHull { .. }
    ));

    // Not convex: a point strictly inside the hull of the others.
    let mut dented = points.clone();
    let centroid: Vec<f64> = (0..V::DIM)
        .map(|k| points.iter().map(|x| x[k]).sum::<f64>() / points.len() as f64)
        .collect();
    let inner: Vec<f64> = centroid
        .iter()
        .zip(&points[1])
        .map(|(c, x)| c + 0.5 * (x - c))
        .collect();
    dented.insert(4, inner.clone());
    let error = refused::<V>(ObstacleSpec::ConvexHull { points: dented });
    assert_eq!(
        error,
        ObstacleError::PointInsideHull {
            index: 4,
            point: inner.clone()
        }
    );
    assert_error(
        &error,
        "points[4]",
        &format!(
            "`points[4]` is {}, strictly inside the convex hull of the other points, so the outline \
             is not convex: the obstacle is the convex hull of `points`; remove the point, or split \
             a non-convex obstacle into convex ones",
            ron(vector::<V>([inner[0], inner[1], *inner.last().unwrap()]))
        ),
    );

    // Points on the hull's boundary that are not corners, and repeated corners, are accepted.
    let mut redundant = points.clone();
    let middle: Vec<f64> = points[0]
        .iter()
        .zip(&points[1])
        .map(|(a, b)| 0.5 * (a + b))
        .collect();
    if V::DIM == 2 {
        redundant.push(middle);
    }
    redundant.push(points[0].clone());
    assert!(V::obstacle(&ObstacleSpec::ConvexHull { points: redundant }).is_ok());
}

#[test]
fn hull_2d() {
    check_hull::<DVec2>();
}

#[test]
fn hull_3d() {
    check_hull::<DVec3>();
}

fn check_segment_and_triangle<V: Space>() {
    let a = vector::<V>([1.0, 2.0, 3.0]);
    let error = refused::<V>(ObstacleSpec::Segment {
        a: coords(a),
        b: coords(a),
    });
    assert_error(
        &error,
        "b",
        &format!(
            "`b` equals `a` = {}, so the segment is a single point: give two distinct endpoints",
            ron(a)
        ),
    );
    let (b, c) = (a * 2.0, a * -0.5);
    let error = refused::<V>(ObstacleSpec::Triangle {
        a: coords(a),
        b: coords(b),
        c: coords(c),
    });
    assert_error(
        &error,
        "c",
        &format!(
            "`c` = {} is on the line through `a` = {} and `b` = {}, so the triangle is flat: give \
             three vertices not on one line",
            ron(c),
            ron(a),
            ron(b)
        ),
    );
    assert!(matches!(
        refused::<V>(ObstacleSpec::Triangle {
            a: coords(a),
            b: coords(a),
            c: coords(b),
        }),
        ObstacleError::FlatTriangle { .. }
    ));
}

#[test]
fn segment_and_triangle_2d() {
    check_segment_and_triangle::<DVec2>();
}

#[test]
fn segment_and_triangle_3d() {
    check_segment_and_triangle::<DVec3>();
}

/// A capsule with `a = b` is the ball `B(a, R)` (accepted, not refused).
fn check_capsule_as_ball<V: Space>() {
    let a = vector::<V>([1.0, -2.0, 0.5]);
    let capsule = V::obstacle(&ObstacleSpec::Capsule {
        a: coords(a),
        b: coords(a),
        radius: 0.75,
    })
    .unwrap();
    let ball = V::Obstacle::ball(a, 0.75).unwrap();
    for q in [
        vector::<V>([3.0, 1.0, -1.0]),
        a + vector::<V>([0.1, 0.2, 0.3]),
    ] {
        let p = vector::<V>([0.3, -1.0, 2.0]);
        assert_eq!(capsule.beta_agent(q, p), ball.beta_agent(q, p));
    }
}

#[test]
fn capsule_as_ball_2d() {
    check_capsule_as_ball::<DVec2>();
}

#[test]
fn capsule_as_ball_3d() {
    check_capsule_as_ball::<DVec3>();
}

/// `ObstacleField::from_specs` names the obstacle by its index, in the field path and the message.
fn check_index<V: Space>() {
    let mut specs: Vec<ObstacleSpec> = catalogue::<V>().into_iter().map(|(_, s)| s).collect();
    assert_eq!(
        ObstacleField::<V>::from_specs(&specs).unwrap().len(),
        specs.len()
    );
    specs[2] = ObstacleSpec::Cuboid {
        centre: vec![0.0; V::DIM],
        half_extents: coords(V::from_fn(|k| if k == 0 { -1.0 } else { 1.0 })),
        rotation: vec![],
    };
    let error = ObstacleField::<V>::from_specs(&specs).unwrap_err();
    assert!(
        matches!(&error, ObstacleError::InObstacle { index: 2, error } if matches!(**error, ObstacleError::InvalidHalfExtent { axis: 0, .. })),
        "{error:?}"
    );
    assert_error(
        &error,
        "obstacles[2].half_extents[0]",
        "`obstacles[2].half_extents[0]` is -1.0, but every half extent must be a finite number > 0: \
         give the box a positive half-width along axis 0",
    );
    specs[2] = ObstacleSpec::Segment {
        a: vec![0.0; V::DIM],
        b: vec![0.0; V::DIM],
    };
    let message = ObstacleField::<V>::from_specs(&specs)
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("`obstacles[2].b` equals `obstacles[2].a` = (0.0, 0.0"),
        "{message}"
    );
}

#[test]
fn index_2d() {
    check_index::<DVec2>();
}

#[test]
fn index_3d() {
    check_index::<DVec3>();
}

#[test]
fn typed_constructors() {
    assert!(matches!(
        Obstacle2d::cuboid(DVec2::ZERO, DVec2::ONE, f64::NAN),
        Err(ObstacleError::InvalidRotation { dim: 2, .. })
    ));
    assert!(matches!(
        Obstacle3d::cuboid(DVec3::ZERO, DVec3::ONE, DVec3::new(0.0, f64::NAN, 0.0)),
        Err(ObstacleError::InvalidRotation { dim: 3, .. })
    ));
    assert!(matches!(
        Obstacle3d::convex_hull(&[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)]),
        Err(ObstacleError::FlatHull { dim: 3 })
    ));
    assert!(matches!(
        Obstacle2d::triangle(DVec2::ZERO, DVec2::X, DVec2::X * 3.0),
        Err(ObstacleError::FlatTriangle { .. })
    ));
}

#[test]
fn is_a_std_error() {
    let error: Box<dyn std::error::Error> = Box::new(ObstacleError::InvalidRadius { radius: 0.0 });
    assert!(error.to_string().starts_with("`radius` is 0.0"));
}

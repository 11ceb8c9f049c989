//! `ObstacleSpec` in RON: vectors as tuples or lists, a 2D rotation as one number, unknown fields
//! refused, round trips.

use flock_obstacles::{ObstacleSpec, Space};
use glam::{DVec2, DVec3};

use crate::common::catalogue;

fn parse(text: &str) -> ObstacleSpec {
    ron::from_str(text).unwrap_or_else(|error| panic!("{text}: {error}"))
}

#[test]
fn vectors_as_tuples_or_lists() {
    let ball = ObstacleSpec::Ball {
        centre: vec![1.0, 2.0],
        radius: 0.5,
    };
    assert_eq!(parse("Ball(centre: (1.0, 2.0), radius: 0.5)"), ball);
    assert_eq!(parse("Ball(centre: [1.0, 2.0], radius: 0.5)"), ball);
    assert_eq!(parse("Ball(centre: (1, 2), radius: 0.5)"), ball);
    assert_eq!(
        parse("ConvexHull(points: [(0.0, 0.0), [1.0, 0.0], (0, 1)])"),
        ObstacleSpec::ConvexHull {
            points: vec![vec![0.0, 0.0], vec![1.0, 0.0], vec![0.0, 1.0]]
        }
    );
    assert_eq!(
        parse("ConvexHull(points: ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)))"),
        parse("ConvexHull(points: [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])")
    );
}

#[test]
fn rotations() {
    let cuboid = |rotation: Vec<f64>| ObstacleSpec::Cuboid {
        centre: vec![0.0, 0.0],
        half_extents: vec![1.0, 2.0],
        rotation,
    };
    for text in ["0.3", "(0.3,)", "[0.3]"] {
        assert_eq!(
            parse(&format!(
                "Cuboid(centre: (0.0, 0.0), half_extents: (1.0, 2.0), rotation: {text})"
            )),
            cuboid(vec![0.3])
        );
    }
    assert_eq!(
        parse("Cuboid(centre: (0.0, 0.0), half_extents: (1.0, 2.0))"),
        cuboid(vec![])
    );
    assert_eq!(
        parse("Cuboid(centre: (0, 0, 0), half_extents: (1, 2, 3), rotation: (0.0, 0.0, 1.5))"),
        ObstacleSpec::Cuboid {
            centre: vec![0.0; 3],
            half_extents: vec![1.0, 2.0, 3.0],
            rotation: vec![0.0, 0.0, 1.5],
        }
    );
}

#[test]
fn unknown_fields_and_kinds_are_refused() {
    for text in [
        "Ball(centre: (0.0, 0.0), radius: 1.0, colour: 3)",
        "Ball(centre: (0.0, 0.0))",
        "Sphere(centre: (0.0, 0.0), radius: 1.0)",
        "Ball(centre: \"here\", radius: 1.0)",
        "Wall(point: (0.0, x), normal: (0.0, 1.0))",
    ] {
        assert!(ron::from_str::<ObstacleSpec>(text).is_err(), "{text}");
    }
    let error = ron::from_str::<ObstacleSpec>("Ball(centre: \"here\", radius: 1.0)").unwrap_err();
    assert!(
        error
            .to_string()
            .contains("a vector of numbers, e.g. (1.0, 2.0) or [1.0, 2.0]"),
        "{error}"
    );
}

fn check_round_trip<V: Space>() {
    for (name, spec) in catalogue::<V>() {
        let text = ron::to_string(&spec).unwrap();
        assert_eq!(parse(&text), spec, "{name}: {text}");
        assert!(V::obstacle(&parse(&text)).is_ok(), "{name}");
    }
    let unturned = ObstacleSpec::Cuboid {
        centre: vec![0.0; V::DIM],
        half_extents: vec![1.0; V::DIM],
        rotation: vec![],
    };
    let text = ron::to_string(&unturned).unwrap();
    assert!(!text.contains("rotation"), "{text}");
    assert_eq!(parse(&text), unturned);
}

#[test]
fn round_trip_2d() {
    check_round_trip::<DVec2>();
}

#[test]
fn round_trip_3d() {
    check_round_trip::<DVec3>();
}

#[test]
fn kind_names() {
    let names: Vec<&str> = catalogue::<DVec2>()
        .iter()
        .map(|(_, spec)| spec.kind())
        .collect();
    assert_eq!(
        names,
        [
            "Ball",
            "Wall",
            "Cuboid",
            "ConvexHull",
            "Capsule",
            "Segment",
            "Triangle"
        ]
    );
}

//! The metric figure (TAC 2006 Fig. 18): four labelled panels with axes and units, and more.

use flock_viz::{Metrics, MetricsOptions, VizError, metrics_png, metrics_svg};

use crate::support::{decode_png, flocking_metrics};

/// The text of an SVG's `<text>` elements.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .map(|t| {
            t.split('>')
                .nth(1)
                .unwrap()
                .split('<')
                .next()
                .unwrap()
                .trim()
                .to_owned()
        })
        .collect()
}

#[test]
fn four_panels_of_fig_18_with_titles_axes_and_units() {
    let svg = metrics_svg(&flocking_metrics(false), &MetricsOptions::default()).unwrap();
    let texts = texts(&svg);
    for title in [
        "connectivity C",
        "cohesion radius R",
        "deviation energy Ẽ",
        "velocity mismatch K̃",
        "energy H",
        "min distance between agents",
    ] {
        assert_eq!(texts.iter().filter(|t| *t == title).count(), 1, "{title}");
    }
    assert!(!texts.iter().any(|t| t == "obstacle clearance"));
    // One time axis per panel, and the units of each vertical axis.
    assert_eq!(texts.iter().filter(|t| *t == "t (s)").count(), 6);
    for label in [
        "C (dimensionless)",
        "R (m)",
        "Ẽ (dimensionless, log scale)",
        "K̃ (m²/s², log scale)",
        "min ‖q_j − q_i‖ (m)",
    ] {
        assert!(texts.iter().any(|t| t == label), "{label}");
    }
    assert!(texts.iter().any(|t| t == "C* (giant component)"));
    // Log axes label decades.
    assert!(texts.iter().any(|t| t == "1e-9"), "{texts:?}");
}

#[test]
fn obstacle_clearance_gets_a_panel_when_the_run_has_it() {
    let options = MetricsOptions {
        title: "with obstacles".into(),
        length_unit: "d".into(),
        ..MetricsOptions::default()
    };
    let svg = metrics_svg(&flocking_metrics(true), &options).unwrap();
    let texts = texts(&svg);
    assert!(texts.iter().any(|t| t == "obstacle clearance"));
    assert!(texts.iter().any(|t| t == "clearance (d)"));
    assert!(texts.iter().any(|t| t == "with obstacles"));
    assert_eq!(texts.iter().filter(|t| *t == "t (s)").count(), 7);
}

#[test]
fn the_png_has_one_panel_per_metric() {
    let options = MetricsOptions {
        panel_size: (320, 200),
        ..MetricsOptions::default()
    };
    let png = metrics_png(&flocking_metrics(true), &options).unwrap();
    let image = decode_png(&png);
    // 7 panels in 2 columns: 4 rows.
    assert_eq!(image.size, (640, 800));
    let curve = flock_viz::style::CURVE;
    assert!(image.pixels.iter().filter(|&&p| p == curve).count() > 500);
}

#[test]
fn metrics_without_plotted_columns_are_refused() {
    let m = Metrics::from_columns(vec![("t".into(), vec![0.0]), ("x".into(), vec![1.0])]).unwrap();
    assert!(matches!(
        metrics_svg(&m, &MetricsOptions::default()),
        Err(VizError::Invalid(msg)) if msg.contains("\"x\"")
    ));
    let empty = Metrics::from_columns(vec![("t".into(), vec![])]).unwrap();
    assert!(metrics_svg(&empty, &MetricsOptions::default()).is_err());
    assert!(Metrics::from_columns(vec![("x".into(), vec![])]).is_err());
    assert!(Metrics::from_columns(vec![("t".into(), vec![0.0]), ("a".into(), vec![])]).is_err());
}

#[test]
fn non_finite_and_non_positive_values_leave_gaps() {
    let m = Metrics::from_columns(vec![
        ("t".into(), vec![0.0, 1.0, 2.0, 3.0]),
        ("velocity_mismatch".into(), vec![0.0, 1e-3, f64::NAN, 1e-5]),
        ("cohesion_radius".into(), vec![f64::NAN; 4]),
    ])
    .unwrap();
    let svg = metrics_svg(&m, &MetricsOptions::default()).unwrap();
    assert!(svg.contains("velocity mismatch K̃"));
}

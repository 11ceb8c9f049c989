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

/// Issue 50: the panels show what matters for each model — the order parameters, the groups,
/// the spread and the spacing for the models that set velocities, with no lattice (Ẽ), energy
/// H or collision panel, which mean nothing for them; the distance from the γ-agent for a run
/// that has one.
#[test]
fn each_model_gets_the_panels_that_matter_for_it() {
    use flocking::VerdictKind;
    let base = flocking_metrics(false);
    let t = base.time().to_vec();
    let mut columns: Vec<(String, Vec<f64>)> = base
        .names()
        .iter()
        .map(|n| (n.clone(), base.column(n).unwrap().to_vec()))
        .collect();
    for name in [
        "polarisation",
        "milling",
        "nearest_neighbour_mean",
        "gamma_position_error",
    ] {
        columns.push((name.to_owned(), t.iter().map(|t| 0.5 + 0.01 * t).collect()));
    }
    let metrics = Metrics::from_columns(columns).unwrap();
    let titles = |kind: VerdictKind| {
        let options = MetricsOptions {
            kind,
            ..MetricsOptions::default()
        };
        texts(&metrics_svg(&metrics, &options).unwrap())
    };
    let couzin = titles(VerdictKind::Couzin);
    for title in [
        "order: polarisation and milling",
        "connectivity C",
        "cohesion radius R",
        "mean nearest-neighbour distance",
    ] {
        assert!(couzin.iter().any(|t| t == title), "{title}: {couzin:?}");
    }
    for title in [
        "deviation energy Ẽ",
        "energy H",
        "min distance between agents",
        "velocity mismatch K̃",
    ] {
        assert!(!couzin.iter().any(|t| t == title), "{title}");
    }
    let cucker_smale = titles(VerdictKind::CuckerSmale);
    assert!(cucker_smale.iter().any(|t| t == "velocity mismatch K̃"));
    assert!(!cucker_smale.iter().any(|t| t == "energy H"));
    let lattice = titles(VerdictKind::Definition5);
    assert!(
        lattice
            .iter()
            .any(|t| t == "distance from the γ-agent ‖q̄ − q_r‖")
    );
    assert!(lattice.iter().any(|t| t == "deviation energy Ẽ"));
    assert!(
        !lattice
            .iter()
            .any(|t| t == "order: polarisation and milling")
    );
}

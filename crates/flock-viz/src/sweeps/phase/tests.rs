//! Series, references and bounds: where they are drawn and where they are refused.

use super::grid::cell_position;
use super::*;
use crate::draw::style;

/// Two panels of a line: N = 40 and N = 400, two x each.
fn two_series() -> Vec<PhasePoint> {
    [(0, 1.0, 0.9), (0, 2.0, 0.6), (1, 1.0, 0.8), (1, 2.0, 0.3)]
        .map(|(panel, x, value)| PhasePoint {
            x,
            y: None,
            value,
            panel,
        })
        .to_vec()
}

fn series_options(references: Vec<Reference>) -> PhaseOptions {
    PhaseOptions {
        panels: vec!["N = 40".into(), "N = 400".into()],
        series: true,
        references,
        ..PhaseOptions::default()
    }
}

/// Series share one set of axes: one legend entry per panel and per reference, each
/// series in its colour and the references in black, drawn within the points' range even
/// where they lie outside the sweep's values.
#[test]
fn series_and_references_share_one_set_of_axes() {
    let reference = Reference {
        label: "N = 40, paper".into(),
        series: Some(0),
        points: vec![(1.5, 0.05)],
    };
    let svg = phase_svg(&two_series(), &series_options(vec![reference])).unwrap();
    for label in ["N = 40", "N = 400", "N = 40, paper"] {
        assert!(
            svg.contains(&format!("\n{label}\n</text>")),
            "no legend entry {label}"
        );
    }
    for colour in [SERIES[0], SERIES[1], style::INK] {
        assert!(svg.contains(&style::hex(colour)), "no {colour:?}");
    }
    // one set of axes: the x label once
    let without = phase_svg(&two_series(), &series_options(Vec::new())).unwrap();
    assert!(!without.contains("paper"));
    assert_ne!(svg, without);
}

/// A heatmap has no series, and a reference must belong to a drawn panel and be finite.
#[test]
fn series_and_references_are_refused_where_they_cannot_be_drawn() {
    let heatmap: Vec<PhasePoint> = [(1.0, 1.0, 0.1), (2.0, 1.0, 0.2)]
        .map(|(x, y, value)| PhasePoint {
            x,
            y: Some(y),
            value,
            panel: 0,
        })
        .to_vec();
    let options = PhaseOptions {
        y_label: Some("y".into()),
        series: true,
        ..PhaseOptions::default()
    };
    assert!(phase_svg(&heatmap, &options).is_err());
    let stray = Reference {
        label: "stray".into(),
        series: Some(2),
        points: vec![(1.0, 0.5)],
    };
    assert!(phase_svg(&two_series(), &series_options(vec![stray])).is_err());
    let infinite = Reference {
        label: "infinite".into(),
        series: None,
        points: vec![(1.0, f64::INFINITY)],
    };
    assert!(phase_svg(&two_series(), &series_options(vec![infinite])).is_err());
}

/// Over a heatmap a reference is a red line through its points, placed between the cells
/// of the values around it, and changes the drawing.
#[test]
fn a_reference_over_a_heatmap_is_a_labelled_red_line() {
    let points: Vec<PhasePoint> = [(0.0, 1.0), (0.0, 2.0), (1.0, 1.0), (1.0, 2.0)]
        .map(|(x, y)| PhasePoint {
            x,
            y: Some(y),
            value: x + y,
            panel: 0,
        })
        .to_vec();
    let options = |references| PhaseOptions {
        y_label: Some("y".into()),
        references,
        ..PhaseOptions::default()
    };
    let border = Reference {
        label: "border".into(),
        series: None,
        points: vec![(0.5, 1.0), (0.5, 2.0)],
    };
    let svg = phase_svg(&points, &options(vec![border])).unwrap();
    assert!(svg.contains("\nborder\n</text>"));
    assert!(svg.contains(&style::hex(BOUND)));
    assert!(
        !phase_svg(&points, &options(Vec::new()))
            .unwrap()
            .contains(&style::hex(BOUND))
    );
    assert_eq!(cell_position(&[0.0, 1.0, 3.0], 2.0, false), 1.5);
    assert_eq!(cell_position(&[0.0, 1.0, 3.0], 4.0, false), 2.5);
}

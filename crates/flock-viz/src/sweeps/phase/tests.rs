//! Series, references and bounds: where they are drawn and where they are refused.

use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};

use super::cells::{CellAxis, Layout};
use super::grid;
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
}

/// Two categories along x, three seeds each: "PointMass" (0) and "Unicycle(())" (1).
fn categorical_points() -> Vec<PhasePoint> {
    [
        (0.0, 0.2),
        (0.0, 0.4),
        (0.0, 0.9),
        (1.0, 0.1),
        (1.0, 0.3),
        (1.0, f64::NAN),
    ]
    .map(|(x, value)| PhasePoint {
        x,
        y: None,
        value,
        panel: 0,
    })
    .to_vec()
}

fn categorical_options() -> PhaseOptions {
    PhaseOptions {
        x_label: "vehicle".into(),
        metric: "m".into(),
        x_categories: vec!["PointMass".into(), "Unicycle(x: 1, y: 2)".into()],
        ..PhaseOptions::default()
    }
}

/// A categorical x is labelled with its categories' names, in the given order; the table names
/// them (quoted where they hold a comma); indices outside the categories, a log x and a bound
/// are refused.
#[test]
fn categories_are_named_on_the_axis_and_in_the_table() {
    let svg = phase_svg(&categorical_points(), &categorical_options()).unwrap();
    for name in ["PointMass", "Unicycle(x: 1, y: 2)"] {
        assert!(svg.contains(&format!("\n{name}\n</text>")), "no {name}");
    }
    let table = phase_table(&categorical_points(), &categorical_options()).unwrap();
    assert_eq!(
        table,
        "panel,x,y,runs,mean,low,high\n,PointMass,,3,0.5,0.2,0.9\n,\"Unicycle(x: 1, y: 2)\",,2,0.2,0.1,0.3\n"
    );
    let mut stray = categorical_points();
    stray[0].x = 2.0;
    assert!(phase_svg(&stray, &categorical_options()).is_err());
    for options in [
        PhaseOptions {
            log_x: true,
            ..categorical_options()
        },
        PhaseOptions {
            bound: Some(Bound {
                x: 0.5,
                label: "b".into(),
            }),
            ..categorical_options()
        },
    ] {
        assert!(phase_svg(&categorical_points(), &options).is_err());
    }
}

/// The band's meaning is in the legend of a line diagram, as the band drawn.
#[test]
fn the_legend_says_what_the_band_is() {
    for (band, meaning, other) in [
        (
            Band::MinMax,
            "min–max over the seeds",
            "25–75 % of the seeds",
        ),
        (
            Band::Quantiles,
            "25–75 % of the seeds",
            "min–max over the seeds",
        ),
    ] {
        let options = PhaseOptions {
            band,
            ..PhaseOptions::default()
        };
        let svg = phase_svg(&two_series()[..2], &options).unwrap();
        assert!(svg.contains(&format!("\n{meaning}\n</text>")), "{meaning}");
        assert!(!svg.contains(other), "{other}");
        assert!(svg.contains("\nmean over the seeds\n</text>"));
    }
}

/// A log colour scale places the geometric mean of the least and largest means at mid-scale
/// (the linear one their arithmetic mean), and is refused where a value is not positive.
#[test]
fn a_log_colour_scale_is_linear_in_ln_value() {
    let heatmap = |values: [f64; 3]| -> Vec<PhasePoint> {
        values
            .iter()
            .enumerate()
            .map(|(k, &value)| PhasePoint {
                x: k as f64,
                y: Some(0.0),
                value,
                panel: 0,
            })
            .collect()
    };
    let options = |log_colour| PhaseOptions {
        y_label: Some("y".into()),
        log_colour,
        ..PhaseOptions::default()
    };
    let points = heatmap([0.001, 0.1, 10.0]);
    let options_log = options(true);
    let diagram = grid::Diagram::new(&points, &options_log).unwrap();
    let middle = ViridisRGB.get_color_normalized(0.5, 0.0, 1.0);
    // within one level of the map's middle (0.5 is not exact in floating point)
    let near = |c: plotters::style::RGBColor| {
        [(c.0, middle.0), (c.1, middle.1), (c.2, middle.2)]
            .iter()
            .all(|&(a, b)| a.abs_diff(b) <= 1)
    };
    assert!(near(diagram.colour(0.1, (0.001, 10.0))));
    let options_linear = options(false);
    let linear = grid::Diagram::new(&points, &options_linear).unwrap();
    assert!(near(linear.colour(5.0005, (0.001, 10.0))));
    assert!(!near(linear.colour(0.1, (0.001, 10.0))));
    let svg_log = phase_svg(&points, &options(true)).unwrap();
    assert_ne!(svg_log, phase_svg(&points, &options(false)).unwrap());
    let error = phase_svg(&heatmap([0.0, 0.1, 10.0]), &options(true)).unwrap_err();
    assert!(error.to_string().contains("positive"), "{error}");
}

/// The overlay (series) honours --log-x and --log-y where every value drawn is positive, and
/// stays linear where one is not (as a line diagram does).
#[test]
fn series_take_log_axes_where_the_values_allow() {
    let points = |first: f64| -> Vec<PhasePoint> {
        [
            (0, 0.01, first),
            (0, 1.0, 0.5),
            (1, 0.01, 0.01),
            (1, 1.0, 5.0),
        ]
        .map(|(panel, x, value)| PhasePoint {
            x,
            y: None,
            value,
            panel,
        })
        .to_vec()
    };
    let options = |log_x, log_y| PhaseOptions {
        log_x,
        log_y,
        ..series_options(Vec::new())
    };
    let linear = phase_svg(&points(0.001), &options(false, false)).unwrap();
    for (log_x, log_y) in [(true, false), (false, true), (true, true)] {
        let svg = phase_svg(&points(0.001), &options(log_x, log_y)).unwrap();
        assert_ne!(svg, linear, "log_x {log_x}, log_y {log_y}");
    }
    // a zero metric: no log y
    let zero = phase_svg(&points(0.0), &options(false, false)).unwrap();
    assert_eq!(
        phase_svg(&points(0.0), &options(false, true)).unwrap(),
        zero
    );
}

/// A numeric axis's cells are centred on their values and meet halfway between them (in ln
/// value on a log axis), the outer ones as wide beyond their value as towards their neighbour; a
/// categorical axis has equal cells.
#[test]
fn heatmap_cells_span_halfway_to_their_neighbours() {
    let axis = CellAxis::new(&[0.0, 0.01, 0.1, 0.5], Layout::Values { log: false });
    assert_eq!(axis.centres, [0.0, 0.01, 0.1, 0.5]);
    let expected = [-0.005, 0.005, 0.055, 0.3, 0.7];
    for (edge, expected) in axis.edges.iter().zip(expected) {
        approx::assert_relative_eq!(*edge, expected, epsilon = 1e-12);
    }
    // on a log axis, at the geometric means: a decade grid has equal cells
    let log = CellAxis::new(&[1.0, 10.0, 100.0], Layout::Values { log: true });
    let decade = 10f64.ln();
    for (k, edge) in log.edges.iter().enumerate() {
        approx::assert_relative_eq!(*edge, (k as f64 - 0.5) * decade, epsilon = 1e-12);
    }
    approx::assert_relative_eq!(log.at(10f64.sqrt()), 0.5 * decade, epsilon = 1e-12);
    assert_eq!(
        log.at(1e9),
        log.edges[3],
        "beyond the last cell: at its edge"
    );
    // a log scale needs positive values; categories are their indices
    assert_eq!(
        CellAxis::new(&[0.0, 1.0], Layout::Values { log: true }).edges,
        [-0.5, 0.5, 1.5]
    );
    let categories = CellAxis::new(&[0.0, 2.0, 3.0], Layout::Categories);
    assert_eq!(categories.centres, [0.0, 1.0, 2.0]);
    assert_eq!(categories.edges, [-0.5, 0.5, 1.5, 2.5]);
    assert_eq!(
        CellAxis::new(&[4.0], Layout::Values { log: false }).edges,
        [3.5, 4.5]
    );
}

/// Even cells: the values in equal cells at their indices, a value between two of the grid's
/// placed between their cells in proportion, one beyond the grid at the outer edge.
#[test]
fn even_cells_are_equal_and_place_values_between_them_in_proportion() {
    let axis = CellAxis::new(&[0.0, 0.01, 0.1, 0.8], Layout::Even);
    assert_eq!(axis.centres, [0.0, 1.0, 2.0, 3.0]);
    assert_eq!(axis.edges, [-0.5, 0.5, 1.5, 2.5, 3.5]);
    assert_eq!(axis.at(0.01), 1.0);
    approx::assert_relative_eq!(axis.at(0.45), 2.5, epsilon = 1e-12);
    approx::assert_relative_eq!(axis.at(0.687), 2.0 + 0.587 / 0.7, epsilon = 1e-12);
    assert_eq!(axis.at(0.8), 3.0);
    assert_eq!(axis.at(5.0), 3.5, "beyond the last value: the outer edge");
    assert_eq!(
        axis.at(-1.0),
        -0.5,
        "before the first value: the outer edge"
    );
    assert_eq!(CellAxis::new(&[2.0], Layout::Even).at(2.0), 0.0);
}

/// The rectangles (left pixel, width) of the cells of a heatmap of one row over `xs`, cell k's
/// mean k, drawn with `options`.
fn drawn_cells(xs: &[f64], options: &PhaseOptions) -> Vec<(f64, f64)> {
    let points: Vec<PhasePoint> = xs
        .iter()
        .enumerate()
        .map(|(k, &x)| PhasePoint {
            x,
            y: Some(1.0),
            value: k as f64,
            panel: 0,
        })
        .collect();
    let svg = phase_svg(&points, options).unwrap();
    let diagram = grid::Diagram::new(&points, options).unwrap();
    let number = |rect: &str, name: &str| -> f64 {
        let start = rect.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        rect[start..].split('"').next().unwrap().parse().unwrap()
    };
    // each cell's rectangle: the tallest of its colour (the colour bar's steps are short)
    (0..xs.len())
        .map(|k| {
            let c = diagram.colour(k as f64, diagram.range);
            let fill = format!("fill=\"{}\"", style::hex([c.0, c.1, c.2]));
            let rect = svg
                .split("<rect")
                .filter(|r| r.contains(&fill))
                .max_by(|a, b| number(a, "height").total_cmp(&number(b, "height")))
                .unwrap_or_else(|| panic!("no cell of {fill}"));
            (number(rect, "x"), number(rect, "width"))
        })
        .collect()
}

/// The drawn heatmap of x = 0, 0.01, 0.1, 0.5: each cell's rectangle spans from the midpoint
/// with its left neighbour to the midpoint with its right one, on a linear value axis; with
/// even cells, the four are equal.
#[test]
fn uneven_values_are_drawn_as_cells_of_uneven_widths() {
    let xs = [0.0, 0.01, 0.1, 0.5];
    let options = PhaseOptions {
        y_label: Some("y".into()),
        ..PhaseOptions::default()
    };
    let cells = drawn_cells(&xs, &options);
    let edges = CellAxis::new(&xs, Layout::Values { log: false }).edges;
    let (left, width) = (cells[0].0, cells.iter().map(|c| c.1).sum::<f64>());
    let pixel = |u: f64| left + width * (u - edges[0]) / (edges[4] - edges[0]);
    for (k, &(x, w)) in cells.iter().enumerate() {
        assert!(
            (x - pixel(edges[k])).abs() <= 1.5 && (x + w - pixel(edges[k + 1])).abs() <= 1.5,
            "cell {k} drawn over {x}..{}, its edges at {:.1}..{:.1}",
            x + w,
            pixel(edges[k]),
            pixel(edges[k + 1])
        );
    }
    assert!(
        cells[3].1 > 30.0 * cells[0].1,
        "0.5's cell 40 times 0's: {cells:?}"
    );
    let even = drawn_cells(
        &xs,
        &PhaseOptions {
            even_cells: true,
            ..options
        },
    );
    for (k, &(x, w)) in even.iter().enumerate() {
        assert!(
            (w - even[0].1).abs() <= 1.5 && (x - (even[0].0 + k as f64 * even[0].1)).abs() <= 3.0,
            "even cells: {even:?}"
        );
    }
}

/// Even cells are for a heatmap's numeric axes and replace a log scale: asked of a line diagram
/// or with a log axis, they are refused, naming why.
#[test]
fn even_cells_are_refused_where_they_mean_nothing() {
    let point = |x: f64, y: Option<f64>| PhasePoint {
        x,
        y,
        value: 1.0,
        panel: 0,
    };
    let heatmap = [point(0.0, Some(1.0)), point(0.5, Some(2.0))];
    let even = PhaseOptions {
        y_label: Some("y".into()),
        even_cells: true,
        ..PhaseOptions::default()
    };
    assert!(phase_svg(&heatmap, &even).is_ok());
    let logged = phase_svg(
        &heatmap,
        &PhaseOptions {
            log_y: true,
            ..even.clone()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        logged.contains("either even cells or a log axis"),
        "{logged}"
    );
    let line_even = PhaseOptions {
        even_cells: true,
        ..PhaseOptions::default()
    };
    let line = phase_svg(&[point(0.0, None), point(0.5, None)], &line_even)
        .unwrap_err()
        .to_string();
    assert!(line.contains("even cells are for a heatmap"), "{line}");
}

/// Where an uneven axis crowds its values, a label is shown only clear of the last one shown.
#[test]
fn crowded_labels_are_thinned() {
    let labels = [(0, 20), (10, 20), (30, 20), (60, 20), (83, 20)];
    assert_eq!(
        super::heatmap::clear_of_each_other(&labels),
        [true, false, true, true, false]
    );
}

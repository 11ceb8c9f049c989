//! The numbers a phase diagram draws, as CSV.

use super::grid::{Diagram, mean};
use super::{PhaseOptions, PhasePoint};
use crate::error::VizError;

/// The numbers a phase diagram draws, as CSV: `panel,x,y,runs,mean,low,high`, one line per
/// grid point of each panel (panels in order, then x, then y, ascending) — the panel's title, the
/// point, how many finite values it has, their mean and the band ([`PhaseOptions::band`]), empty
/// where it has none. Numbers are written as Rust prints them (shortest round trip).
///
/// # Errors
/// As [`phase_svg`](super::phase_svg).
///
/// # Example
/// ```
/// use flock_viz::phase::{PhaseOptions, PhasePoint, phase_table};
///
/// let points: Vec<PhasePoint> = [(0.1, 1.0), (0.1, 3.0), (0.2, f64::NAN)]
///     .map(|(x, value)| PhasePoint { x, y: None, value, panel: 0 })
///     .to_vec();
/// let table = phase_table(&points, &PhaseOptions::default()).unwrap();
/// assert_eq!(table, "panel,x,y,runs,mean,low,high\n,0.1,,2,2,1,3\n,0.2,,0,,,\n");
/// ```
pub fn phase_table(points: &[PhasePoint], options: &PhaseOptions) -> Result<String, VizError> {
    let diagram = Diagram::new(points, options)?;
    let mut table = String::from("panel,x,y,runs,mean,low,high\n");
    for (k, cells) in diagram.panels.iter().enumerate() {
        let title = field(options.panels.get(k).map_or("", String::as_str));
        for (&x, column) in diagram.xs.iter().zip(cells) {
            let x = value(x, &options.x_categories);
            for (&y, cell) in diagram.ys.iter().zip(column) {
                let y = if options.y_label.is_some() {
                    value(y, &options.y_categories)
                } else {
                    String::new()
                };
                let (mean, low, high) = match mean(cell) {
                    Some(mean) => {
                        let (low, high) = options.band.of(cell);
                        (mean.to_string(), low.to_string(), high.to_string())
                    }
                    None => Default::default(),
                };
                table += &format!("{title},{x},{y},{},{mean},{low},{high}\n", cell.len());
            }
        }
    }
    Ok(table)
}

/// A grid value: the name of its category, or the number.
fn value(v: f64, categories: &[String]) -> String {
    match categories.get(v as usize) {
        Some(name) => field(name),
        None => v.to_string(),
    }
}

/// `text` as a CSV field: quoted where it holds a comma or a quote.
fn field(text: &str) -> String {
    if text.contains([',', '"']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

//! A finished sweep's phase diagram, from its directory (`sweep.ron`, `runs.csv`) to a file: what
//! `flocking sweep plot` and Python's `SweepResult.plot` draw, through [`plot_sweep`]. The axes
//! are read from `runs.csv` as the sweep wrote them; an axis whose values are not numbers (an
//! `algorithm`, a `vehicle`, a loss model) is drawn as categories in the sweep's order.

use std::fmt;
use std::path::{Path, PathBuf};

use flocking::owned::{self, DirError};
use flocking::sweep::store::{self, RUNS_FILE};
use flocking::sweep::{ParameterLabel, SEED_COLUMN as SEED, metric_label, value_field};

use super::phase::{
    Band, Bound, PhaseOptions, PhasePoint, Reference, phase_png, phase_svg, phase_table,
};
use super::shown::shown;

/// What a phase diagram of a sweep draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweepPlot {
    /// The axis along x (a parameter path of the sweep).
    pub x: String,
    /// The axis along y (a heatmap).
    pub y: Option<String>,
    /// The runs drawn: those with these values of other axes, as runs.csv writes them.
    pub fixed: Vec<(String, String)>,
    /// One panel per value of this axis, on shared scales.
    pub facet: Option<String>,
    /// One line per value of this axis on one set of axes (an overlay; a line diagram).
    pub series: Option<String>,
    /// A CSV file of values from a source (`series,label,x,y`) drawn beside the sweep's.
    pub reference: Option<PathBuf>,
    /// The runs.csv column drawn.
    pub metric: String,
    /// The band of a line diagram.
    pub band: Band,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic metric axis (a line diagram).
    pub log_y: bool,
    /// Logarithmic colour scale (a heatmap).
    pub log_colour: bool,
    /// A heatmap's numeric axes in equal cells, in order ([`PhaseOptions::even_cells`]).
    pub even_cells: bool,
    /// A theoretical bound on x drawn as a labelled vertical line.
    pub bound: Option<Bound>,
}

/// Why a sweep could not be drawn: a request the sweep cannot answer (`Refused`: an axis or a
/// metric it does not have, a file flocking did not write; exit code 2 in the CLI), or a failure
/// while reading or writing (`Failed`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SweepPlotError {
    /// The request cannot be drawn as asked; the message says what to give.
    Refused(String),
    /// Reading the sweep or writing the figure failed.
    Failed(String),
}

impl fmt::Display for SweepPlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Refused(message) | Self::Failed(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for SweepPlotError {}

impl From<String> for SweepPlotError {
    fn from(message: String) -> Self {
        Self::Failed(message)
    }
}

/// What [`plot_sweep`] wrote.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plotted {
    /// The file written.
    pub path: PathBuf,
    /// What the reader should know (points pooled over an axis that is neither drawn nor fixed),
    /// without the "warning: " prefix.
    pub warnings: Vec<String>,
}

/// The size of each panel of a faceted diagram.
const FACET_PANEL: (u32, u32) = (560, 420);

/// Draws the phase diagram `request` of the sweep in `dir` into `out` (default
/// `dir/<metric>.svg`): SVG, PNG, or with `.csv` the numbers drawn ([`phase_table`]). Never over
/// a file flocking did not write.
///
/// # Errors
/// [`SweepPlotError::Refused`] for an axis or metric the sweep does not have (a mistyped metric
/// with the nearest names), a value no run has, axes drawn twice, or an existing file flocking
/// did not write; [`SweepPlotError::Failed`] for an I/O error or a `runs.csv` that does not
/// parse.
pub fn plot_sweep(
    dir: &Path,
    request: &SweepPlot,
    out: Option<&Path>,
) -> Result<Plotted, SweepPlotError> {
    let (bytes, warnings, out) = draw_sweep(dir, request, out)?;
    // never over a file that flocking did not write
    owned::write_file(&out, &bytes).map_err(|e| match e {
        DirError::Io(e) => SweepPlotError::Failed(e.to_string()),
        refused => SweepPlotError::Refused(refused.to_string()),
    })?;
    Ok(Plotted {
        path: out,
        warnings,
    })
}

/// A value of runs.csv as a number: booleans as 1 or 0, empty as NaN.
fn number(field: &str) -> Option<f64> {
    match field {
        "true" => Some(1.0),
        "false" => Some(0.0),
        "" => Some(f64::NAN),
        other => other.parse().ok(),
    }
}

/// An axis of the sweep as the plot uses it: its column of runs.csv, its values as runs.csv
/// writes them (in the sweep's order) and its label.
struct AxisColumn {
    column: usize,
    values: Vec<String>,
    label: ParameterLabel,
}

impl AxisColumn {
    /// "n = 50".
    fn equals(&self, value: &str) -> String {
        format!("{} = {}", self.label.short(), shown(value))
    }

    /// "n ∈ {25, 50, 100, 200}".
    fn among(&self) -> String {
        let values: Vec<String> = self.values.iter().map(|v| shown(v)).collect();
        format!("{} ∈ {{{}}}", self.label.short(), values.join(", "))
    }

    /// Whether its values are categories: some value is not a number (an enum variant, a
    /// name).
    fn categorical(&self) -> bool {
        self.values.iter().any(|v| v.parse::<f64>().is_err())
    }

    /// The names of its categories in the sweep's order, or nothing for a numeric axis.
    fn categories(&self) -> Vec<String> {
        if self.categorical() {
            self.values.iter().map(|v| shown(v)).collect()
        } else {
            Vec::new()
        }
    }

    /// The value of `field` on this axis: its category's index, or the number.
    fn position(&self, field: &str) -> Option<f64> {
        if self.categorical() {
            self.values
                .iter()
                .position(|v| v == field)
                .map(|k| k as f64)
        } else {
            number(field)
        }
    }
}

/// "20 seeds", "1 seed".
fn seeds(count: u64) -> String {
    if count == 1 {
        "1 seed".to_owned()
    } else {
        format!("{count} seeds")
    }
}

/// `wanted` is not among `names`, which are `among` ("a metric of DIR/runs.csv", "the metrics"):
/// the message names the nearest ones (Jaro–Winkler similarity above 0.8, at most three), then
/// every one.
fn unknown(what: &str, wanted: &str, names: &[&str], among: (&str, &str)) -> SweepPlotError {
    let mut near: Vec<(f64, &str)> = names
        .iter()
        .map(|&n| (strsim::jaro_winkler(wanted, n), n))
        .filter(|&(score, _)| score > 0.8)
        .collect();
    near.sort_by(|a, b| b.0.total_cmp(&a.0));
    let hint = match near.as_slice() {
        [] => String::new(),
        near => {
            let names: Vec<&str> = near.iter().take(3).map(|&(_, n)| n).collect();
            format!(" (did you mean {}?)", names.join(" or "))
        }
    };
    SweepPlotError::Refused(format!(
        "--{what} {wanted:?} is not {}{hint}; {} are {}",
        among.0,
        among.1,
        names.join(", ")
    ))
}

/// The diagram's bytes, the warnings, and the file they go to.
fn draw_sweep(
    dir: &Path,
    request: &SweepPlot,
    out: Option<&Path>,
) -> Result<(Vec<u8>, Vec<String>, PathBuf), SweepPlotError> {
    let sweep = store::read_sweep(dir).map_err(|e| {
        if e.is_refusal() {
            SweepPlotError::Refused(e.to_string())
        } else {
            SweepPlotError::Failed(e.to_string())
        }
    })?;
    let base = sweep
        .base_scenario()
        .map_err(|e| SweepPlotError::Refused(e.to_string()))?;
    let path = dir.join(RUNS_FILE);
    let mut reader =
        csv::Reader::from_path(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let header = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let names: Vec<&str> = header.iter().collect();
    let among = format!("a column of {}", path.display());
    let column = |name: &str, what: &str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| unknown(what, name, &names, (&among, "its columns")))
    };
    // an axis of the sweep, or its seeds (numbers, drawn as such)
    let axis = |name: &str, what: &str| {
        let values = match sweep.axes.iter().find(|a| a.path == name) {
            Some(axis) => axis.values.expand().iter().map(value_field).collect(),
            None if name == SEED => Vec::new(),
            None => {
                let mut axes: Vec<&str> = sweep.axes.iter().map(|a| a.path.as_str()).collect();
                axes.push(SEED);
                return Err(unknown(
                    what,
                    name,
                    &axes,
                    ("an axis of the sweep", "its axes"),
                ));
            }
        };
        Ok(AxisColumn {
            column: column(name, what)?,
            values,
            label: ParameterLabel::of(&base, name),
        })
    };
    // the measured columns lie between `seed` and `error`; the others are not metrics
    let measured = match (
        header.iter().position(|h| h == SEED),
        header.iter().position(|h| h == "error"),
    ) {
        (Some(seed), Some(error)) if seed < error => seed + 1..error,
        _ => 0..header.len(),
    };
    let metrics = &names[measured.clone()];
    let cm = match header.iter().position(|h| h == request.metric) {
        Some(cm) if measured.contains(&cm) => cm,
        _ => {
            return Err(unknown(
                "metric",
                &request.metric,
                metrics,
                (&format!("a metric of {}", path.display()), "the metrics"),
            ));
        }
    };
    let x = axis(&request.x, "x")?;
    let y = request.y.as_deref().map(|y| axis(y, "y")).transpose()?;
    let mut shown_axes = vec![request.x.as_str()];
    shown_axes.extend(request.y.as_deref());
    let panels = match (&request.facet, &request.series) {
        (Some(_), Some(_)) => {
            return Err(SweepPlotError::Refused(
                "give --facet (panels side by side) or --series (lines on one set of axes), not both"
                    .into(),
            ));
        }
        (Some(name), None) => Some((name, false)),
        (None, Some(name)) => Some((name, true)),
        (None, None) => None,
    };
    let (facet, series) = match panels {
        Some((name, series)) => {
            let what = if series { "series" } else { "facet" };
            if shown_axes.contains(&name.as_str()) {
                return Err(SweepPlotError::Refused(format!(
                    "--{what} {name} is drawn along an axis already; give another axis"
                )));
            }
            if series && y.is_some() {
                return Err(SweepPlotError::Refused(format!(
                    "--series {name} draws lines on one set of axes; a heatmap (--y) takes --facet"
                )));
            }
            shown_axes.push(name);
            (Some(axis(name, what)?), series)
        }
        None => (None, false),
    };
    let mut fixed = Vec::new();
    for (name, value) in &request.fixed {
        if shown_axes.contains(&name.as_str())
            || fixed
                .iter()
                .any(|(a, _): &(AxisColumn, String)| a.label.path == *name)
        {
            return Err(SweepPlotError::Refused(format!(
                "--where {name}={value}: {name} is drawn or fixed already; fix another axis"
            )));
        }
        let fixed_axis = axis(name, "where")?;
        let same = |v: &String| {
            v == value
                || shown(v) == *value
                || matches!((v.parse::<f64>(), value.parse::<f64>()), (Ok(a), Ok(b)) if a == b)
        };
        let Some(chosen) = fixed_axis.values.iter().find(|v| same(v)).cloned() else {
            return Err(SweepPlotError::Refused(format!(
                "--where {name}={value}: no run has {name} = {value}; its values are {}",
                fixed_axis.values.join(", ")
            )));
        };
        fixed.push((fixed_axis, chosen));
    }
    let pooled: Vec<AxisColumn> = sweep
        .axes
        .iter()
        .filter(|a| {
            !shown_axes.contains(&a.path.as_str())
                && !fixed.iter().any(|(f, _)| f.label.path == a.path)
        })
        .map(|a| axis(&a.path, "x"))
        .collect::<Result<_, _>>()?;

    let mut points = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
        if fixed.iter().any(|(a, value)| record[a.column] != **value) {
            continue;
        }
        let row = || format!("{} row {}", path.display(), k + 1);
        let along = |a: &AxisColumn| {
            a.position(&record[a.column]).ok_or_else(|| {
                format!(
                    "{}: {} {:?} is not a value of the sweep",
                    row(),
                    a.label.path,
                    &record[a.column]
                )
            })
        };
        let panel = match &facet {
            Some(a) => a
                .values
                .iter()
                .position(|v| *v == record[a.column])
                .ok_or_else(|| {
                    format!(
                        "{}: {} {:?} is not a value of the sweep",
                        row(),
                        a.label.path,
                        &record[a.column]
                    )
                })?,
            None => 0,
        };
        let value = number(&record[cm])
            .ok_or_else(|| format!("{}: the metric {:?} is not a number", row(), &record[cm]))?;
        points.push(PhasePoint {
            x: along(&x)?,
            y: y.as_ref().map(along).transpose()?,
            value,
            panel,
        });
    }

    let metric = metric_label(&request.metric);
    let per_point = pooled
        .iter()
        .map(|a| a.values.len() as u64)
        .product::<u64>()
        * sweep.seeds;
    let mut title = if pooled.is_empty() {
        format!("{metric}: mean over {}", seeds(sweep.seeds))
    } else {
        let over: Vec<String> = pooled.iter().map(AxisColumn::among).collect();
        format!(
            "{metric}: mean over {per_point} runs pooled over {} × {}",
            over.join(" × "),
            seeds(sweep.seeds)
        )
    };
    for (a, value) in &fixed {
        title = format!("{title}, {}", a.equals(value));
    }
    let mut warnings = Vec::new();
    if !pooled.is_empty() {
        let names: Vec<&str> = pooled.iter().map(|a| a.label.path.as_str()).collect();
        warnings.push(format!(
            "each point pools {per_point} runs over {}: fix {} with --where {}=VALUE, or draw one panel per value with --facet {}",
            names.join(", "),
            if names.len() == 1 { "it" } else { "them" },
            names[0],
            names[0]
        ));
    }
    let options = PhaseOptions {
        title,
        x_label: x.label.axis(),
        y_label: y.as_ref().map(|y| y.label.axis()),
        metric: metric.to_owned(),
        panels: facet
            .as_ref()
            .map_or_else(Vec::new, |a| a.values.iter().map(|v| a.equals(v)).collect()),
        log_x: request.log_x,
        log_y: request.log_y,
        band: request.band,
        size: if facet.is_some() && !series {
            FACET_PANEL
        } else {
            PhaseOptions::default().size
        },
        bound: request.bound.clone(),
        series,
        references: match &request.reference {
            Some(file) => references(file, facet.as_ref())?,
            None => Vec::new(),
        },
        x_categories: x.categories(),
        y_categories: y.as_ref().map_or_else(Vec::new, AxisColumn::categories),
        log_colour: request.log_colour,
        even_cells: request.even_cells,
    };
    let out = out.map_or_else(
        || dir.join(format!("{}.svg", request.metric)),
        Path::to_path_buf,
    );
    let bytes = match out.extension().and_then(|e| e.to_str()) {
        Some("png") => phase_png(&points, &options),
        Some("csv") => phase_table(&points, &options).map(String::into_bytes),
        _ => phase_svg(&points, &options).map(String::into_bytes),
    }
    .map_err(|e| SweepPlotError::Failed(e.to_string()))?;
    Ok((bytes, warnings, out))
}

/// The references of `--reference FILE` (`series,label,x,y`), the series matched to the values
/// of the panels' axis `panels`.
fn references(file: &Path, panels: Option<&AxisColumn>) -> Result<Vec<Reference>, SweepPlotError> {
    let refused = |message: String| SweepPlotError::Refused(message);
    let at = |line: u64| format!("{} line {line}", file.display());
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(file)
        .map_err(|e| refused(format!("--reference {}: {e}", file.display())))?;
    let header = reader
        .headers()
        .map_err(|e| refused(format!("--reference {}: {e}", file.display())))?;
    if header != vec!["series", "label", "x", "y"] {
        return Err(refused(format!(
            "--reference {}: the header is {:?}; give series,label,x,y",
            file.display(),
            header.iter().collect::<Vec<_>>().join(",")
        )));
    }
    let mut references: Vec<Reference> = Vec::new();
    let mut last: Option<(String, String)> = None;
    for record in reader.records() {
        let record = record.map_err(|e| refused(format!("--reference {e}")))?;
        let line = record.position().map_or(0, csv::Position::line);
        let number = |k: usize| {
            record[k]
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    refused(format!(
                        "{}: {:?} is not a finite number",
                        at(line),
                        &record[k]
                    ))
                })
        };
        let point = (number(2)?, number(3)?);
        let key = (record[0].to_owned(), record[1].to_owned());
        if last.as_ref() == Some(&key) {
            references
                .last_mut()
                .expect("the last reference")
                .points
                .push(point);
            continue;
        }
        let series = match (record[0].is_empty(), panels) {
            (true, _) => None,
            (false, Some(axis)) => Some(
                axis.values
                    .iter()
                    .position(|v| {
                        *v == record[0]
                            || matches!((v.parse::<f64>(), record[0].parse::<f64>()), (Ok(a), Ok(b)) if a == b)
                    })
                    .ok_or_else(|| {
                        refused(format!(
                            "{}: series {:?} is not a value of {}; its values are {}",
                            at(line),
                            &record[0],
                            axis.label.path,
                            axis.values.join(", ")
                        ))
                    })?,
            ),
            (false, None) => {
                return Err(refused(format!(
                    "{}: a series ({:?}) needs --series or --facet",
                    at(line),
                    &record[0]
                )));
            }
        };
        references.push(Reference {
            label: key.1.clone(),
            series,
            points: vec![point],
        });
        last = Some(key);
    }
    Ok(references)
}

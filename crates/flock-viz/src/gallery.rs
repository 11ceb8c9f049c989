//! The page of the papers' figures that `flocking figures` writes: per fixture its paper reference,
//! the paper's caption and statements beside our measures ([`crate::papers`]), its description,
//! its snapshot and metric PNGs and a table of its final metrics ([`index_html`]); one
//! self-contained page, no script, no network.

use std::fmt::Write as _;

use flocking::RunSummary;

use crate::metrics::Metrics;
use crate::papers::paper_figure;

/// One fixture on the page.
#[derive(Clone, Debug)]
pub struct FigureEntry {
    /// The fixture's file stem (its directory under the output directory).
    pub stem: String,
    /// The paper and figure the stem names, e.g. "TAC 2006 Fig. 11".
    pub reference: String,
    /// The scenario's `description`.
    pub description: String,
    /// The run's summary.
    pub summary: RunSummary,
    /// The run's `metrics.csv`.
    pub metrics: Metrics,
    /// The figure files kept, relative to the output directory (`/`-separated).
    pub images: Vec<String>,
    /// Whether `<stem>/figures/player.html` was kept (the page links to it).
    pub player: bool,
}

/// The paper and figure a fixture's stem names: `tac2006_fig11_…` → "TAC 2006 Fig. 11"; stems of
/// no paper (or unknown prefixes) give "no paper".
#[must_use]
pub fn paper_reference(stem: &str) -> String {
    let mut parts = stem.split('_');
    let paper = match parts.next().unwrap_or_default() {
        "tac2006" => "Olfati-Saber, TAC 2006",
        "tr2003" => "Olfati-Saber, CDS 03-006 (2003)",
        "cdc2003" => "Olfati-Saber & Murray, CDC 2003",
        "acc2004" => "Olfati-Saber, ACC 2004",
        "tanner2003" => "Tanner, Jadbabaie & Pappas 2003",
        _ => return "no paper".to_owned(),
    };
    match parts.next().and_then(|p| p.strip_prefix("fig")) {
        Some(number) if !number.is_empty() => format!("{paper}, Fig. {number}"),
        _ => paper.to_owned(),
    }
}

/// Escapes text for HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The rows of a fixture's final-metrics table: name and value.
fn metric_rows(summary: &RunSummary) -> Vec<(String, String)> {
    let m = &summary.metrics;
    let mut rows = vec![
        (
            "connectivity C".to_owned(),
            format!("{:.4} ({} component(s))", m.connectivity, m.components),
        ),
        (
            "giant component C*".to_owned(),
            format!("{:.4}", m.giant_component),
        ),
        (
            "deviation energy Ẽ".to_owned(),
            format!("{:.3e}", m.deviation_energy),
        ),
        (
            "velocity mismatch K̃".to_owned(),
            format!("{:.3e}", m.velocity_mismatch),
        ),
        ("min distance".to_owned(), format!("{:.4}", m.min_distance)),
        ("colliding pairs".to_owned(), m.collisions.to_string()),
    ];
    for (name, value) in &summary.diagnostics {
        let value = if *name == "inside_obstacles" {
            format!("{value}")
        } else {
            format!("{value:.4e}")
        };
        rows.push(((*name).replace('_', " "), value));
    }
    rows
}

/// The static page: per fixture its reference, description, PNGs and final metrics.
#[must_use]
pub fn index_html(entries: &[FigureEntry]) -> String {
    let mut html = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>flocking: the papers' figures</title>\n<style>\n\
         body { font-family: sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #222; }\n\
         section { border-top: 1px solid #ccc; padding: 1em 0; }\n\
         img { max-width: 100%; display: block; margin: 0.5em 0; }\n\
         table { border-collapse: collapse; }\n\
         td { padding: 0.15em 0.8em; border-bottom: 1px solid #eee; }\n\
         td.v { font-family: monospace; text-align: right; }\n\
         blockquote { font-style: italic; margin: 0.5em 0 0.5em 1.5em; }\n\
         th { text-align: left; padding: 0.15em 0.8em; border-bottom: 1px solid #ccc; }\n\
         </style>\n</head>\n<body>\n<h1>flocking: the papers' figures</h1>\n\
         <p>Written by <code>flocking figures</code>: every fixture run and drawn; the tables give the \
         metrics at the final time.</p>\n<ul>\n",
    );
    for e in entries {
        let _ = writeln!(
            html,
            "<li><a href=\"#{0}\">{1}</a>: {2}</li>",
            escape(&e.stem),
            escape(&e.reference),
            escape(&e.stem)
        );
    }
    html.push_str("</ul>\n");
    for e in entries {
        let s = &e.summary;
        let _ = writeln!(
            html,
            "<section id=\"{0}\">\n<h2>{1}: <code>{0}</code></h2>\n<p>{2}</p>\n\
             <p>{3}D, n = {4}, {5} steps to t = {6}; {7}\
             <a href=\"{0}/scenario.ron\">scenario</a>, \
             <a href=\"{0}/metrics.csv\">metrics.csv</a>, \
             <a href=\"{0}/flocking.txt\">Definition 5</a></p>",
            escape(&e.stem),
            escape(&e.reference),
            escape(&e.description),
            s.dim,
            s.agents,
            s.steps,
            s.t,
            if e.player {
                format!(
                    "<a href=\"{}/figures/player.html\">player</a>, ",
                    escape(&e.stem)
                )
            } else {
                String::new()
            }
        );
        if let Some(figure) = paper_figure(&e.stem) {
            let _ = writeln!(
                html,
                "<blockquote>{}</blockquote>\n<table>\n<tr><th>the paper</th><th>ours</th></tr>",
                escape(figure.caption)
            );
            for statement in figure.statements {
                let _ = writeln!(
                    html,
                    "<tr><td>{}</td><td>{}</td></tr>",
                    escape(statement.paper),
                    escape(&statement.ours.of(s, &e.metrics))
                );
            }
            html.push_str("</table>\n");
        }
        for image in &e.images {
            let _ = writeln!(
                html,
                "<img src=\"{0}\" alt=\"{0}\" loading=\"lazy\">",
                escape(image)
            );
        }
        html.push_str("<table>\n");
        for (name, value) in metric_rows(s) {
            let _ = writeln!(
                html,
                "<tr><td>{}</td><td class=\"v\">{}</td></tr>",
                escape(&name),
                escape(&value)
            );
        }
        html.push_str("</table>\n</section>\n");
    }
    html.push_str("</body>\n</html>\n");
    html
}

//! The page of the papers' figures that `flocking figures` writes: per fixture its paper reference,
//! a sentence at the top when our run does not reproduce the figure, the paper's caption and
//! statements quoted beside our measures and its parameters marked as the paper's or ours
//! ([`crate::gallery::papers`]), its description, our measures over the whole run
//! ([`crate::gallery::whole_run`]), its snapshot and metric PNGs and a table of its final metrics
//! ([`index_html`]); one self-contained page, no script, no network.

use std::fmt::Write as _;

use flocking::RunSummary;

use crate::curves::functions::ReportFunction;
use crate::data::metric_series::Metrics;
use crate::gallery::papers::paper_figure;
use crate::gallery::whole_run::whole_run_rows;

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
    /// The model's verdict (TAC 2006 Definition 5, or a classic model's states): the first line
    /// of the run's `flocking.txt`.
    pub verdict: String,
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
        let count = [
            "inside_obstacles",
            "stress_towards",
            "stress_away",
            "stress_neutral",
        ];
        let value = if count.contains(name) {
            format!("{value}")
        } else {
            format!("{value:.4e}")
        };
        rows.push(((*name).replace('_', " "), value));
    }
    rows
}

/// Appends a two-column table of `rows` under a header row, the values in `class`.
fn push_table(html: &mut String, header: [&str; 2], rows: &[(String, String)], class: &str) {
    let _ = writeln!(
        html,
        "<table>\n<tr><th>{}</th><th>{}</th></tr>",
        escape(header[0]),
        escape(header[1])
    );
    for (name, value) in rows {
        let _ = writeln!(
            html,
            "<tr><td>{}</td><td{class}>{}</td></tr>",
            escape(name),
            escape(value)
        );
    }
    html.push_str("</table>\n");
}

/// The static page: per fixture its reference, description, PNGs and final metrics; then the
/// report's function plots `functions`, each at [`function_image`] (which `flocking figures`
/// writes).
#[must_use]
pub fn index_html(entries: &[FigureEntry], functions: &[ReportFunction]) -> String {
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
         p.not { background: #fde8e8; border-left: 4px solid #c33; padding: 0.4em 0.8em; }\n\
         </style>\n</head>\n<body>\n<h1>flocking: the papers' figures</h1>\n\
         <p>Written by <code>flocking figures</code>: every fixture run and drawn. Per figure: the \
         paper's caption and statements, quoted from the seeds, beside our measures; its parameters, \
         each the paper's or ours; our measures over the whole run; the metrics at the final time. \
         A figure our run does not reproduce says so at its top.</p>\n<ul>\n",
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
        let figure = paper_figure(&e.stem);
        let _ = writeln!(
            html,
            "<section id=\"{0}\">\n<h2>{1}: <code>{0}</code></h2>\n{8}<p>{2}</p>\n\
             <p>{3}D, n = {4}, {5} steps to t = {6}; {7}\
             <a href=\"{0}/scenario.ron\">scenario</a>, \
             <a href=\"{0}/metrics.csv\">metrics.csv</a>, \
             <a href=\"{0}/flocking.txt\">verdict</a></p>",
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
            },
            figure
                .and_then(|f| f.not_reproduced)
                .map_or_else(String::new, |why| format!(
                    "<p class=\"not\"><strong>Not reproduced:</strong> {}</p>\n",
                    escape(why)
                ))
        );
        if let Some(figure) = figure {
            let _ = writeln!(html, "<blockquote>{}</blockquote>", escape(figure.caption));
            let statements: Vec<(String, String)> = figure
                .statements
                .iter()
                .map(|s| (s.paper.to_owned(), s.ours.of(&e.summary, &e.metrics)))
                .collect();
            push_table(&mut html, ["the paper", "ours"], &statements, "");
            let parameters: Vec<(String, String)> = figure
                .parameters
                .iter()
                .flat_map(|group| group.iter())
                .map(|p| (p.text.to_owned(), p.source.label().to_owned()))
                .collect();
            push_table(&mut html, ["parameter", "from"], &parameters, "");
        }
        push_table(
            &mut html,
            ["over the whole run", "ours"],
            &whole_run_rows(s, &e.metrics, &e.verdict),
            "",
        );
        for image in &e.images {
            let _ = writeln!(
                html,
                "<img src=\"{0}\" alt=\"{0}\" loading=\"lazy\">",
                escape(image)
            );
        }
        push_table(
            &mut html,
            ["at the final time", ""],
            &metric_rows(s),
            " class=\"v\"",
        );
        html.push_str("</section>\n");
    }
    if !functions.is_empty() {
        html.push_str(
            "<section id=\"functions\">\n<h2>Olfati-Saber, CDS 03-006 (2003): the functions</h2>\n\
             <p>Drawn from the functions the simulations call; the parameters of Fig. 5 are the \
             report's Example 2 (d = 10, r = 1.2 d, a = 1, b = 5); the bump's form in Fig. 2 is \
             ours (the cosine influence map of CDC 2003 eq. 5; the report asks only a bump with \
             k₀ = 5/6).</p>\n",
        );
        for function in functions {
            let image = function_image(*function);
            let _ = writeln!(
                html,
                "<blockquote>{}</blockquote>\n<img src=\"{1}\" alt=\"{1}\" loading=\"lazy\">",
                escape(function.caption()),
                escape(&image)
            );
        }
        html.push_str("</section>\n");
    }
    html.push_str("</body>\n</html>\n");
    html
}

/// The directory of the gallery that holds the function plots.
pub const FUNCTIONS_DIR: &str = "functions";

/// The PNG of `function` on the page, relative to the gallery: `functions/<stem>.png`.
#[must_use]
pub fn function_image(function: ReportFunction) -> String {
    format!("{FUNCTIONS_DIR}/{}.png", function.stem())
}

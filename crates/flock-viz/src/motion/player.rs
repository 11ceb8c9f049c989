//! The whole run as ONE self-contained HTML page with a canvas player: play/pause, a scrub slider,
//! a speed selector, an edges toggle, a zoom-to-flock toggle (and for 3D runs a view selector),
//! drawing the agents as
//! oriented triangles, the net's edges (‖q_j − q_i‖ < r), the obstacles and the γ-agent, as the
//! snapshots of TAC 2006 Figs. 10–13 do. The page's script and data are inline: it needs no
//! server and no network.
//!
//! Beside the canvas a readout (`#readout`) gives t and the run's measures at the frame shown
//! (the columns of its `metrics.csv`: C, C*, R, Ẽ, K̃, …, at the record nearest the frame).
//! Agents that have merged (closer than [`MERGE_FRACTION`] · d, or of the range r when the scene
//! has no d: one point, however many markers) are ringed and labelled with their count. A 3D view
//! draws the x, y, z axis triad in its lower right corner. The markers are 10 px whatever the
//! scale, so that 200 agents over 300 m stay visible.
//!
//! A page may be given a byte budget ([`PlayerOptions::max_bytes`], the notebook's embedded
//! player): its frames are then subsampled evenly (first and last kept) until it fits, and the page
//! says so under the canvas (`#note`: "167 of 501 frames, evenly spaced, to fit 1 MB"), as it says
//! when `max_frames` left frames out.
//!
//! The controls have stable ids for tests that drive the page in a browser: `#play` (button),
//! `#scrub` (range input, one step per frame), `#speed` (select, simulated seconds per second),
//! `#edges` (checkbox), `#zoom` (checkbox: frame the flock instead of the whole run), `#view`
//! (select, 3D only), `#canvas`, `#time` (the shown time), `#readout` (a table: time t, then each
//! measure's label, value and unit), `#note` (only when frames were left out) and the data
//! in `<script id="flock-data" type="application/json">`. The canvas's `data-frame` attribute holds
//! the index of the frame drawn, and `window.flockPlayer` offers `frame()`, `frames`, `show(k)`.
//! Unzoomed, a view's `window` `[x0, y0, x1, y1]` is fitted into the canvas with a 12 px margin,
//! centred, y up, and each agent's triangle, filled with [`AGENT`] above the edges, has its centroid
//! on the agent: `tests/browser/player.mjs` checks the page against this in headless Chromium (see
//! `docs/figures.md`).
//!
//! - [`player_html`]: the page.
//! - [`PlayerOptions`]: canvas size, frame budget, the view of 3D runs.

use std::fmt::Write as _;

use serde::Serialize;

use flocking::graph::{Components, NeighbourSearch, ProximityNet};
use flocking::merging::MERGE_FRACTION;
use flocking::run_dir::is_count_column;

use crate::data::metric_series::{Metrics, TIME};
use crate::draw::format;
use crate::draw::style::{
    self, AGENT, BACKGROUND, EDGE, FAILED, GAMMA, INK, OBSTACLE, OBSTACLE_OUTLINE, WALL_PLANE,
};
use crate::error::VizError;
use crate::scene::drawable::{Drawable, Shape};
use crate::scene::frames::Scene;
use crate::scene::framing::Framer;
use crate::scene::projection::View;

/// How the player is built.
#[derive(Clone, Debug, PartialEq)]
pub struct PlayerOptions {
    /// The canvas size in pixels (width, height).
    pub canvas_size: (u32, u32),
    /// At most this many frames are embedded: a longer run is subsampled evenly.
    pub max_frames: usize,
    /// The first view of a 3D run (the top view is always offered beside it).
    pub view: View,
    /// The scenario's unit of length (for the scale bar).
    pub length_unit: String,
    /// At most this many bytes of page, or `None` for no bound: the frames are subsampled further
    /// (evenly, first and last kept) until the page fits, and the page says so.
    pub max_bytes: Option<usize>,
}

impl Default for PlayerOptions {
    fn default() -> Self {
        Self {
            canvas_size: (720, 720),
            max_frames: 2000,
            view: View::default(),
            length_unit: "m".to_owned(),
            max_bytes: None,
        }
    }
}

/// The speeds offered, in simulated seconds per second.
const SPEEDS: [f64; 9] = [0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0];

/// The player page of a run (see the module documentation), with the readout of `metrics` (the
/// run's `metrics.csv`) when given.
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn, the canvas size is 0, or the page
/// cannot fit `max_bytes` even with its first and last frames only.
///
/// # Example
/// ```
/// use flock_viz::{Frame, PlayerOptions, Scene, player_html};
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)];
/// let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]));
/// let html = player_html(&scene, None, &PlayerOptions::default()).unwrap();
/// assert!(html.contains(r#"id="play""#) && html.contains(r#"id="scrub""#));
/// assert!(!html.contains("http"));
/// ```
pub fn player_html(
    scene: &Scene,
    metrics: Option<&Metrics>,
    options: &PlayerOptions,
) -> Result<String, VizError> {
    scene.validate()?;
    let (w, h) = options.canvas_size;
    if w == 0 || h == 0 {
        return Err(VizError::invalid(
            "the player's canvas has a side of 0 pixels",
        ));
    }
    let mut count = options.max_frames.max(1).min(scene.frames.len());
    let mut budget_bound = None;
    loop {
        let frames = scene.evenly_spaced_frames(count);
        let html = page(scene, metrics, &frames, options, budget_bound);
        let Some(budget) = options.max_bytes else {
            return Ok(html);
        };
        if html.len() <= budget {
            return Ok(html);
        }
        if count <= 2 {
            return Err(VizError::invalid(format!(
                "the player of {} agents does not fit {} with two frames ({} bytes): raise max_bytes",
                scene.frames[0].positions.len(),
                bytes_text(budget),
                html.len()
            )));
        }
        // The frames' data is nearly all of the page: shrink it in proportion, 5 % to spare.
        let shrunk = (count as f64 * budget as f64 / html.len() as f64 * 0.95).floor() as usize;
        count = shrunk.clamp(2, count - 1);
        budget_bound = Some(budget);
    }
}

/// `bytes` as the page states its budget: `1 MB`, `500 kB`, `2.5 MB` (SI prefixes).
fn bytes_text(bytes: usize) -> String {
    if bytes >= 1_000_000 {
        format!("{} MB", format::number(bytes as f64 / 1e6, 2))
    } else {
        format!("{} kB", format::number(bytes as f64 / 1e3, 1))
    }
}

/// What the page says of its frames when it holds fewer than the run (`167 of 501 frames, evenly
/// spaced, to fit 1 MB`; the budget when it is why); empty when it holds them all.
fn subsample_note(shown: usize, recorded: usize, budget: Option<usize>) -> String {
    if shown >= recorded {
        return String::new();
    }
    let why = budget.map_or_else(String::new, |b| format!(", to fit {}", bytes_text(b)));
    format!("{shown} of {recorded} frames, evenly spaced{why}")
}

/// The page showing `frames` of the scene.
/// The page showing `frames` of the scene; `budget`: the byte budget, when it is why frames were
/// left out.
fn page(
    scene: &Scene,
    metrics: Option<&Metrics>,
    frames: &[usize],
    options: &PlayerOptions,
    budget: Option<usize>,
) -> String {
    let (w, h) = options.canvas_size;
    let data = data_json(scene, metrics, frames, options);
    let duration = scene.frames[frames[frames.len() - 1]].t - scene.frames[frames[0]].t;
    let title = if scene.title.is_empty() {
        "flocking run".to_owned()
    } else {
        scene.title.clone()
    };

    let mut speeds = String::new();
    let default_speed = default_speed(duration);
    for s in SPEEDS {
        let selected = if s == default_speed { " selected" } else { "" };
        let _ = write!(
            speeds,
            r#"<option value="{v}"{selected}>{v}×</option>"#,
            v = format::number(s, 2)
        );
    }
    let view_select = if scene.dim == 3 {
        r#"<label>view <select id="view"><option value="0" selected>oblique</option><option value="1">top</option></select></label>"#
    } else {
        ""
    };
    let note = subsample_note(frames.len(), scene.frames.len(), budget);

    let mut html = String::with_capacity(data.len() + 8192);
    html.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    let _ = writeln!(html, "<title>{}</title>", escape_html(&title));
    let _ = writeln!(
        html,
        "<style>\nbody {{ font-family: sans-serif; margin: 16px; color: {ink}; background: {bg}; }}\n\
         h1 {{ font-size: 18px; font-weight: normal; margin: 0 0 8px 0; }}\n\
         #controls {{ display: flex; gap: 12px; align-items: center; flex-wrap: wrap; margin-bottom: 8px; font-size: 14px; }}\n\
         #scrub {{ width: 260px; }}\n\
         #time {{ font-variant-numeric: tabular-nums; min-width: 110px; }}\n\
         #stage {{ display: flex; gap: 12px; align-items: flex-start; flex-wrap: wrap; }}\n\
         #readout {{ font-size: 13px; border-collapse: collapse; font-variant-numeric: tabular-nums; }}\n\
         #readout th {{ text-align: left; font-weight: normal; padding: 1px 8px 1px 0; }}\n\
         #readout td {{ text-align: right; padding: 1px 0; min-width: 80px; }}\n\
         #readout td + th {{ padding: 1px 0 1px 4px; }}\n\
         #note {{ font-size: 12px; margin: 4px 0 0 0; }}\n\
         canvas {{ border: 1px solid {ink}; display: block; }}\n</style>\n</head>\n<body>",
        ink = style::hex(INK),
        bg = style::hex(BACKGROUND)
    );
    let _ = writeln!(html, "<h1>{}</h1>", escape_html(&title));
    let _ = writeln!(
        html,
        "<div id=\"controls\">\n<button id=\"play\" type=\"button\">Play</button>\n\
         <input id=\"scrub\" type=\"range\" min=\"0\" max=\"{max}\" step=\"1\" value=\"0\" aria-label=\"frame\">\n\
         <label>speed <select id=\"speed\">{speeds}</select></label>\n\
         <label><input id=\"edges\" type=\"checkbox\" checked> edges</label>\n\
         <label><input id=\"zoom\" type=\"checkbox\"> zoom to flock</label>\n{view_select}\n\
         <span id=\"time\">t = 0 s</span>\n</div>",
        max = frames.len() - 1
    );
    let _ = writeln!(
        html,
        "<div id=\"stage\"><div><canvas id=\"canvas\" width=\"{w}\" height=\"{h}\" data-frame=\"0\"></canvas>"
    );
    if !note.is_empty() {
        let _ = writeln!(html, "<p id=\"note\">{}</p>", escape_html(&note));
    }
    html.push_str(
        "</div>\n<table id=\"readout\" aria-label=\"measures at the frame shown\"></table></div>\n",
    );
    let _ = writeln!(
        html,
        "<script id=\"flock-data\" type=\"application/json\">{data}</script>"
    );
    html.push_str("<script>\n");
    html.push_str(PLAYER_JS);
    html.push_str("</script>\n</body>\n</html>\n");
    html
}

/// The speed (simulated seconds per second) that plays a run of `duration` seconds in about 15 s.
fn default_speed(duration: f64) -> f64 {
    let target = duration / 15.0;
    SPEEDS
        .into_iter()
        .min_by(|a, b| {
            (a.ln() - target.max(1e-9).ln())
                .abs()
                .total_cmp(&(b.ln() - target.max(1e-9).ln()).abs())
        })
        .unwrap_or(1.0)
}

/// Decimals that resolve a thousandth of `extent`.
fn decimals_for(extent: f64) -> usize {
    if !(extent.is_finite() && extent > 0.0) {
        return 3;
    }
    (3.0 - extent.log10().floor()).clamp(0.0, 8.0) as usize
}

/// `x` rounded to `decimals`, `None` (JSON `null`) when not finite. An integer over a power of ten
/// is the double nearest the decimal, so JSON writes it with at most `decimals` digits.
fn rounded(x: f64, decimals: usize) -> Option<f64> {
    let scale = 10f64.powi(decimals as i32);
    x.is_finite().then(|| (x * scale).round() / scale)
}

/// The colours of [`crate::draw::style`], named as the script uses them.
#[derive(Serialize)]
struct Colours {
    background: String,
    ink: String,
    agent: String,
    edge: String,
    obstacle: String,
    plane: String,
    outline: String,
    gamma: String,
    failed: String,
}

impl Colours {
    fn of_style() -> Self {
        Self {
            background: style::hex(BACKGROUND),
            ink: style::hex(INK),
            agent: style::hex(AGENT),
            edge: style::hex(EDGE),
            obstacle: style::hex(OBSTACLE),
            plane: style::hex(WALL_PLANE),
            outline: style::hex(OBSTACLE_OUTLINE),
            gamma: style::hex(GAMMA),
            failed: style::hex(FAILED),
        }
    }
}

/// The data the script reads: per frame its time `t`, positions `q` and velocities `p` (flat,
/// `dim` numbers per agent, `null` where not finite), the γ-agent `g` and, for a run with faults,
/// the agents failed by then (`failed`); the views.
#[derive(Serialize)]
struct PlayerData<'a> {
    title: &'a str,
    dim: usize,
    range: Option<f64>,
    unit: &'a str,
    colours: Colours,
    t: Vec<Option<f64>>,
    q: Vec<Vec<Option<f64>>>,
    p: Vec<Vec<Option<f64>>>,
    g: Vec<Option<Vec<Option<f64>>>>,
    views: Vec<ViewData<'a>>,
    /// The fixed interaction graph's edges (i, j) flattened, drawn instead of the proximity net.
    #[serde(skip_serializing_if = "Option::is_none")]
    edges: Option<Vec<u32>>,
    /// Per frame, the agents that have failed, when any frame has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    failed: Option<Vec<Vec<u32>>>,
    /// Per frame, the points where agents have merged, flattened as (first agent, count) pairs,
    /// when any frame has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    merged: Option<Vec<Vec<u32>>>,
    /// The readout's measures at each frame (the run's metrics), when the run has them.
    measures: Vec<MeasureData>,
}

/// One row of the readout: a label, its unit ("" for a ratio or count), whether it counts
/// (printed as a whole number), and its value at each frame (4 significant digits, `null` where
/// not finite).
#[derive(Serialize)]
struct MeasureData {
    label: String,
    unit: &'static str,
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    count: bool,
    v: Vec<Option<f64>>,
}

/// How the readout names the columns of `metrics.csv` (docs/outputs.md) and their units; a
/// column not listed shows under its own name, without unit. `nearest_neighbour_min` is left out:
/// it equals `min_distance`.
const READOUT: [(&str, &str, &str); 15] = [
    ("connectivity", "connectivity C", ""),
    ("giant_component", "giant component C*", ""),
    ("components", "groups", ""),
    ("cohesion_radius", "cohesion radius R", "m"),
    ("deviation_energy", "deviation energy Ẽ", ""),
    ("velocity_mismatch", "velocity mismatch K̃", "m²/s²"),
    ("energy", "energy H", "m²/s²"),
    ("min_distance", "least distance", "m"),
    ("collisions", "colliding pairs", ""),
    ("polarisation", "polarisation", ""),
    ("milling", "milling", ""),
    ("nearest_neighbour_mean", "mean nearest neighbour", "m"),
    ("group_speed", "group speed ‖p_c‖", "m/s"),
    ("gamma_position_error", "‖q̄ − q_r‖", "m"),
    ("gamma_velocity_error", "‖p̄ − p_r‖", "m/s"),
];

/// The readout's rows: the columns of `metrics` but `t` (in [`READOUT`]'s order, then the others
/// in the file's), each at the record nearest each of `frames`.
fn measures(scene: &Scene, metrics: Option<&Metrics>, frames: &[usize]) -> Vec<MeasureData> {
    let Some(metrics) = metrics.filter(|m| !m.is_empty()) else {
        return Vec::new();
    };
    let times = metrics.time();
    let rows: Vec<usize> = frames
        .iter()
        .map(|&f| nearest(times, scene.frames[f].t))
        .collect();
    let known = READOUT.iter().filter_map(|&(column, label, unit)| {
        Some((column, metrics.column(column)?, label.to_owned(), unit))
    });
    let others = metrics
        .names()
        .iter()
        .filter(|name| {
            name.as_str() != TIME
                && name.as_str() != "nearest_neighbour_min"
                && !READOUT.iter().any(|(column, _, _)| column == name)
        })
        .filter_map(|name| {
            Some((
                name.as_str(),
                metrics.column(name)?,
                name.replace('_', " "),
                "",
            ))
        });
    known
        .chain(others)
        .map(|(column, values, label, unit)| MeasureData {
            label,
            unit,
            count: is_count_column(column),
            v: rows.iter().map(|&k| significant(values[k], 4)).collect(),
        })
        .collect()
}

/// The index of the value of the ascending `times` nearest `t` (the earlier on a tie).
fn nearest(times: &[f64], t: f64) -> usize {
    let k = times.partition_point(|&x| x < t);
    if k == 0 {
        0
    } else if k == times.len() || t - times[k - 1] <= times[k] - t {
        k - 1
    } else {
        k
    }
}

/// `x` rounded to `digits` significant digits, `None` when not finite.
fn significant(x: f64, digits: i32) -> Option<f64> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some(0.0);
    }
    let decimals = digits - 1 - x.abs().log10().floor() as i32;
    let scale = 10f64.powi(decimals);
    Some(if decimals >= 0 {
        (x * scale).round() / scale
    } else {
        (x / 10f64.powi(-decimals)).round() * 10f64.powi(-decimals)
    })
}

/// The points where agents of a frame have merged, flattened as (first agent, count) pairs:
/// the groups of agents within `tolerance` of another (chains of such pairs).
fn merged_points(positions: &[glam::DVec3], tolerance: f64) -> Vec<u32> {
    let mut net = ProximityNet::new();
    NeighbourSearch::new().build(positions, tolerance, &mut net);
    let groups = Components::of(net.graph());
    let mut first = vec![u32::MAX; groups.count()];
    for (i, &label) in groups.labels().iter().enumerate() {
        if first[label as usize] == u32::MAX {
            first[label as usize] = i as u32;
        }
    }
    groups
        .sizes()
        .iter()
        .zip(first)
        .filter(|&(&size, _)| size > 1)
        .flat_map(|(&size, agent)| [agent, size as u32])
        .collect()
}

/// A view: its projection basis (`u`, `v`), the run's window `[x0, y0, x1, y1]` and the obstacles
/// drawn in it.
#[derive(Serialize)]
struct ViewData<'a> {
    name: &'a str,
    u: [Option<f64>; 3],
    v: [Option<f64>; 3],
    window: [Option<f64>; 4],
    obstacles: Vec<ObstacleData>,
}

/// A projected obstacle: a disc (`c`, `r`) or a polygon (flat `poly`), `plane` for a wall.
#[derive(Serialize)]
#[serde(untagged)]
enum ObstacleData {
    Disc {
        c: [Option<f64>; 2],
        r: Option<f64>,
    },
    Polygon {
        poly: Vec<Option<f64>>,
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        plane: bool,
    },
}

/// The player's data as compact JSON (numbers rounded to a thousandth of the run's extent), with
/// `<`, `>` and `&` escaped so that it cannot close the script.
fn data_json(
    scene: &Scene,
    metrics: Option<&Metrics>,
    frames: &[usize],
    options: &PlayerOptions,
) -> String {
    let dim = scene.dim;
    let views: Vec<(&str, View)> = if dim == 3 {
        vec![("oblique", options.view), ("top", View::TOP)]
    } else {
        vec![("xy", options.view)]
    };
    let framers: Vec<Framer<'_>> = views
        .iter()
        .map(|&(_, view)| Framer::new(scene, view, 0))
        .collect();
    let extent = framers[0].run_window().size().max_element();
    let dq = decimals_for(extent);
    let speed = frames
        .iter()
        .flat_map(|&k| scene.frames[k].velocities.iter())
        .map(|p| p.abs().max_element())
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let dp = decimals_for(speed);
    let flat = |vectors: &[glam::DVec3], d: usize| -> Vec<Option<f64>> {
        vectors
            .iter()
            .flat_map(|v| (0..dim).map(move |c| rounded(v[c], d)))
            .collect()
    };
    let views = views
        .iter()
        .zip(&framers)
        .map(|(&(name, view), framer)| {
            let (u, v, _) = view.basis();
            let window = framer.run_window();
            // Walls are cut to the whole run's box, padded by the window so they reach the border.
            let world = framer.world_for(window.padded(window.size().max_element()));
            let obstacles = Drawable::project_all(&scene.obstacles, view, dim, world)
                .into_iter()
                .map(|(shape, _)| match shape {
                    Shape::Circle { centre, radius } => ObstacleData::Disc {
                        c: [rounded(centre.x, dq), rounded(centre.y, dq)],
                        r: rounded(radius, dq),
                    },
                    Shape::Polygon(points) => ObstacleData::Polygon {
                        poly: points
                            .iter()
                            .flat_map(|p| [rounded(p.x, dq), rounded(p.y, dq)])
                            .collect(),
                        plane: false,
                    },
                    Shape::Plane(points) => ObstacleData::Polygon {
                        poly: points
                            .iter()
                            .flat_map(|p| [rounded(p.x, dq), rounded(p.y, dq)])
                            .collect(),
                        plane: true,
                    },
                })
                .collect();
            ViewData {
                name,
                u: [u.x, u.y, u.z].map(|x| rounded(x, 9)),
                v: [v.x, v.y, v.z].map(|x| rounded(x, 9)),
                window: [window.min.x, window.min.y, window.max.x, window.max.y]
                    .map(|x| rounded(x, dq)),
                obstacles,
            }
        })
        .collect();
    let data = PlayerData {
        title: &scene.title,
        dim,
        range: rounded(scene.range, 6),
        unit: &options.length_unit,
        colours: Colours::of_style(),
        t: frames
            .iter()
            .map(|&f| rounded(scene.frames[f].t, 4))
            .collect(),
        q: frames
            .iter()
            .map(|&f| flat(&scene.frames[f].positions, dq))
            .collect(),
        p: frames
            .iter()
            .map(|&f| {
                let frame = &scene.frames[f];
                flat(frame.headings.as_ref().unwrap_or(&frame.velocities), dp)
            })
            .collect(),
        g: frames
            .iter()
            .map(|&f| scene.frames[f].gamma.map(|g| flat(&[g], dq)))
            .collect(),
        views,
        edges: scene
            .interaction_graph
            .as_ref()
            .map(|edges| edges.iter().flat_map(|&(i, j)| [i, j]).collect()),
        failed: frames
            .iter()
            .any(|&f| scene.frames[f].failed_count() > 0)
            .then(|| {
                frames
                    .iter()
                    .map(|&f| {
                        let frame = &scene.frames[f];
                        (0..frame.positions.len())
                            .filter(|&i| frame.has_failed(i))
                            .map(|i| i as u32)
                            .collect()
                    })
                    .collect()
            }),
        merged: {
            let tolerance = MERGE_FRACTION * scene.desired_distance.unwrap_or(scene.range);
            let merged: Vec<Vec<u32>> = frames
                .iter()
                .map(|&f| merged_points(&scene.frames[f].positions, tolerance))
                .collect();
            merged.iter().any(|m| !m.is_empty()).then_some(merged)
        },
        measures: measures(scene, metrics, frames),
    };
    let json = serde_json::to_string(&data).expect("plain data serializes");
    // In JSON these characters can only stand inside strings, where the escapes mean the same.
    json.replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026")
}

/// Text escaped for HTML content.
fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The player's script (`assets/player.js`); its colours come from the data.
const PLAYER_JS: &str = include_str!("../../assets/player.js");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_data_cannot_close_the_script() {
        let q = [glam::DVec2::ZERO];
        let scene = Scene::new(2, 8.4)
            .with_title("a</script>&\"")
            .with_frame(crate::Frame::from_vectors(0.0, &q, &q));
        let json = data_json(&scene, None, &[0], &PlayerOptions::default());
        assert!(
            !json.contains('<') && !json.contains('>') && !json.contains('&'),
            "{json}"
        );
        let back: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
        assert_eq!(back["title"], "a</script>&\"");
        assert_eq!(back["q"][0], serde_json::json!([0.0, 0.0]));
    }

    #[test]
    fn numbers_are_rounded_to_their_decimals_and_non_finite_ones_are_null() {
        assert_eq!(rounded(0.123_456, 3), Some(0.123));
        assert_eq!(
            serde_json::to_string(&rounded(2.0 / 3.0, 2)).unwrap(),
            "0.67"
        );
        assert_eq!(rounded(f64::NAN, 3), None);
    }

    #[test]
    fn default_speed_plays_in_about_fifteen_seconds() {
        assert_eq!(default_speed(100.0), 5.0);
        assert_eq!(default_speed(4.0), 0.25);
        assert_eq!(default_speed(0.0), 0.25);
    }

    #[test]
    fn measures_keep_four_significant_digits() {
        assert_eq!(significant(2.811_449e-4, 4), Some(2.811e-4));
        assert_eq!(significant(40.133_12, 4), Some(40.13));
        assert_eq!(significant(578_810.0, 4), Some(578_800.0));
        assert_eq!(significant(0.0, 4), Some(0.0));
        assert_eq!(significant(f64::INFINITY, 4), None);
    }

    #[test]
    fn the_nearest_record_is_found_on_either_side() {
        let times = [0.0, 0.2, 0.4, 0.6];
        assert_eq!(nearest(&times, -1.0), 0);
        assert_eq!(nearest(&times, 0.29), 1);
        assert_eq!(nearest(&times, 0.31), 2);
        assert_eq!(nearest(&times, 0.3), 1);
        assert_eq!(nearest(&times, 9.0), 3);
    }

    #[test]
    fn merged_agents_are_one_point_with_their_count() {
        use glam::DVec3;
        // agents 1, 3 and 4 on one point (a chain within the tolerance), 0 and 2 apart
        let q = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(5.0, 3.0, 0.0),
            DVec3::new(5.0005, 0.0, 0.0),
            DVec3::new(5.0, 0.0005, 0.0),
        ];
        assert_eq!(merged_points(&q, 7e-3), vec![1, 3]);
        assert_eq!(merged_points(&q, 1e-4), Vec::<u32>::new());
    }

    #[test]
    fn the_note_says_how_the_frames_were_subsampled() {
        assert_eq!(subsample_note(501, 501, Some(1_000_000)), "");
        assert_eq!(
            subsample_note(167, 501, Some(1_000_000)),
            "167 of 501 frames, evenly spaced, to fit 1 MB"
        );
        assert_eq!(
            subsample_note(51, 501, None),
            "51 of 501 frames, evenly spaced"
        );
        assert_eq!(bytes_text(2_500_000), "2.5 MB");
        assert_eq!(bytes_text(500_000), "500 kB");
    }

    #[test]
    fn decimals_resolve_a_thousandth() {
        assert_eq!(decimals_for(100.0), 1);
        assert_eq!(decimals_for(1.0), 3);
        assert_eq!(decimals_for(5000.0), 0);
    }
}

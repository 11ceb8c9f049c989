//! The whole run as ONE self-contained HTML page with a canvas player: play/pause, a scrub slider,
//! a speed selector, an edges toggle, a zoom-to-flock toggle (and for 3D runs a view selector),
//! drawing the agents as
//! oriented triangles, the net's edges (‖q_j − q_i‖ < r), the obstacles and the γ-agent, as the
//! snapshots of TAC 2006 Figs. 10–13 do. The page's script and data are inline: it needs no
//! server and no network.
//!
//! The controls have stable ids for tests that drive the page in a browser: `#play` (button),
//! `#scrub` (range input, one step per frame), `#speed` (select, simulated seconds per second),
//! `#edges` (checkbox), `#zoom` (checkbox: frame the flock instead of the whole run), `#view`
//! (select, 3D only), `#canvas`, `#time` (the shown time) and the data
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

use crate::drawable::{Drawable, Shape};
use crate::error::VizError;
use crate::format;
use crate::framing::Framer;
use crate::scene::Scene;
use crate::style::{
    self, AGENT, BACKGROUND, EDGE, GAMMA, INK, OBSTACLE, OBSTACLE_OUTLINE, WALL_PLANE,
};
use crate::view::View;

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
}

impl Default for PlayerOptions {
    fn default() -> Self {
        Self {
            canvas_size: (720, 720),
            max_frames: 2000,
            view: View::default(),
            length_unit: "m".to_owned(),
        }
    }
}

/// The speeds offered, in simulated seconds per second.
const SPEEDS: [f64; 9] = [0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0];

/// The player page of a run (see the module documentation).
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn or the canvas size is 0.
///
/// # Example
/// ```
/// use flock_viz::{Frame, PlayerOptions, Scene, player_html};
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)];
/// let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]));
/// let html = player_html(&scene, &PlayerOptions::default()).unwrap();
/// assert!(html.contains(r#"id="play""#) && html.contains(r#"id="scrub""#));
/// assert!(!html.contains("http"));
/// ```
pub fn player_html(scene: &Scene, options: &PlayerOptions) -> Result<String, VizError> {
    scene.validate()?;
    let (w, h) = options.canvas_size;
    if w == 0 || h == 0 {
        return Err(VizError::invalid(
            "the player's canvas has a side of 0 pixels",
        ));
    }
    let frames = scene.evenly_spaced_frames(options.max_frames.max(1).min(scene.frames.len()));
    let data = data_json(scene, &frames, options);
    let duration = scene.frames[frames[frames.len() - 1]].t - scene.frames[frames[0]].t;
    let title = if scene.title.is_empty() {
        "flock run".to_owned()
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
        "<canvas id=\"canvas\" width=\"{w}\" height=\"{h}\" data-frame=\"0\"></canvas>"
    );
    let _ = writeln!(
        html,
        "<script id=\"flock-data\" type=\"application/json\">{data}</script>"
    );
    html.push_str("<script>\n");
    html.push_str(&PLAYER_JS.replace("/*COLOURS*/", &colours_js()));
    html.push_str("</script>\n</body>\n</html>\n");
    Ok(html)
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

/// The colours of [`crate::style`] as a JavaScript object literal.
fn colours_js() -> String {
    format!(
        "const COLOURS = {{ background: '{}', ink: '{}', agent: '{}', edge: '{}', obstacle: '{}', plane: '{}', outline: '{}', gamma: '{}' }};",
        style::hex(BACKGROUND),
        style::hex(INK),
        style::hex(AGENT),
        style::hex(EDGE),
        style::hex(OBSTACLE),
        style::hex(WALL_PLANE),
        style::hex(OBSTACLE_OUTLINE),
        style::hex(GAMMA),
    )
}

/// Decimals that resolve a thousandth of `extent`.
fn decimals_for(extent: f64) -> usize {
    if !(extent.is_finite() && extent > 0.0) {
        return 3;
    }
    (3.0 - extent.log10().floor()).clamp(0.0, 8.0) as usize
}

/// The player's data as compact JSON (numbers rounded to a thousandth of the run's extent).
fn data_json(scene: &Scene, frames: &[usize], options: &PlayerOptions) -> String {
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
    let num = |x: f64, d: usize| {
        if x.is_finite() {
            format::number(x, d)
        } else {
            "null".to_owned()
        }
    };

    let mut s = String::new();
    let _ = write!(
        s,
        "{{\"title\":{},\"dim\":{dim},\"range\":{},\"unit\":{},",
        json_string(&scene.title),
        num(scene.range, 6),
        json_string(&options.length_unit)
    );
    s.push_str("\"t\":[");
    for (k, &f) in frames.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        s.push_str(&num(scene.frames[f].t, 4));
    }
    s.push_str("],\"q\":[");
    let push_vectors = |s: &mut String, vectors: &[glam::DVec3], d: usize| {
        s.push('[');
        for (i, v) in vectors.iter().enumerate() {
            for c in 0..dim {
                if i > 0 || c > 0 {
                    s.push(',');
                }
                s.push_str(&num(v[c], d));
            }
        }
        s.push(']');
    };
    for (k, &f) in frames.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        push_vectors(&mut s, &scene.frames[f].positions, dq);
    }
    s.push_str("],\"p\":[");
    for (k, &f) in frames.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        push_vectors(&mut s, &scene.frames[f].velocities, dp);
    }
    s.push_str("],\"g\":[");
    for (k, &f) in frames.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        match scene.frames[f].gamma {
            Some(g) => push_vectors(&mut s, &[g], dq),
            None => s.push_str("null"),
        }
    }
    s.push_str("],\"views\":[");
    for (k, ((name, view), framer)) in views.iter().zip(&framers).enumerate() {
        if k > 0 {
            s.push(',');
        }
        let (u, v, _) = view.basis();
        let window = framer.run_window();
        let _ = write!(
            s,
            "{{\"name\":{},\"u\":[{},{},{}],\"v\":[{},{},{}],\"window\":[{},{},{},{}],\"obstacles\":[",
            json_string(name),
            num(u.x, 9),
            num(u.y, 9),
            num(u.z, 9),
            num(v.x, 9),
            num(v.y, 9),
            num(v.z, 9),
            num(window.min.x, dq),
            num(window.min.y, dq),
            num(window.max.x, dq),
            num(window.max.y, dq),
        );
        // Walls are cut to the whole run's box, padded by the window so they reach the border.
        let world = framer.world_for(window.padded(window.size().max_element()));
        let mut first = true;
        for shape in Drawable::project_all(&scene.obstacles, *view, dim, world) {
            if !first {
                s.push(',');
            }
            first = false;
            let plane = matches!(shape, Shape::Plane(_));
            match shape {
                Shape::Circle { centre, radius } => {
                    let _ = write!(
                        s,
                        "{{\"c\":[{},{}],\"r\":{}}}",
                        num(centre.x, dq),
                        num(centre.y, dq),
                        num(radius, dq)
                    );
                }
                Shape::Polygon(points) | Shape::Plane(points) => {
                    s.push_str(if plane {
                        "{\"plane\":1,\"poly\":["
                    } else {
                        "{\"poly\":["
                    });
                    for (i, p) in points.iter().enumerate() {
                        if i > 0 {
                            s.push(',');
                        }
                        let _ = write!(s, "{},{}", num(p.x, dq), num(p.y, dq));
                    }
                    s.push_str("]}");
                }
            }
        }
        s.push_str("]}");
    }
    s.push_str("]}");
    s
}

/// A JSON string literal, with `<`, `>` and `&` escaped so that it cannot close the script.
fn json_string(text: &str) -> String {
    let mut s = String::with_capacity(text.len() + 2);
    s.push('"');
    for c in text.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '<' => s.push_str("\\u003c"),
            '>' => s.push_str("\\u003e"),
            '&' => s.push_str("\\u0026"),
            c if (c as u32) < 0x20 => {
                let _ = write!(s, "\\u{:04x}", c as u32);
            }
            c => s.push(c),
        }
    }
    s.push('"');
    s
}

/// Text escaped for HTML content.
fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The player's script. `/*COLOURS*/` is replaced by the colours of [`crate::style`].
const PLAYER_JS: &str = r#"'use strict';
(function () {
/*COLOURS*/
const data = JSON.parse(document.getElementById('flock-data').textContent);
const canvas = document.getElementById('canvas');
const ctx = canvas.getContext('2d');
const playButton = document.getElementById('play');
const scrub = document.getElementById('scrub');
const speedSelect = document.getElementById('speed');
const edgesBox = document.getElementById('edges');
const zoomBox = document.getElementById('zoom');
const viewSelect = document.getElementById('view');
const timeLabel = document.getElementById('time');
const dim = data.dim;
const frames = data.t.length;
const r2 = data.range * data.range;
let current = 0;
let playing = false;
let simTime = data.t[0];
let lastStamp = null;

function fmt(x) {
  return (Math.round(x * 100) / 100).toString();
}

// The proximity net: pairs i < j with |q_j - q_i|^2 < r^2, found on a grid of cells of side r.
function edgesOf(q) {
  const n = q.length / dim;
  const out = [];
  if (!(data.range > 0)) return out;
  const cells = new Map();
  const key = (a, b, c) => a + ',' + b + ',' + c;
  const cellOf = (i) => [0, 1, 2].map((c) => (c < dim ? Math.floor(q[i * dim + c] / data.range) : 0));
  for (let i = 0; i < n; i++) {
    if (q[i * dim] === null) continue;
    const [a, b, c] = cellOf(i);
    const k = key(a, b, c);
    if (!cells.has(k)) cells.set(k, []);
    cells.get(k).push(i);
  }
  for (let i = 0; i < n; i++) {
    if (q[i * dim] === null) continue;
    const [a, b, c] = cellOf(i);
    for (let da = -1; da <= 1; da++) for (let db = -1; db <= 1; db++) for (let dc = (dim === 3 ? -1 : 0); dc <= (dim === 3 ? 1 : 0); dc++) {
      const list = cells.get(key(a + da, b + db, c + dc));
      if (!list) continue;
      for (const j of list) {
        if (j <= i) continue;
        let d2 = 0;
        for (let e = 0; e < dim; e++) { const d = q[j * dim + e] - q[i * dim + e]; d2 += d * d; }
        if (d2 < r2) out.push(i, j);
      }
    }
  }
  return out;
}

function currentView() {
  return data.views[viewSelect ? Number(viewSelect.value) : 0];
}

function project(view, v, i) {
  if (dim === 2) return [v[i * 2], v[i * 2 + 1]];
  const x = v[i * 3], y = v[i * 3 + 1], z = v[i * 3 + 2];
  return [view.u[0] * x + view.u[1] * y + view.u[2] * z, view.v[0] * x + view.v[1] * y + view.v[2] * z];
}

// The window around the agents and the gamma-agent of a frame, with a margin of half the range.
function flockWindow(view, q) {
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  const add = (c) => {
    if (c[0] === null || !isFinite(c[0]) || !isFinite(c[1])) return;
    x0 = Math.min(x0, c[0]); x1 = Math.max(x1, c[0]);
    y0 = Math.min(y0, c[1]); y1 = Math.max(y1, c[1]);
  };
  for (let i = 0; i < q.length / dim; i++) add(project(view, q, i));
  if (data.g[current]) add(project(view, data.g[current], 0));
  if (!(x0 <= x1)) return view.window;
  const pad = Math.max(data.range / 2, 0.04 * Math.max(x1 - x0, y1 - y0), 1e-9);
  return [x0 - pad, y0 - pad, x1 + pad, y1 + pad];
}

function draw() {
  const view = currentView();
  const W = canvas.width, H = canvas.height, pad = 12;
  const q = data.q[current], p = data.p[current];
  const n = q.length / dim;
  const [x0, y0, x1, y1] = zoomBox.checked ? flockWindow(view, q) : view.window;
  const s = Math.min((W - 2 * pad) / (x1 - x0), (H - 2 * pad) / (y1 - y0));
  const ox = (W - s * (x1 - x0)) / 2, oy = (H - s * (y1 - y0)) / 2;
  const X = (x) => ox + (x - x0) * s;
  const Y = (y) => H - (oy + (y - y0) * s);
  ctx.fillStyle = COLOURS.background;
  ctx.fillRect(0, 0, W, H);

  for (const o of view.obstacles) {
    ctx.beginPath();
    if (o.poly) {
      for (let k = 0; k < o.poly.length; k += 2) {
        if (k === 0) ctx.moveTo(X(o.poly[k]), Y(o.poly[k + 1]));
        else ctx.lineTo(X(o.poly[k]), Y(o.poly[k + 1]));
      }
      ctx.closePath();
    } else {
      ctx.arc(X(o.c[0]), Y(o.c[1]), o.r * s, 0, 2 * Math.PI);
    }
    ctx.fillStyle = o.plane ? COLOURS.plane : COLOURS.obstacle;
    ctx.fill();
    ctx.strokeStyle = COLOURS.outline;
    ctx.lineWidth = 1;
    ctx.stroke();
  }

  if (edgesBox.checked) {
    const e = edgesOf(q);
    ctx.strokeStyle = COLOURS.edge;
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (let k = 0; k < e.length; k += 2) {
      const a = project(view, q, e[k]), b = project(view, q, e[k + 1]);
      ctx.moveTo(X(a[0]), Y(a[1]));
      ctx.lineTo(X(b[0]), Y(b[1]));
    }
    ctx.stroke();
  }

  ctx.fillStyle = COLOURS.agent;
  const L = 10;
  for (let i = 0; i < n; i++) {
    if (q[i * dim] === null) continue;
    const c = project(view, q, i), h = project(view, p, i);
    const cx = X(c[0]), cy = Y(c[1]);
    const len = Math.hypot(h[0], h[1]);
    ctx.beginPath();
    if (len > 0) {
      const ex = h[0] / len, ey = -h[1] / len;
      const sx = -ey * 0.36 * L, sy = ex * 0.36 * L;
      const bx = cx - ex * L / 3, by = cy - ey * L / 3;
      ctx.moveTo(cx + ex * 2 * L / 3, cy + ey * 2 * L / 3);
      ctx.lineTo(bx + sx, by + sy);
      ctx.lineTo(bx - sx, by - sy);
      ctx.closePath();
    } else {
      ctx.arc(cx, cy, L / 4, 0, 2 * Math.PI);
    }
    ctx.fill();
  }

  const g = data.g[current];
  if (g) {
    const c = project(view, g, 0);
    const gx = X(c[0]), gy = Y(c[1]), R = 0.7 * L;
    ctx.beginPath();
    ctx.moveTo(gx + R, gy); ctx.lineTo(gx, gy - R); ctx.lineTo(gx - R, gy); ctx.lineTo(gx, gy + R);
    ctx.closePath();
    ctx.fillStyle = COLOURS.gamma;
    ctx.fill();
    ctx.strokeStyle = COLOURS.ink;
    ctx.stroke();
  }

  // A scale bar of a round length, about a fifth of the window.
  const target = (x1 - x0) / 5;
  const pow = Math.pow(10, Math.floor(Math.log10(target)));
  const bar = [1, 2, 5, 10].map((m) => m * pow).filter((b) => b <= target).pop() || pow;
  ctx.strokeStyle = COLOURS.ink;
  ctx.fillStyle = COLOURS.ink;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.moveTo(16, H - 16);
  ctx.lineTo(16 + bar * s, H - 16);
  ctx.stroke();
  ctx.font = '13px sans-serif';
  ctx.fillText(fmt(bar) + ' ' + data.unit, 16, H - 22);

  timeLabel.textContent = 't = ' + fmt(data.t[current]) + ' s';
  scrub.value = String(current);
  canvas.dataset.frame = String(current);
}

function show(k) {
  current = Math.max(0, Math.min(frames - 1, k));
  simTime = data.t[current];
  draw();
}

function frameAt(t) {
  let k = current;
  while (k + 1 < frames && data.t[k + 1] <= t) k++;
  while (k > 0 && data.t[k] > t) k--;
  return k;
}

function tick(stamp) {
  if (!playing) return;
  if (lastStamp !== null) {
    simTime += (stamp - lastStamp) / 1000 * Number(speedSelect.value);
  }
  lastStamp = stamp;
  const k = frameAt(simTime);
  if (k !== current) { current = k; draw(); }
  if (current >= frames - 1) { setPlaying(false); return; }
  requestAnimationFrame(tick);
}

function setPlaying(on) {
  playing = on;
  playButton.textContent = on ? 'Pause' : 'Play';
  lastStamp = null;
  if (on) {
    if (current >= frames - 1) show(0);
    requestAnimationFrame(tick);
  }
}

playButton.addEventListener('click', () => setPlaying(!playing));
scrub.addEventListener('input', () => show(Number(scrub.value)));
edgesBox.addEventListener('change', draw);
zoomBox.addEventListener('change', draw);
if (viewSelect) viewSelect.addEventListener('change', draw);
window.flockPlayer = { frames: frames, frame: () => current, show: show, play: () => setPlaying(true), pause: () => setPlaying(false) };
draw();
})();
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_strings_cannot_close_the_script() {
        assert_eq!(
            json_string("a</script>\"\n"),
            r#""a\u003c/script\u003e\"\u000a""#
        );
    }

    #[test]
    fn default_speed_plays_in_about_fifteen_seconds() {
        assert_eq!(default_speed(100.0), 5.0);
        assert_eq!(default_speed(4.0), 0.25);
        assert_eq!(default_speed(0.0), 0.25);
    }

    #[test]
    fn decimals_resolve_a_thousandth() {
        assert_eq!(decimals_for(100.0), 1);
        assert_eq!(decimals_for(1.0), 3);
        assert_eq!(decimals_for(5000.0), 0);
    }
}

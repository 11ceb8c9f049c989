// The player of `flocking run --plot` (crates/flock-viz/src/player.rs embeds this file in the page):
// draws one frame of the run data in <script id="flock-data"> on the canvas — agents as oriented
// triangles (failed ones as crosses), the proximity net's edges (|q_j - q_i| < r; a fixed graph's
// `edges` if the data has them), obstacles, the gamma-agent, a scale bar, merged agents ringed with
// their count, the x, y, z axis triad of a 3D view — and a readout of t and the run's measures at
// the frame shown (`measures`); plays, scrubs, zooms and (3D) switches views. Colours come from the
// data (`colours`).
'use strict';
(function () {
const data = JSON.parse(document.getElementById('flock-data').textContent);
const COLOURS = data.colours;
const canvas = document.getElementById('canvas');
const ctx = canvas.getContext('2d');
const playButton = document.getElementById('play');
const scrub = document.getElementById('scrub');
const speedSelect = document.getElementById('speed');
const edgesBox = document.getElementById('edges');
const zoomBox = document.getElementById('zoom');
const viewSelect = document.getElementById('view');
const timeLabel = document.getElementById('time');
const readout = document.getElementById('readout');
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

// A measure as the readout prints it: 4 significant digits, the exponent form below 1e-3 and
// from 1e5 on, '–' for a value that is not finite (null in the data).
function sig(x) {
  if (x === null || !isFinite(x)) return '–';
  const a = Math.abs(x);
  if (a === 0) return '0';
  if (a < 1e-3 || a >= 1e5) return x.toExponential(3).replace('e+', 'e');
  return x.toPrecision(4);
}

// The readout's rows, built once; their values are set per frame.
const readoutCells = [];
function buildReadout() {
  if (!readout) return;
  const row = (label, unit) => {
    const tr = document.createElement('tr');
    const th = document.createElement('th');
    th.textContent = label;
    const td = document.createElement('td');
    const u = document.createElement('th');
    u.textContent = unit;
    tr.append(th, td, u);
    readout.append(tr);
    return td;
  };
  readoutCells.push(row('time t', 's'));
  for (const m of data.measures) readoutCells.push(row(m.label, m.unit));
}

function updateReadout() {
  if (!readout) return;
  readoutCells[0].textContent = sig(data.t[current]);
  data.measures.forEach((m, k) => {
    const v = m.v[current];
    readoutCells[k + 1].textContent = m.count && v !== null ? String(Math.round(v)) : sig(v);
  });
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

  // 3D: the x, y, z axes as this view projects them, in the lower right corner, under the
  // agents.
  if (dim === 3) {
    const ax = W - 48, ay = H - 48, A = 30;
    ctx.save();
    ctx.strokeStyle = COLOURS.ink;
    ctx.fillStyle = COLOURS.ink;
    ctx.lineWidth = 1.5;
    ctx.font = '12px sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ['x', 'y', 'z'].forEach((name, e) => {
      const dx = view.u[e], dy = view.v[e];
      ctx.beginPath();
      ctx.moveTo(ax, ay);
      ctx.lineTo(ax + A * dx, ay - A * dy);
      ctx.stroke();
      // an axis seen end-on (top view's z) is a dot with its name beside it
      const len = Math.hypot(dx, dy);
      const lx = len > 0.2 ? ax + (A + 9) * dx / Math.max(len, 1) : ax + 9;
      const ly = len > 0.2 ? ay - (A + 9) * dy / Math.max(len, 1) : ay + 9;
      if (len <= 0.2) { ctx.beginPath(); ctx.arc(ax, ay, 2, 0, 2 * Math.PI); ctx.fill(); }
      ctx.fillText(name, lx, ly);
    });
    ctx.restore();
  }

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
    const e = data.edges || edgesOf(q);
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
  // failed agents (a run with faults) as crosses, the others as triangles
  const failed = new Set(data.failed ? data.failed[current] : []);
  for (let i = 0; i < n; i++) {
    if (q[i * dim] === null) continue;
    const c = project(view, q, i), h = project(view, p, i);
    const cx = X(c[0]), cy = Y(c[1]);
    if (failed.has(i)) {
      const a = 0.35 * L;
      ctx.save();
      ctx.strokeStyle = COLOURS.failed;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(cx - a, cy - a); ctx.lineTo(cx + a, cy + a);
      ctx.moveTo(cx - a, cy + a); ctx.lineTo(cx + a, cy - a);
      ctx.stroke();
      ctx.restore();
      continue;
    }
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

  // Merged agents: one point however many markers, ringed and labelled with their count.
  const merged = data.merged ? data.merged[current] : [];
  ctx.save();
  ctx.strokeStyle = COLOURS.ink;
  ctx.fillStyle = COLOURS.ink;
  ctx.lineWidth = 1.5;
  ctx.font = 'bold 12px sans-serif';
  for (let k = 0; k < merged.length; k += 2) {
    if (q[merged[k] * dim] === null) continue;
    const c = project(view, q, merged[k]);
    const cx = X(c[0]), cy = Y(c[1]);
    ctx.beginPath();
    ctx.arc(cx, cy, L, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.fillText(String(merged[k + 1]), cx + 0.8 * L, cy - 0.8 * L);
  }
  ctx.restore();

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

  timeLabel.textContent = 't = ' + fmt(data.t[current]) + ' s' +
    (failed.size > 0 ? ', ' + failed.size + ' failed (×)' : '');
  scrub.value = String(current);
  canvas.dataset.frame = String(current);
  updateReadout();
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
buildReadout();
window.flockPlayer = { frames: frames, frame: () => current, show: show, play: () => setPlaying(true), pause: () => setPlaying(false) };
draw();
})();

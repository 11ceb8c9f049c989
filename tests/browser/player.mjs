// Drives flocking's HTML player (crates/flock-viz/src/player.rs) in the system's headless Chromium and
// checks that it loads without errors, draws its agents where the data puts them, and that every
// control works. Usage:
//
//     node tests/browser/player.mjs PLAYER_HTML SCREENSHOT_PNG 2d|3d
//
// The browser is /usr/bin/chromium (or $FLOCK_CHROMIUM); nothing is downloaded. On success prints
// a JSON summary on stdout and exits 0; on the first failed check prints `FAIL: ...` on stderr and
// exits 1 (2 for bad arguments).

import { mkdtemp, rm, stat } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

import { chromium } from 'playwright-core';

const CHROMIUM = process.env.FLOCK_CHROMIUM || '/usr/bin/chromium';
const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];
/** The whole check must finish within this time. */
const WATCHDOG_MS = 120_000;
/** The γ-agent's diamond (radius 7 px, outlined) may cover agents within this many pixels. */
const GAMMA_COVER_PX = 9;

class CheckFailed extends Error {}

/** Console errors, page errors and network requests of the page: each one fails the check. */
const problems = [];

/** Fails the check if the page has reported a problem. */
function noProblems(when) {
  check(problems.length === 0, `${when}: ${problems.join('; ')}`);
}

/** Fails the check with `message` unless `condition` holds. */
function check(condition, message) {
  if (!condition) throw new CheckFailed(message);
}

const sleep = (ms) => new Promise((done) => setTimeout(done, ms));

/** `#RRGGBB` as [r, g, b]. */
function rgb(hex) {
  const m = /^#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(hex);
  check(m, `not a #RRGGBB colour: ${hex}`);
  return [1, 2, 3].map((k) => parseInt(m[k], 16));
}

/** The page's colours, from its data's `colours` (flock-viz's style.rs), as [r, g, b]. */
function colours(data) {
  check(data.colours, 'the player data defines no colours');
  const out = {};
  const keys = ['background', 'agent', 'edge', 'gamma', 'ink'].concat(data.failed ? ['failed'] : []);
  for (const key of keys) {
    check(/^#[0-9A-Fa-f]{6}$/.test(data.colours[key] || ''), `colours.${key} missing`);
    out[key] = rgb(data.colours[key]);
  }
  return out;
}

/** Agent i of a frame projected on a view (the page's `project`), or null when not finite. */
function project(data, view, v, i) {
  const dim = data.dim;
  const c = v.slice(i * dim, i * dim + dim);
  if (c.some((x) => x === null || !Number.isFinite(x))) return null;
  if (dim === 2) return c;
  return [0, 1].map((row) => {
    const axis = row === 0 ? view.u : view.v;
    return axis[0] * c[0] + axis[1] * c[1] + axis[2] * c[2];
  });
}

/**
 * The canvas pixel of world point `c` when the whole-run window of `view` is shown: the window
 * fitted into the canvas with a 12 px margin, centred, y up (the contract of player.rs).
 */
function toCanvas(view, size, c) {
  const [W, H] = size;
  const [x0, y0, x1, y1] = view.window;
  const s = Math.min((W - 24) / (x1 - x0), (H - 24) / (y1 - y0));
  const ox = (W - s * (x1 - x0)) / 2;
  const oy = (H - s * (y1 - y0)) / 2;
  return [ox + (c[0] - x0) * s, H - (oy + (c[1] - y0) * s)];
}

/** The number of net edges (pairs closer than the range) of frame k, counted directly. */
function edgeCount(data, k) {
  const q = data.q[k];
  const dim = data.dim;
  const n = q.length / dim;
  let count = 0;
  for (let i = 0; i < n; i++) {
    for (let j = i + 1; j < n; j++) {
      let d2 = 0;
      for (let e = 0; e < dim; e++) d2 += (q[j * dim + e] - q[i * dim + e]) ** 2;
      if (d2 < data.range * data.range) count++;
    }
  }
  return count;
}

/**
 * What the canvas shows: the frame and time shown, pixel counts by colour, the 8-connected blobs of
 * agent-coloured pixels and their bounding box, a hash of the pixels, and which of `points` (canvas
 * coordinates) have no agent-coloured pixel within 1 px.
 */
async function look(page, colours, points = []) {
  return page.evaluate(
    ({ colours, points }) => {
      const canvas = document.getElementById('canvas');
      const { width: W, height: H } = canvas;
      // Read a copy, so that the player's own canvas is never read back (Chromium warns when it is).
      const copy = document.createElement('canvas');
      copy.width = W;
      copy.height = H;
      const copyContext = copy.getContext('2d', { willReadFrequently: true });
      copyContext.drawImage(canvas, 0, 0);
      const px = copyContext.getImageData(0, 0, W, H).data;
      const [ar, ag, ab] = colours.agent;
      const [br, bg, bb] = colours.background;
      const edgeLevel = colours.edge[0];
      const isAgent = (o) => px[o] === ar && px[o + 1] === ag && px[o + 2] === ab;
      const agent = new Uint8Array(W * H);
      let agentPixels = 0, background = 0, grey = 0, hash = 2166136261;
      let bx0 = W, by0 = H, bx1 = -1, by1 = -1;
      for (let y = 0; y < H; y++) {
        for (let x = 0; x < W; x++) {
          const o = (y * W + x) * 4;
          const r = px[o], g = px[o + 1], b = px[o + 2];
          hash = Math.imul(hash ^ r ^ (g << 8) ^ (b << 16), 16777619) >>> 0;
          if (isAgent(o)) {
            agent[y * W + x] = 1;
            agentPixels++;
            bx0 = Math.min(bx0, x); bx1 = Math.max(bx1, x);
            by0 = Math.min(by0, y); by1 = Math.max(by1, y);
          } else if (r === br && g === bg && b === bb) {
            background++;
          } else if (r === g && g === b && r >= edgeLevel) {
            // the edge colour and its anti-aliased blends with the white background
            grey++;
          }
        }
      }
      // 8-connected blobs of agent pixels
      let blobs = 0;
      const stack = [];
      for (let start = 0; start < W * H; start++) {
        if (agent[start] !== 1) continue;
        blobs++;
        agent[start] = 2;
        stack.push(start);
        while (stack.length) {
          const p = stack.pop();
          const x = p % W, y = (p - x) / W;
          for (let dy = -1; dy <= 1; dy++) for (let dx = -1; dx <= 1; dx++) {
            const nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
            const np = ny * W + nx;
            if (agent[np] === 1) { agent[np] = 2; stack.push(np); }
          }
        }
      }
      const missed = [];
      for (const [i, cx, cy] of points) {
        let hit = false;
        for (let dy = -1; dy <= 1 && !hit; dy++) for (let dx = -1; dx <= 1 && !hit; dx++) {
          const x = Math.floor(cx) + dx, y = Math.floor(cy) + dy;
          hit = x >= 0 && y >= 0 && x < W && y < H && agent[y * W + x] === 2;
        }
        if (!hit) missed.push([i, Math.round(cx), Math.round(cy)]);
      }
      return {
        frame: Number(canvas.dataset.frame),
        time: document.getElementById('time').textContent,
        size: [W, H],
        agentPixels, background, grey, blobs, hash,
        bbox: bx1 < 0 ? null : [bx0, by0, bx1, by1],
        missed,
      };
    },
    { colours, points },
  );
}

/**
 * The canvas points of the agents of frame k in view v (unzoomed), without those the γ-agent covers:
 * the working agents, or with `failed` the agents failed by then (a run with faults).
 */
function agentPoints(data, size, k, v, failed = false) {
  const view = data.views[v];
  const gamma = data.g[k] ? project(data, view, data.g[k], 0) : null;
  const g = gamma && toCanvas(view, size, gamma);
  const down = new Set(data.failed ? data.failed[k] : []);
  const points = [];
  const n = data.q[k].length / data.dim;
  for (let i = 0; i < n; i++) {
    if (down.has(i) !== failed) continue;
    const c = project(data, view, data.q[k], i);
    if (!c) continue;
    const [x, y] = toCanvas(view, size, c);
    if (g && Math.hypot(x - g[0], y - g[1]) < GAMMA_COVER_PX) continue;
    points.push([i, x, y]);
  }
  return points;
}

/** Checks that frame k is drawn: every agent where the data puts it, about one blob per agent. */
async function checkAgents(page, colours, data, size, k, v, what) {
  const points = agentPoints(data, size, k, v);
  const seen = await look(page, colours, points);
  const n = data.q[k].length / data.dim;
  check(seen.frame === k, `${what}: canvas shows frame ${seen.frame}, expected ${k}`);
  const down = data.failed ? data.failed[k].length : 0;
  check(
    points.length >= (n - down) / 2,
    `${what}: only ${points.length} of ${n - down} working agents are not under the γ-agent`,
  );
  check(
    seen.missed.length === 0,
    `${what}: ${seen.missed.length} of ${points.length} agents have no agent-coloured pixel at their ` +
      `position, e.g. [agent, x, y] = ${JSON.stringify(seen.missed.slice(0, 5))}`,
  );
  // A marker is a triangle of 36 px² (a few of its pixels anti-aliased): about 15-36 px of agent colour.
  check(
    seen.agentPixels >= 12 * points.length && seen.agentPixels <= 40 * n,
    `${what}: ${seen.agentPixels} agent-coloured pixels for ${n} agents (expected 12-40 per agent)`,
  );
  check(
    seen.blobs >= 0.5 * points.length && seen.blobs <= n + 1,
    `${what}: ${seen.blobs} separate agent markers drawn for ${n} agents`,
  );
  if (down > 0) {
    // each failed agent is a cross of the failed colour through its position
    const failed = agentPoints(data, size, k, v, true);
    const crossed = [];
    for (const [i, cx, cy] of failed) {
      const px = await pixels(page, Math.floor(cx) - 1, Math.floor(cy) - 1, 3, 3);
      let hit = false;
      for (let o = 0; o < px.length; o += 4) {
        hit ||= px[o] === colours.failed[0] && px[o + 1] === colours.failed[1] && px[o + 2] === colours.failed[2];
      }
      if (!hit) crossed.push(i);
    }
    check(
      crossed.length === 0,
      `${what}: failed agents ${JSON.stringify(crossed.slice(0, 5))} have no cross at their position`,
    );
  }
  return seen;
}

/** The radius of a merged point's ring, in canvas pixels (player.js's marker size `L`). */
const RING_PX = 10;

/**
 * Checks frame k's merged points (agents closer than 10⁻³ d, `data.merged`: first agent and
 * count): each is ringed in ink at its position, with ink where its count is written (up right of
 * the ring); returns how many there are.
 */
async function checkMerged(page, colours, data, size, k, v, what) {
  const merged = data.merged ? data.merged[k] : [];
  const view = data.views[v];
  const ink = colours.ink;
  const near = (px, o) => Math.abs(px[o] - ink[0]) + Math.abs(px[o + 1] - ink[1]) + Math.abs(px[o + 2] - ink[2]) < 90;
  for (let m = 0; m < merged.length; m += 2) {
    const [agent, count] = [merged[m], merged[m + 1]];
    check(count >= 2, `${what}: a merged point of ${count} agent`);
    const c = project(data, view, data.q[k], agent);
    if (!c) continue;
    const [cx, cy] = toCanvas(view, size, c);
    // the ring: ink within a pixel of the circle at 48 angles
    const box = 2 * RING_PX + 6;
    const x0 = Math.floor(cx) - RING_PX - 3;
    const y0 = Math.floor(cy) - RING_PX - 3;
    const px = await pixels(page, x0, y0, box, box);
    let onRing = 0;
    for (let a = 0; a < 48; a++) {
      const x = Math.round(cx + RING_PX * Math.cos((a * Math.PI) / 24)) - x0;
      const y = Math.round(cy + RING_PX * Math.sin((a * Math.PI) / 24)) - y0;
      let hit = false;
      for (let dy = -1; dy <= 1; dy++) {
        for (let dx = -1; dx <= 1; dx++) hit ||= near(px, 4 * ((y + dy) * box + x + dx));
      }
      if (hit) onRing++;
    }
    check(onRing >= 40, `${what}: the ${count} agents merged at agent ${agent} (${cx.toFixed(1)}, ${cy.toFixed(1)}) have ink on ${onRing} of 48 points of their ring`);
    // the count, written from (cx + 0.8 L, cy − 0.8 L) up and to the right
    const label = await pixels(page, Math.floor(cx + 0.8 * RING_PX), Math.floor(cy - 0.8 * RING_PX) - 11, 8 * String(count).length + 2, 12);
    let inked = 0;
    for (let o = 0; o < label.length; o += 4) if (near(label, o)) inked++;
    check(inked >= 6, `${what}: no count beside the ring of the agents merged at agent ${agent} (${inked} ink pixels)`);
  }
  return merged.length / 2;
}

/** The time in `t = 1.2 s` (the #time label) and the failed agents of `t = 1.2 s, 3 failed (×)`. */
function shownTime(text) {
  const m = /^t = (-?[0-9.e+-]+) s(?:, ([0-9]+) failed \(×\))?$/.exec(text);
  check(m, `#time reads "${text}", expected "t = <number> s" (", <count> failed (×)" with failures)`);
  return [Number(m[1]), Number(m[2] || 0)];
}

/** The readout's rows as [label, value, unit] (`#readout`). */
async function readoutRows(page) {
  return page.$$eval('#readout tr', (rows) =>
    rows.map((row) => Array.from(row.children).map((cell) => cell.textContent)),
  );
}

/**
 * The readout shows t and every measure of the data at frame k: the labels and units of
 * `data.measures`, each value the frame's to 4 significant digits.
 */
async function checkReadout(page, data, k, what) {
  const rows = await readoutRows(page);
  check(rows.length === 1 + data.measures.length, `${what}: ${rows.length} readout rows for ${data.measures.length} measures`);
  check(rows[0][0] === 'time t' && rows[0][2] === 's', `${what}: the first readout row is ${JSON.stringify(rows[0])}`);
  const near = (text, x) => {
    if (x === null) return text === '–';
    const shown = Number(text);
    return Number.isFinite(shown) && Math.abs(shown - x) <= 5e-4 * Math.max(Math.abs(x), 1e-300);
  };
  check(near(rows[0][1], data.t[k]), `${what}: the readout's t is ${rows[0][1]}, frame ${k} is at ${data.t[k]}`);
  data.measures.forEach((m, j) => {
    const [label, value, unit] = rows[j + 1];
    check(label === m.label && unit === m.unit, `${what}: readout row ${j + 1} is ${JSON.stringify(rows[j + 1])}, expected ${m.label} (${m.unit})`);
    check(near(value, m.v[k]), `${what}: ${m.label} reads ${value}, frame ${k} has ${m.v[k]}`);
  });
}

/**
 * The RGBA bytes of the canvas's w × h pixels from (x, y), read from a copy, so that the player's
 * own canvas is never read back (Chromium warns when it is).
 */
async function pixels(page, x, y, w, h) {
  return page.evaluate(([x, y, w, h]) => {
    const canvas = document.getElementById('canvas');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d', { willReadFrequently: true });
    context.drawImage(canvas, 0, 0);
    return Array.from(context.getImageData(x, y, w, h).data);
  }, [x, y, w, h]);
}

/**
 * The pixels near the `ink` colour (anti-aliased lines included) in the canvas's 96 × 96 lower
 * right corner, where a 3D view draws its axis triad.
 */
async function cornerInk(page, colours, size) {
  const px = await pixels(page, size[0] - 96, size[1] - 96, 96, 96);
  const ink = colours.ink;
  let count = 0;
  for (let o = 0; o < px.length; o += 4) {
    if (Math.abs(px[o] - ink[0]) + Math.abs(px[o + 1] - ink[1]) + Math.abs(px[o + 2] - ink[2]) < 90) count++;
  }
  return count;
}

function checkTime(data, seen, what) {
  const [t, failed] = shownTime(seen.time);
  check(
    Math.abs(t - data.t[seen.frame]) <= 0.006,
    `${what}: #time reads ${t} s but frame ${seen.frame} is at t = ${data.t[seen.frame]} s`,
  );
  const down = data.failed ? data.failed[seen.frame].length : 0;
  check(failed === down, `${what}: #time counts ${failed} failed agents, frame ${seen.frame} has ${down}`);
}

/** Shows frame k with the scrub slider, as a user dragging it would (value set, input event). */
async function scrubTo(page, k) {
  await page.evaluate((k) => {
    const scrub = document.getElementById('scrub');
    scrub.value = String(k);
    scrub.dispatchEvent(new Event('input', { bubbles: true }));
  }, k);
}

async function isPlaying(page) {
  return (await page.textContent('#play')).trim() === 'Pause';
}

/** Plays from frame `from` at `speed` for `ms` of wall time; returns simulated seconds per second. */
async function playRate(page, data, speed, from, ms) {
  const values = await page.$$eval('#speed option', (options) => options.map((o) => o.value));
  const value = values.find((v) => Number(v) === speed);
  check(value !== undefined, `#speed offers no ${speed}× (offers ${values.join(', ')})`);
  const selected = await page.selectOption('#speed', value);
  check(selected.length === 1 && selected[0] === value, `#speed did not accept ${value}`);
  await scrubTo(page, from);
  await page.click('#play');
  check(await isPlaying(page), `#play did not start playing at ${speed}×`);
  // Timed inside the page, so that the round trips of the driver do not count.
  const [start, end] = await page.evaluate(async (ms) => {
    const start = [performance.now(), window.flockPlayer.frame()];
    await new Promise((done) => setTimeout(done, ms));
    return [start, [performance.now(), window.flockPlayer.frame()]];
  }, ms);
  await page.click('#play');
  noProblems(`playing at ${speed}×`);
  check(!(await isPlaying(page)), 'the player did not pause');
  const last = data.t.length - 1;
  check(end[1] < last, `at ${speed}× the run ended within ${ms} ms: the run is too short for this check`);
  const seconds = (end[0] - start[0]) / 1000;
  return { speed, seconds, frames: end[1] - start[1], rate: (data.t[end[1]] - data.t[start[1]]) / seconds };
}

async function main() {
  const [html, screenshot, mode] = process.argv.slice(2);
  if (!html || !screenshot || !['2d', '3d'].includes(mode)) {
    console.error('usage: node player.mjs PLAYER_HTML SCREENSHOT_PNG 2d|3d');
    process.exit(2);
  }
  const started = Date.now();
  const userDataDir = await mkdtemp(join(tmpdir(), 'flock-chromium-'));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 900, height: 860 },
    deviceScaleFactor: 1,
    offline: true,
  });
  const warnings = [];
  try {
    const page = context.pages()[0] || (await context.newPage());
    page.on('console', (msg) => {
      if (msg.type() === 'error') problems.push(`console error: ${msg.text()}`);
      else if (msg.type() === 'warning') warnings.push(msg.text());
    });
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    page.on('request', (request) => {
      const url = request.url();
      if (!url.startsWith('file:') && !url.startsWith('data:')) problems.push(`network request: ${url}`);
    });
    page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));

    await page.goto(pathToFileURL(resolve(html)).href, { waitUntil: 'load' });
    await page.waitForFunction(() => window.flockPlayer !== undefined, null, { timeout: 10_000 });
    noProblems('loading the page');

    const data = await page.evaluate(() => JSON.parse(document.getElementById('flock-data').textContent));
    const colour = colours(data);
    const frames = data.t.length;
    const agents = data.q[0].length / data.dim;
    const size = await page.evaluate(() => {
      const c = document.getElementById('canvas');
      return [c.width, c.height];
    });
    check(data.dim === (mode === '3d' ? 3 : 2), `the page holds a ${data.dim}D run, expected ${mode}`);
    check(await page.evaluate(() => window.flockPlayer.frames) === frames, 'flockPlayer.frames ≠ frames of the data');
    check(frames >= 20, `only ${frames} frames: the run is too short for the checks`);
    for (const id of ['play', 'scrub', 'speed', 'edges', 'zoom', 'canvas', 'time']) {
      check(await page.$(`#${id}`), `#${id} missing`);
    }
    check(((await page.$('#view')) !== null) === (data.dim === 3), '#view is offered exactly for 3D runs');
    check(await page.isChecked('#edges'), '#edges starts checked');
    check(!(await page.isChecked('#zoom')), '#zoom starts unchecked');
    const initialSpeed = await page.inputValue('#speed');
    const summary = { html, mode, frames, agents, checks: {} };

    // 1. The first frame as loaded.
    const first = await checkAgents(page, colour, data, size, 0, 0, 'first frame');
    checkTime(data, first, 'first frame');
    check(data.measures.length >= 10, `the readout holds ${data.measures.length} measures: the run's metrics are missing`);
    await checkReadout(page, data, 0, 'first frame');
    summary.checks.first_frame = { agent_pixels: first.agentPixels, markers: first.blobs, measures: data.measures.length };
    const mergedFirst = await checkMerged(page, colour, data, size, 0, 0, 'first frame');

    // 2. Play, then pause.
    check(!(await isPlaying(page)), '#play reads "Play" before playing');
    await page.click('#play');
    check(await isPlaying(page), '#play reads "Pause" while playing');
    await sleep(900);
    const playing = await look(page, colour);
    check(playing.frame > 0, `after 0.9 s of playing the canvas still shows frame ${playing.frame}`);
    check(playing.hash !== first.hash, 'playing did not change the drawing');
    checkTime(data, playing, 'while playing');
    await page.click('#play');
    check(!(await isPlaying(page)), '#play reads "Play" after pausing');
    const paused = await look(page, colour);
    await sleep(500);
    const stillPaused = await look(page, colour);
    check(
      stillPaused.frame === paused.frame && stillPaused.time === paused.time && stillPaused.hash === paused.hash,
      `paused at frame ${paused.frame} but 0.5 s later the canvas shows frame ${stillPaused.frame}`,
    );
    noProblems('playing and pausing');
    summary.checks.play_pause = { frame_after_900ms: playing.frame, paused_at: paused.frame };

    // 3. The scrub slider shows the frame it is set to, drawn from that frame's data.
    const last = frames - 1;
    await scrubTo(page, last);
    const scrubbed = await checkAgents(page, colour, data, size, last, 0, `scrubbed to frame ${last}`);
    checkTime(data, scrubbed, 'scrubbed');
    await checkReadout(page, data, last, `scrubbed to frame ${last}`);
    check(scrubbed.hash !== stillPaused.hash, 'scrubbing did not change the drawing');
    check(await page.evaluate(() => window.flockPlayer.frame()) === last, 'flockPlayer.frame() ≠ scrubbed frame');
    const mid = Math.floor(frames / 2);
    await scrubTo(page, mid);
    const middle = await checkAgents(page, colour, data, size, mid, 0, `scrubbed to frame ${mid}`);
    await checkReadout(page, data, mid, `scrubbed to frame ${mid}`);
    check(middle.hash !== scrubbed.hash, 'frames differ but their drawings do not');
    noProblems('scrubbing');
    summary.checks.scrub = { frames: [last, mid] };
    const mergedMiddle = await checkMerged(page, colour, data, size, mid, 0, `scrubbed to frame ${mid}`);
    await scrubTo(page, last);
    const mergedLast = await checkMerged(page, colour, data, size, last, 0, `scrubbed to frame ${last}`);
    summary.checks.merged_points = [mergedFirst, mergedMiddle, mergedLast];

    // 4. Speed: the simulated time played per second follows #speed.
    // Frames are data.t apart, so a rate is measured to within a frame's time per window.
    const slow = await playRate(page, data, 0.5, 0, 1000);
    const fast = await playRate(page, data, 10, 0, 600);
    check(
      fast.frames > 5 * Math.max(slow.frames, 1),
      `10× played ${fast.frames} frames in ${fast.seconds} s, 0.5× ${slow.frames} in ${slow.seconds} s`,
    );
    check(fast.rate > 5 && fast.rate < 12, `at 10× the player advanced ${fast.rate.toFixed(2)} simulated s per s`);
    check(slow.rate < 1, `at 0.5× the player advanced ${slow.rate.toFixed(2)} simulated s per s`);
    await page.selectOption('#speed', initialSpeed);
    noProblems('changing the speed');
    summary.checks.speed = { slow, fast };

    // 5. Edges: the net's edges add edge-grey pixels where the data has edges; the agents stay.
    await scrubTo(page, last);
    const edges = edgeCount(data, last);
    check(edges > 0, `frame ${last} has no edges: the run does not test the edges toggle`);
    const withEdges = await look(page, colour);
    await page.uncheck('#edges');
    const noEdges = await checkAgents(page, colour, data, size, last, 0, 'edges off');
    check(
      withEdges.grey - noEdges.grey >= 3 * edges,
      `edges on: ${withEdges.grey} edge-grey pixels, off: ${noEdges.grey}, for ${edges} edges`,
    );
    await page.check('#edges');
    const edgesAgain = await look(page, colour);
    check(edgesAgain.hash === withEdges.hash, 'edges back on does not restore the drawing');
    noProblems('toggling the edges');
    summary.checks.edges = { edges, grey_on: withEdges.grey, grey_off: noEdges.grey };

    // 6. Zoom to the flock: a tighter window, so the same markers spread over a larger box.
    await page.check('#zoom');
    const zoomed = await look(page, colour);
    check(zoomed.hash !== withEdges.hash, 'zoom did not change the drawing');
    check(zoomed.frame === last, 'zoom changed the frame');
    const area = (b) => (b[2] - b[0] + 1) * (b[3] - b[1] + 1);
    check(zoomed.bbox && area(zoomed.bbox) > 1.2 * area(withEdges.bbox),
      `zoomed, the agents cover ${JSON.stringify(zoomed.bbox)}, unzoomed ${JSON.stringify(withEdges.bbox)}`);
    check(zoomed.blobs >= withEdges.blobs && zoomed.blobs <= agents + 1,
      `zoomed, ${zoomed.blobs} markers are drawn for ${agents} agents (unzoomed ${withEdges.blobs})`);
    await page.uncheck('#zoom');
    check((await look(page, colour)).hash === withEdges.hash, 'zoom off does not restore the drawing');
    noProblems('toggling the zoom');
    summary.checks.zoom = { bbox_unzoomed: withEdges.bbox, bbox_zoomed: zoomed.bbox, markers: zoomed.blobs };

    // 7. 3D: an axis triad in the lower right corner of each view (2D: none); the top view
    // projects the agents on (x, y).
    const triad = await cornerInk(page, colour, size);
    check(data.dim === 3 ? triad >= 40 : triad < 40, `${triad} ink pixels in the lower right corner of a ${data.dim}D view`);
    summary.checks.triad_ink = triad;
    if (data.dim === 3) {
      const names = data.views.map((v) => v.name);
      check(names.length === 2, `3D views: ${names.join(', ')}`);
      await page.selectOption('#view', '1');
      const top = await checkAgents(page, colour, data, size, last, 1, `view ${names[1]}`);
      check(top.hash !== withEdges.hash, 'the view selector did not change the drawing');
      await page.selectOption('#view', '0');
      check((await look(page, colour)).hash === withEdges.hash, 'view 0 again does not restore the drawing');
      noProblems('changing the view');
      summary.checks.view = { views: names, top_markers: top.blobs };
    }

    // The screenshot: the last frame, edges on, at the page's own speed.
    await page.screenshot({ path: screenshot, fullPage: true });
    const png = await stat(screenshot);
    check(png.size > 1000, `the screenshot ${screenshot} is only ${png.size} bytes`);
    summary.screenshot = screenshot;
    summary.console_warnings = warnings;
    noProblems('taking the screenshot');
    summary.seconds = (Date.now() - started) / 1000;
    console.log(JSON.stringify(summary, null, 2));
  } finally {
    await context.close();
    await rm(userDataDir, { recursive: true, force: true });
  }
}

const watchdog = setTimeout(() => {
  console.error(`FAIL: the browser check took longer than ${WATCHDOG_MS / 1000} s`);
  process.exit(1);
}, WATCHDOG_MS);
watchdog.unref();

main().then(
  () => process.exit(0),
  (error) => {
    console.error(error instanceof CheckFailed ? `FAIL: ${error.message}` : `FAIL: ${error.stack || error}`);
    process.exit(1);
  },
);

// The gain swept up and down, and the (w, β) map of motion classes.

import { $, field, num, si, niceAtLeast } from './util.js';
import { latest, isAbort } from './api.js';
import { state, statusEl, clearErrors, showError, value, modelParams } from './state.js';
import { logicalSize, prepare, label, TextBoxes } from './scope.js';

// ---------------------------------------------------------------- sweep and map
/** `pwl`, `shockley` or `mechanics`: the system an answer was computed for. */
export const kindOf = (answer) => (answer.system === 'mechanics' ? 'mechanics' : answer.model);
export const KIND_NAMES = { pwl: 'the circuit with PWL diodes', shockley: 'the circuit with Shockley diodes', mechanics: 'the mechanical oscillator' };

/** Mark a view whose answer no longer matches the inputs (`why`), or clear the mark. */
export function setStale(canvas, statusEl, why) {
  if (why) {
    canvas.dataset.stale = 'true';
    statusEl.dataset.stale = 'true';
    statusEl.textContent = why;
  } else {
    delete canvas.dataset.stale;
    delete statusEl.dataset.stale;
  }
}

export function markSweepAndMapStale() {
  const s = state.steady;
  const now = state.system;
  if (state.sweep) {
    const kind = kindOf(state.sweep);
    let why = '';
    if (kind !== now) why = `stale: computed for ${KIND_NAMES[kind]}; press Sweep for ${KIND_NAMES[now]}`;
    else if (state.sweep.experimentBase !== experimentBase(s)) why = 'stale: computed for other parts; press Sweep';
    else if (Math.abs(state.sweep.beta - s.beta) > 1e-12 * Math.max(1, s.beta)) why = `stale: computed at β = ${num(state.sweep.beta, 4)}; press Sweep for β = ${num(s.beta, 4)}`;
    setStale($('#sweep-plot'), $('[data-sweep="status"]'), why);
  }
  if (state.map) {
    const kind = kindOf(state.map);
    let why = '';
    if (kind !== now) why = `stale: computed for ${KIND_NAMES[kind]}; press Map for ${KIND_NAMES[now]}`;
    else if (state.map.experimentBase !== experimentBase(s)) why = 'stale: computed for other parts; press Map';
    setStale($('#map-plot'), $('[data-map="status"]'), why);
  }
  drawSweep();
  drawMap();
}

/** The description of an experiment without its drive (what a sweep or a map keeps). */
export function experimentBase(answer) {
  if (!answer || !answer.experiment) return '';
  return answer.experiment.split(';')[0];
}

/** Axes, grid and labels of a plot; `legendRows` rows (0, 1 or 2) under the x label. */
export function plotFrame(canvas, xr, yr, xlabel, ylabel, legendRows = 0) {
  const { g, w, h } = prepare(canvas);
  const box = { l: 56, r: w - 14, t: 14, b: h - 40 - 16 * legendRows };
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, w, h);
  const X = (x) => box.l + ((x - xr[0]) / (xr[1] - xr[0])) * (box.r - box.l);
  const Y = (y) => box.b - ((y - yr[0]) / (yr[1] - yr[0])) * (box.b - box.t);
  g.font = '11px system-ui, sans-serif';
  g.strokeStyle = '#d9ded9';
  g.lineWidth = 1;
  const ticks = (lo, hi) => {
    const step = niceAtLeast((hi - lo) / 8);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push(Number(v.toPrecision(12)));
    return out;
  };
  for (const x of ticks(...xr)) {
    g.beginPath();
    g.moveTo(X(x), box.t);
    g.lineTo(X(x), box.b);
    g.stroke();
    label(g, num(x, 3), X(x), box.b + 14, '#333', 'center');
  }
  for (const y of ticks(...yr)) {
    g.beginPath();
    g.moveTo(box.l, Y(y));
    g.lineTo(box.r, Y(y));
    g.stroke();
    label(g, num(y, 3), box.l - 4, Y(y) + 4, '#333', 'right');
  }
  g.strokeStyle = '#555';
  g.strokeRect(box.l, box.t, box.r - box.l, box.b - box.t);
  label(g, xlabel, (box.l + box.r) / 2, box.b + 32, '#222', 'center');
  g.save();
  g.translate(14, (box.t + box.b) / 2);
  g.rotate(-Math.PI / 2);
  label(g, ylabel, 0, 0, '#222', 'center');
  g.restore();
  return { g, X, Y, box };
}

export function polyline(g, pts, color, width = 1.5, dash = []) {
  g.strokeStyle = color;
  g.lineWidth = width;
  g.setLineDash(dash);
  g.beginPath();
  let pen = false;
  for (const [x, y] of pts) {
    if (!Number.isFinite(y) || y === null) {
      pen = false;
      continue;
    }
    if (pen) g.lineTo(x, y);
    else g.moveTo(x, y);
    pen = true;
  }
  g.stroke();
  g.setLineDash([]);
}

/** The static part of a plot, drawn once per result into an offscreen canvas and copied
 *  onto the screen at each redraw (only the current point moves). */
export const layers = {};
export function cached(name, canvas, source, render) {
  const ratio = window.devicePixelRatio || 1;
  const { w, h } = logicalSize(canvas);
  let layer = layers[name];
  if (!layer || layer.source !== source || layer.ratio !== ratio || layer.w !== w || layer.h !== h) {
    const off = document.createElement('canvas');
    off.width = w;
    off.height = h;
    layer = { source, ratio, w, h, canvas: off, ...render(off) };
    layers[name] = layer;
  }
  const { g } = prepare(canvas);
  g.save();
  g.setTransform(1, 0, 0, 1, 0, 0);
  g.drawImage(layer.canvas, 0, 0);
  g.restore();
  return { g, layer };
}

export function placeholder(canvas, text) {
  const { g, w, h } = prepare(canvas);
  g.fillStyle = '#fff';
  g.fillRect(0, 0, w, h);
  g.font = '13px system-ui, sans-serif';
  label(g, text, w / 2, h / 2, '#555', 'center');
}

export function drawSweep() {
  const canvas = $('#sweep-plot');
  const sw = state.sweep;
  const s = state.steady;
  if (!sw) {
    placeholder(canvas, 'Press “Sweep up and down”: the gain against w, each step from the last.');
    return;
  }
  const { g, layer } = cached('sweep', canvas, sw, (off) => {
    const xs = sw.points.map((p) => p.value);
    const xr = [Math.min(...xs), Math.max(...xs)];
    if (xr[0] === xr[1]) xr[1] = xr[0] + 1;
    const gains = sw.points.map((p) => p.gain).concat(sw.theory.exact_gain.filter(Number.isFinite));
    const ymax = Math.max(...gains.filter(Number.isFinite), 0.1) * 1.08;
    const f0 = sw.conversion ? sw.conversion.f0 : null;
    const frame = plotFrame(off, xr, [0, ymax], f0 ? `w = Ω/ω0 (f0 = ${si(f0, 'Hz')})` : 'w', 'gain G = (y_max − y_min)/2β');
    const { g: o, X, Y, box } = frame;
    const th = sw.theory;
    polyline(o, th.x.map((x, i) => [X(x), th.paper_gain1[i] === null || th.paper_gain1[i] > ymax ? NaN : Y(th.paper_gain1[i])]), '#cc79a7', 2, [6, 4]);
    polyline(o, th.x.map((x, i) => [X(x), th.exact_gain[i] === null ? NaN : Y(th.exact_gain[i])]), '#000000', 2);
    for (const [leg, color, dash] of [['up', '#0072b2', []], ['down', '#d55e00', [5, 3]]]) {
      const pts = sw.points.filter((p) => p.direction === leg);
      polyline(o, pts.map((p) => [X(p.value), Y(p.gain)]), color, 2, dash);
      o.fillStyle = color;
      for (const p of pts) {
        if (p.stops_per_period > 0) o.fillRect(X(p.value) - 2.5, Y(p.gain) - 2.5, 5, 5);
      }
    }
    const legend = [['#0072b2', 'swept up'], ['#d55e00', 'swept down'], ['#cc79a7', `${th.prefix}paper, eq. (11): G1 = A1/β`], ['#000', `${th.prefix}exact orbit: G`], ['#c00', 'now']];
    // The legend's box fits its longest line (the PWL-theory prefix of Shockley diodes
    // included), on a white ground over the curves.
    const note = 'squares: motion with stops';
    const textWidth = Math.max(...legend.map(([, text]) => o.measureText(text).width), o.measureText(note).width);
    const lx = Math.max(box.l + 4, box.r - textWidth - 30);
    o.fillStyle = 'rgba(255, 255, 255, 0.85)';
    o.fillRect(lx - 4, box.t + 2, box.r - lx + 2, 14 * legend.length + 16);
    let ly = box.t + 12;
    for (const [c, text] of legend) {
      o.fillStyle = c;
      o.fillRect(lx, ly - 7, 14, 3);
      label(o, text, lx + 20, ly - 2, '#222');
      ly += 14;
    }
    label(o, note, lx, ly, '#555');
    window.stickslipLab.sweepLegend = { left: lx - 4, right: lx + 20 + textWidth, plotRight: box.r + 14 };
    return { X, Y, xr };
  });
  // The current point, when the sweep is at its β.
  if (s && Math.abs(s.beta - sw.beta) <= 1e-9 * Math.max(1, s.beta) && s.w >= layer.xr[0] && s.w <= layer.xr[1]) {
    g.strokeStyle = '#c00';
    g.lineWidth = 2;
    g.beginPath();
    g.arc(layer.X(s.w), layer.Y(s.gain), 6, 0, 2 * Math.PI);
    g.stroke();
  }
}

// Every class of the library, in its order (docs/plot-style.md); the last three are a belt's
// self-excited motions, which a map of (w, β) does not show.
export const CLASS_COLORS = { sliding: '#dadada', 'periodic-stick': '#0072b2', undecided: '#d55e00', static: '#009e73', chaotic: '#7570b3', 'stick-slip-cycle': '#0072b2', 'pure-slip-cycle': '#e69f00', 'steady-sliding': '#dadada' };
export function drawMap() {
  const canvas = $('#map-plot');
  const m = state.map;
  const s = state.steady;
  if (!m) {
    placeholder(canvas, 'Press “Map”: the motion class at every (w, β), each from rest.');
    return;
  }
  const { g, layer } = cached('map', canvas, m, (off) => {
    const half = (arr) => (arr.length > 1 ? (arr[1] - arr[0]) / 2 : 0.05);
    const hw = half(m.w);
    const hb = half(m.beta);
    const xr = [m.w[0] - hw, m.w[m.w.length - 1] + hw];
    const yr = [m.beta[0] - hb, m.beta[m.beta.length - 1] + hb];
    // The legend under the x label: the classes found on this map (in the library's order),
    // and the boundaries' key on the right; on two rows where one is too narrow for both.
    const found = new Set(m.points.map((p) => p.class));
    const classes = Object.keys(CLASS_COLORS).filter((k) => found.has(k));
    const key = `${m.boundary.prefix}β_c: exact ━, paper ╍`;
    const measure = off.getContext('2d');
    measure.font = '11px system-ui, sans-serif';
    const classesWidth = classes.reduce((sum, c) => sum + measure.measureText(c).width + 26, 6);
    const plotWidth = logicalSize(canvas).w - 14 - 56;
    const rows = classesWidth + 12 + measure.measureText(key).width <= plotWidth ? 1 : 2;
    const { g: o, X, Y, box } = plotFrame(off, xr, yr, 'w = Ω/ω0', 'β = U/U_t', rows);
    const nb = m.beta.length;
    for (let i = 0; i < m.w.length; i++) {
      for (let j = 0; j < nb; j++) {
        o.fillStyle = CLASS_COLORS[m.points[i * nb + j].class] || '#888';
        const x = X(m.w[i] - hw);
        const y = Y(m.beta[j] + hb);
        o.fillRect(x, y, X(m.w[i] + hw) - x + 0.5, Y(m.beta[j] - hb) - y + 0.5);
      }
    }
    o.save();
    o.beginPath();
    o.rect(box.l, box.t, box.r - box.l, box.b - box.t);
    o.clip();
    const b = m.boundary;
    polyline(o, b.w.map((w, i) => [X(w), b.paper[i] === null ? NaN : Y(b.paper[i])]), '#cc79a7', 2, [6, 4]);
    polyline(o, b.w.map((w, i) => [X(w), b.exact[i] === null ? NaN : Y(b.exact[i])]), '#000', 2);
    o.restore();
    const text = [];
    let lx = box.l + 6;
    for (const c of classes) {
      o.fillStyle = CLASS_COLORS[c];
      o.fillRect(lx, box.b + 40, 10, 10);
      o.strokeStyle = '#999';
      o.strokeRect(lx, box.b + 40, 10, 10);
      label(o, c, lx + 13, box.b + 49, '#222');
      text.push(TextBoxes.box(o, c, lx + 13, box.b + 49, 'left'));
      lx += o.measureText(c).width + 26;
    }
    const ky = box.b + 49 + 16 * (rows - 1);
    label(o, key, box.r, ky, '#222', 'right');
    text.push(TextBoxes.box(o, key, box.r, ky, 'right'));
    window.stickslipLab.mapText = text;
    return { X, Y, box, xr, yr };
  });
  drawCurves(g, layer, m);
  // The current point.
  if (s && s.system === m.system) {
    const { X, Y, box } = layer;
    const cx = X(s.w);
    const cy = Y(s.beta);
    g.save();
    g.beginPath();
    g.rect(box.l, box.t, box.r - box.l, box.b - box.t);
    g.clip();
    g.strokeStyle = '#000';
    g.lineWidth = 3;
    g.beginPath();
    g.arc(cx, cy, 7, 0, 2 * Math.PI);
    g.stroke();
    g.strokeStyle = '#ffdd00';
    g.lineWidth = 1.5;
    g.beginPath();
    g.arc(cx, cy, 7, 0, 2 * Math.PI);
    g.moveTo(cx - 12, cy);
    g.lineTo(cx + 12, cy);
    g.moveTo(cx, cy - 12);
    g.lineTo(cx, cy + 12);
    g.stroke();
    g.restore();
  }
}

export async function runSweep() {
  const out = $('[data-sweep="status"]');
  const p = modelParams({ frequency: false });
  p.set('over', 'w');
  p.set('from', value('sweep-from'));
  p.set('to', value('sweep-to'));
  p.set('steps', value('sweep-steps'));
  p.set('direction', 'both');
  clearErrors($('#sweep'));
  out.textContent = 'computing…';
  out.dataset.state = 'computing';
  try {
    const answer = await latest('sweep', 'sweep', p);
    answer.beta = answer.points.length ? answer.points[0].beta : NaN;
    answer.experimentBase = experimentBase(answer);
    setStale($('#sweep-plot'), out, '');
    state.sweep = answer;
    out.textContent = `${answer.points.length} steady states at β = ${num(answer.beta, 4)}`;
    out.dataset.state = 'ready';
    drawSweep();
  } catch (e) {
    if (isAbort(e)) return;
    out.dataset.state = 'error';
    out.textContent = '';
    showError(e, out);
  }
}

export async function runMap() {
  const out = $('[data-map="status"]');
  const p = modelParams({ frequency: false, amplitude: false });
  const [nw, nb] = field('map-size').value.split('x');
  p.set('w-min', value('map-w-min'));
  p.set('w-max', value('map-w-max'));
  p.set('w-steps', nw);
  p.set('beta-min', value('map-beta-min'));
  p.set('beta-max', value('map-beta-max'));
  p.set('beta-steps', nb);
  clearErrors($('#sweep'));
  out.textContent = 'computing…';
  out.dataset.state = 'computing';
  // Progress for a map that takes more than a second: cells and seconds so far, against
  // the time limit.
  const cells = Number(nw) * Number(nb);
  const began = performance.now();
  const ticker = setInterval(() => {
    const sec = (performance.now() - began) / 1000;
    if (sec >= 1) out.textContent = `computing ${cells} cells… ${sec.toFixed(0)} s`;
  }, 250);
  try {
    const answer = await latest('map', 'map', p);
    clearInterval(ticker);
    answer.experimentBase = experimentBase(answer);
    setStale($('#map-plot'), out, '');
    state.map = answer;
    const counts = {};
    for (const p of answer.points) counts[p.class] = (counts[p.class] || 0) + 1;
    out.textContent = Object.entries(counts).map(([k, v]) => `${k} ${v}`).join(', ');
    out.dataset.state = 'ready';
    drawMap();
    if (field('map-curves').checked) runCurves();
  } catch (e) {
    clearInterval(ticker);
    if (isAbort(e)) return;
    out.dataset.state = 'error';
    out.textContent = '';
    showError(e, out);
  }
}

// ---------------------------------------------------------------- curves over the map
/** The curves drawn over the map, in the order they are asked for: colour and dash of each
 *  special point followed (/api/curve's `follow`). */
export const CURVE_STYLES = { grazing: ['#e69f00', []], fold: ['#cc0000', [7, 3]], 'period-doubling': ['#56b4e9', [2, 3]] };
const CURVE_WORDS = { grazing: 'grazing', fold: 'fold', 'period-doubling': 'period doubling' };

/** The curves of the current circuit over the map on the screen (when "curves" is ticked):
 *  the orbit the motion settles on at the top of the map (the largest β, at the current
 *  point's w, or the middle of the map's w when the point lies outside) is followed down in
 *  β to its first special point of each kind, which is then followed over the map's w range,
 *  as `stickslip curve --vary beta --vary-to <β min> --over w --from <w min> --to <w max>`. */
export async function runCurves() {
  const out = $('[data-curves="status"]');
  const m = state.map;
  if (!field('map-curves').checked || !m) {
    state.curves = null;
    out.textContent = '';
    delete out.dataset.state;
    drawMap();
    return;
  }
  const [wLo, wHi] = [m.w[0], m.w[m.w.length - 1]];
  const [bLo, bHi] = [m.beta[0], m.beta[m.beta.length - 1]];
  const s = state.steady;
  const w0 = s && s.w > wLo && s.w < wHi ? s.w : (wLo + wHi) / 2;
  const curves = { map: m, answers: {}, queries: {} };
  state.curves = curves;
  out.textContent = 'computing curves…';
  out.dataset.state = 'computing';
  out.title = '';
  try {
    for (const follow of Object.keys(CURVE_STYLES)) {
      const p = modelParams({ frequency: false, amplitude: false });
      for (const [k, v] of [['w', w0], ['beta', bHi], ['follow', follow], ['vary', 'beta'], ['vary-to', bLo], ['over', 'w'], ['from', wLo], ['to', wHi]]) p.set(k, String(v));
      curves.queries[follow] = p.toString();
      const answer = await latest('curve', 'curve', p);
      if (state.curves !== curves) return;
      curves.answers[follow] = answer;
      drawMap();
    }
    const parts = Object.entries(curves.answers).map(([follow, a]) => (a.points ? `${CURVE_WORDS[follow]} ${a.report.points} points` : `no ${CURVE_WORDS[follow]}`));
    out.textContent = `curves: ${parts.join(', ')}`;
    out.title = Object.values(curves.answers).map((a) => a.none || `${CURVE_WORDS[a.follow]}: ends at ${a.report.end_text}`).join('\n');
    out.dataset.state = 'ready';
  } catch (e) {
    if (isAbort(e)) return;
    out.dataset.state = 'error';
    out.textContent = `curves: ${e.message}`;
  }
}

/** Draw the curves of `state.curves` over the map `m` in the map's axes (`layer`: X, Y, box),
 *  each in its colour, with a key in the plot's upper left corner. The drawn points are kept
 *  in `window.stickslipLab.mapCurves` with the axes. */
function drawCurves(g, layer, m) {
  const c = state.curves;
  const drawn = {};
  window.stickslipLab.mapCurves = { xr: layer.xr, yr: layer.yr, box: layer.box, curves: drawn, queries: c ? c.queries : {} };
  if (!c || c.map !== m || !field('map-curves').checked) return;
  const { X, Y, box } = layer;
  g.save();
  g.beginPath();
  g.rect(box.l, box.t, box.r - box.l, box.b - box.t);
  g.clip();
  const shown = [];
  for (const [follow, answer] of Object.entries(c.answers)) {
    if (!answer.points) continue;
    // The columns named by the report's parameters: the table's own names.
    const xs = answer.points[answer.report.over];
    const ys = answer.points[answer.report.vary];
    const pts = xs.map((x, i) => [X(x), Y(ys[i])]);
    const [color, dash] = CURVE_STYLES[follow];
    polyline(g, pts, 'rgba(255, 255, 255, 0.8)', 4.5);
    polyline(g, pts, color, 2.5, dash);
    drawn[follow] = { x: xs, y: ys, pixels: pts };
    shown.push(follow);
  }
  let ky = box.t + 14;
  g.font = '11px system-ui, sans-serif';
  for (const follow of shown) {
    const text = `${CURVE_WORDS[follow]} curve`;
    g.fillStyle = 'rgba(255, 255, 255, 0.85)';
    g.fillRect(box.l + 4, ky - 10, g.measureText(text).width + 30, 14);
    const [color, dash] = CURVE_STYLES[follow];
    polyline(g, [[box.l + 8, ky - 3], [box.l + 26, ky - 3]], color, 2.5, dash);
    label(g, text, box.l + 30, ky, '#222');
    ky += 14;
  }
  g.restore();
}

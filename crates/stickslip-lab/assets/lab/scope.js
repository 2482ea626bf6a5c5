// The scope: its settings, the graticule, Y-T, X-Y and FFT, and the cursors.

import { $, field, num, si, STEPS, niceAtLeast, nice125, FFT_SPAN_HARMONICS } from './util.js';
import { state } from './state.js';
import { scales, units, staticNote, beltOf, traceSeconds } from './panels.js';
import { drawRefsYT, drawRefsXY, refLabel } from './record.js';

// ---------------------------------------------------------------- scope settings
/** A position field's value within its range (the field's min and max): a scope's knob
 * turns no further. Anything else typed (1e17, text) counts as the nearest end or 0, and the
 * field says so (aria-invalid, and its title). */
export function position(name) {
  const el = field(name);
  const x = Number(el.value);
  const lo = Number(el.min);
  const hi = Number(el.max);
  const ok = el.value.trim() !== '' && Number.isFinite(x) && x >= lo && x <= hi;
  if (ok) {
    if (el.getAttribute('aria-invalid')) {
      el.removeAttribute('aria-invalid');
      el.title = '';
    }
    return x;
  }
  el.setAttribute('aria-invalid', 'true');
  el.title = `from ${lo} to ${hi} divisions`;
  return Number.isFinite(x) ? Math.max(lo, Math.min(hi, x)) : 0;
}
export const tdiv = () => Number(field('tdiv').value);
export const hpos = () => position('hpos');
export const chOn = (k) => field(`ch${k}-on`).checked;
export const vdiv = (k) => Number(field(`ch${k}-vdiv`).value);
export const vpos = (k) => position(`ch${k}-pos`);

export function fillScaleSelect(select, unit) {
  const current = Number(select.value);
  select.innerHTML = '';
  for (const v of STEPS) {
    const o = document.createElement('option');
    o.value = String(v);
    o.textContent = si(v, unit, 3);
    select.append(o);
  }
  if (current) select.value = String(niceAtLeast(current));
}
export function setSelect(select, v) {
  select.value = String(niceAtLeast(v));
}

/** Time/div for two drive periods (or the whole cycle) across the screen; V/div for each channel. */
export function autoscale() {
  const s = state.steady;
  if (!s || !s.drive) return;
  const u = units();
  fillScaleSelect(field('ch1-vdiv'), u.drive);
  fillScaleSelect(field('ch2-vdiv'), u.position);
  fillScaleSelect(field('ch3-vdiv'), u.velocity);
  // About two cycles across the ten divisions (at least 1.9): drive periods, or a
  // self-excited belt's own cycles.
  const periods = Math.max(2, s.trace.periods);
  if (beltOf(s).selfExcited) setSelect(field('tdiv'), (0.95 * periods * traceSeconds(s)) / 10);
  else setSelect(field('tdiv'), (0.95 * periods) / s.drive.f_Hz / 10);
  field('hpos').value = '0';
  const cols = channelColumns();
  const span = (arr) => Math.max(...arr) - Math.min(...arr);
  setSelect(field('ch1-vdiv'), Math.max(span(cols.ch1), 1e-9) / 6);
  setSelect(field('ch2-vdiv'), Math.max(span(cols.ch2), 1e-9) / 6);
  setSelect(field('ch3-vdiv'), Math.max(span(cols.ch3), 1e-9) / 6);
  for (const k of [1, 2, 3]) field(`ch${k}-pos`).value = '0';
}

/** The dimensionless columns of a trajectory; the physical ones follow them in its `columns`. */
const DIMENSIONLESS = ['tau', 'y', 'v', 'drive', 'phase'];

/** The physical columns of a trace: t (s, from its start), ch1 drive, ch2 position, ch3 velocity.
 * A steady state's recorded cycle is in its `trace.columns` and its `columns` names the four
 * physical ones; a simulation is a trajectory report, its columns at the top level and its
 * `columns` naming every one. */
export function channelColumns(answer = state.steady) {
  const cols = answer.trace ? answer.trace.columns : answer;
  const physical = (answer.columns || []).filter((name) => !DIMENSIONLESS.includes(name));
  const names = physical.length ? physical : ['t_s', 'uc_V', 'i_A', 'u_V'];
  const t = cols[names[0]] || cols.tau;
  const t0 = t[0];
  return {
    t: t.map((x) => x - t0),
    ch1: cols[names[3]] || cols.drive,
    ch2: cols[names[1]] || cols.y,
    ch3: cols[names[2]] || cols.v,
    names,
  };
}

// ---------------------------------------------------------------- drawing helpers
/** A canvas's size in CSS pixels: as laid out on the page, or (off screen) its backing
 * size over the ratio it was drawn at. */
export function logicalSize(canvas) {
  if (canvas.isConnected && canvas.clientWidth > 0 && canvas.clientHeight > 0) {
    return { w: canvas.clientWidth, h: canvas.clientHeight };
  }
  const r = Number(canvas.dataset.ratio || 1);
  return { w: canvas.width / r, h: canvas.height / r };
}

/** Size the canvas's backing store to its CSS size × devicePixelRatio (sharp on any
 * screen) and return a context that draws in CSS pixels. */
export function prepare(canvas) {
  const ratio = window.devicePixelRatio || 1;
  const { w, h } = logicalSize(canvas);
  const bw = Math.round(w * ratio);
  const bh = Math.round(h * ratio);
  if (canvas.width !== bw || canvas.height !== bh || Number(canvas.dataset.ratio || 1) !== ratio) {
    canvas.width = bw;
    canvas.height = bh;
    canvas.dataset.ratio = String(ratio);
  }
  const g = canvas.getContext('2d');
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  return { g, w, h };
}

export const COLORS = { ch1: '#f2c12e', ch2: '#35c9e6', ch3: '#f06bd1', grid: '#2b4a3f', axis: '#4f7a69', text: '#cfe3da' };
export const SCREEN = { left: 40, top: 26, divX: 10, divY: 8 };

export function graticule(g, box) {
  g.fillStyle = '#0c1a15';
  g.fillRect(0, 0, box.W, box.H);
  g.strokeStyle = COLORS.grid;
  g.lineWidth = 1;
  g.beginPath();
  for (let i = 0; i <= SCREEN.divX; i++) {
    const x = box.x0 + i * box.dx + 0.5;
    g.moveTo(x, box.y0);
    g.lineTo(x, box.y0 + SCREEN.divY * box.dy);
  }
  for (let j = 0; j <= SCREEN.divY; j++) {
    const y = box.y0 + j * box.dy + 0.5;
    g.moveTo(box.x0, y);
    g.lineTo(box.x0 + SCREEN.divX * box.dx, y);
  }
  g.stroke();
  g.strokeStyle = COLORS.axis;
  g.beginPath();
  const cx = box.x0 + 5 * box.dx + 0.5;
  const cy = box.y0 + 4 * box.dy + 0.5;
  for (let i = 0; i <= SCREEN.divX * 5; i++) {
    const x = box.x0 + (i * box.dx) / 5;
    g.moveTo(x, cy - 3);
    g.lineTo(x, cy + 3);
  }
  for (let j = 0; j <= SCREEN.divY * 5; j++) {
    const y = box.y0 + (j * box.dy) / 5;
    g.moveTo(cx - 3, y);
    g.lineTo(cx + 3, y);
  }
  g.stroke();
}

/** The graticule's place: `head` lines of text above it, `foot` lines under it (16 px
 * each). The divisions' width depends on the width alone (the cursors are dragged on it). */
export function screenBox(w, h, head = 1, foot = 1) {
  const x0 = 12;
  const y0 = 10 + 16 * head;
  const dx = (w - 24) / SCREEN.divX;
  const dy = (h - y0 - 14 - 16 * foot) / SCREEN.divY;
  return { x0, y0, dx, dy, W: w, H: h, head, foot };
}

export function label(g, text, x, y, color = COLORS.text, align = 'left') {
  g.fillStyle = color;
  g.textAlign = align;
  g.fillText(text, x, y);
}

// ---------------------------------------------------------------- text that never overlaps
/** The boxes of the text on a canvas as drawn (CSS pixels): each label is placed only where
 * no other is, so that none covers another; the tests read them (window.stickslipLab). */
export class TextBoxes {
  constructor() {
    this.boxes = [];
  }

  /** The box of `text` drawn at (x, y) with this alignment in the context's font. */
  static box(g, text, x, y, align) {
    const m = g.measureText(text);
    const width = m.width;
    const left = align === 'right' ? x - width : align === 'center' ? x - width / 2 : x;
    const ascent = m.actualBoundingBoxAscent || 10;
    const descent = m.actualBoundingBoxDescent || 3;
    return { text, left, right: left + width, top: y - ascent, bottom: y + descent };
  }

  fits(b) {
    return !this.boxes.some((o) => b.left < o.right && o.left < b.right && b.top < o.bottom && o.top < b.bottom);
  }

  /** Draw `text` if it covers no text drawn before; whether it was drawn. `backing`: a
   * ground under it (labels over traces). */
  place(g, text, x, y, color = COLORS.text, align = 'left', backing = null) {
    const b = TextBoxes.box(g, text, x, y, align);
    if (!this.fits(b)) return false;
    if (backing) {
      g.fillStyle = backing;
      g.fillRect(b.left - 2, b.top - 1, b.right - b.left + 4, b.bottom - b.top + 2);
    }
    label(g, text, x, y, color, align);
    this.boxes.push(b);
    return true;
  }
}

/** Items of text (`{ text, color }`) in lines no wider than `width`, `gap` pixels apart. */
export function flow(g, items, width, gap = 18) {
  const lines = [];
  let line = [];
  let used = 0;
  for (const item of items) {
    const w = g.measureText(item.text).width;
    if (line.length && used + gap + w > width) {
      lines.push(line);
      line = [];
      used = 0;
    }
    used += (line.length ? gap : 0) + w;
    line.push(item);
  }
  if (line.length) lines.push(line);
  return lines;
}

// ---------------------------------------------------------------- the scope
/** What the screen shows, as series of physical values: used to draw and to export. */
export function displayed() {
  const s = state.steady;
  if (!s) return null;
  const cols = channelColumns(s);
  const transient = state.trigger === 'transient' && state.transient ? channelColumns(state.transient) : null;
  const T = tdiv();
  const left = -hpos() * T;
  const right = left + SCREEN.divX * T;
  const out = { t: [], ch1: [], ch2: [], ch3: [], left, right, names: cols.names, periodic: !transient };
  if (transient) {
    for (let i = 0; i < transient.t.length; i++) {
      const t = transient.t[i];
      if (t < left || t > right) continue;
      out.t.push(t);
      out.ch1.push(transient.ch1[i]);
      out.ch2.push(transient.ch2[i]);
      out.ch3.push(transient.ch3[i]);
    }
    return out;
  }
  // The steady cycle repeats: its samples, continued over the window (sample j at j·dt, the
  // cycle's sample j mod n), at most about 60000 of them (every stride-th on a long window).
  const n = cols.t.length;
  const P = traceSeconds(s);
  const dt = P / n;
  const stride = Math.max(1, Math.ceil((right - left) / dt / 60000));
  const first = Math.floor(left / dt / stride) * stride - stride;
  const last = Math.ceil(right / dt) + stride;
  for (let j = first; j <= last; j += stride) {
    const t = j * dt;
    if (t < left - stride * dt || t > right + stride * dt) continue;
    const i = ((j % n) + n) % n;
    out.t.push(t);
    out.ch1.push(cols.ch1[i]);
    out.ch2.push(cols.ch2[i]);
    out.ch3.push(cols.ch3[i]);
  }
  return out;
}

/** A trace as a polyline. Where x only grows (Y-T), at most the lowest and the highest
 *  point of each half pixel are drawn, in their order: the same picture, fewer segments. */
export function drawTrace(g, box, xs, ys, color, monotonic = false) {
  const top = box.y0 - 4;
  const bottom = box.y0 + SCREEN.divY * box.dy + 4;
  const clampY = (y) => Math.max(top, Math.min(bottom, y));
  g.strokeStyle = color;
  g.lineWidth = 1;
  g.lineJoin = 'round';
  g.beginPath();
  if (!monotonic || xs.length < 4 * box.dx * SCREEN.divX) {
    for (let i = 0; i < xs.length; i++) {
      if (i === 0) g.moveTo(xs[i], clampY(ys[i]));
      else g.lineTo(xs[i], clampY(ys[i]));
    }
  } else {
    let bucket = null;
    let lo = 0;
    let hi = 0;
    let first = true;
    const emit = () => {
      const [a, b] = lo < hi ? [lo, hi] : [hi, lo];
      for (const i of a === b ? [a] : [a, b]) {
        if (first) g.moveTo(xs[i], clampY(ys[i]));
        else g.lineTo(xs[i], clampY(ys[i]));
        first = false;
      }
    };
    for (let i = 0; i < xs.length; i++) {
      const b = Math.floor(xs[i] * 2);
      if (b !== bucket) {
        if (bucket !== null) emit();
        bucket = b;
        lo = i;
        hi = i;
      } else {
        if (ys[i] < ys[lo]) lo = i;
        if (ys[i] > ys[hi]) hi = i;
      }
    }
    if (bucket !== null) emit();
  }
  g.stroke();
}

export function redraw() {
  if (!state.steady) return;
  // Every position field says whether its value is in range, shown or not.
  for (const name of ['hpos', 'ch1-pos', 'ch2-pos', 'ch3-pos']) position(name);
  const canvas = $('#screen');
  const { g, w, h } = prepare(canvas);
  g.font = '12px system-ui, sans-serif';
  const text = screenText(g, w);
  const box = screenBox(w, h, text.head.length, text.foot.length);
  graticule(g, box);
  const labels = new TextBoxes();
  drawText(g, box, text, labels);
  g.save();
  g.beginPath();
  g.rect(box.x0, box.y0 - 6, SCREEN.divX * box.dx, SCREEN.divY * box.dy + 12);
  g.clip();
  // The record's reference traces beside the computed ones (Y-T and X-Y): how many.
  let refs = 0;
  if (state.mode === 'yt') refs = drawYT(g, box, labels);
  else if (state.mode === 'xy') refs = drawXY(g, box, labels);
  else drawFFT(g, box, labels);
  canvas.dataset.refCount = String(refs);
  g.restore();
  window.stickslipLab.screenText = labels.boxes;
  showCursorReadout();
}

export function yOf(box, k, v) {
  return box.y0 + 4 * box.dy - (v / vdiv(k) + vpos(k)) * box.dy;
}
/** yOf for a whole channel, its settings read once. */
export function ysOf(box, k, values) {
  const scale = vdiv(k);
  const base = box.y0 + 4 * box.dy - vpos(k) * box.dy;
  return values.map((v) => base - (v / scale) * box.dy);
}

export function drawYT(g, box, labels) {
  const d = displayed();
  const perDiv = tdiv();
  const xOf = (t) => box.x0 + ((t - d.left) / perDiv) * box.dx;
  const xs = d.t.map(xOf);
  for (const k of [1, 2, 3]) {
    if (!chOn(k)) continue;
    drawTrace(g, box, xs, ysOf(box, k, d[`ch${k}`]), COLORS[`ch${k}`], true);
  }
  // Channel ground markers on the left edge, side by side where they meet.
  for (const k of [1, 2, 3]) {
    if (!chOn(k)) continue;
    const y = Math.max(box.y0 + 10, Math.min(box.y0 + SCREEN.divY * box.dy, yOf(box, k, 0) + 4));
    for (let x = box.x0 + 2; x < box.x0 + 60; x += 14) if (labels.place(g, `${k}▸`, x, y, COLORS[`ch${k}`])) break;
  }
  const refs = drawRefsYT(g, box, xOf);
  // Trigger marker: t = 0 is the start of the drive period (phase φ).
  const xt = xOf(0);
  if (xt >= box.x0 && xt <= box.x0 + SCREEN.divX * box.dx) labels.place(g, '▼T', xt, box.y0 + 4, '#ffffff', 'center');
  if (field('cursors').checked) {
    g.strokeStyle = '#ffffff';
    g.setLineDash([4, 4]);
    g.beginPath();
    for (const c of [cursorDiv(1), cursorDiv(2)]) {
      const x = box.x0 + c * box.dx + 0.5;
      g.moveTo(x, box.y0);
      g.lineTo(x, box.y0 + SCREEN.divY * box.dy);
    }
    g.stroke();
    g.setLineDash([]);
  }
  return refs;
}

export function drawXY(g, box, labels) {
  const s = state.steady;
  const src = state.trigger === 'transient' && state.transient ? channelColumns(state.transient) : channelColumns(s);
  const xScale = vdiv(1);
  const xBase = box.x0 + 5 * box.dx + vpos(1) * box.dx;
  const xOf = (v) => xBase + (v / xScale) * box.dx;
  const xs = src.ch1.map(xOf);
  const ys = ysOf(box, 2, src.ch2);
  if (state.trigger !== 'transient') {
    xs.push(xs[0]);
    ys.push(ys[0]);
  }
  drawTrace(g, box, xs, ys, '#7cf08a');
  const refs = drawRefsXY(g, box, xOf);
  if (field('cursors').checked) {
    for (const c of [1, 2]) {
      const t = cursorTime(c);
      const v = valuesAt(t);
      if (!v) continue;
      g.fillStyle = '#ffffff';
      g.beginPath();
      g.arc(xOf(v.ch1), yOf(box, 2, v.ch2), 4, 0, 2 * Math.PI);
      g.fill();
      labels.place(g, `t${c}`, xOf(v.ch1) + 6, yOf(box, 2, v.ch2) - 6, '#ffffff');
    }
  }
  return refs;
}

/** Bars of the steady cycle's harmonics of one channel (the library's exact spectrum). */
export function spectrum() {
  const s = state.steady;
  const src = field('fft-source').value;
  const sc = scales();
  let amps;
  if (src === 'ch1') amps = s.harmonics.map((_, k) => (k === 0 ? s.drive.amplitude : 0));
  else if (src === 'ch3') amps = s.current_harmonics.map((a) => a * sc.velocity);
  else amps = s.harmonics.map((a) => a * sc.position);
  const f = s.drive.f_Hz;
  return amps.map((a, k) => ({ k: k + 1, f: (k + 1) * f, a }));
}

/** The unit of the FFT's source channel (V, A; m, m/s, N for the mechanical twin). */
export function fftUnit() {
  const u = units();
  return { ch1: u.drive, ch2: u.position, ch3: u.velocity }[field('fft-source').value];
}

/** The FFT's axes: the span follows the drive (FFT_SPAN_HARMONICS and a half at least, on a
 * 1-2-5 step per division), and the bars are the harmonics on it (the page asks the lab for
 * as many as any span shows); dB re 1 unit RMS by default. */
export function fftAxes() {
  const f = state.steady.drive.f_Hz;
  const hzdiv = nice125(((FFT_SPAN_HARMONICS + 0.5) * f) / SCREEN.divX);
  const bars = spectrum().filter((b) => b.f <= SCREEN.divX * hzdiv);
  const scale = field('fft-scale').value;
  const db = scale !== 'linear';
  // dBV RMS (as bench scopes show it) by default: 20·log10(A/√2 / 1 V); dBV peak on request.
  const rms = scale !== 'db-peak';
  const max = Math.max(...bars.map((b) => b.a), 1e-30);
  const unit = fftUnit();
  if (db) {
    const top = Math.ceil((20 * Math.log10(rms ? max / Math.SQRT2 : max)) / 20) * 20 + 20;
    return { bars, hzdiv, db, rms, top, perDiv: 20, unit };
  }
  return { bars, hzdiv, db, rms, top: 0, perDiv: niceAtLeast(max / 7), unit };
}

/** A harmonic of amplitude `a` in dB re 1 unit, RMS (a/√2) or peak. */
export function dbLevel(a, rms) {
  return 20 * Math.log10(Math.max(rms ? a / Math.SQRT2 : a, 1e-300));
}

export function drawFFT(g, box, labels) {
  const ax = fftAxes();
  const bottom = box.y0 + SCREEN.divY * box.dy;
  const xOf = (f) => box.x0 + (f / ax.hzdiv) * box.dx;
  const level = (a) => (ax.db ? dbLevel(a, ax.rms) : a);
  const yOfLevel = (v) => (ax.db ? box.y0 + ((ax.top - v) / ax.perDiv) * box.dy : bottom - (v / ax.perDiv) * box.dy);
  const color = COLORS[field('fft-source').value];
  for (const b of ax.bars) {
    const x = xOf(b.f);
    const y = Math.max(box.y0, Math.min(bottom, yOfLevel(level(b.a))));
    g.fillStyle = color;
    g.fillRect(x - 3, y, 6, bottom - y);
  }
  // The levels of the divisions on the right edge (over the bars, on the screen's ground),
  // then each bar's order above it where it covers no other text.
  for (let j = 0; j < SCREEN.divY; j++) {
    const v = ax.db ? ax.top - j * ax.perDiv : (SCREEN.divY - j) * ax.perDiv;
    labels.place(g, ax.db ? `${v} dB${ax.unit}` : si(v, ax.unit, 3), box.x0 + SCREEN.divX * box.dx - 4, box.y0 + j * box.dy + 13, COLORS.axis, 'right', 'rgba(12, 26, 21, 0.7)');
  }
  for (const b of ax.bars) {
    const y = Math.max(box.y0, Math.min(bottom, yOfLevel(level(b.a))));
    if (bottom - y > 4) labels.place(g, `${b.k}Ω`, xOf(b.f), y - 4, '#ffffff', 'center');
  }
}

/** The screen's text around the graticule: the lines above it (what the screen shows, and
 * the motion's class on the right) and under it (the channels' scales, the record, or the
 * FFT's frequency axis and levels), each line fitted to the width. */
export function screenText(g, w) {
  const s = state.steady;
  const u = units();
  const width = w - 24;
  const belt = beltOf(s);
  const period = belt.selfExcited ? (s.cycle_period_s ? `, period ${si(s.cycle_period_s, 's')}` : '') : s.period ? `, period ${s.period}` : '';
  const motion = { text: `${s.class}${period}${staticNote(s, true)}`, color: COLORS.text, right: true };
  let head;
  const foot = [];
  if (state.mode === 'fft') {
    const ax = fftAxes();
    head = { text: `FFT of ${field('fft-source').value.toUpperCase()} (steady cycle), ${si(ax.hzdiv, 'Hz', 3)}/div`, color: COLORS.text };
    // The frequency axis: the odd divisions' frequencies under the graticule.
    foot.push({ axis: true, ticks: [1, 3, 5, 7, 9].map((i) => ({ i, text: si(i * ax.hzdiv, 'Hz', 3) })) });
    const level = ax.db ? `${ax.perDiv} dB/div, top ${ax.top} dB${ax.unit} ${ax.rms ? 'RMS' : 'peak'} (re 1 ${ax.unit}${ax.rms ? ' RMS' : ' peak'})` : `${si(ax.perDiv, ax.unit)}/div`;
    foot.push(...flow(g, [{ text: level, color: COLORS.text }, { text: `${si(ax.hzdiv, 'Hz', 3)}/div`, color: COLORS.text }], width));
  } else {
    const trig = state.trigger === 'transient' ? 'from rest (t = 0: start)' : belt.selfExcited ? 'self-excited cycle (no drive)' : 'steady cycle, trigger on the drive';
    head = { text: state.mode === 'xy' ? `X-Y: X = CH1, Y = CH2; ${trig}` : `${si(tdiv(), 's')}/div; ${trig}`, color: COLORS.text };
    const names = { 1: u.drive, 2: u.position, 3: u.velocity };
    const items = [];
    for (const k of [1, 2, 3]) if (chOn(k) || (state.mode === 'xy' && k < 3)) items.push({ text: `CH${k} ${si(vdiv(k), names[k])}/div`, color: COLORS[`ch${k}`] });
    const ref = refLabel();
    if (ref) items.push(ref);
    foot.push(...flow(g, items, width));
  }
  // The class on the head's line when both fit, else on a line of its own.
  const both = g.measureText(head.text).width + 16 + g.measureText(motion.text).width <= width;
  const headLines = both ? [[head, motion]] : [[head], [motion]];
  return { head: headLines, foot: foot.length ? foot : [[]] };
}

/** Draw the screen's text (`screenText`) around the graticule `box`. */
export function drawText(g, box, text, labels) {
  const right = box.x0 + SCREEN.divX * box.dx;
  text.head.forEach((line, n) => {
    const y = 16 + 16 * n;
    for (const item of line) labels.place(g, item.text, item.right ? right : box.x0, y, item.color, item.right ? 'right' : 'left');
  });
  const bottom = box.y0 + SCREEN.divY * box.dy;
  text.foot.forEach((line, n) => {
    const y = bottom + 18 + 16 * n;
    if (line.axis) {
      for (const t of line.ticks) labels.place(g, t.text, box.x0 + t.i * box.dx, y, COLORS.axis, 'center');
      return;
    }
    let x = box.x0;
    for (const item of line) {
      labels.place(g, item.text, x, y, item.color);
      x += g.measureText(item.text).width + 18;
    }
  });
}

// ---------------------------------------------------------------- cursors
export const cursorDiv = (c) => Math.max(0, Math.min(10, Number(field(`cursor${c}`).value) || 0));
export const cursorTime = (c) => -hpos() * tdiv() + cursorDiv(c) * tdiv();

/** The channels at time t of the screen (interpolated between samples). */
export function valuesAt(t) {
  const s = state.steady;
  if (!s) return null;
  const transient = state.trigger === 'transient' && state.transient;
  const cols = transient ? channelColumns(state.transient) : channelColumns(s);
  const n = cols.t.length;
  let x;
  if (transient) {
    const dt = cols.t[1] - cols.t[0];
    x = t / dt;
    if (x < 0 || x > n - 1) return null;
  } else {
    const P = traceSeconds(s);
    x = ((((t % P) + P) % P) / P) * n;
  }
  const i = Math.floor(x) % n;
  const j = (i + 1) % n;
  const a = x - Math.floor(x);
  const at = (arr) => arr[i] * (1 - a) + arr[j] * a;
  return { ch1: at(cols.ch1), ch2: at(cols.ch2), ch3: at(cols.ch3) };
}

export function showCursorReadout() {
  const out = $('[data-cursor="readout"]');
  if (!field('cursors').checked || !state.steady || state.mode === 'fft') {
    out.textContent = state.mode === 'fft' ? 'cursors: Y-T and X-Y modes' : '—';
    return;
  }
  const t1 = cursorTime(1);
  const t2 = cursorTime(2);
  const v1 = valuesAt(t1);
  const v2 = valuesAt(t2);
  const u = units();
  const dt = t2 - t1;
  out.dataset.dt = String(dt);
  let text = `t1 ${si(t1, 's')}, t2 ${si(t2, 's')}, Δt ${si(dt, 's')}, 1/Δt ${si(dt ? 1 / Math.abs(dt) : NaN, 'Hz')}`;
  if (v1 && v2) {
    text += `; CH2 ${si(v1.ch2, u.position)} → ${si(v2.ch2, u.position)}, ΔV ${si(v2.ch2 - v1.ch2, u.position)}`;
    text += `; CH1 ΔV ${si(v2.ch1 - v1.ch1, u.drive)}`;
  }
  out.textContent = text;
}

// For tests: the FFT's axes as drawn (span per division, dB convention).
window.stickslipLab.fftAxes = () => fftAxes();

// Drag a cursor on the screen.
(() => {
  const canvas = $('#screen');
  let dragging = 0;
  const divAt = (event) => {
    const rect = canvas.getBoundingClientRect();
    const { w, h } = logicalSize(canvas);
    const box = screenBox(w, h);
    const x = ((event.clientX - rect.left) / rect.width) * w;
    return (x - box.x0) / box.dx;
  };
  canvas.addEventListener('pointerdown', (event) => {
    if (!field('cursors').checked || state.mode !== 'yt') return;
    const d = divAt(event);
    dragging = Math.abs(d - cursorDiv(1)) <= Math.abs(d - cursorDiv(2)) ? 1 : 2;
    canvas.setPointerCapture(event.pointerId);
    field(`cursor${dragging}`).value = Math.max(0, Math.min(10, d)).toFixed(2);
    redraw();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!dragging) return;
    field(`cursor${dragging}`).value = Math.max(0, Math.min(10, divAt(event))).toFixed(2);
    redraw();
  });
  canvas.addEventListener('pointerup', () => {
    dragging = 0;
  });
})();

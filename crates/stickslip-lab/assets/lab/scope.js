// The scope: its settings, the graticule, Y-T, X-Y and FFT, and the cursors.

import { $, field, si, STEPS, niceAtLeast, nice125, FFT_MIN_HARMONICS } from './util.js';
import { state } from './state.js';
import { scales, units } from './panels.js';
import { drawRefsYT, drawRefsXY, drawRefLabel } from './record.js';

// ---------------------------------------------------------------- scope settings
export const tdiv = () => Number(field('tdiv').value);
export const hpos = () => Number(field('hpos').value) || 0;
export const chOn = (k) => field(`ch${k}-on`).checked;
export const vdiv = (k) => Number(field(`ch${k}-vdiv`).value);
export const vpos = (k) => Number(field(`ch${k}-pos`).value) || 0;

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
  // About two cycles across the ten divisions (at least 1.9).
  const periods = Math.max(2, s.trace.periods);
  setSelect(field('tdiv'), (0.95 * periods) / s.drive.f_Hz / 10);
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

export function screenBox(w, h) {
  const x0 = 12;
  const y0 = SCREEN.top;
  const dx = (w - 24) / SCREEN.divX;
  const dy = (h - SCREEN.top - 30) / SCREEN.divY;
  return { x0, y0, dx, dy, W: w, H: h };
}

export function label(g, text, x, y, color = COLORS.text, align = 'left') {
  g.fillStyle = color;
  g.textAlign = align;
  g.fillText(text, x, y);
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
  // The steady cycle repeats: lay copies of it side by side over the window.
  const n = cols.t.length;
  const P = s.trace.periods / s.drive.f_Hz;
  const dt = P / n;
  const first = Math.floor(left / P) - 1;
  const last = Math.ceil(right / P);
  const reps = last - first + 1;
  const stride = Math.max(1, Math.ceil((reps * n) / 60000));
  for (let r = first; r <= last; r++) {
    for (let i = 0; i < n; i += stride) {
      const t = r * P + i * dt;
      if (t < left - dt || t > right + dt) continue;
      out.t.push(t);
      out.ch1.push(cols.ch1[i]);
      out.ch2.push(cols.ch2[i]);
      out.ch3.push(cols.ch3[i]);
    }
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
  const canvas = $('#screen');
  const { g, w, h } = prepare(canvas);
  const box = screenBox(w, h);
  graticule(g, box);
  g.font = '12px system-ui, sans-serif';
  g.save();
  g.beginPath();
  g.rect(box.x0, box.y0 - 6, SCREEN.divX * box.dx, SCREEN.divY * box.dy + 12);
  g.clip();
  // The record's reference traces beside the computed ones (Y-T and X-Y): how many.
  let refs = 0;
  if (state.mode === 'yt') refs = drawYT(g, box);
  else if (state.mode === 'xy') refs = drawXY(g, box);
  else drawFFT(g, box);
  canvas.dataset.refCount = String(refs);
  g.restore();
  drawFooter(g, box);
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

export function drawYT(g, box) {
  const d = displayed();
  const perDiv = tdiv();
  const xOf = (t) => box.x0 + ((t - d.left) / perDiv) * box.dx;
  const xs = d.t.map(xOf);
  for (const k of [1, 2, 3]) {
    if (!chOn(k)) continue;
    drawTrace(g, box, xs, ysOf(box, k, d[`ch${k}`]), COLORS[`ch${k}`], true);
    // Channel ground marker.
    label(g, `${k}▸`, box.x0 + 2, yOf(box, k, 0) + 4, COLORS[`ch${k}`]);
  }
  const refs = drawRefsYT(g, box, xOf);
  // Trigger marker: t = 0 is the start of the drive period (phase φ).
  const xt = xOf(0);
  if (xt >= box.x0 && xt <= box.x0 + SCREEN.divX * box.dx) label(g, '▼T', xt, box.y0 + 4, '#ffffff', 'center');
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

export function drawXY(g, box) {
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
      label(g, `t${c}`, xOf(v.ch1) + 6, yOf(box, 2, v.ch2) - 6, '#ffffff');
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

export function fftAxes() {
  const bars = spectrum();
  const f = state.steady.drive.f_Hz;
  const shown = Math.max(bars.length, FFT_MIN_HARMONICS) + 0.5;
  const hzdiv = nice125((shown * f) / SCREEN.divX);
  const scale = field('fft-scale').value;
  const db = scale !== 'linear';
  // dBV RMS (as bench scopes show it) by default: 20·log10(A/√2 / 1 V); dBV peak on request.
  const rms = scale !== 'db-peak';
  const max = Math.max(...bars.map((b) => b.a), 1e-30);
  if (db) {
    const top = Math.ceil((20 * Math.log10(rms ? max / Math.SQRT2 : max)) / 20) * 20 + 20;
    return { bars, hzdiv, db, rms, top, perDiv: 20 };
  }
  return { bars, hzdiv, db, rms, top: 0, perDiv: niceAtLeast(max / 7) };
}

/** A harmonic of amplitude `a` in dB re 1 unit, RMS (a/√2) or peak. */
export function dbLevel(a, rms) {
  return 20 * Math.log10(Math.max(rms ? a / Math.SQRT2 : a, 1e-300));
}

export function drawFFT(g, box) {
  const ax = fftAxes();
  const bottom = box.y0 + SCREEN.divY * box.dy;
  const xOf = (f) => box.x0 + (f / ax.hzdiv) * box.dx;
  const level = (a) => (ax.db ? dbLevel(a, ax.rms) : a);
  const yOfLevel = (v) => (ax.db ? box.y0 + ((ax.top - v) / ax.perDiv) * box.dy : bottom - (v / ax.perDiv) * box.dy);
  const color = COLORS[field('fft-source').value];
  const unit = { ch1: units().drive, ch2: units().position, ch3: units().velocity }[field('fft-source').value];
  for (let j = 0; j < SCREEN.divY; j++) {
    const v = ax.db ? ax.top - j * ax.perDiv : (SCREEN.divY - j) * ax.perDiv;
    label(g, ax.db ? `${v} dB${unit} ${ax.rms ? 'RMS' : 'peak'}` : si(v, unit, 3), box.x0 + SCREEN.divX * box.dx - 4, box.y0 + j * box.dy + 13, COLORS.axis, 'right');
  }
  for (let i = 1; i < SCREEN.divX; i += 2) {
    label(g, si(i * ax.hzdiv, 'Hz', 3), box.x0 + i * box.dx, box.y0 + 13, COLORS.axis, 'center');
  }
  for (const b of ax.bars) {
    const x = xOf(b.f);
    const y = Math.max(box.y0, Math.min(bottom, yOfLevel(level(b.a))));
    g.fillStyle = color;
    g.fillRect(x - 3, y, 6, bottom - y);
    if (bottom - y > 4) label(g, `${b.k}Ω`, x, y - 4, '#ffffff', 'center');
  }
}

export function drawFooter(g, box) {
  const s = state.steady;
  const u = units();
  const y = box.y0 + SCREEN.divY * box.dy + 18;
  g.font = '12px system-ui, sans-serif';
  if (state.mode === 'fft') {
    const ax = fftAxes();
    label(g, `FFT of ${field('fft-source').value.toUpperCase()} (steady cycle)  ${si(ax.hzdiv, 'Hz')}/div`, box.x0, 16);
    label(g, ax.db ? `${ax.perDiv} dB/div, top ${ax.top} dB${u.position} ${ax.rms ? 'RMS' : 'peak'} (re 1 ${u.position}${ax.rms ? ' RMS' : ' peak'}), ${si(ax.hzdiv, 'Hz', 3)}/div` : `${si(ax.perDiv, u.position)}/div, ${si(ax.hzdiv, 'Hz', 3)}/div`, box.x0, y);
  } else {
    const parts = [];
    const names = { 1: u.drive, 2: u.position, 3: u.velocity };
    for (const k of [1, 2, 3]) if (chOn(k) || (state.mode === 'xy' && k < 3)) parts.push([k, `CH${k} ${si(vdiv(k), names[k])}/div`]);
    let x = box.x0;
    for (const [k, text] of parts) {
      label(g, text, x, y, COLORS[`ch${k}`]);
      x += g.measureText(text).width + 18;
    }
    drawRefLabel(g, box, y);
    const trig = state.trigger === 'transient' ? 'from rest (t = 0: start)' : 'steady cycle, trigger on the drive';
    const head = state.mode === 'xy' ? `X-Y: X = CH1, Y = CH2; ${trig}` : `${si(tdiv(), 's')}/div; ${trig}`;
    label(g, head, box.x0, 16);
  }
  label(g, `${s.class}${s.period ? `, period ${s.period}` : ''}`, box.x0 + SCREEN.divX * box.dx, 16, COLORS.text, 'right');
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
    const P = s.trace.periods / s.drive.f_Hz;
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

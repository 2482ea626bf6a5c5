// stickslip lab: the page of `stickslip lab`. Every number it shows comes from the server's
// JSON API (docs/lab.md); this script only asks, draws and exports. No framework, no build.
'use strict';

(() => {
  const $ = (selector, root = document) => root.querySelector(selector);
  const $$ = (selector, root = document) => Array.from(root.querySelectorAll(selector));
  // The page's controls never change: look each up once (redraws read them per sample).
  const fields = new Map();
  const field = (name) => {
    if (!fields.has(name)) fields.set(name, document.querySelector(`[name="${name}"]`));
    return fields.get(name);
  };

  // ---------------------------------------------------------------- numbers and units
  /** x to `digits` significant digits, without trailing zeros (plain notation where short). */
  function num(x, digits = 6) {
    if (x === null || x === undefined || !Number.isFinite(x)) return '—';
    if (x === 0) return '0';
    const a = Math.abs(x);
    if (a >= 1e-4 && a < 1e7) {
      const decimals = Math.max(0, digits - 1 - Math.floor(Math.log10(a)));
      let s = x.toFixed(Math.min(decimals, 20));
      if (s.includes('.')) s = s.replace(/0+$/, '').replace(/\.$/, '');
      return s;
    }
    return x.toPrecision(digits).replace(/\.?0+e/, 'e');
  }

  const PREFIXES = [[1e9, 'G'], [1e6, 'M'], [1e3, 'k'], [1, ''], [1e-3, 'm'], [1e-6, 'µ'], [1e-9, 'n'], [1e-12, 'p'], [1e-15, 'f']];
  /** x with an SI prefix and unit: 11.5 mH, 9.97 kHz. */
  function si(x, unit = '', digits = 4) {
    if (x === null || x === undefined || !Number.isFinite(x)) return '—';
    if (x === 0) return `0 ${unit}`.trim();
    const a = Math.abs(x);
    const [scale, prefix] = PREFIXES.find(([s]) => a >= s * 0.9995) || PREFIXES[PREFIXES.length - 1];
    return `${num(x / scale, digits)} ${prefix}${unit}`.trim();
  }
  /** The same, as the API reads it back: 11.5m, 20n (no space, no unit). */
  function siText(x) {
    if (!Number.isFinite(x)) return '';
    if (x === 0) return '0';
    const a = Math.abs(x);
    // No prefix from 0.1 to 1000: 0.7 (V), not 700m.
    if (a >= 0.1 && a < 1000) return num(x, 10);
    const [scale, prefix] = PREFIXES.find(([s]) => a >= s * 0.9995) || PREFIXES[PREFIXES.length - 1];
    return `${num(x / scale, 10)}${prefix === 'µ' ? 'u' : prefix}`;
  }
  /** The 1-2-5 values from 1e-9 to 1e3. */
  const STEPS = (() => {
    const out = [];
    for (let e = -9; e <= 3; e++) for (const m of [1, 2, 5]) out.push(m * 10 ** e);
    return out.map((v) => Number(v.toPrecision(3)));
  })();
  const niceAtLeast = (x) => STEPS.find((s) => s >= x * 0.999) || STEPS[STEPS.length - 1];
  /** The smallest 1-2-5 value at least `x`, at any magnitude (frequency spans). */
  function nice125(x) {
    const e = 10 ** Math.floor(Math.log10(x));
    for (const m of [1, 2, 5, 10]) if (m * e >= x * 0.999) return Number((m * e).toPrecision(3));
    return 10 * e;
  }
  /** Harmonics the FFT span shows at least, as a scope's span follows its signal. */
  const FFT_MIN_HARMONICS = 7;

  // ---------------------------------------------------------------- the API
  class ApiFailure extends Error {
    constructor(status, message, field) {
      super(message);
      this.status = status;
      this.field = field;
    }
  }

  /** GET /api/<name>?<params>; the JSON answer, or an ApiFailure with the server's line. */
  // The page's own name for the server's fair queues (one per open page, not stored).
  const CLIENT_ID = Array.from(crypto.getRandomValues(new Uint8Array(12)), (b) => b.toString(16).padStart(2, '0')).join('');
  async function api(name, params, signal) {
    const response = await fetch(`/api/${name}?${params}`, { signal, headers: { 'X-Lab-Client': CLIENT_ID } });
    let body = null;
    try {
      body = await response.json();
    } catch (e) {
      throw new ApiFailure(response.status, `the server answered ${response.status} without JSON`);
    }
    if (!response.ok) throw new ApiFailure(response.status, body.error || `error ${response.status}`, body.field);
    return body;
  }

  /** One request per slot at a time: a new one aborts the one before (a stale answer is dropped). */
  const slots = {};
  async function latest(slot, name, params) {
    if (slots[slot]) slots[slot].abort();
    const controller = new AbortController();
    slots[slot] = controller;
    try {
      return await api(name, params, controller.signal);
    } finally {
      if (slots[slot] === controller) delete slots[slot];
    }
  }
  const isAbort = (e) => e && e.name === 'AbortError';

  // ---------------------------------------------------------------- state
  const state = {
    presets: [],
    shockley: {},
    system: 'pwl',
    paperParts: true, // the circuit's parts are the paper's: send preset=paper
    shockleyEdited: false,
    drive: { w: 0.95, beta: 2.14 }, // dimensionless drive from a preset, until the user turns a knob
    steady: null,
    steadyQuery: '',
    transient: null,
    theory: null,
    theoryNote: '',
    sweep: null,
    map: null,
    mode: 'yt',
    trigger: 'steady',
    autoscalePending: true,
    started: false,
    seq: 0, // input counter
    shownSeq: 0,
    pendingInputs: [], // [seq, time] of inputs not yet on the screen
  };
  // Latency of input → redraw, in ms, for every input (see docs/lab.md).
  window.stickslipLab = { latencies: [], redraws: 0, state };
  // For tests: the FFT's axes as drawn (span per division, dB convention).
  window.stickslipLab.fftAxes = () => fftAxes();

  const statusEl = $('#status');
  function setStatus(kind, text) {
    statusEl.dataset.labStatus = kind;
    statusEl.textContent = text;
  }

  // ---------------------------------------------------------------- errors beside fields
  function clearErrors(scope) {
    for (const el of $$('.error', scope)) el.textContent = '';
    for (const el of $$('[aria-invalid="true"]', scope)) el.removeAttribute('aria-invalid');
  }
  function showError(failure, fallbackScope) {
    const name = failure.field;
    const slot = name ? $(`[data-error-for~="${CSS.escape(name)}"]`) : null;
    if (slot) {
      slot.textContent = failure.message;
      const input = field(name) || field(`sweep-${name}`) || field(`map-${name}`) || (/-steps$/.test(name) ? field('map-size') : null) || field(slot.dataset.errorFor.split(' ')[0]);
      if (input) input.setAttribute('aria-invalid', 'true');
    } else if (fallbackScope) {
      fallbackScope.textContent = failure.message;
    }
  }

  // ---------------------------------------------------------------- the model query
  const PART_KEYS = ['inductance', 'capacitance', 'resistance', 'ut'];
  const SHOCKLEY_KEYS = ['diode-is', 'diode-n', 'diode-rs', 'temperature'];
  const MECHANICS_KEYS = ['mass', 'stiffness', 'damping', 'friction', 'mu-s'];
  const value = (name) => (field(name).value || '').trim();

  /** The model keys for the API: the description, and the drive unless `withoutDrive`. */
  function modelParams({ frequency = true, amplitude = true } = {}) {
    const p = new URLSearchParams();
    if (state.system === 'mechanics') {
      for (const k of MECHANICS_KEYS) p.set(k, value(k));
    } else {
      if (state.paperParts) p.set('preset', 'paper');
      else {
        for (const k of PART_KEYS) p.set(k, value(k));
        if (state.system === 'pwl') p.set('rd', value('rd'));
      }
      if (state.system === 'shockley') {
        p.set('model', 'shockley');
        // The 1N4148 defaults are the library's own until a value is edited.
        if (state.shockleyEdited) for (const k of SHOCKLEY_KEYS) p.set(k, value(k));
      }
    }
    if (frequency) {
      if (state.drive.w !== null) p.set('w', String(state.drive.w));
      else p.set('freq', value('freq'));
    }
    if (amplitude) {
      if (state.drive.beta !== null) p.set('beta', String(state.drive.beta));
      else p.set('amplitude', value('amplitude'));
    }
    const degrees = Number(value('phase'));
    if (value('phase') !== '' && value('phase') !== '0') {
      p.set('phi', Number.isFinite(degrees) ? String((degrees * Math.PI) / 180) : value('phase'));
    }
    return p;
  }

  // ---------------------------------------------------------------- computing
  // One computation in flight at a time. Inputs that arrive meanwhile are merged: when the
  // answer comes it is drawn (the screen follows a dragged knob), and the newest input is
  // sent next. A computation that has run longer than STALE_MS (the stiff solver, a
  // transient) is dropped for the newest input: its request is aborted.
  const STALE_MS = 150;
  const flight = { busy: false, since: 0, again: false };
  let debounce = null;

  /** Something changed: compute again (at once, or after typing pauses). */
  function schedule(delay = 0) {
    state.seq += 1;
    state.pendingInputs.push([state.seq, performance.now()]);
    performance.mark(`lab-input-${state.seq}`);
    if (!flight.busy) setStatus('pending', 'waiting…');
    clearTimeout(debounce);
    if (delay > 0) debounce = setTimeout(update, delay);
    else update();
  }

  function update() {
    if (flight.busy) {
      flight.again = true;
      if (performance.now() - flight.since > STALE_MS) {
        for (const slot of ['steady', 'transient', 'theory']) if (slots[slot]) slots[slot].abort();
      }
      return;
    }
    flight.busy = true;
    flight.since = performance.now();
    flight.again = false;
    compute().finally(() => {
      flight.busy = false;
      if (flight.again) update();
    });
  }

  async function compute() {
    const seq = state.seq;
    const params = modelParams();
    const query = params.toString();
    setStatus('computing', state.system === 'shockley' ? 'computing (stiff solver)…' : 'computing…');
    const steadyParams = new URLSearchParams(params);
    steadyParams.set('samples', '512');
    const jobs = [latest('steady', 'steady', steadyParams)];
    if (state.trigger === 'transient') jobs.push(latest('transient', 'simulate', transientParams(params)));
    let steady;
    let transient = null;
    try {
      [steady, transient = null] = await Promise.all(jobs);
    } catch (e) {
      if (isAbort(e) || seq !== state.seq) return; // a newer input follows at once
      clearErrors(document.body);
      showError(e, null);
      setStatus('error', e.message);
      // What is on the screen no longer matches the inputs: say so, and export nothing.
      for (const el of [$('#screen'), $('#measurements')]) el.dataset.stale = 'true';
      for (const b of $$('[data-action="export-csv"], [data-action="export-png"], [data-action="copy-measurements"]')) b.disabled = true;
      statusEl.dataset.query = query;
      finishInputs(seq, false);
      return;
    }
    clearErrors($('#generator'));
    clearErrors($('#circuit'));
    for (const el of [$('#screen'), $('#measurements')]) delete el.dataset.stale;
    for (const b of $$('[data-action="export-csv"], [data-action="export-png"], [data-action="copy-measurements"]')) b.disabled = false;
    state.steady = steady;
    state.steadyQuery = query;
    state.transient = transient;
    showDerived();
    if (state.autoscalePending) {
      autoscale();
      state.autoscalePending = false;
    }
    redraw();
    showMeasurements();
    markSweepAndMapStale();
    finishInputs(seq, true);
    statusEl.dataset.query = query;
    if (seq === state.seq) {
      setStatus('ready', `${steady.class}, ${steady.model === 'shockley' ? 'Shockley diodes' : 'exact solution'}`);
    }
    // The theory beside the measurements follows on its own (it does not hold the screen up).
    refreshTheory(params, query);
    if (!state.started) {
      // The first answer: compute the sweep and the map of this circuit once.
      state.started = true;
      runSweep().then(runMap);
    }
  }

  /** The paper's series and the exact orbit at the shown point (PWL model only). */
  function refreshTheory(params, query) {
    const table = $('#measurements');
    if (state.system === 'shockley') {
      if (slots.theory) slots.theory.abort();
      state.theory = null;
      state.theoryNote = 'The series and the exact orbit are those of the PWL model; with Shockley diodes they are not shown.';
      table.dataset.theory = 'none';
      showTheory();
      return;
    }
    table.dataset.theory = 'computing';
    latest('theory', 'theory', params).then(
      (t) => {
        state.theory = t;
        state.theoryNote = '';
        table.dataset.theory = query === state.steadyQuery ? 'ready' : 'computing';
        showTheory();
      },
      (e) => {
        if (isAbort(e)) return;
        state.theory = null;
        state.theoryNote = e.message;
        table.dataset.theory = 'error';
        showTheory();
      },
    );
  }

  /** Every input up to `seq` is now answered on the screen: record how long each took. */
  function finishInputs(seq, drawn) {
    const now = performance.now();
    const lab = window.stickslipLab;
    if (drawn) performance.measure('lab-redraw', `lab-input-${seq}`);
    state.pendingInputs = state.pendingInputs.filter(([s, t]) => {
      if (s > seq) return true;
      lab.latencies.push(now - t);
      performance.clearMarks(`lab-input-${s}`);
      return false;
    });
    if (lab.latencies.length > 5000) lab.latencies.splice(0, lab.latencies.length - 5000);
    if (performance.getEntriesByName('lab-redraw').length > 5000) performance.clearMeasures('lab-redraw');
    lab.redraws += 1;
  }

  function transientParams(params) {
    const p = new URLSearchParams(params);
    const f = state.steady && state.steady.drive ? state.steady.drive.f_Hz : Number(value('freq')) || 1;
    const window = 10 * tdiv();
    const periods = Math.min(2000, Math.max(1, Math.ceil((window + hpos() * tdiv()) * f) + 1));
    const samples = Math.max(8, Math.min(2000, Math.floor(100000 / periods)));
    p.set('periods', String(periods));
    p.set('samples', String(samples));
    return p;
  }

  // ---------------------------------------------------------------- derived readouts
  function scales() {
    return (state.steady && state.steady.scales) || { position: 1, velocity: 1, force: 1, omega0: 1 };
  }
  function units() {
    const mech = state.steady && state.steady.system === 'mechanics';
    return mech ? { drive: 'N', position: 'm', velocity: 'm/s' } : { drive: 'V', position: 'V', velocity: 'A' };
  }

  function showDerived() {
    const s = state.steady;
    const c = s.conversion;
    $('[data-derived="w"]').textContent = num(s.w, 6);
    $('[data-derived="beta"]').textContent = num(s.beta, 6);
    if (c) {
      $('[data-derived="natural"]').textContent =
        `f0 = ${si(c.f0, 'Hz', 6)}, ω0 = ${num(c.omega0, 6)} rad/s, ζ = ${num(c.zeta, 5)}, Q = ${num(c.Q, 5)}`;
    }
    if (s.drive) {
      if (state.drive.w !== null || document.activeElement !== field('freq')) {
        if (state.drive.w !== null) field('freq').value = num(s.drive.f_Hz, 6);
      }
      if (state.drive.beta !== null) field('amplitude').value = num(s.drive.amplitude, 6);
      placeKnobs();
    }
    const u = units();
    for (const el of $$('[data-unit]')) el.textContent = u[el.dataset.unit] || el.textContent;
    const mech = s.system === 'mechanics';
    $('[data-label="ch1"]').textContent = mech ? 'F' : 'U';
    $('[data-label="ch2"]').textContent = mech ? 'position r' : 'u_C';
    $('[data-label="ch3"]').textContent = mech ? 'velocity ṙ' : 'current i';
    $('[data-derived="twin"]').textContent = mech
      ? 'The block is the model itself: spring k, damping γ, dry friction F0 (static μs·F0), driven by F cos Ωt.'
      : 'The same model as a mass on a spring: u_C ↔ position, i ↔ velocity, U ↔ drive force, the diode pair ↔ dry friction (U_t ↔ F0). Red: the motion stops.';
  }

  // The knobs: frequency logarithmic from f0/10 to 3 f0, amplitude linear to 20 U_t.
  function knobRange() {
    const c = state.steady && state.steady.conversion;
    const f0 = c ? c.f0 : 1;
    const force = scales().force;
    return { fmin: f0 / 10, fmax: 3 * f0, amax: 20 * force };
  }
  function placeKnobs() {
    const r = knobRange();
    const f = Number(state.steady.drive.f_Hz);
    field('freq-knob').value = String(Math.round((1000 * Math.log(f / r.fmin)) / Math.log(r.fmax / r.fmin)));
    field('amplitude-knob').value = String(Math.round((1000 * state.steady.drive.amplitude) / r.amax));
  }

  // ---------------------------------------------------------------- scope settings
  const tdiv = () => Number(field('tdiv').value);
  const hpos = () => Number(field('hpos').value) || 0;
  const chOn = (k) => field(`ch${k}-on`).checked;
  const vdiv = (k) => Number(field(`ch${k}-vdiv`).value);
  const vpos = (k) => Number(field(`ch${k}-pos`).value) || 0;

  function fillScaleSelect(select, unit) {
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
  function setSelect(select, v) {
    select.value = String(niceAtLeast(v));
  }

  /** Time/div for two drive periods (or the whole cycle) across the screen; V/div for each channel. */
  function autoscale() {
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

  /** The physical columns of a trace: t (s, from its start), ch1 drive, ch2 position, ch3 velocity. */
  function channelColumns(answer = state.steady) {
    const cols = answer.trace.columns;
    const names = answer.columns || ['t_s', 'uc_V', 'i_A', 'u_V'];
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
  function logicalSize(canvas) {
    if (canvas.isConnected && canvas.clientWidth > 0 && canvas.clientHeight > 0) {
      return { w: canvas.clientWidth, h: canvas.clientHeight };
    }
    const r = Number(canvas.dataset.ratio || 1);
    return { w: canvas.width / r, h: canvas.height / r };
  }

  /** Size the canvas's backing store to its CSS size × devicePixelRatio (sharp on any
   * screen) and return a context that draws in CSS pixels. */
  function prepare(canvas) {
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

  const COLORS = { ch1: '#f2c12e', ch2: '#35c9e6', ch3: '#f06bd1', grid: '#2b4a3f', axis: '#4f7a69', text: '#cfe3da' };
  const SCREEN = { left: 40, top: 26, divX: 10, divY: 8 };

  function graticule(g, box) {
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

  function screenBox(w, h) {
    const x0 = 12;
    const y0 = SCREEN.top;
    const dx = (w - 24) / SCREEN.divX;
    const dy = (h - SCREEN.top - 30) / SCREEN.divY;
    return { x0, y0, dx, dy, W: w, H: h };
  }

  function label(g, text, x, y, color = COLORS.text, align = 'left') {
    g.fillStyle = color;
    g.textAlign = align;
    g.fillText(text, x, y);
  }

  // ---------------------------------------------------------------- the scope
  /** What the screen shows, as series of physical values: used to draw and to export. */
  function displayed() {
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
  function drawTrace(g, box, xs, ys, color, monotonic = false) {
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

  function redraw() {
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
    if (state.mode === 'yt') drawYT(g, box);
    else if (state.mode === 'xy') drawXY(g, box);
    else drawFFT(g, box);
    g.restore();
    drawFooter(g, box);
    showCursorReadout();
  }

  function yOf(box, k, v) {
    return box.y0 + 4 * box.dy - (v / vdiv(k) + vpos(k)) * box.dy;
  }
  /** yOf for a whole channel, its settings read once. */
  function ysOf(box, k, values) {
    const scale = vdiv(k);
    const base = box.y0 + 4 * box.dy - vpos(k) * box.dy;
    return values.map((v) => base - (v / scale) * box.dy);
  }

  function drawYT(g, box) {
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
  }

  function drawXY(g, box) {
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
  }

  /** Bars of the steady cycle's harmonics of one channel (the library's exact spectrum). */
  function spectrum() {
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

  function fftAxes() {
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
  function dbLevel(a, rms) {
    return 20 * Math.log10(Math.max(rms ? a / Math.SQRT2 : a, 1e-300));
  }

  function drawFFT(g, box) {
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

  function drawFooter(g, box) {
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
      const trig = state.trigger === 'transient' ? 'from rest (t = 0: start)' : 'steady cycle, trigger on the drive';
      const head = state.mode === 'xy' ? `X-Y: X = CH1, Y = CH2; ${trig}` : `${si(tdiv(), 's')}/div; ${trig}`;
      label(g, head, box.x0, 16);
    }
    label(g, `${s.class}${s.period ? `, period ${s.period}` : ''}`, box.x0 + SCREEN.divX * box.dx, 16, COLORS.text, 'right');
  }

  // ---------------------------------------------------------------- cursors
  const cursorDiv = (c) => Math.max(0, Math.min(10, Number(field(`cursor${c}`).value) || 0));
  const cursorTime = (c) => -hpos() * tdiv() + cursorDiv(c) * tdiv();

  /** The channels at time t of the screen (interpolated between samples). */
  function valuesAt(t) {
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

  function showCursorReadout() {
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

  // ---------------------------------------------------------------- measurements
  function setMeasure(name, text, value) {
    const el = $(`[data-measure="${name}"]`);
    el.textContent = text;
    if (value !== undefined && Number.isFinite(value)) el.dataset.value = String(value);
    else delete el.dataset.value;
  }
  function setTheory(name, text) {
    $(`[data-theory="${name}"]`).textContent = text;
  }

  function showMeasurements() {
    const s = state.steady;
    const sc = scales();
    const deg = (rad) => (rad === null || rad === undefined ? null : (rad * 180) / Math.PI);
    setMeasure('class', s.class);
    setMeasure('stops', num(s.stops_per_cycle, 4), s.stops_per_cycle);
    setMeasure('period', s.period === null ? 'none found' : `${s.period} (settled after ${s.periods_to_settle})`, s.period);
    setMeasure('gain', num(s.gain, 6), s.gain);
    const a1 = s.harmonics[0] * sc.position;
    const a3 = s.harmonics[2] * sc.position;
    const a5 = s.harmonics[4] * sc.position;
    setMeasure('A1', num(a1, 6), a1);
    setMeasure('A3', num(a3, 6), a3);
    setMeasure('A5', num(a5, 6), a5);
    setMeasure('phase', num(deg(s.phase_lag), 5), deg(s.phase_lag));
    setMeasure('beta', `β = ${num(s.beta, 5)}`, s.beta);

    // Scope measurements over the recorded cycle (steady) or the screen (transient).
    const source = state.trigger === 'transient' && state.transient ? displayed() : channelColumns(s);
    const stats = (arr) => {
      if (!arr.length) return null;
      let lo = Infinity;
      let hi = -Infinity;
      let sq = 0;
      for (const v of arr) {
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
        sq += v * v;
      }
      return { lo, hi, rms: Math.sqrt(sq / arr.length) };
    };
    for (const k of [1, 2]) {
      const st = stats(source[`ch${k}`]);
      setMeasure(`ch${k}-vpp`, st ? num(st.hi - st.lo, 5) : '—', st ? st.hi - st.lo : undefined);
      setMeasure(`ch${k}-stats`, st ? `${num(st.hi, 5)} / ${num(st.lo, 5)} / ${num(st.rms, 5)}` : '—');
    }
    const st3 = stats(source.ch3);
    setMeasure('ch3-vpp', st3 ? num(st3.hi - st3.lo, 5) : '—', st3 ? st3.hi - st3.lo : undefined);
    const f = s.drive ? s.drive.f_Hz : NaN;
    setMeasure('frequency', `${num(f, 6)} / ${num(s.period ? f / s.period : NaN, 6)}`, f);

    showTheory();
  }

  function showTheory() {
    const s = state.steady;
    if (!s) return;
    const sc = scales();
    const deg = (rad) => (rad === null || rad === undefined ? null : (rad * 180) / Math.PI);
    const t = state.theory;
    const p = t ? t.paper : {};
    const e = t ? t.exact : {};
    const volts = (x) => (x === null || x === undefined ? '—' : num(x * sc.position, 6));
    setTheory('paper-A1', volts(p.A1));
    setTheory('paper-A3', volts(p.A3));
    setTheory('paper-A5', volts(p.A5));
    setTheory('exact-A1', volts(e.A1));
    setTheory('exact-A3', volts(e.A3));
    setTheory('exact-A5', volts(e.A5));
    setTheory('paper-gain', t ? num(p.gain, 6) : '—');
    // The simulated gain is the peak over β; on a sliding orbit that is the orbit's peak/β.
    const beta = t ? t.params.beta : NaN;
    setTheory('exact-gain', t && e.peak !== null && e.peak !== undefined && beta > 0 ? num(e.peak / beta, 6) : '—');
    setTheory('paper-phase', t ? num(deg(p.phi0), 5) : '—');
    setTheory('exact-phase', t ? num(deg(e.phase), 5) : '—');
    setTheory('paper-beta_c', t ? num(p.beta_c, 5) : '—');
    setTheory('exact-beta_c', t ? num(e.beta_c, 5) : '—');
    setTheory('paper-class', t && p.beta_c !== null ? (beta >= p.beta_c ? 'slides (β ≥ β_c)' : 'sticks (β < β_c)') : '—');
    setTheory('exact-class', t ? (e.exists ? 'sliding orbit exists' : 'no sliding orbit') : '—');
    // Each theory describes a motion that never sticks: where its own verdict is that the
    // motion sticks, its numbers do not apply and are greyed.
    const table = $('#measurements');
    table.dataset.paperApplies = t && p.beta_c !== null && beta < p.beta_c ? 'no' : 'yes';
    table.dataset.exactApplies = t && !e.exists ? 'no' : 'yes';
    const notes = [];
    if (state.theoryNote) notes.push(state.theoryNote);
    if (t && p.note) notes.push(`paper: ${p.note}`);
    if (t && e.note) notes.push(`exact: ${e.note}`);
    if (table.dataset.paperApplies === 'no') notes.push('The paper’s series assumes sliding; its own β_c says the motion sticks here, so its numbers (greyed) do not apply.');
    if (table.dataset.exactApplies === 'no') notes.push('No sliding orbit exists here: the exact orbit’s column (greyed) does not apply.');
    notes.push('exact gain: the orbit’s peak/β (the measured G is (max − min)/2β); paper gain: its A1/β.');
    setTheory('notes', notes.join(' '));
  }

  // ---------------------------------------------------------------- the mechanical view
  const mech = { start: performance.now() };
  function drawMechanics(now) {
    const canvas = $('#mechanics-view');
    const s = state.steady;
    if (!s || document.hidden) return;
    const { g, w, h } = prepare(canvas);
    g.fillStyle = '#fbfcfa';
    g.fillRect(0, 0, w, h);
    const cols = s.trace.columns;
    const n = cols.y.length;
    const cycleSeconds = 2.5 * s.trace.periods;
    const phase = (((now - mech.start) / 1000) % cycleSeconds) / cycleSeconds;
    const i = Math.min(n - 1, Math.floor(phase * n));
    if (!s.extent) {
      s.extent = {
        y: Math.max(...cols.y.map(Math.abs), 1e-9),
        drive: Math.max(...cols.drive.map(Math.abs), 1e-9),
      };
    }
    const ymax = s.extent.y;
    const floor = h - 28;
    const x0 = w / 2 + 20;
    const reach = w / 2 - 90;
    const x = x0 + (cols.y[i] / ymax) * reach;
    // Ground with friction hatching.
    g.strokeStyle = '#6b756f';
    g.lineWidth = 1;
    g.beginPath();
    g.moveTo(20, floor);
    g.lineTo(w - 10, floor);
    for (let k = 24; k < w - 10; k += 9) {
      g.moveTo(k, floor);
      g.lineTo(k - 6, floor + 7);
    }
    g.moveTo(20, 12);
    g.lineTo(20, floor);
    g.stroke();
    // Spring from the wall to the block.
    const bw = 48;
    const bh = 36;
    const left = x - bw / 2;
    g.strokeStyle = '#444';
    g.lineWidth = 1.6;
    g.beginPath();
    const y = floor - bh / 2;
    g.moveTo(20, y);
    const coils = 12;
    for (let k = 0; k <= coils; k++) {
      const px = 30 + ((left - 40) * k) / coils;
      g.lineTo(px, y + (k % 2 ? -8 : 8) * (k && k < coils ? 1 : 0));
    }
    g.lineTo(left, y);
    g.stroke();
    // The block: red while stuck (velocity zero).
    const v = cols.v[i];
    const stuck = Math.abs(v) <= (s.model === 'shockley' ? 1e-3 : 1e-9);
    g.fillStyle = stuck ? '#c0392b' : '#2e7d66';
    g.fillRect(left, floor - bh, bw, bh);
    // The drive force.
    const arrow = (cols.drive[i] / s.extent.drive) * 60;
    g.strokeStyle = COLORS.ch1;
    g.fillStyle = COLORS.ch1;
    g.lineWidth = 3;
    g.beginPath();
    g.moveTo(x, floor - bh - 10);
    g.lineTo(x + arrow, floor - bh - 10);
    g.stroke();
    if (Math.abs(arrow) > 4) {
      const d = Math.sign(arrow);
      g.beginPath();
      g.moveTo(x + arrow + d * 7, floor - bh - 10);
      g.lineTo(x + arrow, floor - bh - 15);
      g.lineTo(x + arrow, floor - bh - 5);
      g.fill();
    }
    g.font = '11px system-ui, sans-serif';
    label(g, stuck ? 'stuck' : 'sliding', left + bw / 2, floor - bh / 2 + 4, '#ffffff', 'center');
    label(g, 'drive force', w - 12, 14, '#8a6d00', 'right');
  }
  function animate(now) {
    drawMechanics(now);
    requestAnimationFrame(animate);
  }

  // ---------------------------------------------------------------- sweep and map
  /** `pwl`, `shockley` or `mechanics`: the system an answer was computed for. */
  const kindOf = (answer) => (answer.system === 'mechanics' ? 'mechanics' : answer.model);
  const KIND_NAMES = { pwl: 'the circuit with PWL diodes', shockley: 'the circuit with Shockley diodes', mechanics: 'the mechanical oscillator' };

  /** Mark a view whose answer no longer matches the inputs (`why`), or clear the mark. */
  function setStale(canvas, statusEl, why) {
    if (why) {
      canvas.dataset.stale = 'true';
      statusEl.dataset.stale = 'true';
      statusEl.textContent = why;
    } else {
      delete canvas.dataset.stale;
      delete statusEl.dataset.stale;
    }
  }

  function markSweepAndMapStale() {
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
  function experimentBase(answer) {
    if (!answer || !answer.experiment) return '';
    return answer.experiment.split(';')[0];
  }

  /** Axes, grid and labels of a plot; `legendRow` leaves a row under the x label. */
  function plotFrame(canvas, xr, yr, xlabel, ylabel, legendRow = false) {
    const { g, w, h } = prepare(canvas);
    const box = { l: 56, r: w - 14, t: 14, b: h - (legendRow ? 58 : 40) };
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

  function polyline(g, pts, color, width = 1.5, dash = []) {
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
  const layers = {};
  function cached(name, canvas, source, render) {
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

  function placeholder(canvas, text) {
    const { g, w, h } = prepare(canvas);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, w, h);
    g.font = '13px system-ui, sans-serif';
    label(g, text, w / 2, h / 2, '#555', 'center');
  }

  function drawSweep() {
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
      const gains = sw.points.map((p) => p.gain).concat(sw.theory.exact_peak_gain.filter(Number.isFinite));
      const ymax = Math.max(...gains.filter(Number.isFinite), 0.1) * 1.08;
      const f0 = sw.conversion ? sw.conversion.f0 : null;
      const frame = plotFrame(off, xr, [0, ymax], f0 ? `w = Ω/ω0 (f0 = ${si(f0, 'Hz')})` : 'w', 'gain G');
      const { g: o, X, Y, box } = frame;
      const th = sw.theory;
      polyline(o, th.x.map((x, i) => [X(x), th.paper_gain[i] === null || th.paper_gain[i] > ymax ? NaN : Y(th.paper_gain[i])]), '#cc79a7', 2, [6, 4]);
      polyline(o, th.x.map((x, i) => [X(x), th.exact_peak_gain[i] === null ? NaN : Y(th.exact_peak_gain[i])]), '#000000', 2);
      for (const [leg, color, dash] of [['up', '#0072b2', []], ['down', '#d55e00', [5, 3]]]) {
        const pts = sw.points.filter((p) => p.leg === leg);
        polyline(o, pts.map((p) => [X(p.value), Y(p.gain)]), color, 2, dash);
        o.fillStyle = color;
        for (const p of pts) {
          if (p.stops_per_cycle > 0) o.fillRect(X(p.value) - 2.5, Y(p.gain) - 2.5, 5, 5);
        }
      }
      const legend = [['#0072b2', 'swept up'], ['#d55e00', 'swept down'], ['#cc79a7', `${th.prefix}paper, eq. (11): A1/β`], ['#000', `${th.prefix}exact orbit: peak/β`], ['#c00', 'now']];
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

  const CLASS_COLORS = { sliding: '#dadada', 'periodic-stick': '#0072b2', 'nonperiodic-stick': '#d55e00', static: '#009e73', chaotic: '#7570b3' };
  function drawMap() {
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
      const { g: o, X, Y, box } = plotFrame(off, xr, yr, 'w = Ω/ω0', 'β = U/U_t', true);
      const nb = m.beta.length;
      for (let i = 0; i < m.w.length; i++) {
        for (let j = 0; j < nb; j++) {
          o.fillStyle = CLASS_COLORS[m.classes[m.class[i * nb + j]]] || '#888';
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
      let lx = box.l + 6;
      // The classes found on this map, in the library's order.
      const found = new Set(m.class);
      for (const c of m.classes.filter((_, k) => found.has(k))) {
        o.fillStyle = CLASS_COLORS[c];
        o.fillRect(lx, box.b + 40, 10, 10);
        o.strokeStyle = '#999';
        o.strokeRect(lx, box.b + 40, 10, 10);
        label(o, c, lx + 13, box.b + 49, '#222');
        lx += o.measureText(c).width + 26;
      }
      label(o, `${b.prefix}β_c: exact ━, paper ╍`, box.r, box.b + 49, '#222', 'right');
      return { X, Y, box };
    });
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

  async function runSweep() {
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

  async function runMap() {
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
      for (const c of answer.class) counts[answer.classes[c]] = (counts[answer.classes[c]] || 0) + 1;
      out.textContent = Object.entries(counts).map(([k, v]) => `${k} ${v}`).join(', ');
      out.dataset.state = 'ready';
      drawMap();
    } catch (e) {
      clearInterval(ticker);
      if (isAbort(e)) return;
      out.dataset.state = 'error';
      out.textContent = '';
      showError(e, out);
    }
  }

  // ---------------------------------------------------------------- export
  function download(blob, name) {
    const url = URL.createObjectURL(blob);
    const a = document.createElement('a');
    a.href = url;
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
  }

  /** The displayed traces as CSV (Y-T: the screen's samples; X-Y: the loop; FFT: the bars). */
  function csv() {
    const s = state.steady;
    const u = units();
    const lines = [];
    if (state.mode === 'fft') {
      const ax = fftAxes();
      const unit = { ch1: u.drive, ch2: u.position, ch3: u.velocity }[field('fft-source').value];
      const u2 = unit.replace('/', '_');
      lines.push(`harmonic,f_Hz,amplitude_peak_${u2},level_dB${u2}_rms,level_dB${u2}_peak`);
      for (const b of ax.bars) lines.push(`${b.k},${b.f},${b.a},${dbLevel(b.a, true)},${dbLevel(b.a, false)}`);
    } else {
      const names = channelColumns(s).names;
      const d = state.mode === 'xy'
        ? (state.trigger === 'transient' && state.transient ? channelColumns(state.transient) : channelColumns(s))
        : displayed();
      lines.push([names[0], names[3], names[1], names[2]].join(','));
      // Time from the first sample, as a scope's export counts it.
      const t0 = d.t.length ? d.t[0] : 0;
      for (let i = 0; i < d.t.length; i++) lines.push(`${d.t[i] - t0},${d.ch1[i]},${d.ch2[i]},${d.ch3[i]}`);
    }
    return `${lines.join('\n')}\n`;
  }

  function fileStem() {
    const s = state.steady;
    const f = s.drive ? `${num(s.drive.f_Hz, 5)}Hz-${num(s.drive.amplitude, 4)}${units().drive}` : `w${s.w}-beta${s.beta}`;
    const view = state.mode === 'fft' ? 'fft' : `${state.mode}-${state.trigger === 'transient' ? 'transient' : 'steady'}`;
    return `stickslip-lab-${view}-${f}`;
  }

  /** The caption of an exported picture: the experiment in full, the drive, the result. */
  function captionText() {
    const s = state.steady;
    const u = units();
    const parts = [s.experiment];
    if (s.drive) parts.push(`drive f = ${si(s.drive.f_Hz, 'Hz', 6)}, amplitude ${si(s.drive.amplitude, u.drive, 5)}`);
    parts.push(`w = Ω/ω0 = ${num(s.w, 6)}, β = ${num(s.beta, 6)}`);
    parts.push(`class ${s.class}, gain G = ${num(s.gain, 6)}, ${s.stops_per_cycle} stops per period`);
    parts.push(`view ${state.mode === 'fft' ? `FFT (${field('fft-scale').value})` : state.mode}, ${state.trigger}; stickslip lab`);
    return parts.join('; ');
  }

  /** `text` broken into lines of at most `width` pixels in the context's font. */
  function wrapText(g, text, width) {
    const lines = [];
    let line = '';
    for (const word of text.split(' ')) {
      const next = line ? `${line} ${word}` : word;
      if (line && g.measureText(next).width > width) {
        lines.push(line);
        line = word;
      } else {
        line = next;
      }
    }
    if (line) lines.push(line);
    return lines;
  }

  function exportPng() {
    const screen = $('#screen');
    const ratio = screen.width / (screen.clientWidth || screen.width) || 1;
    const measure = document.createElement('canvas').getContext('2d');
    measure.font = '12px system-ui, sans-serif';
    const cssWidth = screen.width / ratio;
    const lines = wrapText(measure, captionText(), cssWidth - 16);
    const out = document.createElement('canvas');
    out.width = screen.width;
    out.height = screen.height + Math.round((10 + 16 * lines.length) * ratio);
    const g = out.getContext('2d');
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, out.width, out.height);
    g.drawImage(screen, 0, 0);
    g.scale(ratio, ratio);
    g.font = '12px system-ui, sans-serif';
    g.fillStyle = '#222';
    lines.forEach((line, k) => g.fillText(line, 8, screen.height / ratio + 16 + 16 * k));
    window.stickslipLab.lastCaption = lines;
    out.toBlob((blob) => download(blob, `${fileStem()}.png`), 'image/png');
  }

  /** The measurements table as tab-separated text (pasted into a spreadsheet or a report). */
  function measurementsTsv() {
    const rows = [];
    const table = $('#measurements table');
    for (const tr of $$('tr', table)) {
      rows.push(Array.from(tr.children, (c) => c.textContent.replace(/\s+/g, ' ').replace(/ \?$/, '').trim()).join('\t'));
    }
    if (state.steady) rows.unshift(`experiment\t${captionText()}`);
    return `${rows.join('\n')}\n`;
  }

  async function copyMeasurements() {
    const text = measurementsTsv();
    window.stickslipLab.lastCopied = text;
    const out = $('[data-copy="status"]');
    try {
      await navigator.clipboard.writeText(text);
      out.textContent = 'copied: paste into a spreadsheet or a report';
    } catch (e) {
      // Without clipboard permission: select the text for Ctrl-C.
      const area = document.createElement('textarea');
      area.value = text;
      document.body.append(area);
      area.select();
      const ok = document.execCommand && document.execCommand('copy');
      area.remove();
      out.textContent = ok ? 'copied: paste into a spreadsheet or a report' : 'the browser refused the clipboard';
    }
  }

  // ---------------------------------------------------------------- presets
  function applyPreset(id) {
    const preset = state.presets.find((p) => p.id === id);
    if (!preset) return;
    const v = preset.values;
    if (preset.system === 'mechanics') {
      state.system = 'mechanics';
      for (const k of MECHANICS_KEYS) if (k in v) field(k).value = num(v[k], 6);
    } else {
      if (state.system === 'mechanics') state.system = 'pwl';
      for (const k of PART_KEYS.concat(['rd'])) if (k in v) field(k).value = siText(v[k]);
      state.paperParts = preset.paper;
    }
    field('system').value = state.system;
    if ('w' in v) state.drive.w = v.w;
    if ('beta' in v) state.drive.beta = v.beta;
    showSystem();
    state.autoscalePending = true;
  }

  /** Map sizes that finish within the time limit (10 s) on a 2-core laptop: the exact
   * solver takes about 0.3 ms a point, the stiff one about 6 ms (docs/lab.md). */
  const MAP_SIZES = {
    pwl: [['40x30', '40 × 30'], ['60x50', '60 × 50'], ['120x100', '120 × 100']],
    shockley: [['16x12', '16 × 12'], ['24x20', '24 × 20'], ['32x24', '32 × 24']],
  };
  function fillMapSizes() {
    const select = field('map-size');
    const sizes = MAP_SIZES[state.system === 'shockley' ? 'shockley' : 'pwl'];
    const keep = select.value;
    select.replaceChildren(...sizes.map(([v, text]) => new Option(text, v)));
    select.value = sizes.some(([v]) => v === keep) ? keep : sizes[1][0];
  }

  function showSystem() {
    for (const fs of $$('fieldset[data-for-system]')) fs.hidden = !fs.dataset.forSystem.split(' ').includes(state.system);
  }

  // ---------------------------------------------------------------- wiring
  /** A knob or a typed drive value leaves a preset's point: the preset reads "custom". */
  function leavePresetPoint() {
    const select = field('preset-choice');
    if (select.value.startsWith('fig3-')) select.value = 'custom';
  }

  function wire() {
    // Typing: compute when typing pauses, at once on Enter or leaving the field.
    const typed = (name, onEdit) => {
      const el = field(name);
      el.addEventListener('input', () => {
        onEdit();
        schedule(350);
      });
      el.addEventListener('change', () => {
        onEdit();
        schedule(0);
      });
    };
    typed('freq', () => {
      state.drive.w = null;
      leavePresetPoint();
    });
    typed('amplitude', () => {
      state.drive.beta = null;
      leavePresetPoint();
    });
    typed('phase', () => {});
    for (const k of PART_KEYS.concat(['rd'])) {
      typed(k, () => {
        state.paperParts = false;
        field('preset-choice').value = 'custom';
      });
    }
    for (const k of SHOCKLEY_KEYS) {
      typed(k, () => {
        state.shockleyEdited = true;
        field('preset-choice').value = 'custom';
      });
    }
    for (const k of MECHANICS_KEYS) typed(k, () => {});

    // Knobs: every movement computes at once; a newer request drops the one before.
    field('freq-knob').addEventListener('input', (event) => {
      leavePresetPoint();
      const r = knobRange();
      const f = r.fmin * (r.fmax / r.fmin) ** (Number(event.target.value) / 1000);
      field('freq').value = num(f, 5);
      state.drive.w = null;
      schedule(0);
    });
    field('amplitude-knob').addEventListener('input', (event) => {
      leavePresetPoint();
      const r = knobRange();
      field('amplitude').value = num((r.amax * Number(event.target.value)) / 1000, 4);
      state.drive.beta = null;
      schedule(0);
    });

    field('preset-choice').addEventListener('change', (event) => {
      applyPreset(event.target.value);
      schedule(0);
    });
    field('system').addEventListener('change', (event) => {
      const before = state.system;
      state.system = event.target.value;
      if (state.system === 'mechanics' && before !== 'mechanics') applyPreset('mechanics');
      else if (before === 'mechanics' && state.system !== 'mechanics') {
        const keepSystem = state.system;
        applyPreset('fig3-2b');
        state.system = keepSystem;
        field('system').value = keepSystem;
        showSystem();
      }
      // A Fig. 3 point is the paper's PWL circuit: with Shockley diodes it is a custom point.
      field('preset-choice').value = state.system === 'mechanics' ? 'mechanics' : state.system === 'shockley' ? 'custom' : field('preset-choice').value;
      fillMapSizes();
      showSystem();
      state.autoscalePending = true;
      schedule(0);
    });

    for (const radio of $$('input[name="mode"]')) {
      radio.addEventListener('change', () => {
        state.mode = radio.value;
        redraw();
      });
    }
    field('trigger').addEventListener('change', (event) => {
      state.trigger = event.target.value;
      schedule(0);
    });
    field('tdiv').addEventListener('change', () => (state.trigger === 'transient' ? schedule(0) : redraw()));
    field('hpos').addEventListener('input', () => (state.trigger === 'transient' ? schedule(200) : redraw()));
    for (const name of ['ch1-on', 'ch2-on', 'ch3-on', 'ch1-vdiv', 'ch2-vdiv', 'ch3-vdiv', 'ch1-pos', 'ch2-pos', 'ch3-pos', 'fft-source', 'fft-scale', 'cursors', 'cursor1', 'cursor2']) {
      field(name).addEventListener('input', redraw);
      field(name).addEventListener('change', redraw);
    }
    $('[data-action="autoscale"]').addEventListener('click', () => {
      autoscale();
      redraw();
    });
    $('[data-action="export-csv"]').addEventListener('click', () => {
      if (state.steady) download(new Blob([csv()], { type: 'text/csv' }), `${fileStem()}.csv`);
    });
    $('[data-action="export-png"]').addEventListener('click', () => {
      if (state.steady) exportPng();
    });
    $('[data-action="sweep"]').addEventListener('click', runSweep);
    $('[data-action="copy-measurements"]').addEventListener('click', copyMeasurements);
    $('[data-action="map"]').addEventListener('click', runMap);
    window.addEventListener('resize', () => {
      redraw();
      drawSweep();
      drawMap();
    });
  }

  async function start() {
    fillScaleSelect(field('tdiv'), 's');
    fillScaleSelect(field('ch1-vdiv'), 'V');
    fillScaleSelect(field('ch2-vdiv'), 'V');
    fillScaleSelect(field('ch3-vdiv'), 'A');
    let presets;
    try {
      presets = await api('presets', '');
    } catch (e) {
      setStatus('error', `cannot reach the lab server: ${e.message}`);
      return;
    }
    state.presets = presets.presets;
    state.shockley = presets.shockley;
    const select = field('preset-choice');
    for (const p of state.presets) {
      const o = document.createElement('option');
      o.value = p.id;
      o.textContent = p.label;
      select.append(o);
    }
    const custom = document.createElement('option');
    custom.value = 'custom';
    custom.textContent = 'custom (values of your own)';
    select.append(custom);
    for (const k of SHOCKLEY_KEYS) field(k).value = siText(state.shockley[k]);
    field('temperature').value = num(state.shockley.temperature, 6);
    field('diode-n').value = num(state.shockley['diode-n'], 6);
    // Mechanical parts start as the example, for when the model is switched.
    const m = state.presets.find((p) => p.id === 'mechanics');
    for (const k of MECHANICS_KEYS) field(k).value = num(m.values[k], 6);
    // The paper's circuit at its Fig. 3 point (2b): Ω/ω0 = 0.95, β = 2.14.
    select.value = 'fig3-2b';
    applyPreset('fig3-2b');
    fillMapSizes();
    wire();
    drawSweep();
    drawMap();
    schedule(0);
    requestAnimationFrame(animate);
  }

  start();
})();

// stickslip lab: the page of `stickslip lab`. Every number it shows comes from the server's
// JSON API (docs/lab.md); these modules only ask, draw and export. No framework, no build:
// the browser loads the ES modules of lab/ as they are. This one computes and wires the page.

import { $, $$, field, num, FFT_MAX_HARMONICS } from './lab/util.js';
import { api, slots, latest, isAbort } from './lab/api.js';
import { state, statusEl, setStatus, clearErrors, showError, value, modelParams, holdGenerator } from './lab/state.js';
import { showDerived, knobRange, showMeasurements, showTheory, animate, applyPreset, fillMapSizes, showSystem, beltOf } from './lab/panels.js';
import { tdiv, hpos, fillScaleSelect, autoscale, redraw } from './lab/scope.js';
import { markSweepAndMapStale, drawSweep, drawMap, runSweep, runMap, runCurves } from './lab/sweepmap.js';
import { download, csv, fileStem, exportPng, copyMeasurements } from './lab/export.js';
import { wireRecord } from './lab/record.js';
import { refreshOrbit } from './lab/orbit.js';
import { buildForm, fieldsOf, isPart, fieldText, showLawFields, lawChooserFlag } from './lab/form.js';

// ---------------------------------------------------------------- computing
// One computation in flight at a time. Inputs that arrive meanwhile are merged: when the
// answer comes it is drawn (the screen follows a dragged knob), and the newest input is
// sent next. A computation that has run longer than STALE_MS (the stiff solver, a
// transient) is dropped for the newest input: its request is aborted.
export const STALE_MS = 150;
export const flight = { busy: false, since: 0, again: false };
let debounce = null;

/** Something changed: compute again (at once, or after typing pauses). */
export function schedule(delay = 0) {
  state.seq += 1;
  state.pendingInputs.push([state.seq, performance.now()]);
  performance.mark(`lab-input-${state.seq}`);
  if (!flight.busy) setStatus('pending', 'waiting…');
  clearTimeout(debounce);
  if (delay > 0) debounce = setTimeout(update, delay);
  else update();
}

export function update() {
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

export async function compute() {
  const seq = state.seq;
  const params = modelParams();
  const query = params.toString();
  setStatus('computing', state.system === 'shockley' ? 'computing (stiff solver)…' : 'computing…');
  const steadyParams = new URLSearchParams(params);
  steadyParams.set('samples', '512');
  // As many harmonics as any FFT span shows (the screen shows those on its span).
  steadyParams.set('harmonics', String(FFT_MAX_HARMONICS));
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
  // The theory beside the measurements follows on its own (it does not hold the screen up),
  // and so does the periodic orbit with its multipliers.
  refreshTheory(params, query);
  refreshOrbit(params, query);
  if (!state.started) {
    // The first answer: compute the sweep and the map of this circuit once.
    state.started = true;
    runSweep().then(runMap);
  }
}

/** The paper's series and the exact orbit at the shown point (PWL model only). */
export function refreshTheory(params, query) {
  const table = $('#measurements');
  const belt = state.steady ? beltOf(state.steady) : { moving: false };
  if (state.system === 'shockley' || belt.moving) {
    if (slots.theory) slots.theory.abort();
    state.theory = null;
    state.theoryNote = belt.moving
      ? 'The series and the exact orbit are those of Coulomb friction on a surface at rest; on a belt, or with another friction law, they are not shown.'
      : 'The series and the exact orbit are those of the PWL model; with Shockley diodes they are not shown.';
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
export function finishInputs(seq, drawn) {
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

export function transientParams(params) {
  const p = new URLSearchParams(params);
  const f = state.steady && state.steady.drive ? state.steady.drive.f_Hz : Number(value('freq')) || 1;
  const window = 10 * tdiv();
  // Within the server's caps: its periods, and half its samples (a screenful needs no more).
  const periods = Math.min(state.caps.simulate_periods, Math.max(1, Math.ceil((window + hpos() * tdiv()) * f) + 1));
  const samples = Math.max(8, Math.min(2000, Math.floor(state.caps.simulate_total / 2 / periods)));
  p.set('periods', String(periods));
  p.set('samples', String(samples));
  return p;
}

// ---------------------------------------------------------------- wiring
/** A knob or a typed drive value leaves a preset's point: the preset reads "custom". */
export function leavePresetPoint() {
  const select = field('preset-choice');
  if (select.value.startsWith('fig3-')) select.value = 'custom';
}

export function wire() {
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
  // The circuit's parts (a preset's, or the paper's until one is edited), the Shockley
  // diodes' parameters (the library's defaults until one is edited), the mechanical parts.
  // A part changed: the generator stays where it is (Hz and V), w and β follow.
  for (const k of fieldsOf('pwl').filter(isPart)) {
    typed(k, () => {
      state.paperParts = false;
      holdGenerator();
      field('preset-choice').value = 'custom';
    });
  }
  for (const k of fieldsOf('shockley').filter((f) => !isPart(f))) {
    typed(k, () => {
      state.shockleyEdited = true;
      holdGenerator();
      field('preset-choice').value = 'custom';
    });
  }
  for (const k of fieldsOf('mechanics')) typed(k, holdGenerator);
  // The friction law shows its own parameters (and the map the sizes its solver finishes).
  const chooser = lawChooserFlag();
  if (chooser) {
    field(chooser).addEventListener('change', () => {
      showLawFields();
      fillMapSizes();
    });
  }

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
    fillMapSizes();
    schedule(0);
  });
  field('system').addEventListener('change', (event) => {
    const before = state.system;
    state.system = event.target.value;
    // Another kind of oscillator takes its preset (the generator with it); another diode law
    // is another part: the generator stays.
    if (state.system === 'mechanics' && before !== 'mechanics') applyPreset('mechanics');
    else if (before === 'mechanics' && state.system !== 'mechanics') {
      const keepSystem = state.system;
      applyPreset('fig3-2b');
      state.system = keepSystem;
      field('system').value = keepSystem;
      showSystem();
      if (keepSystem === 'shockley') holdGenerator();
    } else holdGenerator();
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
  field('map-curves').addEventListener('change', runCurves);
  wireRecord({ schedule, redraw, leavePresetPoint });
  window.addEventListener('resize', () => {
    redraw();
    drawSweep();
    drawMap();
  });
}

export async function start() {
  fillScaleSelect(field('tdiv'), 's');
  fillScaleSelect(field('ch1-vdiv'), 'V');
  fillScaleSelect(field('ch2-vdiv'), 'V');
  fillScaleSelect(field('ch3-vdiv'), 'A');
  let presets;
  let keys;
  try {
    [presets, keys] = await Promise.all([api('presets', ''), api('keys', '')]);
  } catch (e) {
    setStatus('error', e.message);
    return;
  }
  // The model's fields come from the key table: before anything below reads them.
  buildForm(keys);
  state.caps = keys.caps;
  state.stuckVelocity = keys.stuck_velocity;
  state.staticGain = keys.static_gain;
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
  for (const k of fieldsOf('shockley').filter((f) => !isPart(f))) field(k).value = fieldText(k, state.shockley[k]);
  // Mechanical parts start as the example, for when the model is switched.
  const m = state.presets.find((p) => p.id === 'mechanics');
  for (const k of fieldsOf('mechanics')) if (typeof m.values[k] === 'number') field(k).value = num(m.values[k], 6);
  // Each friction law's parameters start from the served values, for when it is chosen.
  for (const values of Object.values(presets.laws)) for (const [k, x] of Object.entries(values)) field(k).value = num(x, 6);
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

// A scope record on the scope: read by the server's readers (POST /api/record: the page has
// no CSV reader of its own), drawn as the reference traces REF1 (the drive) and REF2 (u_C)
// beside the computed ones, and the circuit fitted to it (POST /api/fit). The file's text
// stays in the page: it is sent to the lab when the file is dropped (to be read) and when
// Fit is pressed, and the lab keeps nothing. Several files dropped at once are the channels of
// one record (a Tektronix export writes a file per channel), merged by the lab.

import { $, field, num, si } from './util.js';
import { latest, slots, isAbort } from './api.js';
import { state, clearErrors, showError, modelParams } from './state.js';
import { drawTrace, ysOf, chOn } from './scope.js';
import { fieldsOf, isPart, fitParametersOf, fieldText, symbolAndUnit, symbolNodes } from './form.js';

export const REF_COLORS = { ref1: '#fff6c2', ref2: '#c4f4ff', xy: '#f0f0f0' };
// Degrees to a millionth (a phase of 1e-12° is 0).
const deg = (rad) => Math.round((rad * 180e6) / Math.PI) / 1e6;

/** The record's channel named `name`. */
function channel(r, name) {
  return r.channels.find((c) => c.name === name);
}

/** Whether reference traces are drawn: a record, and a circuit on the screen. */
const showing = () => state.record && state.system !== 'mechanics';

// ---------------------------------------------------------------- drawing (scope.js calls these)
/** REF1 on CH1's scale and REF2 on CH2's, at the record's times (its first sample at t = 0,
 * where the generator's phase puts the computed cycle's start); the number drawn. */
export function drawRefsYT(g, box, xOf) {
  if (!showing()) return 0;
  const r = state.record;
  const xs = r.t_s.map(xOf);
  let count = 0;
  g.setLineDash([6, 3]);
  for (const [k, name, color] of [[1, r.drive_channel, REF_COLORS.ref1], [2, r.response_channel, REF_COLORS.ref2]]) {
    if (!chOn(k)) continue;
    drawTrace(g, box, xs, ysOf(box, k, channel(r, name).values), color, true);
    count += 1;
  }
  g.setLineDash([]);
  return count;
}

/** The record's loop: REF2 against REF1, on CH1's and CH2's scales; the number drawn. */
export function drawRefsXY(g, box, xOf) {
  if (!showing()) return 0;
  const r = state.record;
  const xs = channel(r, r.drive_channel).values.map(xOf);
  const ys = ysOf(box, 2, channel(r, r.response_channel).values);
  g.setLineDash([6, 3]);
  drawTrace(g, box, xs, ys, REF_COLORS.xy);
  g.setLineDash([]);
  return 1;
}

/** The record's name under the screen (after the channels' scales), or null. */
export function refLabel() {
  if (!showing()) return null;
  const r = state.record;
  return { text: `REF1: ${r.drive_channel}, REF2: ${r.response_channel} of ${r.file} (dashed)`, color: REF_COLORS.ref2 };
}

// ---------------------------------------------------------------- reading a record
function recordStatus(text, kind) {
  const out = $('[data-record="status"]');
  out.textContent = text;
  out.dataset.state = kind;
}

/** Read `files` (one File, or a File per channel of the same record, as a Tektronix scope
 * writes them) on the lab's readers and show the record; the generator takes its drive. */
export async function loadRecord(files, hooks) {
  clearErrors($('.toolbar.record'));
  files = Array.from(files);
  const names = files.map((f) => f.name).join('+');
  const size = files.reduce((sum, f) => sum + f.size, 0);
  const cap = state.caps && state.caps.upload_bytes;
  if (cap && size > cap) {
    recordStatus(`${names} is ${size} bytes: over the lab's cap of ${num(cap / 1048576, 4)} MB (${cap} bytes); export fewer samples`, 'error');
    return;
  }
  if (files.length > 4) {
    recordStatus(`${files.length} files: drop one record (one file, or one file per channel, at most 4)`, 'error');
    return;
  }
  recordStatus(`reading ${names}…`, 'computing');
  let texts;
  try {
    texts = await Promise.all(files.map((f) => f.text()));
  } catch (e) {
    recordStatus(`${names}: cannot be read (${e.message})`, 'error');
    return;
  }
  // One file: its text; several: JSON with each file's name and text (merged by the lab).
  const upload =
    files.length === 1
      ? { body: texts[0], type: 'text/csv; charset=utf-8' }
      : { body: JSON.stringify({ files: files.map((f, i) => ({ name: f.name, text: texts[i] })) }), type: 'application/json' };
  const p = new URLSearchParams();
  if (files.length === 1) p.set('file', files[0].name.slice(0, 120) || 'record.csv');
  let r;
  try {
    r = await latest('record', 'record', p, upload);
  } catch (e) {
    if (isAbort(e)) return;
    recordStatus('', 'error');
    showError(e, $('[data-record="status"]'));
    return;
  }
  state.record = r;
  state.recordUpload = upload;
  state.recordFileKey = files.length === 1 ? p.get('file') : null;
  state.fit = null;
  $('[data-fit="table"]').hidden = true;
  const d = r.drive;
  recordStatus(
    `${r.file}: ${r.format}, ${r.samples} samples, ${si(d.f_Hz, 'Hz', 6)}, ${num(d.amplitude_V, 5)} V, ${d.periods} periods, ${r.clipped} clipped`,
    'ready',
  );
  $('[data-action="clear-record"]').disabled = false;
  fitButton();
  // The generator takes the record's drive: frequency, amplitude, and the phase at its first
  // sample (so that the computed cycle starts where the record does).
  field('freq').value = num(d.f_Hz, 7);
  field('amplitude').value = num(d.amplitude_V, 6);
  field('phase').value = num(deg(d.phase), 5);
  state.drive.w = null;
  state.drive.beta = null;
  hooks.leavePresetPoint();
  state.autoscalePending = true;
  hooks.schedule(0);
}

export function clearRecord(hooks) {
  clearErrors($('.toolbar.record'));
  clearErrors($('#fit'));
  state.record = null;
  state.recordUpload = null;
  state.fit = null;
  if (slots.fit) slots.fit.abort();
  $('[data-fit="table"]').hidden = true;
  recordStatus('', 'ready');
  $('[data-fit="status"]').textContent = 'drop a scope CSV on the screen, tick the values to fit, press Fit';
  $('[data-action="clear-record"]').disabled = true;
  fitButton();
  hooks.redraw();
}

/** Fit is offered with a record and a circuit. */
export function fitButton() {
  const button = $('[data-action="fit"]');
  button.disabled = !showing();
}

// ---------------------------------------------------------------- the fit
/** Fit the ticked values to the record; show them ± their errors and put them in the fields. */
export async function runFit(hooks) {
  if (!showing()) return;
  const out = $('[data-fit="status"]');
  const box = $('#fit');
  clearErrors(box);
  const system = state.system === 'shockley' ? 'shockley' : 'pwl';
  // The values of the diode law a fit may free (/api/keys), those with a ticked box.
  const free = fitParametersOf(system).filter((k) => field(`free-${k}`)?.checked);
  if (!free.length) {
    out.dataset.state = 'error';
    out.textContent = 'tick “fit” beside at least one value';
    return;
  }
  // The circuit's values are the starting point; the drive is the record's.
  const p = modelParams({ frequency: false, amplitude: false });
  p.delete('phi');
  p.set('free', free.join(','));
  if (state.recordFileKey) p.set('file', state.recordFileKey);
  out.dataset.state = 'computing';
  out.textContent = `fitting ${free.join(', ')} to ${state.record.file}…`;
  let a;
  try {
    a = await latest('fit', 'fit', p, state.recordUpload);
  } catch (e) {
    if (isAbort(e)) return;
    out.dataset.state = 'error';
    out.textContent = '';
    showError(e, out);
    return;
  }
  state.fit = a;
  showFit(a);
  out.dataset.state = 'ready';
  out.textContent = `${a.converged ? 'converged' : 'NOT converged'} after ${a.iterations} iterations; ${a.records[0].class}; the fitted values are in the fields`;
  applyFit(a);
  hooks.schedule(0);
}

/** The fitted values ± standard errors, their 95 % intervals, and the residual. */
function showFit(a) {
  const rows = $('[data-fit="rows"]');
  rows.replaceChildren();
  for (const [name, p] of Object.entries(a.parameters)) {
    const [symbol, unit] = symbolAndUnit(name);
    const tr = document.createElement('tr');
    const th = document.createElement('th');
    th.scope = 'row';
    th.append(...symbolNodes(symbol));
    const value = document.createElement('td');
    value.dataset.fit = name;
    value.dataset.value = String(p.value);
    value.textContent = num(p.value, 6);
    const stderr = document.createElement('td');
    stderr.dataset.fitStderr = name;
    stderr.textContent = p.stderr === null ? '—' : num(p.stderr, 3);
    const ci = document.createElement('td');
    ci.textContent = p.ci95[0] === null ? '—' : `${num(p.ci95[0], 5)} … ${num(p.ci95[1], 5)} ${unit}`.trim();
    tr.append(th, value, stderr, ci);
    rows.append(tr);
  }
  $('[data-fit="rms_residual_V"]').textContent = num(a.rms_residual_V, 4);
  $('[data-fit="noise_V"]').textContent = num(a.noise_V, 4);
  $('[data-fit="chi2_dof"]').textContent = num(a.chi2_dof, 4);
  $('[data-fit="table"]').hidden = false;
}

/** The fitted experiment into the fields: the circuit's values and the record's drive. */
function applyFit(a) {
  const k = a.keys;
  for (const [name, v] of Object.entries(k)) {
    if (['freq', 'amplitude', 'phi'].includes(name)) continue;
    const input = field(name);
    if (input) input.value = fieldText(name, v, 8);
    if (fieldsOf('shockley').includes(name) && !isPart(name)) state.shockleyEdited = true;
  }
  state.paperParts = false;
  field('preset-choice').value = 'custom';
  field('freq').value = num(k.freq, 7);
  field('amplitude').value = num(k.amplitude, 6);
  field('phase').value = num(deg(k.phi), 5);
  state.drive.w = null;
  state.drive.beta = null;
}

// ---------------------------------------------------------------- wiring
/** Drop a file on the screen or pick it; Fit; Remove. `hooks`: schedule, redraw,
 * leavePresetPoint of the page. */
export function wireRecord(hooks) {
  const screen = $('#screen');
  const over = (on) => {
    if (on) screen.dataset.drop = 'over';
    else delete screen.dataset.drop;
  };
  screen.addEventListener('dragenter', (e) => {
    e.preventDefault();
    over(true);
  });
  screen.addEventListener('dragover', (e) => {
    e.preventDefault();
    e.dataTransfer.dropEffect = 'copy';
  });
  screen.addEventListener('dragleave', () => over(false));
  screen.addEventListener('drop', (e) => {
    e.preventDefault();
    over(false);
    const files = e.dataTransfer && e.dataTransfer.files;
    if (files && files.length) loadRecord(files, hooks);
  });
  const input = field('record-file');
  input.addEventListener('change', () => {
    if (input.files.length) loadRecord(input.files, hooks).finally(() => (input.value = ''));
  });
  $('[data-action="clear-record"]').addEventListener('click', () => clearRecord(hooks));
  $('[data-action="fit"]').addEventListener('click', () => runFit(hooks));
  field('system').addEventListener('change', fitButton);
}

// What the page holds: the answers on screen, the inputs' state, the status line, the errors
// beside fields, and the model keys of the query.

import { $, $$, field } from './util.js';
import { fieldsOf, sentFieldsOf, isPart } from './form.js';

// ---------------------------------------------------------------- state
export const state = {
  presets: [],
  caps: null, // what one request may ask for at most (/api/keys)
  stuckVelocity: {}, // |v| at or below which the block is drawn stuck, by diode law (/api/keys)
  shockley: {},
  system: 'pwl',
  paperParts: true, // the circuit's parts are the paper's: send preset=paper
  shockleyEdited: false,
  // The generator is an instrument: a preset sets it once (its Hz and V, or N), and nothing
  // but the generator's own controls (and a scope record's drive) moves it afterwards. While
  // the preset's parts are unchanged its point is sent as w and β (the same setting, exactly
  // the paper's numbers); once a part changes, the generator's Hz and V are sent, and w and β
  // follow from the parts.
  drive: { w: 0.95, beta: 2.14 },
  // The numbers the page itself put into the generator's fields, with their text: while a
  // field shows that text, the number is sent in full (a preset's 9969.65 Hz is
  // 9969.651571… Hz).
  generator: { freq: null, amplitude: null },
  steady: null,
  steadyQuery: '',
  transient: null,
  theory: null,
  theoryNote: '',
  sweep: null,
  map: null,
  curves: null, // the curves over the map (/api/curve): { map, answers: { follow: answer } }
  mode: 'yt',
  trigger: 'steady',
  autoscalePending: true,
  started: false,
  seq: 0, // input counter
  shownSeq: 0,
  pendingInputs: [], // [seq, time] of inputs not yet on the screen
  record: null, // the scope record on the screen (/api/record), its upload, and its fit (/api/fit)
  recordUpload: null,
  recordFileKey: null,
  fit: null,
};
// Latency of input → redraw, in ms, for every input (see docs/lab.md).
window.stickslipLab = { latencies: [], redraws: 0, state };

export const statusEl = $('#status');
export function setStatus(kind, text) {
  statusEl.dataset.labStatus = kind;
  statusEl.textContent = text;
}

// ---------------------------------------------------------------- errors beside fields
export function clearErrors(scope) {
  for (const el of $$('.error', scope)) el.textContent = '';
  for (const el of $$('[aria-invalid="true"]', scope)) el.removeAttribute('aria-invalid');
}
export function showError(failure, fallbackScope) {
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
export const value = (name) => (field(name).value || '').trim();

/** Put `x` into the generator's field `name` (`freq`, `amplitude`), shown to `digits`
 * significant digits and sent in full while the field shows it. */
export function setGenerator(name, x, text) {
  field(name).value = text;
  state.generator[name] = { text, value: x };
}

/** What the generator's field `name` sends: the number the page put there while it shows
 * that number's text, else what was typed. */
export function generatorValue(name) {
  const g = state.generator[name];
  const text = value(name);
  return g && g.text === text ? String(g.value) : text;
}

/** A part of the experiment changed (or the diode law, or a fitted value): the generator
 * stays where it is, in Hz and V; w and β follow from the parts. */
export function holdGenerator() {
  state.drive.w = null;
  state.drive.beta = null;
}

/** The model keys for the API: the description, and the drive unless `withoutDrive`. The
 * keys are the fields of the system's fieldsets in use (form.js, from /api/keys: a friction
 * law's parameters only while it is chosen). Two keys have
 * behaviour of their own: `preset` (the paper's parts, while none is edited, are sent by the
 * preset's name) and `model` (the diode law, from the system's selector). */
export function modelParams({ frequency = true, amplitude = true } = {}) {
  const p = new URLSearchParams();
  const fields = fieldsOf(state.system);
  if (state.system === 'mechanics') {
    // Its fields in use: the belt, the law, and the chosen law's parameters alone.
    for (const k of sentFieldsOf('mechanics')) p.set(k, value(k));
  } else {
    if (state.paperParts) p.set('preset', 'paper');
    else for (const k of fields.filter(isPart)) p.set(k, value(k));
    if (state.system === 'shockley') {
      p.set('model', 'shockley');
      // The 1N4148 defaults are the library's own until a value is edited.
      if (state.shockleyEdited) for (const k of fields.filter((f) => !isPart(f))) p.set(k, value(k));
    }
  }
  if (frequency) {
    if (state.drive.w !== null) p.set('w', String(state.drive.w));
    else p.set('freq', generatorValue('freq'));
  }
  if (amplitude) {
    if (state.drive.beta !== null) p.set('beta', String(state.drive.beta));
    else p.set('amplitude', generatorValue('amplitude'));
  }
  const degrees = Number(value('phase'));
  if (value('phase') !== '' && value('phase') !== '0') {
    p.set('phi', Number.isFinite(degrees) ? String((degrees * Math.PI) / 180) : value('phase'));
  }
  return p;
}

// The panels beside the scope: derived values, the knobs' ranges, the measurements and the
// theory, the mechanical view, the presets and the model's fieldsets.

import { $, $$, field, num, si, siText } from './util.js';
import { state, setGenerator, holdGenerator } from './state.js';
import { fieldsOf, isPart, showLawFields, chosenLaw } from './form.js';
import { channelColumns, prepare, COLORS, label, displayed } from './scope.js';

// ---------------------------------------------------------------- derived readouts
export function scales() {
  return (state.steady && state.steady.scales) || { position: 1, velocity: 1, force: 1, omega0: 1 };
}
export function units() {
  const mech = state.steady && state.steady.system === 'mechanics';
  return mech ? { drive: 'N', position: 'm', velocity: 'm/s' } : { drive: 'V', position: 'V', velocity: 'A' };
}

/** The belt of a steady state's answer: its speed vb (dimensionless, 0 without a belt), its
 * friction law, and whether the motion is self-excited (a belt without a drive: its period
 * is the cycle's own, `cycle_period_tau`, and it has no drive-period quantities). */
export function beltOf(s) {
  const speed = s.vb ?? 0;
  return { speed, law: s.friction_law ?? 'coulomb', moving: speed !== 0 || s.friction_law !== undefined, selfExcited: s.cycle_period_tau !== undefined };
}

/** The seconds the answer's trace covers, after which the scope repeats it: its drive
 * periods, or a self-excited motion's cycle (`trace.span_s`). */
export function traceSeconds(s) {
  return beltOf(s).selfExcited ? s.trace.span_s : s.trace.periods / s.drive.f_Hz;
}

export function showDerived() {
  const s = state.steady;
  const c = s.conversion;
  $('[data-derived="w"]').textContent = num(s.w, 6);
  $('[data-derived="beta"]').textContent = num(s.beta, 6);
  if (c) {
    $('[data-derived="natural"]').textContent =
      `f0 = ${si(c.f0, 'Hz', 6)}, ω0 = ${num(c.omega0, 6)} rad/s, ζ = ${num(c.zeta, 5)}, Q = ${num(c.Q, 5)}`;
  }
  // The generator's fields are the generator's: an answer never writes them (a preset, a
  // knob, a typed value or a scope record does); its knobs follow the answer's drive.
  if (s.drive) placeKnobs();
  const u = units();
  for (const el of $$('[data-unit]')) el.textContent = u[el.dataset.unit] || el.textContent;
  const mech = s.system === 'mechanics';
  $('[data-label="ch1"]').textContent = mech ? 'F' : 'U';
  $('[data-label="ch2"]').textContent = mech ? 'position r' : 'u_C';
  $('[data-label="ch3"]').textContent = mech ? 'velocity ṙ' : 'current i';
  const belt = beltOf(s);
  $('[data-derived="twin"]').textContent = mech
    ? belt.moving
      ? `The block rides on a belt: friction acts on the slip ṙ − v_belt by the ${belt.law} law (static μs·F0); red: stuck to the belt, carried along${belt.selfExcited ? '; no drive: the belt alone makes it stick and slip' : ', driven by F cos Ωt'}.`
      : 'The block is the model itself: spring k, damping γ, dry friction F0 (static μs·F0), driven by F cos Ωt.'
    : 'The same model as a mass on a spring: u_C ↔ position, i ↔ velocity, U ↔ drive force, the diode pair ↔ dry friction (U_t ↔ F0). Red: the motion stops.';
}

/** The library's rule for `static`, stated where it applies, with the measured gain beside
 * it: `G = 0.0051 ≤ 0.01` (`short`: with a leading separator for the screen's class line, and
 * the stops that a static motion may still make). Empty for the other classes. */
export function staticNote(s, short) {
  if (s.class !== 'static') return '';
  const rule = `G = ${num(s.gain, 2)} ≤ ${num(state.staticGain, 3)}`;
  if (!short) return `${rule}: the swing (max − min)/2 is at most ${num(100 * state.staticGain, 3)} % of β`;
  const stops = s.stops_per_period > 0 ? `, ${num(s.stops_per_period, 3)} stops/period` : '';
  return ` (${rule}${stops})`;
}

// The knobs: frequency logarithmic from f0/10 to 3 f0, amplitude linear to 20 U_t.
export function knobRange() {
  const c = state.steady && state.steady.conversion;
  const f0 = c ? c.f0 : 1;
  const force = scales().force;
  return { fmin: f0 / 10, fmax: 3 * f0, amax: 20 * force };
}
export function placeKnobs() {
  const r = knobRange();
  const f = Number(state.steady.drive.f_Hz);
  field('freq-knob').value = String(Math.round((1000 * Math.log(f / r.fmin)) / Math.log(r.fmax / r.fmin)));
  field('amplitude-knob').value = String(Math.round((1000 * state.steady.drive.amplitude) / r.amax));
}


// ---------------------------------------------------------------- measurements
export function setMeasure(name, text, value) {
  const el = $(`[data-measure="${name}"]`);
  el.textContent = text;
  if (value !== undefined && Number.isFinite(value)) el.dataset.value = String(value);
  else delete el.dataset.value;
}
export function setTheory(name, text) {
  $(`[data-theory="${name}"]`).textContent = text;
}

export function showMeasurements() {
  const s = state.steady;
  const sc = scales();
  const deg = (rad) => (rad === null || rad === undefined ? null : (rad * 180) / Math.PI);
  setMeasure('class', s.class);
  $('[data-note="class"]').textContent = staticNote(s, false);
  // A block on a belt: its extremes; without a drive, its own cycle instead of the
  // drive-period quantities.
  const belt = beltOf(s);
  for (const row of $$('#measurements tr[data-driven]')) row.hidden = belt.selfExcited;
  for (const row of $$('#measurements tr[data-belt]')) row.hidden = !(row.dataset.belt === 'any' ? belt.moving : belt.selfExcited);
  $('[data-label="stops"]').textContent = belt.selfExcited ? 'stops per cycle' : 'stops per period';
  setMeasure('y-extremes', `${num(s.y_max * sc.position, 5)} / ${num(s.y_min * sc.position, 5)}`);
  if (belt.selfExcited) {
    setMeasure('cycle-period', s.cycle_period_s === undefined ? 'none (no cycle)' : num(s.cycle_period_s, 6), s.cycle_period_s);
    setMeasure('stick-fraction', num(s.stick_fraction, 6), s.stick_fraction);
    setMeasure('sliding', `${s.sliding_stability} at ${num(s.sliding_y * sc.position, 4)}`);
  }
  setMeasure('stops', num(s.stops_per_period, 4), s.stops_per_period);
  setMeasure('period', s.period === null ? 'none found' : `${s.period} (settled after ${s.periods_to_settle})`, s.period);
  setMeasure('gain', num(s.gain, 6), s.gain);
  setMeasure('gain1', s.gain1 === null || s.gain1 === undefined ? '—' : num(s.gain1, 6), s.gain1);
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
  if (belt.selfExcited) setMeasure('frequency', `— / ${num(1 / s.cycle_period_s, 6)}`, 1 / s.cycle_period_s);
  else setMeasure('frequency', `${num(f, 6)} / ${num(s.period ? f / s.period : NaN, 6)}`, f);

  showTheory();
}

export function showTheory() {
  const s = state.steady;
  if (!s) return;
  const sc = scales();
  const deg = (rad) => (rad === null || rad === undefined ? null : (rad * 180) / Math.PI);
  const t = state.theory;
  const p = t ? t.paper : {};
  const e = t ? t.exact : {};
  // The theories to five digits (the measured values have six): the columns stay narrow.
  const volts = (x) => (x === null || x === undefined ? '—' : num(x * sc.position, 5));
  setTheory('paper-A1', volts(p.A1));
  setTheory('paper-A3', volts(p.A3));
  setTheory('paper-A5', volts(p.A5));
  setTheory('exact-A1', volts(e.A1));
  setTheory('exact-A3', volts(e.A3));
  setTheory('exact-A5', volts(e.A5));
  // G = (max − min)/2β: the paper's series gives only its fundamental (G1); a sliding orbit
  // is symmetric, so its G is its peak over β. G1 = A1/β.
  const beta = t ? t.params.beta : NaN;
  setTheory('paper-gain', '—');
  setTheory('exact-gain', t && e.peak !== null && e.peak !== undefined && beta > 0 ? num(e.peak / beta, 5) : '—');
  setTheory('paper-gain1', t ? num(p.gain, 5) : '—');
  setTheory('exact-gain1', t && e.A1 !== null && e.A1 !== undefined && beta > 0 ? num(e.A1 / beta, 5) : '—');
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
  notes.push('G = (max − min)/2β (for the exact sliding orbit, its peak/β); G1 = A1/β, the paper’s gain.');
  setTheory('notes', notes.join(' '));
}

// ---------------------------------------------------------------- the mechanical view
export const mech = { start: performance.now() };
export function drawMechanics(now) {
  const canvas = $('#mechanics-view');
  const s = state.steady;
  if (!s || document.hidden) return;
  const { g, w, h } = prepare(canvas);
  g.fillStyle = '#fbfcfa';
  g.fillRect(0, 0, w, h);
  const cols = s.trace.columns;
  const n = cols.y.length;
  // The record plays in 2.5 s per drive period (per cycle, for a self-excited belt).
  const cycleSeconds = 2.5 * s.trace.periods;
  const elapsed = (now - mech.start) / 1000;
  const phase = (elapsed % cycleSeconds) / cycleSeconds;
  const i = Math.min(n - 1, Math.floor(phase * n));
  const belt = beltOf(s);
  if (!s.extent) {
    // The block's swing about the middle of its extremes fills the reach.
    const lo = Math.min(...cols.y);
    const hi = Math.max(...cols.y);
    const centre = belt.moving ? (lo + hi) / 2 : 0;
    s.extent = {
      centre,
      y: Math.max(...cols.y.map((y) => Math.abs(y - centre)), 1e-9),
      drive: Math.max(...cols.drive.map(Math.abs), 1e-9),
    };
  }
  const ymax = s.extent.y;
  const floor = h - 28;
  const x0 = w / 2 + 20;
  const reach = w / 2 - 90;
  const perY = reach / ymax; // pixels per unit of y
  const x = x0 + (cols.y[i] - s.extent.centre) * perY;
  g.strokeStyle = '#6b756f';
  g.lineWidth = 1;
  g.beginPath();
  if (belt.moving) {
    // The belt: a band between two rollers whose marks move at the belt's speed, on the
    // block's scale (y' = vb moves the block and the marks alike: a stuck block rides along).
    const tauPerSecond = s.trace.span_tau / cycleSeconds;
    const spacing = 18;
    const shift = (((belt.speed * elapsed * tauPerSecond * perY) % spacing) + spacing) % spacing;
    const left = 34;
    const right = w - 16;
    g.moveTo(left, floor);
    g.lineTo(right, floor);
    g.moveTo(left, floor + 10);
    g.lineTo(right, floor + 10);
    g.stroke();
    for (const cx of [left, right]) {
      g.beginPath();
      g.arc(cx, floor + 5, 5, 0, 2 * Math.PI);
      g.stroke();
    }
    g.beginPath();
    for (let k = left - spacing + shift; k < right; k += spacing) {
      if (k < left + 2 || k + 4 > right - 2) continue;
      g.moveTo(k, floor + 2);
      g.lineTo(k + 4, floor + 8);
    }
    g.moveTo(20, 12);
    g.lineTo(20, floor - 4);
    g.stroke();
  } else {
    // Ground with friction hatching.
    g.moveTo(20, floor);
    g.lineTo(w - 10, floor);
    for (let k = 24; k < w - 10; k += 9) {
      g.moveTo(k, floor);
      g.lineTo(k - 6, floor + 7);
    }
    g.moveTo(20, 12);
    g.lineTo(20, floor);
    g.stroke();
  }
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
  // The block: red while stuck (its velocity that of the ground or the belt).
  const v = cols.v[i];
  const stuck = Math.abs(v - belt.speed) <= state.stuckVelocity[s.model] * Math.max(1, Math.abs(belt.speed));
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
  if (belt.moving) {
    const u = units();
    const arrowText = belt.speed > 0 ? '→' : belt.speed < 0 ? '←' : '';
    label(g, `belt ${si(belt.speed * scales().velocity, u.velocity, 3)} ${arrowText}`, w - 12, h - 4, '#2e5d50', 'right');
  }
  if (!belt.selfExcited) label(g, 'drive force', w - 12, 14, '#8a6d00', 'right');
  // For tests: what the view shows now.
  canvas.dataset.stuck = String(stuck);
  canvas.dataset.belt = String(belt.moving);
}
export function animate(now) {
  drawMechanics(now);
  requestAnimationFrame(animate);
}


// ---------------------------------------------------------------- presets
export function applyPreset(id) {
  const chosen = state.presets.find((p) => p.id === id);
  if (!chosen) return;
  const v = chosen.values;
  if (chosen.system === 'mechanics') {
    state.system = 'mechanics';
    for (const k of fieldsOf('mechanics')) if (k in v) field(k).value = typeof v[k] === 'string' ? v[k] : num(v[k], 6);
    showLawFields();
  } else {
    if (state.system === 'mechanics') state.system = 'pwl';
    for (const k of fieldsOf('pwl').filter(isPart)) if (k in v) field(k).value = siText(v[k]);
    state.paperParts = chosen.paper;
  }
  field('system').value = state.system;
  // The generator, once: the preset's point in Hz and V (or N), sent as w and β while the
  // preset's parts stay; a preset without a point (the paper's circuit) leaves it as it is.
  if (chosen.drive) {
    const unit = chosen.drive.unit;
    setGenerator('freq', chosen.drive.f_Hz, num(chosen.drive.f_Hz, 6));
    setGenerator('amplitude', chosen.drive.amplitude, num(chosen.drive.amplitude, 6));
    state.drive.w = v.w;
    state.drive.beta = v.beta;
    for (const el of $$('[data-unit="drive"]')) el.textContent = unit;
  } else {
    holdGenerator();
  }
  showSystem();
  state.autoscalePending = true;
}

/** Map sizes that finish within the time limit (10 s) on a 2-core laptop: the exact
 * solver takes about 0.3 ms a point, the stiff one about 6 ms (docs/lab.md); the Stribeck
 * and cubic laws, whose slips it integrates, far longer. */
export const MAP_SIZES = {
  pwl: [['40x30', '40 × 30'], ['60x50', '60 × 50'], ['120x100', '120 × 100']],
  shockley: [['16x12', '16 × 12'], ['24x20', '24 × 20'], ['32x24', '32 × 24']],
  // A forced Stribeck or cubic belt's steady state from rest took about 1 s a point at a
  // load average of 16 on 2 cores (docs/lab.md): small maps only.
  law: [['8x6', '8 × 6'], ['12x9', '12 × 9'], ['16x12', '16 × 12']],
};
export function fillMapSizes() {
  const select = field('map-size');
  // A friction law other than Coulomb's slips on the stiff integrator: small maps.
  const law = state.system === 'mechanics' && !['coulomb', null].includes(chosenLaw());
  const sizes = MAP_SIZES[law ? 'law' : state.system === 'shockley' ? 'shockley' : 'pwl'];
  const keep = select.value;
  select.replaceChildren(...sizes.map(([v, text]) => new Option(text, v)));
  select.value = sizes.some(([v]) => v === keep) ? keep : sizes[1][0];
}

/** The panels of the system shown: its fieldsets, and the panels' titles (a function
 * generator and a circuit, or a drive force and a mass on a spring). */
export function showSystem() {
  for (const fs of $$('fieldset[data-for-system]')) fs.hidden = !fs.dataset.forSystem.split(' ').includes(state.system);
  const mech = state.system === 'mechanics';
  $('#generator-title').textContent = mech ? 'Drive force' : 'Function generator';
  $('#circuit-title').textContent = mech ? 'Mass, spring and friction' : 'Circuit';
  // A value's "fit" box only with the diode laws whose fit may free it (U_t's not with Shockley diodes).
  for (const box of $$('label[data-fit-laws]')) box.hidden = !box.dataset.fitLaws.split(' ').includes(state.system);
}

// The periodic orbit of the shown circuit and its Floquet multipliers (GET /api/orbit, the
// library's OrbitReport and its row of the orbits' table): a table, and the multipliers in
// the complex plane with the unit circle (inside it every perturbation decays). A belt
// without a drive answers its self-excited cycle (the library's SelfExcitedOrbit): its own
// period, its multipliers (1, the trivial one of an autonomous motion, and μ2), and the
// cycle in the phase plane (y, y'); or steady sliding with its eigenvalues.

import { $, num } from './util.js';
import { latest, isAbort } from './api.js';
import { state } from './state.js';

// The orbit is asked for once the inputs rest this long (ms): a dragged knob does not start
// a Newton search per step, and the screen's own requests keep their turns.
export const ORBIT_DELAY_MS = 250;
let timer = null;

const panel = () => $('#orbit');

/** One cell of the table: its text, and the numbers it shows in full (`data-value`, or
 * `data-re` and `data-im`) for those who read on. */
function set(name, text, values = {}) {
  const el = $(`[data-orbit="${name}"]`);
  el.textContent = text;
  for (const key of ['value', 're', 'im']) {
    if (key in values) el.dataset[key] = String(values[key]);
    else delete el.dataset[key];
  }
}

/** The multiplier μ as text: re ± im·i (a real one without its zero imaginary part). */
function complex(re, im) {
  if (im === 0) return num(re, 6);
  return `${num(re, 6)} ${im < 0 ? '−' : '+'} ${num(Math.abs(im), 6)}i`;
}

/** Empty the table (no orbit, or one being computed). */
function clear() {
  for (const el of document.querySelectorAll('#orbit [data-orbit]')) {
    if ((el.tagName === 'TD' || el.tagName === 'SPAN') && el.dataset.orbit !== 'note') set(el.dataset.orbit, '—');
  }
}

/** Fill the table from an answer of /api/orbit. */
function show(answer) {
  const t = answer.table;
  const o = answer.orbit;
  // Each value from the table's row (its columns by name), the arguments beside them.
  const cell = (name) => t[name][0];
  set('period', `${cell('period')} T${cell('least_period') < cell('period') ? ` (repeats after ${cell('least_period')} T)` : ''}`);
  set('y', num(cell('y'), 10), { value: cell('y') });
  set('v', num(cell('v'), 10), { value: cell('v') });
  for (const k of [1, 2]) {
    const [re, im] = [cell(`mu${k}_re`), cell(`mu${k}_im`)];
    set(`mu${k}`, complex(re, im), { re, im });
    set(`mu${k}-modulus`, num(o.moduli[k - 1], 6), { value: o.moduli[k - 1] });
    set(`mu${k}-argument`, num(answer.arguments[k - 1], 6), { value: answer.arguments[k - 1] });
  }
  const lambda = cell('lambda1');
  const finite = Number.isFinite(Number(lambda));
  set('lambda1', finite ? num(Number(lambda), 6) : String(lambda), finite ? { value: Number(lambda) } : {});
  set('stability', cell('stability'));
  set('stops', num(cell('stops_per_period'), 6));
  set('converged', `yes, in ${cell('iterations')} Newton step${cell('iterations') === 1 ? '' : 's'}`);
  const stuck = cell('stuck_at_strobe') === 'true' || cell('stuck_at_strobe') === true;
  $('[data-orbit="note"]').textContent = stuck ? 'The orbit is stuck at its strobe (τ = 0 mod T).' : '';
}

/** Fill the table from an answer of /api/orbit for a belt without a drive: the
 * self-excited cycle (or steady sliding) as `stickslip orbit --json` prints it. */
function showSelfExcited(answer) {
  const c = answer.self_excited;
  const seconds = c.cycle_period_s === null ? '' : ` = ${num(c.cycle_period_s, 6)} s`;
  if (c.cycle_period_tau === null) {
    set('period', 'none: steady sliding');
  } else {
    set('period', `${num(c.cycle_period_tau, 8)} τ${seconds} (its own: no drive)`, { value: c.cycle_period_tau });
  }
  // The cycle's point on the section y' = 0 at its largest y (steady sliding: its state).
  set('y', num(c.y_max, 10), { value: c.y_max });
  set('v', '0', { value: 0 });
  const mu = c.multipliers ?? [];
  for (const k of [1, 2]) {
    const m = mu[k - 1];
    if (m === undefined) {
      for (const name of [`mu${k}`, `mu${k}-modulus`, `mu${k}-argument`]) set(name, '—');
      continue;
    }
    set(`mu${k}`, complex(m.re, m.im), { re: m.re, im: m.im });
    set(`mu${k}-modulus`, num(Math.hypot(m.re, m.im), 6), { value: Math.hypot(m.re, m.im) });
    set(`mu${k}-argument`, num(Math.atan2(m.im, m.re), 6), { value: Math.atan2(m.im, m.re) });
  }
  // A limit cycle's largest exponent is that of its trivial multiplier, 0; steady
  // sliding's is the growth rate of its linearisation.
  const lambda = c.cycle_period_tau === null ? c.sliding.growth_rate : 0;
  set('lambda1', num(lambda, 6), { value: lambda });
  set('stability', c.stability ?? '—');
  set('stops', c.release_y === null ? '0' : `1 per cycle, stuck ${num(100 * c.stick_fraction, 4)} % of it`);
  set('converged', 'yes (the steady state settled on it)');
  const [a, b] = c.sliding_eigenvalues;
  const sliding = `Steady sliding at y = ${num(c.sliding.equilibrium, 8)}: damping 2ζ + μ′ = ${num(c.sliding.damping, 6)}, eigenvalues ${complex(a.re, a.im)} and ${complex(b.re, b.im)} (${c.sliding_stability}).`;
  const about = {
    'stick-slip-cycle': 'No drive: a cycle of its own period. μ1 = 1 is the trivial multiplier of an autonomous motion; μ2 = 0 exactly, for every stop ends in the same state.',
    'pure-slip-cycle': 'No drive: a cycle of its own period that never sticks. μ1 = 1 is the trivial multiplier of an autonomous motion; μ2 is the derivative of its return map on y′ = 0.',
    'steady-sliding': 'No drive: the motion settles on steady sliding.',
  }[c.class] ?? '';
  $('[data-orbit="note"]').textContent = `${about} ${sliding}`;
}

/** The self-excited cycle in the phase plane (y, y'), with steady sliding's point; the
 * canvas is shown for a belt without a drive only. */
function drawCycle(answer) {
  const canvas = $('#orbit-cycle');
  const c = answer && answer.self_excited;
  canvas.hidden = !c;
  if (!c) {
    canvas.dataset.samples = '0';
    return;
  }
  const g = canvas.getContext('2d');
  const w = canvas.width;
  const h = canvas.height;
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, w, h);
  const ys = answer.cycle ? answer.cycle.y : [];
  const speeds = answer.cycle ? answer.cycle.v : [];
  const eq = c.sliding.equilibrium;
  const [y0, y1] = [Math.min(eq, ...ys), Math.max(eq, ...ys)];
  const [v0, v1] = [Math.min(0, ...speeds), Math.max(0, ...speeds)];
  const pad = 22;
  const sy = (w - 2 * pad) / Math.max(y1 - y0, 1e-9);
  const sv = (h - 2 * pad) / Math.max(v1 - v0, 1e-9);
  const at = (y, v) => [pad + (y - y0) * sy, h - pad - (v - v0) * sv];
  g.strokeStyle = '#d6dbd7';
  g.lineWidth = 1;
  g.beginPath();
  g.moveTo(...at(y0, 0));
  g.lineTo(...at(y1, 0));
  g.stroke();
  g.fillStyle = '#5d6763';
  g.font = '11px system-ui, sans-serif';
  g.fillText('y', w - 12, at(y1, 0)[1] - 4);
  g.fillText('y′', 4, 11);
  g.strokeStyle = '#1f6f5c';
  g.lineWidth = 1.5;
  g.beginPath();
  ys.forEach((y, k) => (k === 0 ? g.moveTo(...at(y, speeds[k])) : g.lineTo(...at(y, speeds[k]))));
  if (ys.length > 0) g.closePath();
  g.stroke();
  // Steady sliding: the equilibrium (y_e, 0), filled when stable.
  const [x, y] = at(eq, 0);
  g.strokeStyle = '#c0399b';
  g.fillStyle = '#c0399b';
  g.beginPath();
  g.arc(x, y, 4, 0, 2 * Math.PI);
  if (c.sliding_stability === 'stable') g.fill();
  else g.stroke();
  g.fillText('steady sliding', Math.min(x + 6, w - 84), y - 6);
  canvas.dataset.samples = String(ys.length);
}

/** The multipliers in the complex plane, with the unit circle. */
function draw(answer) {
  const canvas = $('#orbit-plot');
  const g = canvas.getContext('2d');
  const w = canvas.width;
  const h = canvas.height;
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, w, h);
  const mu = (answer && (answer.orbit ? answer.orbit.multipliers : answer.self_excited && answer.self_excited.multipliers)) || [];
  // The plane from −R to R, R at least 1.25 (the circle whole) and past every multiplier.
  const reach = Math.max(1.25, ...mu.map((m) => 1.15 * Math.hypot(m.re, m.im)).filter(Number.isFinite));
  const scale = (Math.min(w, h) / 2 - 14) / reach;
  const cx = w / 2;
  const cy = h / 2;
  const at = (re, im) => [cx + re * scale, cy - im * scale];
  g.strokeStyle = '#d6dbd7';
  g.lineWidth = 1;
  g.beginPath();
  g.moveTo(0, cy);
  g.lineTo(w, cy);
  g.moveTo(cx, 0);
  g.lineTo(cx, h);
  g.stroke();
  g.strokeStyle = '#1f6f5c';
  g.lineWidth = 1.5;
  g.beginPath();
  g.arc(cx, cy, scale, 0, 2 * Math.PI);
  g.stroke();
  g.fillStyle = '#5d6763';
  g.font = '11px system-ui, sans-serif';
  g.fillText('Re μ', w - 30, cy - 4);
  g.fillText('Im μ', cx + 4, 11);
  g.fillText('|μ| = 1', ...at(0.72, 0.78));
  const colors = ['#0a8fb0', '#c0399b'];
  mu.forEach((m, k) => {
    const [x, y] = at(m.re, m.im);
    g.fillStyle = colors[k];
    g.beginPath();
    g.arc(x, y, 5, 0, 2 * Math.PI);
    g.fill();
    g.fillText(`μ${k + 1}`, x + 7, y + (k === 0 ? -6 : 14));
  });
  canvas.dataset.multipliers = String(mu.length);
}

/** Ask for the orbit of the shown point (`params`, the query `query`) when the inputs rest
 * (none newer within ORBIT_DELAY_MS); the panel says what it shows in `data-state`
 * (computing, ready, none: no orbit found, error) and `data-query`. */
export function refreshOrbit(params, query) {
  const p = panel();
  const skip = !state.steady ? 'no steady state' : null;
  if (skip !== null) {
    clearTimeout(timer);
    clear();
    draw(null);
    drawCycle(null);
    p.dataset.state = 'none';
    p.dataset.query = query;
    $('[data-orbit="status"]').textContent = skip;
    $('[data-orbit="note"]').textContent = '';
    return;
  }
  p.dataset.state = 'computing';
  $('[data-orbit="status"]').textContent = 'computing…';
  const seq = state.seq;
  clearTimeout(timer);
  timer = setTimeout(() => {
    if (seq === state.seq) request(params, query);
  }, ORBIT_DELAY_MS);
}

function request(params, query) {
  const p = panel();
  latest('orbit', 'orbit', params).then(
    (answer) => {
      p.dataset.query = query;
      if (answer.converged && answer.self_excited) {
        showSelfExcited(answer);
        p.dataset.state = 'ready';
        $('[data-orbit="status"]').textContent = answer.self_excited.summary;
      } else if (answer.converged) {
        show(answer);
        p.dataset.state = 'ready';
        $('[data-orbit="status"]').textContent = `${state.system === 'shockley' ? 'Shockley diodes (stiff solver)' : 'exact'}: ${answer.orbit.stability}`;
      } else {
        clear();
        p.dataset.state = 'none';
        set('converged', 'no');
        $('[data-orbit="status"]').textContent = `no periodic orbit: ${answer.reason}`;
        $('[data-orbit="note"]').textContent = '';
      }
      draw(answer);
      drawCycle(answer);
    },
    (e) => {
      if (isAbort(e)) return;
      clear();
      p.dataset.query = query;
      p.dataset.state = 'error';
      $('[data-orbit="status"]').textContent = e.message;
      $('[data-orbit="note"]').textContent = '';
      draw(null);
      drawCycle(null);
    },
  );
}

// The lab's small helpers: the page's fields, numbers with SI prefixes, 1-2-5 steps.


export const $ = (selector, root = document) => root.querySelector(selector);
export const $$ = (selector, root = document) => Array.from(root.querySelectorAll(selector));
// The page's controls never change: look each up once (redraws read them per sample).
export const fields = new Map();
export const field = (name) => {
  if (!fields.has(name)) fields.set(name, document.querySelector(`[name="${name}"]`));
  return fields.get(name);
};

// ---------------------------------------------------------------- numbers and units
/** x to `digits` significant digits, without trailing zeros (plain notation where short). */
export function num(x, digits = 6) {
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

export const PREFIXES = [[1e9, 'G'], [1e6, 'M'], [1e3, 'k'], [1, ''], [1e-3, 'm'], [1e-6, 'µ'], [1e-9, 'n'], [1e-12, 'p'], [1e-15, 'f']];
/** x with an SI prefix and unit: 11.5 mH, 9.97 kHz. */
export function si(x, unit = '', digits = 4) {
  if (x === null || x === undefined || !Number.isFinite(x)) return '—';
  if (x === 0) return `0 ${unit}`.trim();
  const a = Math.abs(x);
  const [scale, prefix] = PREFIXES.find(([s]) => a >= s * 0.9995) || PREFIXES[PREFIXES.length - 1];
  return `${num(x / scale, digits)} ${prefix}${unit}`.trim();
}
/** The same, as the API reads it back: 11.5m, 20n (no space, no unit). */
export function siText(x) {
  if (!Number.isFinite(x)) return '';
  if (x === 0) return '0';
  const a = Math.abs(x);
  // No prefix from 0.1 to 1000: 0.7 (V), not 700m.
  if (a >= 0.1 && a < 1000) return num(x, 10);
  const [scale, prefix] = PREFIXES.find(([s]) => a >= s * 0.9995) || PREFIXES[PREFIXES.length - 1];
  return `${num(x / scale, 10)}${prefix === 'µ' ? 'u' : prefix}`;
}
/** The 1-2-5 values from 1e-9 to 1e3. */
export const STEPS = (() => {
  const out = [];
  for (let e = -9; e <= 3; e++) for (const m of [1, 2, 5]) out.push(m * 10 ** e);
  return out.map((v) => Number(v.toPrecision(3)));
})();
export const niceAtLeast = (x) => STEPS.find((s) => s >= x * 0.999) || STEPS[STEPS.length - 1];
/** The smallest 1-2-5 value at least `x`, at any magnitude (frequency spans). */
export function nice125(x) {
  const e = 10 ** Math.floor(Math.log10(x));
  for (const m of [1, 2, 5, 10]) if (m * e >= x * 0.999) return Number((m * e).toPrecision(3));
  return 10 * e;
}
/** Harmonics the FFT span shows at least, as a scope's span follows its signal: the span per
 * division is the 1-2-5 step at or above (FFT_SPAN_HARMONICS + 0.5)·f/10. */
export const FFT_SPAN_HARMONICS = 16;
/** Harmonics a span shows at most (a 1-2-5 step is at most 2.5 times the one below it): the
 * page asks the lab for these, so that the bars fill every span (within the lab's cap of 256). */
export const FFT_MAX_HARMONICS = Math.floor(2.5 * (FFT_SPAN_HARMONICS + 0.5));

// End-to-end tests of `stickslip lab` in headless Chromium: the real server on a free port,
// the real page, and the command-line tool as the reference for every number.
//
// Run: npm test (from this folder), after `cargo build --release -p stickslip-cli`;
// scripts/test runs it. Set LAB_LATENCY_OUT=file.json to keep the slider latencies.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { requireTools, startLab, startBrowser, stickslip, PATIENCE } from './harness.mjs';

let lab;
let browser;
let page;
const consoleErrors = [];
// Console lines a step expects (the browser's own note on an answer with status 400).
let expectedConsole = null;

before(async () => {
  requireTools();
  lab = await startLab();
  browser = await startBrowser();
  page = browser.page;
  page.on('console', (message) => {
    if (message.type() !== 'error' && message.type() !== 'warning') return;
    const text = message.text();
    if (expectedConsole && expectedConsole.test(text)) return;
    consoleErrors.push(`${message.type()}: ${text}`);
  });
  page.on('pageerror', (error) => consoleErrors.push(`page error: ${error.message}`));
  await page.goto(lab.url);
  await ready();
});

after(async () => {
  if (browser) await browser.close();
  if (lab) await lab.stop();
});

/** Wait until the page shows the answer to its latest input. Every wait of these tests is
 * bounded by PATIENCE (600 s, the lab's time limit here): a bound on a hang, never a race
 * with the machine's load. */
async function ready(p = page) {
  await p.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'ready', null, { timeout: PATIENCE });
}

/** Wait until the map (and so the sweep before it) computed on load is on the page. */
async function mapReady(p = page) {
  await p.waitForFunction(() => document.querySelector('[data-map="status"]').dataset.state === 'ready', null, { timeout: PATIENCE });
}

/** The query of the shown answer. */
const shownQuery = () => page.$eval('#status', (e) => e.dataset.query);

/** The number a readout shows (what a person reads). */
async function readout(name) {
  return page.$eval(`[data-measure="${name}"]`, (e) => e.textContent.trim());
}

/** The CLI's steady state for the same flags. */
function cliSteady(flags) {
  return JSON.parse(stickslip(['steady', ...flags, '--json']));
}

/** `shown` equals `expected` to 4 significant digits. */
function sameTo4Digits(shown, expected, what) {
  const x = Number(shown);
  assert.ok(Number.isFinite(x), `${what}: '${shown}' is not a number`);
  const tolerance = 5e-5 * Math.abs(expected);
  assert.ok(Math.abs(x - expected) <= tolerance, `${what}: page ${shown}, CLI ${expected}`);
}

/** The hooked readouts against `stickslip steady --json` (A1, A3 in volts: U_t = 0.7 V
 * unless the flags give another). */
async function readoutsMatch(flags) {
  const cli = cliSteady(flags);
  const ut = flags.includes('--ut') ? Number(flags[flags.indexOf('--ut') + 1]) : 0.7;
  assert.equal(await readout('class'), cli.class, `class for ${flags.join(' ')}`);
  sameTo4Digits(await readout('gain'), cli.gain, `gain for ${flags.join(' ')}`);
  sameTo4Digits(await readout('gain1'), cli.gain1, `gain1 for ${flags.join(' ')}`);
  sameTo4Digits(await readout('A1'), cli.harmonics[0] * ut, `A1 for ${flags.join(' ')}`);
  sameTo4Digits(await readout('A3'), cli.harmonics[2] * ut, `A3 for ${flags.join(' ')}`);
  return cli;
}

/** Type into a field and commit it (Enter), as a person does; wait for the answer. */
async function type(name, text) {
  const input = page.locator(`input[name="${name}"]`);
  await input.fill(text);
  await input.press('Enter');
  await ready();
}

/** Click an export button and read the downloaded file. */
async function exportFile(action) {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click(`[data-action="${action}"]`)]);
  return { name: download.suggestedFilename(), bytes: readFileSync(await download.path()) };
}

function parseCsv(text) {
  const lines = text.trim().split('\n');
  return { header: lines[0].split(','), rows: lines.slice(1).map((l) => l.split(',').map(Number)) };
}

test('the page opens on the paper circuit at its Fig. 3 point (0.95, 2.14)', async () => {
  assert.equal(await shownQuery(), 'preset=paper&w=0.95&beta=2.14');
  await readoutsMatch(['--preset', 'paper', '--w', '0.95', '--beta', '2.14']);
  assert.equal(await page.$eval('[data-derived="w"]', (e) => e.textContent), '0.95');
  assert.equal(await page.$eval('[data-derived="beta"]', (e) => e.textContent), '2.14');
  // The generator shows the same point in hertz and volts.
  const freq = Number(await page.inputValue('input[name="freq"]'));
  assert.ok(Math.abs(freq - 0.95 * 10494.37) < 0.5, `freq ${freq}`);
  assert.equal(await page.inputValue('input[name="amplitude"]'), '1.498');
});

test('issue 19: the model form is built from /api/keys: a field per key, its symbol, unit and help, and the fit boxes served', async () => {
  const keys = await page.evaluate(async () => (await fetch('/api/keys')).json());
  const fields = await page.$$eval('fieldset[data-for-system] .field input[type="text"], fieldset[data-for-system] .field select', (inputs) =>
    inputs.map((i) => ({ id: i.id, name: i.name, title: i.title, fieldset: i.closest('fieldset').dataset.forSystem, label: i.labels[0].innerHTML, unit: i.parentElement.querySelector('.unit')?.textContent ?? '', error: i.parentElement.querySelector('.error').dataset.errorFor })),
  );
  const byId = new Map(fields.map((f) => [f.id, f]));
  // Every number of the system and the diodes has its field (ζ follows from the parts and
  // is shown derived), with the key's flag as id and name, its help as title.
  const numbers = keys.keys.filter((k) => ['system', 'diode'].includes(k.group) && k.form !== 'choice' && k.flag !== 'zeta');
  assert.ok(numbers.length >= 14, `${numbers.length} keys`);
  for (const k of numbers) {
    const f = byId.get(k.flag);
    assert.ok(f, `no field for ${k.flag}`);
    assert.equal(f.name, k.flag);
    assert.equal(f.title, k.help);
    assert.equal(f.error, k.flag);
    assert.ok(f.label.length > 0, `${k.flag} has no label`);
  }
  // Each in its fieldset in the table's order, as the page had them written by hand.
  for (const fieldset of ['pwl shockley', 'pwl', 'shockley', 'mechanics']) {
    assert.deepEqual(fields.filter((f) => f.fieldset === fieldset).map((f) => f.id), keys.form.filter((f) => f.fieldset === fieldset).map((f) => f.flag), fieldset);
  }
  assert.equal(fields.length, keys.form.length);
  assert.deepEqual(
    fields.map((f) => `${f.id}:${f.fieldset}:${f.label}:${f.unit}`),
    ['inductance:pwl shockley:L:H', 'capacitance:pwl shockley:C:F', 'resistance:pwl shockley:R:Ω', 'ut:pwl shockley:U<sub>t</sub>:V', 'rd:pwl:R<sub>D</sub>:Ω', 'diode-is:shockley:I<sub>s</sub>:A', 'diode-n:shockley:n:', 'diode-rs:shockley:R<sub>s</sub>:Ω', 'temperature:shockley:T:°C', 'mu-s:mechanics:μ<sub>s</sub>:≥ 1', 'mass:mechanics:m:kg', 'stiffness:mechanics:k:N/m', 'damping:mechanics:γ:N·s/m', 'friction:mechanics:F<sub>0</sub>:N', 'belt-speed:mechanics:v<sub>belt</sub>:m/s', 'friction-law:mechanics:friction law:', 'stribeck-speed:mechanics:v<sub>S</sub>:m/s', 'delta:mechanics:δ:', 'viscous-friction:mechanics:c<sub>v</sub>:N·s/m', 'cubic-k1:mechanics:K<sub>1</sub>:N·s/m', 'cubic-k3:mechanics:K<sub>3</sub>:N·s³/m³'],
  );
  assert.equal(await page.$eval('#ut', (e) => e.parentElement.outerHTML), `<div class="field"><label for="ut">U<sub>t</sub></label><input id="ut" name="ut" type="text" title="${keys.keys.find((k) => k.flag === 'ut').help}" data-part=""><span class="unit">V</span><label class="free" data-fit-laws="pwl" title="free in the fit: fitted to the record"><input type="checkbox" name="free-ut" data-free="ut" checked=""> fit</label><span class="error" data-error-for="ut" role="alert"></span></div>`);
  assert.equal(await page.$eval('#mu-s', (e) => e.getAttribute('value')), '1');
  assert.deepEqual(await page.$$eval('[data-part]', (els) => els.map((e) => e.id)), ['inductance', 'capacitance', 'resistance', 'ut', 'rd']);
  // The fit boxes: the served fit parameters that have a field beside the fit (μs is the
  // mechanical oscillator's there), ticked as the fit frees them by default.
  const boxes = await page.$$eval('input[data-free]', (els) => els.map((e) => ({ name: e.name, free: e.dataset.free, checked: e.checked })));
  const fitFields = keys.form.filter((f) => keys.fit.parameters.includes(f.flag) && f.fieldset !== 'mechanics').map((f) => f.flag);
  assert.deepEqual(boxes.map((b) => b.free), fitFields);
  assert.deepEqual(fitFields, ['inductance', 'capacitance', 'resistance', 'ut', 'rd', 'diode-is', 'diode-n', 'diode-rs']);
  for (const b of boxes) assert.equal(b.name, `free-${b.free}`);
  assert.deepEqual(boxes.filter((b) => b.checked).map((b) => b.free), fitFields.filter((f) => Object.values(keys.fit.free).some((free) => free.includes(f))));
});

test('sweep up and down and the (w, beta) map, computed on load', async () => {
  await mapReady();
  const sweep = await page.$eval('[data-sweep="status"]', (e) => e.textContent);
  assert.match(sweep, /^120 steady states at β = 2\.14/);
  const map = await page.$eval('[data-map="status"]', (e) => e.textContent);
  // The counts of the classes on the 60 × 50 grid, as stickslip phase-diagram finds them.
  const cli = stickslip(['phase-diagram', '--preset', 'paper', '--w-steps', '60', '--beta-steps', '50']);
  const counts = {};
  for (const line of cli.trim().split('\n').slice(1)) {
    const c = line.split(',')[2];
    counts[c] = (counts[c] || 0) + 1;
  }
  for (const [c, n] of Object.entries(counts)) assert.match(map, new RegExp(`${c} ${n}\\b`));
});

test('the curves over the map: stickslip curve, drawn in the map axes', async () => {
  await mapReady();
  const curvesReady = () => page.waitForFunction(() => ['ready', 'error'].includes(document.querySelector('[data-curves="status"]').dataset.state), null, { timeout: PATIENCE });
  const overlay = () => page.evaluate(() => {
    const o = window.stickslipLab.mapCurves;
    return { xr: o.xr, yr: o.yr, box: o.box, curves: o.curves, queries: o.queries };
  });
  /** Every drawn point at the pixel of the map's axes, the points inside `wRange`, and the
   *  canvas painted in the grazing curve's colour at a point in the middle of the plot. */
  const drawnInAxes = async (o, wRange) => {
    const g = o.curves.grazing;
    assert.ok(g && g.x.length > 10, JSON.stringify(Object.keys(o.curves)));
    const { l, r, t, b } = o.box;
    for (let i = 0; i < g.x.length; i++) {
      assert.ok(g.x[i] >= wRange[0] && g.x[i] <= wRange[1], `w = ${g.x[i]}`);
      const px = l + ((g.x[i] - o.xr[0]) / (o.xr[1] - o.xr[0])) * (r - l);
      const py = b - ((g.y[i] - o.yr[0]) / (o.yr[1] - o.yr[0])) * (b - t);
      assert.ok(Math.abs(g.pixels[i][0] - px) < 1e-9 && Math.abs(g.pixels[i][1] - py) < 1e-9, `point ${i}: ${g.pixels[i]} against ${px}, ${py}`);
    }
    // A point well inside the plot, away from its key (upper left) and its edges.
    const k = g.pixels.findIndex(([x, y]) => x > l + 160 && x < r - 20 && y > t + 60 && y < b - 20);
    assert.ok(k >= 0, 'a point of the curve inside the plot');
    const [x, y] = g.pixels[k];
    const rgb = await page.$eval('#map-plot', (c, [x, y]) => {
      // Read from a copy made for reading (the map's own context is not).
      const ratio = Number(c.dataset.ratio || 1);
      const copy = document.createElement('canvas');
      copy.width = c.width;
      copy.height = c.height;
      const g = copy.getContext('2d', { willReadFrequently: true });
      g.drawImage(c, 0, 0);
      return Array.from(g.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data.slice(0, 3));
    }, [x, y]);
    // #e69f00: orange.
    assert.ok(Math.abs(rgb[0] - 230) < 50 && Math.abs(rgb[1] - 159) < 50 && rgb[2] < 80, `pixel at (${x}, ${y}): ${rgb}`);
  };
  // The query as command-line flags: its keys are the flags without dashes.
  const flags = (query) => [...new URLSearchParams(query)].flatMap(([k, v]) => [`--${k}`, v]);
  const cliCurve = (query) => {
    const lines = stickslip(['curve', ...flags(query)]).trim().split('\n');
    const header = lines[0].split(',');
    const rows = lines.slice(1).map((l) => l.split(','));
    return { w: rows.map((r) => Number(r[header.indexOf('w')])), beta: rows.map((r) => Number(r[header.indexOf('beta')])) };
  };

  await page.check('input[name="map-curves"]');
  await curvesReady();
  let status = await page.$eval('[data-curves="status"]', (e) => e.textContent);
  assert.match(status, /^curves: grazing \d+ points, no fold, no period doubling$/);
  let o = await overlay();
  // The grazing curve of the map's circuit: the tool's for the same query, number for number.
  const sent = (query, expected) => {
    const q = Object.fromEntries(new URLSearchParams(query));
    for (const [k, v] of Object.entries(expected)) {
      if (typeof v === 'number') assert.ok(Math.abs(Number(q[k]) - v) < 1e-12, `${k} in ${query}`);
      else assert.equal(q[k], v, `${k} in ${query}`);
    }
  };
  // From the current point's w at the top of the map, down to its bottom, over its w range.
  sent(o.queries.grazing, { preset: 'paper', w: 0.95, beta: 4, follow: 'grazing', vary: 'beta', 'vary-to': 0.5, over: 'w', from: 0.1, to: 2.5 });
  const cli = cliCurve(o.queries.grazing);
  assert.deepEqual(o.curves.grazing.x, cli.w);
  assert.deepEqual(o.curves.grazing.y, cli.beta);
  await drawnInAxes(o, [0.1, 2.5]);

  // A map of other ranges: the curves are asked for again, over its w, in its axes.
  const setRanges = async (ranges) => {
    for (const [name, v] of Object.entries(ranges)) await page.locator(`input[name="${name}"]`).fill(v);
    await page.click('[data-action="map"]');
    await mapReady();
  };
  await setRanges({ 'map-w-min': '0.5', 'map-w-max': '1.5', 'map-beta-min': '1', 'map-beta-max': '3' });
  await curvesReady();
  o = await overlay();
  sent(o.queries.grazing, { w: 0.95, beta: 3, 'vary-to': 1, from: 0.5, to: 1.5 });
  assert.deepEqual(o.xr.map((x) => Number(x.toFixed(6))), [0.491525, 1.508475]);
  await drawnInAxes(o, [0.5, 1.5]);
  assert.deepEqual(o.curves.grazing.x, cliCurve(o.queries.grazing).w);

  // Unticked: nothing drawn.
  await page.uncheck('input[name="map-curves"]');
  o = await overlay();
  assert.deepEqual(o.curves, {});
  assert.equal(await page.$eval('[data-curves="status"]', (e) => e.textContent), '');
  await setRanges({ 'map-w-min': '0.1', 'map-w-max': '2.5', 'map-beta-min': '0.5', 'map-beta-max': '4' });
});

test('changing frequency and amplitude gives the numbers of stickslip steady', async () => {
  for (const [freq, amplitude] of [['9.5k', '1.2'], ['3050', '0.749'], ['15k', '2.5']]) {
    await type('freq', freq);
    await type('amplitude', amplitude);
    assert.equal(await shownQuery(), `preset=paper&freq=${freq}&amplitude=${amplitude}`);
    await readoutsMatch(['--preset', 'paper', '--freq', freq, '--amplitude', amplitude]);
  }
  // A point that sticks twice a period: the class and the stops come from the exact event log.
  await type('freq', '3050');
  await type('amplitude', '0.749');
  assert.equal(await readout('class'), 'periodic-stick');
  assert.equal(await readout('stops'), '2');
});

test('bad input shows the server message beside its field', async () => {
  expectedConsole = /status of 400/;
  await page.locator('input[name="freq"]').fill('ten kHz');
  await page.locator('input[name="freq"]').press('Enter');
  await page.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'error', null, { timeout: PATIENCE });
  const message = await page.$eval('[data-error-for~="freq"]', (e) => e.textContent);
  assert.match(message, /invalid freq: 'ten kHz' is not a number/);
  assert.equal(await page.getAttribute('input[name="freq"]', 'aria-invalid'), 'true');
  await page.locator('input[name="resistance"]').fill('-5');
  await page.locator('input[name="resistance"]').press('Enter');
  await page.waitForFunction(() => document.querySelector('[data-error-for~="resistance"]').textContent !== '', null, { timeout: PATIENCE });
  assert.match(await page.$eval('[data-error-for~="resistance"]', (e) => e.textContent), /invalid resistance -5: must be finite and from 0 to 1e9/);
  // Both fields are wrong now; mend both, then one answer comes.
  await page.locator('input[name="resistance"]').fill('68');
  await type('freq', '9.97k');
  expectedConsole = null;
  assert.equal(await page.$eval('[data-error-for~="freq"]', (e) => e.textContent), '');
  assert.equal(await page.getAttribute('input[name="freq"]', 'aria-invalid'), null);
  // Custom parts equal to the paper's: the same numbers as --preset paper, to 4 digits.
  await readoutsMatch(['--preset', 'paper', '--freq', '9.97k', '--amplitude', '0.749']);
});

test('Y-T, X-Y and FFT screens, and their CSV exports', async () => {
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  const cli = await readoutsMatch(['--preset', 'paper', '--w', '0.95', '--beta', '2.14']);
  const screen = () => page.$eval('#screen', (c) => c.toDataURL());

  // Y-T: the screen's samples; u_C reaches the exact peak, the drive its amplitude.
  const yt = await screen();
  const ytCsv = parseCsv((await exportFile('export-csv')).bytes.toString());
  assert.deepEqual(ytCsv.header, ['t_s', 'u_V', 'uc_V', 'i_A']);
  assert.ok(ytCsv.rows.length > 500, `${ytCsv.rows.length} rows`);
  const col = (csv, k) => csv.rows.map((r) => r[k]);
  const peakV = cli.peak * 0.7;
  const ucMax = Math.max(...col(ytCsv, 2));
  assert.ok(ucMax <= peakV * (1 + 1e-12) && ucMax > peakV * 0.999, `u_C max ${ucMax}, exact peak ${peakV}`);
  assert.ok(Math.abs(Math.max(...col(ytCsv, 1)) - 1.498) < 1.498 * 1e-3);
  const times = col(ytCsv, 0);
  const tdiv = Number(await page.inputValue('select[name="tdiv"]'));
  assert.ok(times[0] <= 1e-12 && times.at(-1) >= 9.9 * tdiv, `window ${times[0]}..${times.at(-1)}`);

  // X-Y: the loop u_C against U, one drive period.
  await page.check('input[name="mode"][value="xy"]');
  const xy = await screen();
  assert.notEqual(xy, yt);
  const xyCsv = parseCsv((await exportFile('export-csv')).bytes.toString());
  assert.deepEqual(xyCsv.header, ['t_s', 'u_V', 'uc_V', 'i_A']);
  assert.equal(xyCsv.rows.length, 512);

  // FFT: the library's harmonics of u_C, in volts and dB, labelled 1Ω, 3Ω, ...: the bars on
  // the screen's span, each as `stickslip steady --harmonics 41` (what the page asks for).
  await page.check('input[name="mode"][value="fft"]');
  const fft = await screen();
  assert.notEqual(fft, xy);
  const fftFile = await exportFile('export-csv');
  assert.match(fftFile.name, /^stickslip-lab-fft-.*\.csv$/);
  const fftCsv = parseCsv(fftFile.bytes.toString());
  assert.deepEqual(fftCsv.header, ['harmonic', 'f_Hz', 'amplitude_peak_V', 'level_dBV_rms', 'level_dBV_peak']);
  const span = await page.evaluate(() => 10 * window.stickslipLab.fftAxes().hzdiv);
  const many = cliSteady(['--preset', 'paper', '--w', '0.95', '--beta', '2.14', '--harmonics', '41']);
  assert.equal(fftCsv.rows.length, Math.floor(span / (0.95 * 10494.37)), `${fftCsv.rows.length} bars on ${span} Hz`);
  for (const k of [0, 2, 4, fftCsv.rows.length - 1]) {
    const [order, f, a, dbRms, dbPeak] = fftCsv.rows[k];
    assert.equal(order, k + 1);
    assert.ok(Math.abs(a - many.harmonics[k] * 0.7) <= 1e-12 * a, `A${k + 1}`);
    // dBV RMS, as bench scopes: 20·log10(A/√2 / 1 V); peak: 20·log10(A / 1 V).
    assert.ok(Math.abs(dbRms - 20 * Math.log10(a / Math.SQRT2)) < 1e-9);
    assert.ok(Math.abs(dbPeak - 20 * Math.log10(a)) < 1e-9);
    assert.ok(Math.abs(f - (k + 1) * 0.95 * 10494.37) < (k + 1) * 0.5);
  }
  await page.selectOption('select[name="fft-scale"]', 'linear');
  assert.notEqual(await screen(), fft);

  // PNG export of the screen.
  const png = await exportFile('export-png');
  assert.deepEqual([...png.bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  await page.check('input[name="mode"][value="yt"]');
});

test('cursors read time and voltage differences off the screen', async () => {
  await page.check('input[name="cursors"]');
  await page.fill('input[name="cursor1"]', '0');
  await page.fill('input[name="cursor2"]', '5');
  await page.dispatchEvent('input[name="cursor2"]', 'change');
  const [text, dt] = await page.$eval('[data-cursor="readout"]', (e) => [e.textContent, Number(e.dataset.dt)]);
  const tdiv = Number(await page.inputValue('select[name="tdiv"]'));
  assert.ok(Math.abs(dt - 5 * tdiv) <= 1e-12 * tdiv, `Δt ${dt}, 5 div of ${tdiv} s`);
  assert.match(text, /Δt .*; CH2 .* ΔV/);
  await page.uncheck('input[name="cursors"]');
});

test('the transient from rest: the samples of stickslip simulate', async () => {
  let url = null;
  const listener = (request) => {
    if (request.url().includes('/api/simulate')) url = new URL(request.url());
  };
  page.on('request', listener);
  await page.selectOption('select[name="trigger"]', 'transient');
  await ready();
  page.off('request', listener);
  assert.ok(url, 'the page asked for /api/simulate');
  const csv = parseCsv((await exportFile('export-csv')).bytes.toString());
  const [t0, u0, uc0, i0] = csv.rows[0];
  assert.deepEqual([t0, uc0, i0], [0, 0, 0]);
  assert.ok(Math.abs(u0 - 1.498) < 1e-12);
  const periods = url.searchParams.get('periods');
  const samples = url.searchParams.get('samples');
  const cli = parseCsv(
    stickslip(['simulate', '--preset', 'paper', '--w', '0.95', '--beta', '2.14', '--periods', periods, '--samples-per-period', samples]),
  );
  const t = cli.header.indexOf('t_s');
  const uc = cli.header.indexOf('uc_V');
  assert.ok(csv.rows.length > 100);
  for (let k = 0; k < csv.rows.length; k++) {
    assert.equal(csv.rows[k][0], cli.rows[k][t], `t at row ${k}`);
    assert.equal(csv.rows[k][2], cli.rows[k][uc], `u_C at row ${k}`);
  }
  await page.selectOption('select[name="trigger"]', 'steady');
  await ready();
});

test('with Shockley diodes the page says it computes, stays responsive and drops stale requests', async () => {
  // Issue 38, item 17: the lab holds the first sweep (to=2, 40 steps) until the next sweep
  // request arrives (the lab_hold example's test hook): the first is certainly in flight when
  // the second press drops it, however loaded the machine is. A page of its own, on that lab.
  const held = await startLab([], { hold: ['/api/sweep', 'to=2&steps=40'] });
  const own = await startBrowser();
  try {
    const p = own.page;
    const errors = [];
    p.on('pageerror', (error) => errors.push(error.message));
    await p.goto(held.url);
    await ready(p);
    await mapReady(p);
    const aborted = [];
    p.on('requestfailed', (request) => {
      if (request.url().includes('/api/sweep') && /ABORTED/.test(request.failure()?.errorText || '')) aborted.push(request.url());
    });
    await p.selectOption('select[name="system"]', 'shockley');
    await ready(p);
    assert.match(await p.$eval('#status', (e) => e.textContent), /Shockley/);
    const flags = ['--preset', 'paper', '--model', 'shockley', '--w', '0.95', '--beta', '2.14'];
    const cli = cliSteady(flags);
    sameTo4Digits(await p.$eval('[data-measure="gain"]', (e) => e.textContent.trim()), cli.gain, 'Shockley gain');

    // A sweep with the stiff solver takes a while: the page shows it, answers meanwhile, and
    // a second press drops the first request.
    await p.fill('input[name="sweep-steps"]', '40');
    await p.click('[data-action="sweep"]');
    const during = await p.$eval('[data-sweep="status"]', (e) => [e.dataset.state, e.textContent]);
    assert.deepEqual(during, ['computing', 'computing…']);
    // The page stays responsive: a new amplitude is computed while the sweep waits.
    const input = p.locator('input[name="amplitude"]');
    await input.fill('1.4');
    await input.press('Enter');
    await ready(p);
    assert.equal(new URLSearchParams(await p.$eval('#status', (e) => e.dataset.query)).get('amplitude'), '1.4');
    assert.deepEqual(await p.$eval('[data-sweep="status"]', (e) => e.dataset.state), 'computing');
    // The browser reports the dropped request on its own schedule, possibly after the page
    // shows the second sweep: wait for the report itself.
    const dropped = p.waitForEvent('requestfailed', {
      predicate: (request) => request.url().includes('/api/sweep'),
      timeout: PATIENCE,
    });
    await p.fill('input[name="sweep-to"]', '1.9');
    await p.click('[data-action="sweep"]');
    await p.waitForFunction(() => document.querySelector('[data-sweep="status"]').dataset.state === 'ready', null, { timeout: PATIENCE });
    const first = await dropped;
    assert.match(first.failure()?.errorText || '', /ABORTED/);
    assert.match(first.url(), /to=2&steps=40/);
    assert.equal(aborted.length, 1, `aborted sweeps: ${aborted.length}`);
    assert.match(aborted[0], /to=2&steps=40/);
    assert.match(await p.$eval('[data-sweep="status"]', (e) => e.textContent), /^80 steady states/);
    assert.deepEqual(errors, []);
  } finally {
    await own.close();
    await held.stop();
  }
});

test('the mechanical twin: a mass on a spring with dry friction', async () => {
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  const flags = ['--mass', '0.5', '--stiffness', '200', '--damping', '0.94', '--friction', '1', '--mu-s', '1', '--w', '0.95', '--beta', '2.14'];
  const cli = cliSteady(flags);
  assert.equal(await readout('class'), cli.class);
  sameTo4Digits(await readout('gain'), cli.gain, 'mechanical gain');
  await type('mu-s', '1.5');
  const sticky = cliSteady(flags.map((f, i) => (flags[i - 1] === '--mu-s' ? '1.5' : f)));
  assert.equal(await readout('class'), sticky.class);
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
});

test('issue 36: the block on a moving belt: the law shows its own fields, a Stribeck belt sticks and slips on its own, bad laws are named beside their field', async () => {
  const keys = await page.evaluate(async () => (await fetch('/api/keys')).json());
  const lawOf = new Map(keys.form.filter((f) => f.law).map((f) => [f.flag, f.law]));
  assert.deepEqual([...lawOf.keys()], ['stribeck-speed', 'delta', 'viscous-friction', 'cubic-k1', 'cubic-k3']);
  const visible = (flag) => page.$eval(`[name="${flag}"]`, (e) => e.getClientRects().length > 0);
  const sent = async () => [...new URLSearchParams(await shownQuery()).keys()];
  /** The law's fields are shown and sent, the other laws' neither. */
  async function onlyFieldsOf(law) {
    const query = await sent();
    for (const [flag, of] of lawOf) {
      assert.equal(await visible(flag), of === law, `${flag} shown with ${law}`);
      assert.equal(query.includes(flag), of === law, `${flag} sent with ${law}`);
    }
    assert.equal(new URLSearchParams(await shownQuery()).get('friction-law'), law);
  }
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  assert.equal(await page.inputValue('select[name="friction-law"]'), 'coulomb');
  assert.ok(await visible('belt-speed'));
  await onlyFieldsOf('coulomb');
  for (const law of ['stribeck', 'cubic', 'coulomb']) {
    await page.selectOption('select[name="friction-law"]', law);
    await ready();
    await onlyFieldsOf(law);
  }

  // The block on a belt at 3 cm/s with Stribeck friction and no drive: a stick-slip cycle
  // of its own, as `stickslip steady` finds it; its period and extremes instead of the drive
  // period's quantities.
  await page.selectOption('select[name="preset-choice"]', 'belt-stribeck');
  await ready();
  await onlyFieldsOf('stribeck');
  const query = new URLSearchParams(await shownQuery());
  assert.equal(query.get('belt-speed'), '0.03');
  assert.equal(query.get('beta'), '0');
  const flags = [...query].flatMap(([k, v]) => [`--${k}`, v]);
  const cli = cliSteady(flags);
  assert.equal(cli.class, 'stick-slip-cycle');
  assert.equal(await readout('class'), cli.class);
  const omega0 = 20; // √(k/m) = √(200/0.5)
  sameTo4Digits(await readout('cycle-period'), cli.cycle_period_tau / omega0, 'cycle period (s)');
  sameTo4Digits(await readout('stick-fraction'), cli.stick_fraction, 'stick fraction');
  const [max, min] = (await readout('y-extremes')).split(' / ');
  sameTo4Digits(max, cli.y_max * 0.005, 'max (m)');
  sameTo4Digits(min, cli.y_min * 0.005, 'min (m)');
  assert.match(await readout('sliding'), /^unstable at /);
  for (const name of ['gain', 'gain1', 'A1', 'period']) {
    assert.equal(await page.$eval(`[data-measure="${name}"]`, (e) => e.getClientRects().length), 0, `${name} is hidden`);
  }
  assert.equal(await page.$eval('[data-label="stops"]', (e) => e.textContent), 'stops per cycle');
  // The screen repeats the cycle: its class line gives the period in seconds.
  const text = await page.evaluate(() => window.stickslipLab.screenText.map((b) => b.text).join(' | '));
  assert.match(text, /stick-slip-cycle, period \d/);
  // The block on the belt: drawn stuck (riding on the belt) and sliding in turn.
  const view = page.locator('#mechanics-view');
  assert.equal(await view.getAttribute('data-belt'), 'true');
  for (const stuck of ['true', 'false', 'true']) {
    await page.waitForFunction((s) => document.querySelector('#mechanics-view').dataset.stuck === s, stuck, { timeout: PATIENCE });
  }
  // The belt's fields and readouts fit the page, wide and on a phone.
  for (const [width, height] of [[1500, 1100], [390, 844]]) {
    await resize(page, width, height);
    assert.deepEqual(await layoutProblems(page), [], `the belt at ${width} × ${height}`);
  }
  await resize(page, 1500, 1100);

  // Bad laws: the server's message beside the field at fault.
  expectedConsole = /status of 400/;
  for (const [law, flag, text, pattern] of [
    ['stribeck', 'stribeck-speed', '0', /invalid stribeck-speed 0/],
    ['stribeck', 'delta', '-1', /invalid delta -1/],
    ['cubic', 'cubic-k1', '1000', /go negative/],
  ]) {
    if ((await page.inputValue('select[name="friction-law"]')) !== law) {
      await page.selectOption('select[name="friction-law"]', law);
      await ready();
    }
    const before = await page.inputValue(`input[name="${flag}"]`);
    await page.locator(`input[name="${flag}"]`).fill(text);
    await page.locator(`input[name="${flag}"]`).press('Enter');
    await page.waitForFunction((f) => document.querySelector(`[data-error-for~="${f}"]`).textContent !== '', flag, { timeout: PATIENCE });
    assert.match(await page.$eval(`[data-error-for~="${flag}"]`, (e) => e.textContent), pattern);
    assert.equal(await page.getAttribute(`input[name="${flag}"]`, 'aria-invalid'), 'true');
    await type(flag, before);
    assert.equal(await page.$eval(`[data-error-for~="${flag}"]`, (e) => e.textContent), '');
  }
  expectedConsole = null;
  // Back to the paper's circuit for the tests after this one.
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
});

test('dragging the frequency knob: every input reaches the screen, the last one wins', async () => {
  const all = [];
  for (const id of ['fig3-1a', 'fig3-1b', 'fig3-1c', 'fig3-2a', 'fig3-2b', 'fig3-2c']) {
    await page.selectOption('select[name="preset-choice"]', id);
    await ready();
    await page.evaluate(() => {
      window.stickslipLab.latencies.length = 0;
    });
    await page.locator('input[name="freq-knob"]').scrollIntoViewIfNeeded();
    const knob = await page.locator('input[name="freq-knob"]').boundingBox();
    const position = Number(await page.inputValue('input[name="freq-knob"]')) / 1000;
    const y = knob.y + knob.height / 2;
    const x0 = knob.x + 8 + position * (knob.width - 16);
    await page.mouse.move(x0, y);
    await page.mouse.down();
    // A hand's drag: a small step every frame, 30 frames.
    for (let i = 1; i <= 30; i++) {
      await page.mouse.move(x0 + i * 2, y);
      await page.waitForTimeout(16);
    }
    await page.mouse.up();
    await ready();
    const lab = await page.evaluate(() => ({
      latencies: window.stickslipLab.latencies.slice(),
      pending: window.stickslipLab.state.pendingInputs.length,
    }));
    assert.equal(lab.pending, 0, 'an input never reached the screen');
    assert.ok(lab.latencies.length >= 10, `${lab.latencies.length} inputs`);
    all.push(...lab.latencies);
    // The screen shows the last position of the knob.
    const freq = await page.inputValue('input[name="freq"]');
    assert.equal(await shownQuery(), `preset=paper&freq=${freq}&beta=${id.startsWith('fig3-1') ? '1.07' : '2.14'}`);
    const amplitude = id.startsWith('fig3-1') ? 1.07 : 2.14;
    await readoutsMatch(['--preset', 'paper', '--freq', freq, '--beta', String(amplitude)]);
  }
  all.sort((a, b) => a - b);
  const pct = (p) => all[Math.min(all.length - 1, Math.floor((p / 100) * all.length))];
  const summary = { inputs: all.length, p50_ms: pct(50), p95_ms: pct(95), max_ms: all.at(-1) };
  console.log(`slider input → redraw latency over the six Fig. 3 points: ${JSON.stringify(summary)}`);
  if (process.env.LAB_LATENCY_OUT) writeFileSync(process.env.LAB_LATENCY_OUT, JSON.stringify({ ...summary, latencies_ms: all }, null, 1));
});

/** The FFT axes as the page draws them. */
const fftAxes = () => page.evaluate(() => {
  const ax = window.stickslipLab.fftAxes();
  return { hzdiv: ax.hzdiv, db: ax.db, rms: ax.rms, bars: ax.bars.length };
});

test('issue 21 (1, 2): the FFT span follows the drive (7 harmonics at least), in dBV RMS by default', async () => {
  // dB RMS is the default (the first option); the test before left the scale linear.
  assert.deepEqual(await page.$eval('select[name="fft-scale"]', (s) => [s.options[0].value, s.options[0].textContent]), ['db', 'dB RMS']);
  await page.selectOption('select[name="fft-scale"]', 'db');
  await page.check('input[name="mode"][value="fft"]');
  for (const [id, w] of [['fig3-2b', 0.95], ['fig3-2c', 1.43], ['fig3-1c', 1.43], ['fig3-2a', 0.29]]) {
    await page.selectOption('select[name="preset-choice"]', id);
    await ready();
    const f = await page.evaluate(() => window.stickslipLab.state.steady.drive.f_Hz);
    assert.ok(Math.abs(f - w * 10494.37) < 1, `${id}: f = ${f}`);
    const ax = await fftAxes();
    // Ten divisions: the 7th harmonic (and every bar the library computed) on screen.
    assert.ok(10 * ax.hzdiv >= Math.max(7, ax.bars) * f, `${id}: ${ax.hzdiv} Hz/div at f = ${f}`);
    // Not zoomed out needlessly: one 1-2-5 step less would cut bars off.
    assert.ok(10 * ax.hzdiv <= 2.5 * (Math.max(7, ax.bars) + 0.5) * f, `${id}: ${ax.hzdiv} Hz/div`);
  }
  let ax = await fftAxes();
  assert.ok(ax.db && ax.rms, 'dB RMS by default');
  await page.selectOption('select[name="fft-scale"]', 'db-peak');
  ax = await fftAxes();
  assert.ok(ax.db && !ax.rms, 'dB peak on request');
  await page.selectOption('select[name="fft-scale"]', 'db');
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  await page.check('input[name="mode"][value="yt"]');
});

test('issue 21 (3): the PNG caption is wrapped and names the experiment fully', async () => {
  const png = await exportFile('export-png');
  assert.deepEqual([...png.bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  const { lines, widths, cssWidth, experiment } = await page.evaluate(() => {
    const g = document.createElement('canvas').getContext('2d');
    g.font = '12px system-ui, sans-serif';
    const lines = window.stickslipLab.lastCaption;
    return {
      lines,
      widths: lines.map((l) => g.measureText(l).width),
      cssWidth: document.querySelector('#screen').clientWidth,
      experiment: window.stickslipLab.state.steady.experiment,
    };
  });
  const text = lines.join(' ');
  assert.ok(lines.length >= 2, `${lines.length} lines`);
  assert.ok(text.includes(experiment), `the whole description: ${text}`);
  for (const needle of ['drive f = 9.969', 'amplitude 1.498', 'w = Ω/ω0 = 0.95', 'β = 2.14', 'class sliding', 'gain G = ']) {
    assert.ok(text.includes(needle), `'${needle}' not in the caption: ${text}`);
  }
  widths.forEach((w, k) => assert.ok(w <= cssWidth - 16 + 0.5, `line ${k} is ${w} px wide, the picture ${cssWidth}`));
  // The PNG is tall enough for every line: its height in the IHDR chunk.
  const height = png.bytes.readUInt32BE(20);
  const screenHeight = await page.$eval('#screen', (c) => c.height);
  assert.ok(height >= screenHeight + 16 * lines.length, `${height} px for ${lines.length} lines`);
});

test('issue 21 (4): views that no longer match the inputs are marked, and the preset reads custom', async () => {
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  await page.click('[data-action="sweep"]');
  await page.waitForFunction(() => document.querySelector('[data-sweep="status"]').dataset.state === 'ready', null, { timeout: PATIENCE });
  await page.click('[data-action="map"]');
  await page.waitForFunction(() => document.querySelector('[data-map="status"]').dataset.state === 'ready', null, { timeout: PATIENCE });
  const stale = () => page.evaluate(() => ({
    sweep: document.querySelector('#sweep-plot').dataset.stale === 'true',
    map: document.querySelector('#map-plot').dataset.stale === 'true',
    sweepText: document.querySelector('[data-sweep="status"]').textContent,
    mapText: document.querySelector('[data-map="status"]').textContent,
    preset: document.querySelector('select[name="preset-choice"]').value,
  }));
  let s = await stale();
  assert.ok(!s.sweep && !s.map, JSON.stringify(s));
  // A knob leaves the Fig. 3 point: custom (and the sweep, at another β, is marked).
  await page.$eval('input[name="amplitude-knob"]', (k) => {
    k.value = String(Number(k.value) - 40);
    k.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await ready();
  s = await stale();
  assert.equal(s.preset, 'custom');
  assert.ok(s.sweep && /stale: computed at β/.test(s.sweepText), JSON.stringify(s));
  // Shockley diodes: custom, and both views say which circuit they show.
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  await page.selectOption('select[name="system"]', 'shockley');
  await ready();
  s = await stale();
  assert.equal(s.preset, 'custom');
  assert.ok(s.sweep && s.sweepText.includes('PWL diodes') && s.sweepText.includes('press Sweep'), JSON.stringify(s));
  assert.ok(s.map && s.mapText.includes('PWL diodes') && s.mapText.includes('press Map'), JSON.stringify(s));
  // A Shockley sweep's legend (with its "PWL theory:" prefix) stays inside the plot.
  await page.fill('input[name="sweep-steps"]', '4');
  await page.click('[data-action="sweep"]');
  await page.waitForFunction(() => document.querySelector('[data-sweep="status"]').dataset.state === 'ready', null, { timeout: PATIENCE });
  const legend = await page.evaluate(() => window.stickslipLab.sweepLegend);
  const sweepWidth = await page.$eval('#sweep-plot', (c) => c.clientWidth);
  assert.ok(legend.left >= 0 && legend.right <= sweepWidth, `legend ${JSON.stringify(legend)} in a plot ${sweepWidth} px wide`);
  assert.equal(await page.$eval('#sweep-plot', (c) => c.dataset.stale), undefined);
  await page.fill('input[name="sweep-steps"]', '60');
  // Only map sizes that finish with the stiff solver are offered.
  const sizes = await page.$$eval('select[name="map-size"] option', (os) => os.map((o) => o.value));
  for (const v of sizes) {
    const [a, b] = v.split('x').map(Number);
    assert.ok(a * b <= 800, `${v} offered with Shockley diodes`);
  }
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  s = await stale();
  assert.ok(s.sweep && s.sweepText.includes('Shockley diodes') && s.sweepText.includes('mechanical'), JSON.stringify(s));
  assert.ok(s.map && s.mapText.includes('PWL diodes') && s.mapText.includes('mechanical'), JSON.stringify(s));
  // A bad input: the readouts and the screen go pale and nothing stale is exported.
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  expectedConsole = /status of 400/;
  await page.locator('input[name="freq"]').fill('-3');
  await page.locator('input[name="freq"]').press('Enter');
  await page.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'error', null, { timeout: PATIENCE });
  assert.equal(await page.$eval('#screen', (c) => c.dataset.stale), 'true');
  assert.equal(await page.$eval('#measurements', (c) => c.dataset.stale), 'true');
  assert.ok(await page.$eval('[data-action="export-csv"]', (b) => b.disabled));
  await type('freq', '9.97k');
  await ready();
  expectedConsole = null;
  assert.equal(await page.$eval('#screen', (c) => c.dataset.stale), undefined);
  assert.ok(!(await page.$eval('[data-action="export-csv"]', (b) => b.disabled)));
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
});

test('issue 21 (7): field errors, labels, file names, t from 0, and Copy measurements', async () => {
  // A sweep field error marks its field.
  expectedConsole = /status of 400/;
  await page.fill('input[name="sweep-from"]', '3');
  await page.click('[data-action="sweep"]');
  await page.waitForFunction(() => document.querySelector('input[name="sweep-from"]').getAttribute('aria-invalid') === 'true', null, { timeout: PATIENCE });
  await page.fill('input[name="sweep-from"]', '0.2');
  expectedConsole = null;
  // Every map field has an accessible name.
  for (const name of ['map-w-min', 'map-w-max', 'map-beta-min', 'map-beta-max']) {
    const label = await page.$eval(`input[name="${name}"]`, (e) => e.getAttribute('aria-label') || (e.labels && e.labels.length ? e.labels[0].textContent : ''));
    assert.ok(label && label.trim().length > 0, `${name} has no label`);
  }
  // The transient's CSV has a name of its own.
  await page.selectOption('select[name="trigger"]', 'transient');
  await ready();
  const transient = await exportFile('export-csv');
  assert.match(transient.name, /^stickslip-lab-yt-transient-/);
  await page.selectOption('select[name="trigger"]', 'steady');
  await ready();
  const steady = await exportFile('export-csv');
  assert.match(steady.name, /^stickslip-lab-yt-steady-/);
  // The mechanics Y-T CSV starts at t = 0.
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  const mech = parseCsv((await exportFile('export-csv')).bytes.toString());
  assert.equal(mech.rows[0][0], 0);
  assert.ok(mech.rows[1][0] > 0);
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  // Copy measurements: a tab-separated table with the experiment.
  await page.click('[data-action="copy-measurements"]');
  const copied = await page.evaluate(() => window.stickslipLab.lastCopied);
  const rows = copied.trim().split('\n').map((r) => r.split('\t'));
  assert.equal(rows[0][0], 'experiment');
  const gain = rows.find((r) => r[0] === 'gain G');
  assert.ok(gain, copied);
  assert.equal(gain[1], await readout('gain'));
  assert.ok(rows.every((r) => r.length >= 2), copied);
});

test('issue 21 (6): at 800 × 900 the knobs, the scope and the gain are on screen together; canvases are sharp', async () => {
  for (const ratio of [1, 2]) {
    const small = await startBrowser({ width: 800, height: 900 }, ratio);
    try {
      const p = small.page;
      await p.goto(lab.url);
      await ready(p);
      await mapReady(p);
      for (const selector of ['input[name="freq-knob"]', 'input[name="amplitude-knob"]', '#screen', '[data-measure="gain"]']) {
        const box = await p.$eval(selector, (e) => {
          const r = e.getBoundingClientRect();
          return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
        });
        assert.ok(box.left >= 0 && box.top >= 0 && box.right <= 800 && box.bottom <= 900, `${selector} at ${JSON.stringify(box)} (ratio ${ratio})`);
      }
      for (const id of ['#screen', '#sweep-plot', '#map-plot', '#mechanics-view']) {
        const c = await p.$eval(id, (e) => ({ w: e.width, h: e.height, cw: e.clientWidth, ch: e.clientHeight, hidden: e.offsetParent === null }));
        if (c.hidden) continue;
        assert.equal(c.w, Math.round(c.cw * ratio), `${id} backing width ${c.w} for ${c.cw} CSS px at ratio ${ratio}`);
        assert.equal(c.h, Math.round(c.ch * ratio), `${id} backing height ${c.h} for ${c.ch} CSS px at ratio ${ratio}`);
      }
    } finally {
      await small.close();
    }
  }
});

test('issue 20: a scope record dropped on the screen is drawn as REF1 and REF2, and Fit recovers its circuit', async () => {
  // The record: `stickslip simulate` of a circuit other than the paper's (R = 80 Ω,
  // U_t = 0.6 V), in volts, the last 3 of 40 drive periods from rest (the steady state), as a
  // plain CSV with a time column.
  const truth = { resistance: 80, ut: 0.6 };
  const dir = mkdtempSync(join(tmpdir(), 'stickslip-lab-record-'));
  const simFile = join(dir, 'sim.csv');
  stickslip(['simulate', '--inductance', '11.5m', '--capacitance', '20n', '--resistance', '80', '--ut', '0.6', '--rd', '3', '--freq', '5.25k', '--amplitude', '1.5', '--periods', '40', '--samples-per-period', '400', '--out', simFile]);
  const sim = parseCsv(readFileSync(simFile, 'utf8'));
  const col = (name) => sim.header.indexOf(name);
  const kept = sim.rows.slice(37 * 400, 40 * 400);
  const rows = kept.map((r) => `${r[col('t_s')]},${r[col('u_V')]},${r[col('uc_V')]}`);
  // The same record as a Tektronix export: a file per channel, its header in the first columns.
  const tektronix = (k, column) =>
    kept
      .map((r, i) => {
        const [key, value] = [['Record Length', '1.200000e+03'], ['Sample Interval', String(r[col('t_s')] - kept[0][col('t_s')] || 4.7619e-7)], ['Trigger Point', '0'], ['', ''], ['Source', `CH${k}`], ['Vertical Units', 'V']][i] || ['', ''];
        return `${key},${value},,${r[col('t_s')]},${r[col(column)]},`;
      })
      .join('\r\n');
  const text = `t_s,u_V,uc_V\n${rows.join('\n')}\n`;
  try {
    await page.selectOption('select[name="system"]', 'pwl');
    await ready();
    await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
    await ready();
    await page.check('input[name="mode"][value="yt"]');
    await page.check('input[name="ch1-on"]');
    await page.check('input[name="ch2-on"]');
    // Dropped on the screen (a real drop event carrying the file).
    const transfer = await page.evaluateHandle((csvText) => {
      const dt = new DataTransfer();
      dt.items.add(new File([csvText], 'run1.csv', { type: 'text/csv' }));
      return dt;
    }, text);
    await page.dispatchEvent('#screen', 'drop', { dataTransfer: transfer });
    await page.waitForFunction(() => document.querySelector('[data-record="status"]').dataset.state === 'ready', null, { timeout: PATIENCE });
    await ready();
    assert.match(await page.$eval('[data-record="status"]', (e) => e.textContent), /run1\.csv: plain, 1200 samples/);
    // The generator takes the record's drive; the screen shows both reference traces in Y-T
    // and the reference loop in X-Y.
    const freq = Number(await page.inputValue('input[name="freq"]'));
    assert.ok(Math.abs(freq / 5250 - 1) < 1e-6, `frequency ${freq}`);
    const amplitude = Number(await page.inputValue('input[name="amplitude"]'));
    assert.ok(Math.abs(amplitude / 1.5 - 1) < 1e-5, `amplitude ${amplitude}`);
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '2');
    await page.check('input[name="mode"][value="xy"]');
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '1');
    await page.check('input[name="mode"][value="fft"]');
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '0');
    await page.check('input[name="mode"][value="yt"]');
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '2');
    // Fit R and U_t (ticked by default), from the paper's 68 Ω and 0.7 V.
    assert.equal(await page.isChecked('input[name="free-resistance"]'), true);
    assert.equal(await page.isChecked('input[name="free-ut"]'), true);
    await page.click('[data-action="fit"]');
    await page.waitForFunction(() => ['ready', 'error'].includes(document.querySelector('[data-fit="status"]').dataset.state), null, { timeout: PATIENCE });
    assert.equal(await page.$eval('[data-fit="status"]', (e) => e.dataset.state), 'ready', await page.$eval('#fit', (e) => e.textContent));
    for (const [name, value] of Object.entries(truth)) {
      const fitted = Number(await page.$eval(`[data-fit="${name}"]`, (e) => e.textContent.trim()));
      assert.ok(Math.abs(fitted / value - 1) < 0.01, `${name}: fitted ${fitted}, truth ${value}`);
      const stderr = Number(await page.$eval(`[data-fit-stderr="${name}"]`, (e) => e.textContent.trim()));
      assert.ok(Number.isFinite(stderr) && stderr >= 0, `${name} ± ${stderr}`);
      // The fitted value is in its field, and the screen computes with it.
      const shown = Number(await page.inputValue(`input[name="${name}"]`));
      assert.ok(Math.abs(shown / fitted - 1) < 1e-6, `${name} field ${shown}`);
    }
    assert.ok(Number(await page.$eval('[data-fit="rms_residual_V"]', (e) => e.textContent)) < 1e-6);
    // The correlation of the fitted values: 1 on the diagonal, the same number either side,
    // within [−1, 1]; the intervals are the linear ones; no warning for a record made by the
    // model.
    assert.equal(await page.isHidden('[data-fit="correlation"]'), false);
    const cell = (a, b) => page.$eval(`[data-fit-correlation="${a} ${b}"]`, (e) => Number(e.textContent));
    assert.equal(await cell('resistance', 'resistance'), 1);
    const r = await cell('resistance', 'ut');
    assert.ok(Number.isFinite(r) && Math.abs(r) <= 1, `correlation ${r}`);
    assert.equal(await cell('ut', 'resistance'), r);
    assert.deepEqual(await page.$$eval('[data-fit-interval]', (cells) => cells.map((c) => c.dataset.fitInterval)), ['linear', 'linear']);
    assert.equal(await page.isHidden('[data-fit="warnings"]'), true);
    await ready();
    const query = new URLSearchParams(await shownQuery());
    assert.ok(Math.abs(Number(query.get('resistance')) / truth.resistance - 1) < 0.01, await shownQuery());
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '2');
    // A Tektronix export: both channels' files picked at once, merged by the lab.
    writeFileSync(join(dir, 'ch1.csv'), tektronix(1, 'u_V'));
    writeFileSync(join(dir, 'ch2.csv'), tektronix(2, 'uc_V'));
    await page.setInputFiles('input[name="record-file"]', [join(dir, 'ch1.csv'), join(dir, 'ch2.csv')]);
    await page.waitForFunction(() => /merged/.test(document.querySelector('[data-record="status"]').textContent), null, { timeout: PATIENCE });
    assert.match(await page.$eval('[data-record="status"]', (e) => e.textContent), /^ch1\.csv\+ch2\.csv: merged, 1200 samples, 5\.25 kHz, 1\.5 V/);
    await ready();
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '2');
    // Picked with the button instead: a garbage row is refused with the file and the line,
    // beside the record, and the record on the screen stays.
    expectedConsole = /status of 400/;
    const bad = join(dir, 'bad.csv');
    writeFileSync(bad, text.replace(/\n([^\n]*)\n/, '\n$1\n0.00705,abc,1\n'));
    await page.setInputFiles('input[name="record-file"]', bad);
    await page.waitForFunction(() => document.querySelector('[data-error-for~="record"]').textContent !== '', null, { timeout: PATIENCE });
    assert.match(await page.$eval('[data-error-for~="record"]', (e) => e.textContent), /bad\.csv: line 3: .*abc/);
    // A file over the lab's cap is refused in the page, naming the cap.
    const big = join(dir, 'big.csv');
    writeFileSync(big, text + '\n'.repeat(2 * 1024 * 1024));
    await page.setInputFiles('input[name="record-file"]', big);
    await page.waitForFunction(() => /cap of/.test(document.querySelector('[data-record="status"]').textContent), null, { timeout: PATIENCE });
    assert.match(await page.$eval('[data-record="status"]', (e) => e.textContent), /big\.csv is \d+ bytes: over the lab's cap of 2 MB \(2097152 bytes\)/);
    expectedConsole = null;
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '2');
    // Removed: no reference trace, no Fit.
    await page.click('[data-action="clear-record"]');
    assert.equal(await page.getAttribute('#screen', 'data-ref-count'), '0');
    assert.equal(await page.isDisabled('[data-action="fit"]'), true);
  } finally {
    expectedConsole = null;
    rmSync(dir, { recursive: true, force: true });
  }
});

test('issue 19: the query of each system holds exactly the served keys of its fieldsets', async () => {
  const keys = await page.evaluate(async () => (await fetch('/api/keys')).json());
  const drive = new Set(keys.keys.filter((k) => k.group === 'drive').map((k) => k.flag));
  const fieldsOf = (system, part) => keys.form.filter((f) => f.fieldset.split(' ').includes(system) && (part === undefined || f.part === part)).map((f) => f.flag);
  // The model keys of the query on the screen (the drive has its own controls).
  const modelKeys = async () => [...new URLSearchParams(await shownQuery()).keys()].filter((k) => !drive.has(k));
  /** Commit a field's own value again: the value is now the user's. */
  const retype = async (name) => type(name, await page.inputValue(`input[name="${name}"]`));
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  // The paper's parts are sent as its preset until one is edited; then every field of the
  // PWL fieldsets (the parts and R_D), in the table's order.
  assert.deepEqual(await modelKeys(), ['preset']);
  await retype('resistance');
  assert.deepEqual(await modelKeys(), fieldsOf('pwl'));
  assert.deepEqual(fieldsOf('pwl'), ['inductance', 'capacitance', 'resistance', 'ut', 'rd']);
  // Shockley diodes: the parts and the diode law; the diodes' fields once one is edited.
  await page.selectOption('select[name="system"]', 'shockley');
  await ready();
  assert.deepEqual(await modelKeys(), [...fieldsOf('shockley', true), 'model']);
  assert.equal(new URLSearchParams(await shownQuery()).get('model'), 'shockley');
  await retype('diode-n');
  assert.deepEqual(await modelKeys(), [...fieldsOf('shockley', true), 'model', ...fieldsOf('shockley', false)]);
  assert.deepEqual(fieldsOf('shockley', false), ['diode-is', 'diode-n', 'diode-rs', 'temperature']);
  // The mechanical oscillator: every field of its fieldset in use (a friction law's
  // parameters only while that law is chosen: Coulomb's has none).
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  const inUse = (law) => keys.form.filter((f) => f.fieldset === 'mechanics' && (!f.law || f.law === law)).map((f) => f.flag);
  assert.deepEqual(await modelKeys(), inUse('coulomb'));
  assert.deepEqual([...inUse('coulomb')].sort(), ['belt-speed', 'damping', 'friction', 'friction-law', 'mass', 'mu-s', 'stiffness']);
  assert.deepEqual(fieldsOf('mechanics').filter((f) => !inUse('coulomb').includes(f)), ['stribeck-speed', 'delta', 'viscous-friction', 'cubic-k1', 'cubic-k3']);
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  assert.equal(await shownQuery(), 'preset=paper&w=0.95&beta=2.14');
});

// ---------------------------------------------------------------- issue 38
/** What sticks out or overlaps on the page as laid out now: an element outside its panel, a
 * panel outside the window or on another, the page wider than the window, text on text (the
 * page's text nodes, and the labels drawn on the screen and the map). */
function layoutProblems(p) {
  return p.evaluate(() => {
    const problems = [];
    const vw = document.documentElement.clientWidth;
    const sw = document.documentElement.scrollWidth;
    if (sw > vw + 0.5) problems.push(`the page is ${sw} px wide in a window of ${vw}`);
    const visible = (el) => el.getClientRects().length > 0 && getComputedStyle(el).visibility !== 'hidden';
    const name = (el) => `${el.tagName.toLowerCase()}${el.id ? `#${el.id}` : ''}${el.getAttribute('name') ? `[name=${el.getAttribute('name')}]` : ''}${el.dataset.measure ? `[data-measure=${el.dataset.measure}]` : ''}`;
    const meets = (a, b, slack) => a.left + slack < b.right && b.left + slack < a.right && a.top + slack < b.bottom && b.top + slack < a.bottom;
    const panels = [...document.querySelectorAll('.panel')];
    for (const panel of panels) {
      const pr = panel.getBoundingClientRect();
      if (pr.left < -0.5 || pr.right > vw + 0.5) problems.push(`#${panel.id} reaches ${pr.left.toFixed(0)}..${pr.right.toFixed(0)} in ${vw}`);
      for (const el of panel.querySelectorAll('*')) {
        if (!visible(el)) continue;
        const r = el.getBoundingClientRect();
        if (r.width === 0 && r.height === 0) continue;
        const out = Math.max(r.right - pr.right, pr.left - r.left);
        if (out > 0.5) problems.push(`#${panel.id}: ${name(el)} sticks out of its panel by ${out.toFixed(1)} px`);
      }
    }
    for (let i = 0; i < panels.length; i++) {
      for (let j = i + 1; j < panels.length; j++) {
        if (meets(panels[i].getBoundingClientRect(), panels[j].getBoundingClientRect(), 0.5)) problems.push(`#${panels[i].id} and #${panels[j].id} overlap`);
      }
    }
    const texts = [];
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    while (walker.nextNode()) {
      const node = walker.currentNode;
      if (!node.textContent.trim() || !visible(node.parentElement) || node.parentElement.closest('select, option, script, style')) continue;
      const range = document.createRange();
      range.selectNodeContents(node);
      for (const r of range.getClientRects()) if (r.width > 1 && r.height > 1) texts.push({ r, node, text: node.textContent.trim().slice(0, 40) });
    }
    for (let i = 0; i < texts.length; i++) {
      for (let j = i + 1; j < texts.length; j++) {
        if (texts[i].node !== texts[j].node && meets(texts[i].r, texts[j].r, 1.5)) problems.push(`text '${texts[i].text}' overlaps '${texts[j].text}'`);
      }
    }
    for (const [where, list] of [['screen', window.stickslipLab.screenText || []], ['map', window.stickslipLab.mapText || []]]) {
      for (let i = 0; i < list.length; i++) {
        for (let j = i + 1; j < list.length; j++) {
          if (meets(list[i], list[j], 0.5)) problems.push(`${where}: '${list[i].text}' overlaps '${list[j].text}'`);
        }
      }
    }
    return problems;
  });
}

/** The page at `width` × `height`, laid out and drawn again. */
async function resize(p, width, height) {
  await p.setViewportSize({ width, height });
  await p.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
}

/** Keep a picture of the page (LAB_SCREENSHOTS=dir: for people to look at). */
async function picture(p, name) {
  if (process.env.LAB_SCREENSHOTS) await p.screenshot({ path: join(process.env.LAB_SCREENSHOTS, `${name}.png`), fullPage: true });
}

test('issue 38 (1): at 1280 × 720, 1366 × 768, 800 × 900 and 390 × 844, and at every width from 360 px, nothing sticks out or overlaps', async () => {
  const own = await startBrowser({ width: 1280, height: 720 });
  try {
    const p = own.page;
    await p.goto(lab.url);
    await ready(p);
    await mapReady(p);
    for (const [width, height] of [[1280, 720], [1366, 768], [800, 900], [390, 844]]) {
      await resize(p, width, height);
      for (const preset of ['fig3-2b', 'fig3-1a', 'fig3-1c']) {
        await p.selectOption('select[name="preset-choice"]', preset);
        await ready(p);
        for (const mode of ['yt', 'xy', 'fft']) {
          await p.check(`input[name="mode"][value="${mode}"]`);
          assert.deepEqual(await layoutProblems(p), [], `${width} × ${height}, ${preset}, ${mode}`);
          if (preset !== 'fig3-1c') await picture(p, `lab-${width}x${height}-${preset}-${mode}`);
        }
        await p.check('input[name="mode"][value="yt"]');
      }
      // The FFT of the current and the mechanical twin's labels.
      await p.check('input[name="mode"][value="fft"]');
      await p.selectOption('select[name="fft-source"]', 'ch3');
      assert.deepEqual(await layoutProblems(p), [], `${width} × ${height}, FFT of CH3`);
      await p.selectOption('select[name="fft-source"]', 'ch2');
      await p.check('input[name="mode"][value="yt"]');
      // On a phone the panels stand in one column: the generator, the scope, the readouts,
      // the circuit, the sweep and map, the periodic orbit.
      if (width < 700) {
        const boxes = await p.$$eval('.panel', (els) => els.map((e) => ({ id: e.id, left: e.getBoundingClientRect().left, top: e.getBoundingClientRect().top })));
        assert.ok(boxes.every((b) => Math.abs(b.left - boxes[0].left) < 0.5), JSON.stringify(boxes));
        assert.deepEqual([...boxes].sort((a, b) => a.top - b.top).map((b) => b.id), ['generator', 'scope', 'measurements', 'circuit', 'sweep', 'orbit']);
      }
    }
    // Every width from 360 px up, across each layout's edges.
    await p.selectOption('select[name="preset-choice"]', 'fig3-2b');
    await ready(p);
    for (const width of [360, 375, 390, 414, 480, 540, 600, 650, 699, 700, 720, 768, 800, 850, 900, 960, 1024, 1100, 1159, 1160, 1200, 1280, 1300, 1366, 1367, 1440, 1600, 1920]) {
      await resize(p, width, 900);
      assert.deepEqual(await layoutProblems(p), [], `${width} px`);
    }
  } finally {
    await own.close();
  }
});

test('issue 38 (2): the generator is an instrument: a preset sets it once, a part never moves it, w and β follow', async () => {
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  const presets = await page.evaluate(async () => (await fetch('/api/presets')).json());
  const drive = presets.presets.find((x) => x.id === 'fig3-2b').drive;
  assert.equal(drive.unit, 'V');
  const generator = () => page.evaluate(() => ({
    freq: document.querySelector('input[name="freq"]').value,
    amplitude: document.querySelector('input[name="amplitude"]').value,
    w: Number(document.querySelector('[data-derived="w"]').textContent),
    beta: Number(document.querySelector('[data-derived="beta"]').textContent),
  }));
  const query = async () => new URLSearchParams(await shownQuery());
  assert.deepEqual(await generator(), { freq: '9969.65', amplitude: '1.498', w: 0.95, beta: 2.14 });
  // The issue's first example: L from 11.5 mH to 5 mH leaves the generator at 9969.65 Hz
  // and 1.498 V (the preset's, to the bit); w follows the parts (the CLI's w for them).
  const parts = { inductance: '11.5m', capacitance: '20n', resistance: '68', ut: '0.7', rd: '3' };
  const flags = () => [...Object.entries(parts).flatMap(([k, v]) => [`--${k}`, v]), '--freq', String(drive.f_Hz), '--amplitude', String(drive.amplitude)];
  parts.inductance = '5m';
  await type('inductance', '5m');
  let q = await query();
  assert.equal(q.get('freq'), String(drive.f_Hz));
  assert.equal(q.get('amplitude'), String(drive.amplitude));
  assert.equal(q.get('w'), null);
  let g = await generator();
  assert.deepEqual([g.freq, g.amplitude], ['9969.65', '1.498']);
  let cli = await readoutsMatch(flags());
  assert.ok(Math.abs(g.w / cli.w - 1) < 1e-5 && Math.abs(g.w / 0.95 - Math.sqrt(5 / 11.5)) < 1e-5, `w ${g.w}, CLI ${cli.w}`);
  // The second: U_t from 0.7 V to 0.6 V leaves 1.498 V; β = 1.498/0.6 follows.
  parts.ut = '0.6';
  await type('ut', '0.6');
  g = await generator();
  assert.deepEqual([g.freq, g.amplitude], ['9969.65', '1.498']);
  cli = await readoutsMatch(flags());
  assert.ok(Math.abs(g.beta - drive.amplitude / 0.6) < 1e-5 * g.beta, `β ${g.beta}`);
  // The same whatever came before: a knob touched first, then a part changed: the knob's
  // setting stays.
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  await page.$eval('input[name="amplitude-knob"]', (k) => {
    k.value = String(Number(k.value) + 20);
    k.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await ready();
  const touched = await generator();
  await type('inductance', '5m');
  g = await generator();
  assert.deepEqual([g.freq, g.amplitude], [touched.freq, touched.amplitude]);
  q = await query();
  assert.equal(q.get('amplitude'), touched.amplitude);
  // Another diode law is another part: the generator stays too.
  await page.selectOption('select[name="system"]', 'shockley');
  await ready();
  g = await generator();
  assert.deepEqual([g.freq, g.amplitude], [touched.freq, touched.amplitude]);
  // The mechanical twin's preset sets its own drive, in N.
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  const mech = presets.presets.find((x) => x.id === 'mechanics').drive;
  assert.equal(mech.unit, 'N');
  g = await generator();
  assert.deepEqual([Number(g.freq), Number(g.amplitude), g.w, g.beta], [Number(mech.f_Hz.toPrecision(6)), Number(mech.amplitude.toPrecision(6)), 0.95, 2.14]);
  await type('mass', '0.8');
  g = await generator();
  assert.deepEqual([Number(g.freq), Number(g.amplitude)], [Number(mech.f_Hz.toPrecision(6)), Number(mech.amplitude.toPrecision(6))]);
  assert.ok(Math.abs(g.w - 0.95 * Math.sqrt(0.8 / 0.5)) < 1e-5, `w ${g.w}`);
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  assert.equal(await shownQuery(), 'preset=paper&w=0.95&beta=2.14');
});

test('issue 38 (3): "static" is the library\'s rule, stated with G beside it; the FFT says its unit, fills its span, and its labels never meet; mechanics has its own titles', async () => {
  const keys = await page.evaluate(async () => (await fetch('/api/keys')).json());
  assert.equal(keys.static_gain, 0.01);
  await page.selectOption('select[name="preset-choice"]', 'fig3-1c');
  await ready();
  const cli = cliSteady(['--preset', 'paper', '--w', '1.43', '--beta', '1.07']);
  assert.equal(cli.class, 'static');
  assert.ok(cli.gain <= keys.static_gain && cli.stops_per_period === 2, JSON.stringify(cli));
  assert.equal(await readout('class'), 'static');
  const g2 = Number(cli.gain.toPrecision(2));
  assert.equal(await page.$eval('[data-note="class"]', (e) => e.textContent), `G = ${g2} ≤ 0.01: the swing (max − min)/2 is at most 1 % of β`);
  const rule = await page.$eval('[data-measure="class"]', (e) => e.parentElement.querySelector('th').title);
  assert.match(rule, /static: the gain G = \(max − min\)\/2β is at most 0\.01/);
  assert.doesNotMatch(rule, /peak-to-peak/);
  const screenText = () => page.evaluate(() => window.stickslipLab.screenText.map((b) => b.text));
  assert.ok((await screenText()).includes(`static, period 1 (G = ${g2} ≤ 0.01, 2 stops/period)`), (await screenText()).join(' | '));
  // Copy measurements carries the rule.
  await page.click('[data-action="copy-measurements"]');
  assert.match(await page.evaluate(() => window.stickslipLab.lastCopied), /\nclass rule\tG = /);
  // A sliding point has no such line.
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  assert.equal(await page.$eval('[data-note="class"]', (e) => e.textContent), '');
  // The FFT: of CH3 in dBA everywhere (axis and footer), of CH2 in dBV; the bars reach the
  // last division at every Fig. 3 point; no label covers another.
  await page.check('input[name="mode"][value="fft"]');
  for (const [source, unit, other] of [['ch3', 'dBA', 'dBV'], ['ch2', 'dBV', 'dBA']]) {
    await page.selectOption('select[name="fft-source"]', source);
    const text = (await screenText()).join(' | ');
    assert.ok(text.includes(unit) && !text.includes(other), text);
  }
  for (const id of ['fig3-1a', 'fig3-1b', 'fig3-1c', 'fig3-2a', 'fig3-2b', 'fig3-2c']) {
    await page.selectOption('select[name="preset-choice"]', id);
    await ready();
    const ax = await page.evaluate(() => {
      const a = window.stickslipLab.fftAxes();
      return { hzdiv: a.hzdiv, last: a.bars.at(-1).f, count: a.bars.length, computed: window.stickslipLab.state.steady.harmonics.length };
    });
    assert.ok(ax.last > 9 * ax.hzdiv && ax.last <= 10 * ax.hzdiv, `${id}: the last bar at ${ax.last} Hz of ${10 * ax.hzdiv}`);
    assert.ok(ax.computed >= ax.count && ax.computed <= 256, `${id}: ${ax.computed} harmonics computed`);
    assert.deepEqual(await layoutProblems(page), [], id);
  }
  await page.check('input[name="mode"][value="yt"]');
  // The mechanical twin: a drive force and a mass on a spring, not a generator and a circuit.
  const titles = () => page.evaluate(() => [document.querySelector('#generator-title').textContent, document.querySelector('#circuit-title').textContent]);
  assert.deepEqual(await titles(), ['Function generator', 'Circuit']);
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  assert.deepEqual(await titles(), ['Drive force', 'Mass, spring and friction']);
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  assert.deepEqual(await titles(), ['Function generator', 'Circuit']);
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
});

test('issue 38 (4): 1e17 in a scope position neither freezes nor crashes the page; a server that stopped is named', async () => {
  for (const name of ['hpos', 'ch1-pos', 'ch2-pos', 'ch3-pos']) {
    for (const text of ['1e17', '-1e300', '1e15']) {
      await page.fill(`input[name="${name}"]`, text);
      // The page answers (a frozen page never would) and says the value is out of range.
      const state = await page.$eval(`input[name="${name}"]`, (e) => [e.getAttribute('aria-invalid'), e.title]);
      assert.equal(state[0], 'true', `${name} = ${text}`);
      assert.match(state[1], /^from -\d+ to \d+ divisions$/);
    }
    // The export of the screen is its window's samples, not a thousand windows'.
    const csv = parseCsv((await exportFile('export-csv')).bytes.toString());
    assert.ok(csv.rows.length > 100 && csv.rows.length < 70000, `${name}: ${csv.rows.length} rows`);
    await page.fill(`input[name="${name}"]`, '0');
    assert.equal(await page.getAttribute(`input[name="${name}"]`, 'aria-invalid'), null);
  }
  // The transient from rest with the position far out: the simulation asked for stays
  // within the lab's caps.
  await page.fill('input[name="hpos"]', '1e17');
  await page.selectOption('select[name="trigger"]', 'transient');
  await ready();
  await page.selectOption('select[name="trigger"]', 'steady');
  await ready();
  await page.fill('input[name="hpos"]', '0');
  // The lab's server stops: the page says so in words, not the browser's "Failed to fetch".
  const lone = await startLab();
  const own = await startBrowser();
  try {
    const p = own.page;
    await p.goto(lone.url);
    await ready(p);
    await mapReady(p);
    await lone.stop();
    await p.locator('input[name="freq"]').fill('9k');
    await p.locator('input[name="freq"]').press('Enter');
    await p.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'error', null, { timeout: PATIENCE });
    const status = await p.$eval('#status', (e) => e.textContent);
    assert.match(status, /^the lab's server is not answering: is stickslip lab still running/);
    await p.click('[data-action="sweep"]');
    await p.waitForFunction(() => document.querySelector('[data-sweep="status"]').dataset.state === 'error', null, { timeout: PATIENCE });
    assert.match(await p.$eval('[data-sweep="status"]', (e) => e.textContent), /the lab's server is not answering/);
    assert.doesNotMatch(await p.$eval('body', (e) => e.innerText), /Failed to fetch/);
  } finally {
    await own.close();
    await lone.stop();
  }
});

test('issue 38 (3, 4): Fit ticks the default free set of the diode law, absurd values mark their own field, a decimal comma is read', async () => {
  const keys = await page.evaluate(async () => (await fetch('/api/keys')).json());
  // The boxes shown and ticked in each diode law's mode: the library's parameters of the law
  // and its default free set (Shockley: R, I_s and n; U_t's box is not shown there).
  const boxes = () =>
    page.$$eval('label[data-fit-laws]', (labels) =>
      labels.filter((l) => !l.hidden && !l.closest('fieldset').hidden).map((l) => {
        const box = l.querySelector('input[data-free]');
        return { free: box.dataset.free, checked: box.checked };
      }),
    );
  for (const law of ['shockley', 'pwl']) {
    await page.selectOption('select[name="system"]', law);
    await ready();
    const shown = await boxes();
    assert.deepEqual(shown.map((b) => b.free).sort(), [...keys.fit.by_law[law]].filter((f) => f !== 'mu-s').sort(), law);
    assert.deepEqual(shown.filter((b) => b.checked).map((b) => b.free).sort(), [...keys.fit.free[law]].sort(), law);
  }
  assert.deepEqual(keys.fit.free.shockley, ['resistance', 'diode-is', 'diode-n']);

  // An absurd part is blamed on itself: C = 1e308 (was blamed on R), C = 1e-308 (was blamed
  // on the frequency), L = 1e308 (marked no field).
  expectedConsole = /status of 400/;
  for (const [name, text] of [['capacitance', '1e308'], ['capacitance', '1e-308'], ['inductance', '1e308']]) {
    const before = await page.inputValue(`input[name="${name}"]`);
    await page.locator(`input[name="${name}"]`).fill(text);
    await page.locator(`input[name="${name}"]`).press('Enter');
    await page.waitForFunction((n) => document.querySelector(`[data-error-for~="${n}"]`).textContent !== '', name, { timeout: PATIENCE });
    assert.match(await page.$eval(`[data-error-for~="${name}"]`, (e) => e.textContent), new RegExp(`^invalid ${name} ${text}: `));
    assert.equal(await page.getAttribute(`input[name="${name}"]`, 'aria-invalid'), 'true', name);
    for (const other of ['resistance', 'freq']) assert.equal(await page.$eval(`[data-error-for~="${other}"]`, (e) => e.textContent), '', `${name} ${text} blamed ${other}`);
    await type(name, before);
  }
  // The mechanical oscillator's k and γ at 1e308 (marked no field).
  await page.selectOption('select[name="system"]', 'mechanics');
  await ready();
  for (const name of ['stiffness', 'damping']) {
    const before = await page.inputValue(`input[name="${name}"]`);
    await page.locator(`input[name="${name}"]`).fill('1e308');
    await page.locator(`input[name="${name}"]`).press('Enter');
    await page.waitForFunction((n) => document.querySelector(`[data-error-for~="${n}"]`).textContent !== '', name, { timeout: PATIENCE });
    assert.match(await page.$eval(`[data-error-for~="${name}"]`, (e) => e.textContent), new RegExp(`^invalid ${name} 1e308: `));
    assert.equal(await page.getAttribute(`input[name="${name}"]`, 'aria-invalid'), 'true', name);
    await type(name, before);
  }
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  // A map whose β-max is below its β-min marks β-max (it marked β-min).
  await page.fill('input[name="map-beta-max"]', '0');
  await page.click('[data-action="map"]');
  await page.waitForFunction(() => document.querySelector('input[name="map-beta-max"]').getAttribute('aria-invalid') === 'true', null, { timeout: PATIENCE });
  assert.equal(await page.getAttribute('input[name="map-beta-min"]', 'aria-invalid'), null);
  assert.match(await page.$eval('[data-error-for~="beta-max"]', (e) => e.textContent), /invalid beta-max 0: must not be below beta-min 0\.5/);
  await page.fill('input[name="map-beta-max"]', '4');
  // A sweep of 0 steps is told the lab's cap (it said 1 to 100000).
  await page.fill('input[name="sweep-steps"]', '0');
  await page.click('[data-action="sweep"]');
  await page.waitForFunction(() => document.querySelector('input[name="sweep-steps"]').getAttribute('aria-invalid') === 'true', null, { timeout: PATIENCE });
  assert.match(await page.$eval('[data-error-for~="steps"]', (e) => e.textContent), /invalid steps 0: must be from 1 to 400/);
  await page.fill('input[name="sweep-steps"]', '60');
  expectedConsole = null;
  // "9,97k": a decimal comma, read as the point would be.
  await type('freq', '9,97k');
  await type('amplitude', '0,749');
  assert.equal(await page.$eval('[data-error-for~="freq"]', (e) => e.textContent), '');
  await readoutsMatch(['--preset', 'paper', '--freq', '9.97k', '--amplitude', '0.749']);
  await type('freq', '9.97k');
  await type('amplitude', '0.749');
});

/** The command line's flags for a query of the page (its keys are the flags without dashes). */
function flagsOf(query) {
  return [...new URLSearchParams(query)].flatMap(([key, value]) => [`--${key}`, value]);
}

/** Wait until the orbit panel shows the answer for the shown query; its state. */
async function orbitShown() {
  await page.waitForFunction(
    () => {
      const panel = document.querySelector('#orbit');
      return ['ready', 'none', 'error'].includes(panel.dataset.state) && panel.dataset.query === document.querySelector('#status').dataset.query;
    },
    null,
    { timeout: PATIENCE },
  );
  return page.$eval('#orbit', (e) => e.dataset.state);
}

test('issue 34: the orbit panel shows the Floquet multipliers of stickslip orbit at the Fig. 3 point, for both diode laws', async () => {
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  for (const law of ['pwl', 'shockley']) {
    await page.selectOption('select[name="system"]', law);
    await ready();
    assert.equal(await orbitShown(), 'ready', law);
    const query = await shownQuery();
    // The same point on the command line: every key of the query as its flag (the preset's
    // generator setting, 9969.65 Hz and 1.498 V: w = 0.95, β = 2.14).
    const cli = JSON.parse(stickslip(['orbit', ...flagsOf(query), '--json']));
    assert.ok(Math.abs(cli.w - 0.95) < 1e-9 && Math.abs(cli.beta - 2.14) < 1e-9, `${query}: w ${cli.w}, β ${cli.beta}`);
    const shown = await page.$$eval('#orbit [data-orbit]', (els) =>
      Object.fromEntries(els.map((e) => [e.dataset.orbit, { text: e.textContent.trim(), ...e.dataset }])),
    );
    for (const k of [0, 1]) {
      const mu = cli.multipliers[k];
      const cell = shown[`mu${k + 1}`];
      // In full, as the CLI prints them, and as a person reads them (6 digits).
      assert.equal(Number(cell.re), mu.re, `${law} μ${k + 1} re`);
      assert.equal(Number(cell.im), mu.im, `${law} μ${k + 1} im`);
      assert.equal(Number(shown[`mu${k + 1}-modulus`].value), cli.moduli[k], `${law} |μ${k + 1}|`);
      assert.equal(Number(shown[`mu${k + 1}-argument`].value), Math.atan2(mu.im, mu.re), `${law} arg μ${k + 1}`);
      sameTo4Digits(shown[`mu${k + 1}-modulus`].text, cli.moduli[k], `${law} |μ${k + 1}| shown`);
      assert.match(cell.text, /^0\.\d+ [+−] 0\.\d+i$/, `${law} μ${k + 1} shown`);
      sameTo4Digits(cell.text.split(' ')[0], mu.re, `${law} Re μ${k + 1} shown`);
    }
    // The Fig. 3 (2b) orbit slides: a stable complex pair inside the unit circle.
    assert.ok(cli.multipliers[0].im > 0 && cli.moduli[0] < 1, JSON.stringify(cli.multipliers));
    assert.equal(Number(shown.lambda1.value), cli.lambda1, `${law} λ1`);
    assert.equal(Number(shown.y.value), cli.y, `${law} y`);
    assert.equal(Number(shown.v.value), cli.v, `${law} y'`);
    assert.equal(shown.stability.text, cli.stability);
    assert.equal(shown.stops.text, String(cli.stops_per_period));
    assert.equal(shown.period.text, `${cli.period} T`);
    assert.match(shown.converged.text, new RegExp(`^yes, in ${cli.iterations} Newton step`));
    assert.match(await page.$eval('[data-orbit="status"]', (e) => e.textContent), law === 'shockley' ? /Shockley/ : /exact/);
    // Both multipliers drawn in the complex plane.
    assert.equal(await page.$eval('#orbit-plot', (e) => e.dataset.multipliers), '2');
  }
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await orbitShown();
});

test('issue 36: the orbit panel shows a belt without a drive: its self-excited cycle, its multipliers and the cycle in the phase plane', async () => {
  await page.selectOption('select[name="preset-choice"]', 'belt-stribeck');
  await ready();
  assert.equal(await orbitShown(), 'ready');
  const query = await shownQuery();
  const cli = JSON.parse(stickslip(['orbit', ...flagsOf(query), '--json']));
  assert.equal(cli.class, 'stick-slip-cycle');
  const shown = await page.$$eval('#orbit [data-orbit]', (els) =>
    Object.fromEntries(els.map((e) => [e.dataset.orbit, { text: e.textContent.trim(), ...e.dataset }])),
  );
  // The period in full as the CLI prints it, its own (no drive).
  assert.equal(Number(shown.period.value), cli.cycle_period_tau);
  assert.match(shown.period.text, /τ = .* s \(its own: no drive\)$/);
  for (const k of [0, 1]) {
    assert.equal(Number(shown[`mu${k + 1}`].re), cli.multipliers[k].re, `μ${k + 1} re`);
    assert.equal(Number(shown[`mu${k + 1}`].im), cli.multipliers[k].im, `μ${k + 1} im`);
  }
  assert.deepEqual([shown.mu1.text, shown.mu2.text], ['1', '0']);
  assert.equal(shown.stability.text, cli.stability);
  assert.equal(Number(shown.y.value), cli.y_max);
  assert.match(await page.$eval('[data-orbit="status"]', (e) => e.textContent), /^self-excited cycle, period /);
  // Both multipliers in the complex plane, and the cycle in the phase plane.
  assert.equal(await page.$eval('#orbit-plot', (e) => e.dataset.multipliers), '2');
  const cycle = page.locator('#orbit-cycle');
  assert.equal(await cycle.isVisible(), true);
  assert.equal(await cycle.getAttribute('data-samples'), '256');
  // Back to the paper's circuit: the phase plane goes away.
  await page.selectOption('select[name="preset-choice"]', 'fig3-2b');
  await ready();
  assert.equal(await orbitShown(), 'ready');
  assert.equal(await cycle.isVisible(), false);
});

test('no console errors', () => {
  assert.deepEqual(consoleErrors, []);
});

// End-to-end tests of `stickslip lab` in headless Chromium: the real server on a free port,
// the real page, and the command-line tool as the reference for every number.
//
// Run: npm test (from this folder), after `cargo build --release -p stickslip-cli`;
// scripts/test runs it. Set LAB_LATENCY_OUT=file.json to keep the slider latencies.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { requireTools, startLab, startBrowser, stickslip } from './harness.mjs';

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

/** Wait until the page shows the answer to its latest input. */
async function ready(timeout = 30000) {
  await page.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'ready', null, { timeout });
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

/** The four hooked readouts against `stickslip steady --json` (A1, A3 in volts: U_t = 0.7 V). */
async function readoutsMatch(flags) {
  const cli = cliSteady(flags);
  const ut = 0.7;
  assert.equal(await readout('class'), cli.class, `class for ${flags.join(' ')}`);
  sameTo4Digits(await readout('gain'), cli.gain, `gain for ${flags.join(' ')}`);
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

test('sweep up and down and the (w, beta) map, computed on load', async () => {
  await page.waitForFunction(() => document.querySelector('[data-map="status"]').dataset.state === 'ready', null, { timeout: 60000 });
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
  await page.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'error');
  const message = await page.$eval('[data-error-for~="freq"]', (e) => e.textContent);
  assert.match(message, /invalid value for freq: 'ten kHz' is not a number/);
  assert.equal(await page.getAttribute('input[name="freq"]', 'aria-invalid'), 'true');
  await page.locator('input[name="resistance"]').fill('-5');
  await page.locator('input[name="resistance"]').press('Enter');
  await page.waitForFunction(() => document.querySelector('[data-error-for~="resistance"]').textContent !== '');
  assert.match(await page.$eval('[data-error-for~="resistance"]', (e) => e.textContent), /invalid resistance -5: must be finite and >= 0/);
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

  // FFT: the library's harmonics of u_C, in volts and dB, labelled 1Ω, 3Ω, ...
  await page.check('input[name="mode"][value="fft"]');
  const fft = await screen();
  assert.notEqual(fft, xy);
  const fftFile = await exportFile('export-csv');
  assert.match(fftFile.name, /^stickslip-lab-fft-.*\.csv$/);
  const fftCsv = parseCsv(fftFile.bytes.toString());
  assert.deepEqual(fftCsv.header, ['harmonic', 'f_Hz', 'amplitude_V', 'level_dBV']);
  assert.equal(fftCsv.rows.length, cli.harmonics.length);
  for (const k of [0, 2, 4]) {
    const [order, f, a, db] = fftCsv.rows[k];
    assert.equal(order, k + 1);
    assert.ok(Math.abs(a - cli.harmonics[k] * 0.7) <= 1e-12 * a, `A${k + 1}`);
    assert.ok(Math.abs(db - 20 * Math.log10(a)) < 1e-9);
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
  const aborted = [];
  const listener = (request) => {
    if (request.url().includes('/api/sweep') && /ABORTED/.test(request.failure()?.errorText || '')) aborted.push(request.url());
  };
  page.on('requestfailed', listener);
  await page.selectOption('select[name="system"]', 'shockley');
  await ready();
  assert.match(await page.$eval('#status', (e) => e.textContent), /Shockley/);
  const flags = ['--preset', 'paper', '--model', 'shockley', '--w', '0.95', '--beta', '2.14'];
  const cli = cliSteady(flags);
  sameTo4Digits(await readout('gain'), cli.gain, 'Shockley gain');

  // A sweep with the stiff solver takes a while: the page shows it, answers meanwhile, and a
  // second press drops the first request.
  await page.fill('input[name="sweep-steps"]', '40');
  await page.click('[data-action="sweep"]');
  const during = await page.$eval('[data-sweep="status"]', (e) => [e.dataset.state, e.textContent]);
  assert.deepEqual(during, ['computing', 'computing…']);
  // The browser reports the dropped request on its own schedule, possibly after the page
  // shows the second sweep: wait for the report itself.
  const dropped = page.waitForEvent('requestfailed', {
    predicate: (request) => request.url().includes('/api/sweep'),
    timeout: 60000,
  });
  await page.fill('input[name="sweep-to"]', '1.9');
  await page.click('[data-action="sweep"]');
  await page.waitForFunction(() => document.querySelector('[data-sweep="status"]').dataset.state === 'ready', null, { timeout: 60000 });
  const first = await dropped;
  assert.match(first.failure()?.errorText || '', /ABORTED/);
  assert.match(first.url(), /to=2&/);
  assert.equal(aborted.length, 1, `aborted sweeps: ${aborted.length}`);
  assert.match(aborted[0], /to=2&/);
  page.off('requestfailed', listener);
  await page.selectOption('select[name="system"]', 'pwl');
  await ready();
  await page.fill('input[name="sweep-to"]', '2');
  await page.fill('input[name="sweep-steps"]', '60');
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

test('no console errors', () => {
  assert.deepEqual(consoleErrors, []);
});

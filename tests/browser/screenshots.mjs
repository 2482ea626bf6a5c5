// Screenshots of the lab for the documentation (docs/images/lab-*.png): the scope in Y-T, X-Y
// and FFT mode at the paper's Fig. 3 point (2a), Ω/ω0 = 0.29, β = 2.14, and the whole page.
//
// Run: npm run screenshots (from this folder), after `cargo build --release -p stickslip-cli`.
import { join } from 'node:path';
import { ROOT, requireTools, startLab, startBrowser } from './harness.mjs';

requireTools();
const images = join(ROOT, 'docs', 'images');
const lab = await startLab();
const browser = await startBrowser({ width: 1500, height: 1000 });
const page = browser.page;
const ready = () => page.waitForFunction(() => document.querySelector('#status').dataset.labStatus === 'ready');
try {
  await page.goto(lab.url);
  await ready();
  await page.waitForFunction(() => document.querySelector('[data-map="status"]').dataset.state === 'ready', null, { timeout: 60000 });
  await page.screenshot({ path: join(images, 'lab-page.png'), fullPage: true });

  await page.selectOption('select[name="preset-choice"]', 'fig3-2a');
  await ready();
  await page.check('input[name="cursors"]');
  await page.fill('input[name="cursor1"]', '1.2');
  await page.fill('input[name="cursor2"]', '3.7');
  await page.dispatchEvent('input[name="cursor2"]', 'change');
  const scope = page.locator('#scope');
  await scope.screenshot({ path: join(images, 'lab-yt.png') });
  await page.uncheck('input[name="cursors"]');
  await page.check('input[name="mode"][value="xy"]');
  await scope.screenshot({ path: join(images, 'lab-xy.png') });
  await page.check('input[name="mode"][value="fft"]');
  await scope.screenshot({ path: join(images, 'lab-fft.png') });
  console.log(`screenshots in ${images}: lab-page.png, lab-yt.png, lab-xy.png, lab-fft.png`);
} finally {
  await browser.close();
  await lab.stop();
}

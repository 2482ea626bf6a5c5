// Shared by the end-to-end test and the screenshot script: start the real `stickslip lab`
// on a free port, and Debian's Chromium (driven by playwright-core) with a fresh profile.
import { spawn, execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
export const BINARY = process.env.STICKSLIP_BIN || join(ROOT, 'target', 'release', 'stickslip');
// The lab with the browser tests' hook (a request held until the next one to its path
// arrives): the example crates/stickslip-cli/examples/lab_hold.rs, which `stickslip lab` has
// no way to become.
export const HOLDING_BINARY = process.env.STICKSLIP_LAB_HOLD || join(ROOT, 'target', 'release', 'examples', 'lab_hold');
/** The lab's time limit in the tests: far longer than any computation of theirs on a loaded
 * machine, so that no answer depends on the load (the limit itself is tested in Rust). */
export const TIME_LIMIT = '600';
/** How long a test waits for the page (a bound on a hang, not on the machine's speed). */
export const PATIENCE = 600000;
export const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
export const CHROMIUM_FLAGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-dev-shm-usage',
  '--disable-background-networking',
];

/** Fail with one line when something the tests need is missing. */
export function requireTools() {
  if (!existsSync(BINARY)) {
    throw new Error(`the stickslip binary is missing at ${BINARY} (build it: cargo build --release -p stickslip-cli)`);
  }
  if (!existsSync(HOLDING_BINARY)) {
    throw new Error(`the lab_hold example is missing at ${HOLDING_BINARY} (build it: cargo build --release -p stickslip-cli --example lab_hold)`);
  }
  if (!existsSync(CHROMIUM)) {
    throw new Error(`Chromium is missing at ${CHROMIUM} (install it: apt-get install -y chromium)`);
  }
}

/** `stickslip <args>` run to the end; its standard output. */
export function stickslip(args) {
  return execFileSync(BINARY, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
}

/** Start `stickslip lab --port 0 --time-limit 600` (or, with `hold: [path, query]`, the
 * lab_hold example holding those requests); resolves to { url, stop() } once it prints its
 * address. */
export function startLab(extra = [], { hold = null } = {}) {
  return new Promise((resolvePromise, reject) => {
    const args = hold ? [...hold, '--time-limit', TIME_LIMIT] : ['lab', '--port', '0', '--time-limit', TIME_LIMIT, ...extra];
    const child = spawn(hold ? HOLDING_BINARY : BINARY, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    const timer = setTimeout(() => {
      child.kill('SIGKILL');
      reject(new Error(`stickslip lab printed no address within ${PATIENCE / 1000} s; stderr: ${err}`));
    }, PATIENCE);
    child.stdout.on('data', (chunk) => {
      out += chunk;
      const match = out.match(/http:\/\/\S+/);
      if (match) {
        clearTimeout(timer);
        resolvePromise({
          url: match[0],
          stderr: () => err,
          stop: () =>
            new Promise((done) => {
              if (child.exitCode !== null) return done(child.exitCode);
              child.once('exit', (code) => done(code));
              child.kill('SIGINT');
              setTimeout(() => child.kill('SIGKILL'), 5000).unref();
            }),
        });
      }
    });
    child.stderr.on('data', (chunk) => {
      err += chunk;
    });
    child.once('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`stickslip lab exited with ${code}: ${err}`));
    });
  });
}

/** Chromium with a fresh profile; resolves to { context, page, close() }. */
export async function startBrowser(viewport = { width: 1500, height: 1100 }, deviceScaleFactor = 1) {
  const { chromium } = await import('playwright-core');
  const profile = mkdtempSync(join(tmpdir(), 'stickslip-lab-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    args: CHROMIUM_FLAGS,
    viewport,
    deviceScaleFactor,
    acceptDownloads: true,
  });
  const page = context.pages()[0] || (await context.newPage());
  return {
    context,
    page,
    close: async () => {
      await context.close();
      rmSync(profile, { recursive: true, force: true });
    },
  };
}

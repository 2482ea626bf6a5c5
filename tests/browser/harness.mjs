// Shared by the end-to-end test and the screenshot script: start the real `stickslip lab`
// on a free port, and Debian's Chromium (driven by playwright-core) with a fresh profile.
import { spawn, execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
export const BINARY = process.env.STICKSLIP_BIN || join(ROOT, 'target', 'release', 'stickslip');
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
  if (!existsSync(CHROMIUM)) {
    throw new Error(`Chromium is missing at ${CHROMIUM} (install it: apt-get install -y chromium)`);
  }
}

/** `stickslip <args>` run to the end; its standard output. */
export function stickslip(args) {
  return execFileSync(BINARY, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
}

/** Start `stickslip lab --port 0`; resolves to { url, stop() } once it prints its address. */
export function startLab(extra = []) {
  return new Promise((resolvePromise, reject) => {
    const child = spawn(BINARY, ['lab', '--port', '0', ...extra], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    const timer = setTimeout(() => {
      child.kill('SIGKILL');
      reject(new Error(`stickslip lab printed no address within 20 s; stderr: ${err}`));
    }, 20000);
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

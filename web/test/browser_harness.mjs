// Shared by the browser tests: `simlab lab` as the web server (the same server a student
// runs), Debian's Chromium driven by playwright-core, and the page's errors collected.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { repoRoot, skipOrFail } from './wasm_harness.mjs';

// Headless Chromium with software WebGL (SwiftShader) and no background traffic.
const kChromiumFlags = ['--headless', '--no-sandbox', '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// playwright-core from web/node_modules; skipped (or failed, with --require yes) when it
// or Chromium (options.chromium) is missing.
export async function loadPlaywright(options) {
  let playwright = null;
  try {
    playwright = await import(path.join(repoRoot, 'web/node_modules/playwright-core/index.mjs'));
  } catch {
    playwright = null;
  }
  if (!playwright || !fs.existsSync(options.chromium)) {
    skipOrFail(`needs ${options.chromium} and web/node_modules (bash tools/install_deps.sh)`, options);
  }
  return playwright;
}

export function launchChromium(playwright, options) {
  return playwright.chromium.launch({ executablePath: options.chromium, args: kChromiumFlags });
}

// Starts `simlab lab LESSON --port 0` (or another subcommand: `args` such as
// ['view', MODEL]); resolves with {url, stop} once it prints its address.
export function startLabServer(simlabExe, lesson, args = ['lab', lesson]) {
  const child = spawn(simlabExe, [...args, '--port', '0'], { cwd: repoRoot });
  return new Promise((resolve, reject) => {
    let output = '';
    const timer = setTimeout(() => reject(new Error(`no URL from simlab lab: ${output}`)), 15000);
    const read = (chunk) => {
      output += chunk;
      const m = /http:\/\/127\.0\.0\.1:\d+\//.exec(output);
      if (!m) return;
      clearTimeout(timer);
      resolve({ url: m[0], stop: () => child.kill() });
    };
    child.stdout.on('data', read);
    child.stderr.on('data', read);
    child.on('exit', (code) => reject(new Error(`simlab lab exited (${code}): ${output}`)));
  });
}

// In the page: what the lab's 3D view shows now, rendered once: how many distinct
// colours (4 bits a channel), the share of pixels unlike the top-left one, and, given a
// world point, the pixel (x, y) it projects to, its colour `at` and whether it is inside
// the picture (through the main camera, or with `inset` through the inset's camera into
// the inset).
export function pictureStats([point = null, inset = false] = []) {
  const lab = window.lab;
  lab.scene.render();
  const canvas = lab.scene.renderer.domElement;
  const copy = document.createElement('canvas');
  copy.width = canvas.width;
  copy.height = canvas.height;
  const context = copy.getContext('2d');
  context.drawImage(canvas, 0, 0);
  const { data } = context.getImageData(0, 0, copy.width, copy.height);
  const colours = new Set();
  let unlike = 0;
  const [br, bg, bb] = [data[0], data[1], data[2]];
  for (let i = 0; i < data.length; i += 4) {
    colours.add((data[i] >> 4) << 8 | (data[i + 1] >> 4) << 4 | data[i + 2] >> 4);
    if (Math.abs(data[i] - br) + Math.abs(data[i + 1] - bg) + Math.abs(data[i + 2] - bb) > 24) unlike++;
  }
  const stats = { colours: colours.size, unlike: unlike / (data.length / 4) };
  if (!point) return stats;
  // (the point through the main camera, or through the inset's camera into its rectangle)
  const camera = inset ? lab.scene.insetCamera : lab.scene.camera;
  const scale = copy.width / (lab.scene.container.clientWidth || copy.width);
  const rect = inset ? lab.scene.insetRect() : { left: 0, top: 0, width: copy.width / scale, height: copy.height / scale };
  const p = camera.position.clone().set(...point).project(camera);
  const x = Math.round(scale * (rect.left + (p.x + 1) / 2 * rect.width));
  const y = Math.round(scale * (rect.top + (1 - p.y) / 2 * rect.height));
  const inside = Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1 && p.z < 1;
  // (and the 7 x 7 pixels round it, as [r, g, b] each, clipped to the picture)
  const x0 = Math.max(0, x - 3), y0 = Math.max(0, y - 3);
  const near = context.getImageData(x0, y0, Math.min(7, copy.width - x0), Math.min(7, copy.height - y0)).data;
  const around = [];
  for (let i = 0; i < near.length; i += 4) around.push([near[i], near[i + 1], near[i + 2]]);
  return { ...stats, at: Array.from(context.getImageData(x, y, 1, 1).data.slice(0, 3)), around, x, y, inside };
}

// The page's uncaught errors and console errors, as they come.
export function collectProblems(page) {
  const problems = [];
  page.on('pageerror', (e) => problems.push(String(e.stack ?? e)));
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`${m.text()} (${m.location().url})`);
  });
  return problems;
}

// Chromium on `simlab lab`'s server (or `simlab view`'s, with args): {browser, url,
// close()} (close ends both).
export async function openLabSession(options, args = undefined) {
  const playwright = await loadPlaywright(options);
  const server = await startLabServer(options.simlab, options.lesson, args);
  let browser = null;
  try {
    browser = await launchChromium(playwright, options);
  } catch (error) {
    server.stop();
    throw error;
  }
  const close = async () => {
    await browser.close();
    server.stop();
  };
  return { browser, url: server.url, close };
}

// The lesson beside the repository (../shared/lesson), the default of every browser test.
export const kDefaultLesson = path.resolve(repoRoot, '../shared/lesson/lesson-2.3-actuators.txt');

// The lab end to end in headless Chromium (Debian's, driven by playwright-core): serves the
// repository on 127.0.0.1, opens web/lab/index.html (lesson 2.3's lab block, verbatim with
// its typographic quotes), and like a student: turns the toggles on, drags the carriage z
// slider to -0.33 and the grip slider to 0 (mouse, then arrow keys for the exact value),
// waits for the grip force readout to reach the grip actuator's forcerange (read from
// model.actuator_forcerange) with both finger readouts equal, then raises z slowly with
// the arrow keys: the cube height readout must rise. Saves screenshots before and after,
// checks the frame rate and real-time factor shown on the page, and finally drives the
// sliders through the page's API with pacing off and compares every readout with the
// same expressions evaluated on `simlab rollout` of the same control sequence.
//
//   node web/test/lab_e2e.mjs --simlab build/simlab [--dist web/dist] [--shots DIR] [--tol 1e-12]
//
// Exits 77 (ctest: skipped) when the WASM build, Chromium or playwright-core is missing.
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { evaluateExpr, parseExpr } from '../lab/expr.mjs';
import {
  nativeRollout, openBuilds, parseOptions, playwrightOrSkip, repoRoot,
} from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  shots: path.join(os.tmpdir(), 'simlab-lab-e2e'),
  tol: '1e-12',
  chromium: '/usr/bin/chromium',
});

// Serves the repository read-only on 127.0.0.1 (web/dist from --dist).
function serve() {
  const types = { '.mjs': 'text/javascript', '.js': 'text/javascript', '.wasm': 'application/wasm',
    '.html': 'text/html', '.css': 'text/css', '.json': 'application/json' };
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
    if (url === '/favicon.ico') {
      res.writeHead(204);
      res.end();
      return;
    }
    const file = url.startsWith('/web/dist/') ? path.join(options.dist, url.slice(10)) : path.join(repoRoot, url);
    const inside = file.startsWith(repoRoot) || file.startsWith(path.resolve(options.dist));
    if (!inside || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'content-type': types[path.extname(file)] ?? 'text/plain; charset=utf-8' });
    res.end(fs.readFileSync(file));
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

function check(condition, message) {
  if (!condition) throw new Error(message);
  console.log(`ok: ${message}`);
}

// The readouts shown on the page: {label: {value, text, error}}.
async function readouts(page) {
  const list = await page.evaluate(() => window.lab.readoutValues());
  return Object.fromEntries(list.map((r) => [r.label, r]));
}

// Drags slider `label` with the mouse to about `value`, then arrow keys to exactly it.
async function dragSlider(page, label, value) {
  const slider = page.getByRole('slider', { name: label });
  const box = await slider.boundingBox();
  const [min, max, step, current] = await slider.evaluate((s) => [s.min, s.max, s.step, s.value].map(Number));
  const x = (v) => box.x + 8 + (box.width - 16) * (v - min) / (max - min);
  await page.mouse.move(x(current), box.y + box.height / 2);
  await page.mouse.down();
  for (let k = 1; k <= 10; k++) await page.mouse.move(x(current + (value - current) * k / 10), box.y + box.height / 2);
  await page.mouse.up();
  for (let guard = 0; guard < 200; guard++) {
    const now = Number(await slider.inputValue());
    if (Math.abs(now - value) < step / 2) break;
    await slider.press(now < value ? 'ArrowRight' : 'ArrowLeft');
  }
  const final = Number(await slider.inputValue());
  check(Math.abs(final - value) < step / 2, `slider "${label}" dragged to ${final}`);
}

// Waits (real time) until `predicate(readouts)` holds, checking `invariant` on the way.
async function waitFor(page, seconds, predicate, invariant = () => {}) {
  const end = Date.now() + 1000 * seconds;
  for (;;) {
    const r = await readouts(page);
    invariant(r);
    if (predicate(r)) return r;
    if (Date.now() > end) return null;
    await page.waitForTimeout(50);
  }
}

// Samples the readouts for `seconds` (real time), the finger readouts equal in each;
// returns how many samples were taken.
async function fingersStayEqual(page, seconds) {
  const end = Date.now() + 1000 * seconds;
  let samples = 0;
  do {
    fingersEqual(await readouts(page));
    samples++;
    await page.waitForTimeout(50);
  } while (Date.now() < end);
  return samples;
}

function fingersEqual(r) {
  if (r['left finger (m)'].text !== r['right finger (m)'].text) {
    throw new Error(`finger readouts differ: ${r['left finger (m)'].text} vs ${r['right finger (m)'].text}`);
  }
}

// The student's session, paced in real time.
async function interactive(page) {
  const gripId = await page.evaluate(() => window.lab.sim.nameToId('actuator', 'gripper/grip'));
  const range = await page.evaluate((id) => Array.from(window.lab.sim.model('actuator_forcerange')).slice(2 * id, 2 * id + 2), gripId);
  check(gripId === 3 && range[0] < range[1], `grip actuator ${gripId} has forcerange [${range}]`);
  for (const box of await page.locator('input[data-toggle]').all()) await box.check();
  await page.waitForTimeout(1000);
  await page.screenshot({ path: path.join(options.shots, 'lab_before.png'), fullPage: true });

  await dragSlider(page, 'ctrl[2]: carriage z target', -0.33);
  await waitFor(page, 1.5, () => false, fingersEqual);  // the carriage comes down
  await dragSlider(page, 'ctrl[3]: grip half-opening', 0);
  // Closing pulls the fingers to lower qpos: the force saturates at the lower bound.
  const bound = range[0];
  const gripped = await waitFor(page, 5, (r) => Math.abs(r['grip force (N)'].value - bound) < 1e-9, fingersEqual);
  check(gripped !== null, `grip force readout reaches the forcerange bound ${bound}: ${gripped?.['grip force (N)'].text} N`);
  const samples = await fingersStayEqual(page, 0.3);
  check(samples > 0, `finger readouts stayed equal while the gripper closed (${samples} samples)`);
  const before = (await readouts(page))['cube z (m)'].value;
  const clock0 = await page.evaluate(() => window.lab.clock());

  // Raise z slowly, 5 mm at a time, from -0.33 to -0.18 (within a few seconds: the
  // model's soft friction lets a held cube creep and drop after about 6 s).
  const z = page.getByRole('slider', { name: 'ctrl[2]: carriage z target' });
  for (let k = 0; k < 30; k++) {
    await z.press('ArrowRight');
    await page.waitForTimeout(40);
    fingersEqual(await readouts(page));
  }
  await page.waitForTimeout(500);
  const after = await readouts(page);
  const clock1 = await page.evaluate(() => window.lab.clock());
  const stats = await page.evaluate(() => window.lab.stats);
  await page.screenshot({ path: path.join(options.shots, 'lab_after.png'), fullPage: true });
  check(after['cube z (m)'].value > before + 0.1,
        `cube height readout rose from ${before.toFixed(4)} to ${after['cube z (m)'].text} m`);
  const rtf = (clock1.time - clock0.time) / ((clock1.wall - clock0.wall) / 1000);
  const shown = await page.locator('.simlab-lab-stats').textContent();
  console.log(`page shows "${shown}"; real-time factor over the raise ${rtf.toFixed(4)} ` +
              `(${(clock1.time - clock0.time).toFixed(3)} s simulated), frame rate ${stats.fps.toFixed(1)} fps, ` +
              `engine ${stats.engineFactor.toFixed(0)}x real time`);
  check(/fps, real-time factor/.test(shown) && rtf >= 0.99 && stats.engineFactor >= 1,
        'the page keeps real time (the engine is faster than real time)');
  await orbit(page);
  await pauseAndReset(page);
  return range;
}

// The pause button stops time; reset goes back to the keyframe with the sliders at their
// initial values.
async function pauseAndReset(page) {
  await page.getByRole('button', { name: 'pause' }).click();
  const t0 = await page.evaluate(() => window.lab.sim.time);
  await page.waitForTimeout(300);
  const t1 = await page.evaluate(() => window.lab.sim.time);
  const samples = await page.evaluate(() => window.lab.plots.map(({ plot }) => plot.columns[0].length));
  await page.waitForTimeout(300);
  const samplesLater = await page.evaluate(() => window.lab.plots.map(({ plot }) => plot.columns[0].length));
  check(samples.join() === samplesLater.join(), `plots hold ${samples} samples while paused`);
  await page.getByRole('button', { name: 'reset' }).click();
  const state = await page.evaluate(() => ({
    time: window.lab.sim.time, qpos: Array.from(window.lab.sim.data('qpos')),
    ctrl: Array.from(window.lab.sim.data('ctrl')),
    sliders: Array.from(document.querySelectorAll('input[type=range]'), (s) => Number(s.value)),
  }));
  const key = await page.evaluate(() => Array.from(window.lab.sim.model('key_qpos') ?? []).slice(0, 12));
  check(t1 === t0 && state.time === 0 && state.sliders.join() === '0.12,0,0.04' &&
        state.ctrl.join() === '0.12,0,0,0.04' && (key.length === 0 || state.qpos.join() === key.join()),
        `pause holds time at ${t0.toFixed(3)} s; reset: time 0, sliders ${state.sliders}, ctrl ${state.ctrl}`);
  await page.getByRole('button', { name: 'play' }).click();
}

// The mouse orbits (dragging up lowers the elevation, as the camera rises) and zooms.
async function orbit(page) {
  const canvas = await page.locator('canvas.simlab-lab-canvas').boundingBox();
  const view0 = await page.evaluate(() => ({ ...window.lab.scene.view }));
  const [cx, cy] = [canvas.x + canvas.width / 2, canvas.y + canvas.height / 2];
  await page.mouse.move(cx, cy + 50);
  await page.mouse.down();
  await page.mouse.move(cx + 30, cy - 50, { steps: 10 });
  await page.mouse.up();
  await page.mouse.wheel(0, -300);
  await page.waitForTimeout(300);
  const view1 = await page.evaluate(() => ({ ...window.lab.scene.view }));
  check(view1.elevation < view0.elevation - 30 && view1.azimuth !== view0.azimuth &&
        view1.distance < view0.distance,
        `mouse orbit and zoom: elevation ${view0.elevation} -> ${view1.elevation.toFixed(1)}, ` +
        `azimuth ${view0.azimuth} -> ${view1.azimuth.toFixed(1)}, distance ${view0.distance} -> ${view1.distance.toFixed(3)}`);
  await page.screenshot({ path: path.join(options.shots, 'lab_orbit.png'), fullPage: true });
}

// The lab driven through its API with pacing off: slider moves at fixed steps. Returns
// the control rows per step and the readouts at checkpoints.
async function deterministic(page) {
  return page.evaluate(() => {
    const lab = window.lab;
    lab.pause();
    lab.reset();
    const rows = [];
    const checkpoints = [];
    const run = (steps) => {
      for (let i = 0; i < steps; i++) {
        rows.push(Array.from(lab.sim.data('ctrl')));
        lab.step(1);
      }
      checkpoints.push({ step: rows.length, readouts: lab.readoutValues().map((r) => r.value) });
    };
    lab.setControl(1, -0.33);
    run(500);
    lab.setControl(2, 0);
    run(500);
    for (let k = 1; k <= 30; k++) {
      lab.setControl(1, -0.33 + 0.01 * k);
      run(40);
    }
    run(200);
    return { rows, checkpoints, exprs: lab.spec.readouts.map((r) => r.expr),
             labels: lab.spec.readouts.map((r) => r.label) };
  });
}

// The API session did what the sliders asked: ctrl rows with z at -0.33 and the grip at
// 0, the grip force saturated once closed, the cube raised by the end.
function checkSliderSession(result, range) {
  const near = (x, y) => Math.abs(x - y) < 1e-12;
  const lowered = result.rows.findIndex((row) => near(row[2], -0.33));
  const closed = result.rows.findIndex((row) => near(row[2], -0.33) && row[3] === 0);
  check(lowered >= 0 && closed > lowered,
        `control rows hold z -0.33 from step ${lowered} and grip 0 from step ${closed}`);
  const readout = (checkpoint, label) => checkpoint.readouts[result.labels.indexOf(label)];
  const grip = result.checkpoints.map((c) => readout(c, 'grip force (N)'));
  const cube = result.checkpoints.map((c) => readout(c, 'cube z (m)'));
  const last = result.checkpoints.length - 1;
  check(Math.abs(grip[1] - range[0]) < 1e-9 && cube[last] > cube[1] + 0.1,
        `checkpoints: grip force ${grip[1]} N at the bound ${range[0]}, cube z ${cube[1].toFixed(4)} -> ` +
        `${cube[last].toFixed(4)} m`);
}

function compareWithNative(result) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'simlab-lab-'));
  const csv = path.join(dir, 'ctrl.csv');
  fs.writeFileSync(csv, result.rows.map((row) => row.map((x) => x.toPrecision(17)).join(',')).join('\n') + '\n');
  const native = nativeRollout(options.simlab, path.join(repoRoot, 'models/gantry_gripper.xml'),
                               { key: 0, ctrl: csv, steps: result.rows.length });
  fs.rmSync(dir, { recursive: true });
  const trees = result.exprs.map(parseExpr);
  let worst = 0;
  for (const { step, readouts: values } of result.checkpoints) {
    const record = native[step];
    const read = (source, name, i) => {
      if (source !== 'data' || !(name in record)) throw new Error(`native rollout has no ${source}.${name}`);
      return record[name][i];
    };
    trees.forEach((tree, k) => {
      const y = evaluateExpr(tree, read);
      worst = Math.max(worst, Math.abs(values[k] - y) / Math.max(1, Math.abs(y)));
    });
  }
  console.log(`readouts at ${result.checkpoints.length} checkpoints (${result.rows.length} steps) vs native ` +
              `simlab rollout: ${worst === 0 ? 'bit-identical' : `worst ${worst.toExponential(2)}`}`);
  check(worst <= Number(options.tol), `browser readouts equal native within ${options.tol}`);
}

// Chromium on a page of the lab served from here; close() ends both.
async function openLabPage(playwright, query = '') {
  const server = await serve();
  const browser = await playwright.chromium.launch({
    executablePath: options.chromium,
    args: ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync'],
  });
  const page = await browser.newPage({ viewport: { width: 900, height: 900 } });
  const problems = [];
  page.on('pageerror', (e) => problems.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') problems.push(m.text()); });
  await page.goto(`http://127.0.0.1:${server.address().port}/web/lab/index.html${query}`);
  const close = async () => {
    await browser.close();
    server.close();
  };
  return { page, problems, close };
}

async function waitForLab(page) {
  await page.waitForFunction(() => window.lab || document.getElementById('error').textContent, null, { timeout: 60000 });
  const error = await page.locator('#error').textContent();
  check(!error, `the lab mounted${error ? `: ${error}` : ''}`);
  check(await page.locator('canvas.simlab-lab-canvas').count() === 1, 'the lab has its 3D view');
}

// Lesson 2.3's lab, verbatim.
async function testLessonLab({ page, problems }) {
  await waitForLab(page);
  const range = await interactive(page);
  const session = await deterministic(page);
  checkSliderSession(session, range);
  compareWithNative(session);
  check(problems.length === 0, `no page errors${problems.length ? `: ${problems.join('; ')}` : ''}`);
}

// web/lab/fixtures/all_geoms.json: every geom type drawn, bad expressions and a bad
// control target shown as errors while the rest keeps running.
async function testAllGeoms({ page, problems }) {
  await waitForLab(page);
  const drawn = await page.evaluate(() => window.lab.scene.geoms.map(({ g }) => g));
  const types = await page.evaluate(() => Array.from(window.lab.sim.model('geom_type')));
  check(drawn.length === types.length && [0, 1, 2, 3, 4, 5, 6, 7].every((t) => types.includes(t)),
        `all ${types.length} geoms drawn (types ${[...new Set(types)].sort()})`);
  for (const box of await page.locator('input[data-toggle]').all()) await box.check();
  await page.waitForTimeout(1500);
  const r = await readouts(page);
  check(/no data array named 'qpoz'/.test(r.unknown.text), `unknown name: "${r.unknown.text}"`);
  check(/model\.body_mass\[99\]: index out of range/.test(r['out of range'].text),
        `index out of range: "${r['out of range'].text}"`);
  check(/column 16: expected a number/.test(r.syntax.text), `syntax error: "${r.syntax.text}"`);
  check(r['slide (m)'].value > 0.01 && r.arithmetic.value === 1,
        `the other readouts keep working: slide ${r['slide (m)'].text}, arithmetic ${r.arithmetic.text}`);
  const bad = page.getByRole('slider', { name: 'bad target' });
  const message = await page.locator('.simlab-lab-control', { has: bad }).locator('.simlab-lab-error').textContent();
  check(await bad.isDisabled() && /ctrl\[7\]: index out of range/.test(message), `bad control target: "${message}"`);
  await page.screenshot({ path: path.join(options.shots, 'lab_all_geoms.png'), fullPage: true });
  check(problems.length === 0, `no page errors${problems.length ? `: ${problems.join('; ')}` : ''}`);
}

async function main() {
  await openBuilds(options);
  const playwright = await playwrightOrSkip(options);
  fs.mkdirSync(options.shots, { recursive: true });
  for (const [query, test] of [['', testLessonLab],
    ['?spec=fixtures/all_geoms.json&base=fixtures/', testAllGeoms]]) {
    const session = await openLabPage(playwright, query);
    try {
      await test(session);
    } finally {
      await session.close();
    }
  }
  console.log(`screenshots in ${options.shots}`);
  console.log('PASS');
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

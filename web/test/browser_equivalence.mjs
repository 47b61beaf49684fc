// The WebAssembly build in headless Chromium (Debian's, driven by playwright-core): the
// page loads web/dist/simlab.mjs over 127.0.0.1, rolls the gantry gripper out from
// keyframe 0 under the lab's slow-lift controls, and its qpos and actuator_force after
// every 500 steps must equal `simlab rollout` (native) bit for bit, within --tol.
// Prints the browser's step time and real-time factor.
//
//   node web/test/browser_equivalence.mjs --simlab build/simlab [--dist web/dist] [--tol 1e-12]
//
// Exits 77 (ctest: skipped) when the WASM build, Chromium or playwright-core is missing.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import {
  kSkip, nativeRollout, openBuilds, parseOptions, repoRoot,
} from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  tol: '1e-12',
  chromium: '/usr/bin/chromium',
});
const kModel = 'models/gantry_gripper.xml';
const kCtrl = 'tests/models/compose/gantry_lab_slow.csv';
const kEvery = 500;

// Serves the repository (read-only) and the dist folder on 127.0.0.1.
function serve() {
  const types = { '.mjs': 'text/javascript', '.wasm': 'application/wasm', '.html': 'text/html' };
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
    const file = url.startsWith('/dist/') ? path.join(options.dist, url.slice(6)) : path.join(repoRoot, url);
    if (url === '/') {
      res.writeHead(200, { 'content-type': 'text/html' });
      res.end('<!doctype html><title>simlab wasm test</title>');
    } else if (!file.startsWith(repoRoot) && !file.startsWith(options.dist) || !fs.existsSync(file)) {
      res.writeHead(404);
      res.end();
    } else {
      res.writeHead(200, { 'content-type': types[path.extname(file)] ?? 'text/plain' });
      res.end(fs.readFileSync(file));
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// Runs in the page: the rollout, records every kEvery steps, the best of three timings.
async function rolloutInPage({ model, ctrl, every }) {
  const { default: createSimlab } = await import('/dist/simlab.mjs');
  const simlab = await createSimlab();
  const text = async (p) => (await fetch(p)).text();
  const folder = model.slice(0, model.lastIndexOf('/') + 1);
  const sim = new simlab.Simulation(model.slice(folder.length), await text('/' + model),
                                    { 'gripper.xml': await text('/' + folder + 'gripper.xml') });
  const rows = (await text('/' + ctrl)).split('\n')
    .filter((l) => l.trim() !== '' && !l.trim().startsWith('#')).map((l) => l.split(',').map(Number));
  let best = Infinity;
  let records = [];
  for (let repeat = 0; repeat < 3; repeat++) {
    records = [];
    sim.resetKeyframe(0);
    sim.forward();
    const t0 = performance.now();
    rows.forEach((row, k) => {
      sim.setData('ctrl', row);
      sim.step();
      if ((k + 1) % every === 0) {
        records.push({ step: k + 1, qpos: Array.from(sim.data('qpos')),
                       actuator_force: Array.from(sim.data('actuator_force')) });
      }
    });
    best = Math.min(best, performance.now() - t0);
  }
  const timestep = sim.option().timestep;
  sim.delete();
  return { records, steps: rows.length, msPerStep: best / rows.length, timestep };
}

async function loadPlaywright() {
  try {
    return await import(path.join(repoRoot, 'web/node_modules/playwright-core/index.mjs'));
  } catch {
    return null;
  }
}

async function main() {
  await openBuilds(options);
  const playwright = await loadPlaywright();
  if (!playwright || !fs.existsSync(options.chromium)) {
    console.log(`SKIPPED: needs ${options.chromium} and web/node_modules (bash tools/install_deps.sh)`);
    process.exit(kSkip);
  }
  const server = await serve();
  const browser = await playwright.chromium.launch({
    executablePath: options.chromium,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = await browser.newPage();
    await page.goto(`http://127.0.0.1:${server.address().port}/`);
    const result = await page.evaluate(rolloutInPage, { model: kModel, ctrl: kCtrl, every: kEvery });
    const native = nativeRollout(options.simlab, path.join(repoRoot, kModel),
                                 { key: 0, ctrl: path.join(repoRoot, kCtrl), steps: result.steps });
    if (result.records.length === 0) throw new Error('the page recorded no checkpoints');
    let worst = 0;
    for (const r of result.records) {
      for (const field of ['qpos', 'actuator_force']) {
        r[field].forEach((x, i) => {
          const y = native[r.step][field][i];
          worst = Math.max(worst, Math.abs(x - y) / Math.max(1, Math.abs(y)));
        });
      }
    }
    const us = 1000 * result.msPerStep;
    console.log(`chromium: ${result.steps} steps of the gantry gripper, ${us.toFixed(2)} us/step ` +
                `(real-time factor ${(result.timestep * 1e6 / us).toFixed(0)}x)`);
    console.log(`qpos and actuator_force at ${result.records.length} checkpoints vs native: ` +
                (worst === 0 ? 'bit-identical' : `worst ${worst.toExponential(2)}`));
    if (!(worst <= Number(options.tol))) throw new Error(`worst difference ${worst} exceeds ${options.tol}`);
    console.log('PASS');
  } finally {
    await browser.close();
    server.close();
  }
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

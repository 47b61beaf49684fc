// The WebAssembly build in headless Chromium (Debian's, driven by playwright-core): a
// page of `simlab lab`'s server loads /dist/simlab.mjs (web/dist), rolls the gantry gripper out from
// keyframe 0 under the lab's slow-lift controls, and its qpos and actuator_force after
// every 500 steps must equal `simlab rollout` (native) bit for bit, within --tol.
// Prints the browser's step time and real-time factor.
//
//   node web/test/browser_equivalence.mjs --simlab build/simlab [--tol 1e-12] [--require yes]
//
// Exits 77 (ctest: skipped) when the WASM build, Chromium or playwright-core is missing
// (with --require yes: fails). The server serves web/dist, so --dist only names what
// the staleness check looks at.
import path from 'node:path';
import { kDefaultLesson, openLabSession } from './browser_harness.mjs';
import {
  nativeRollout, openBuilds, parseOptions, readControls, repoRoot,
} from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  lesson: kDefaultLesson,
  tol: '1e-12',
  chromium: '/usr/bin/chromium',
});
const kModel = 'models/gantry_gripper.xml';
const kCtrl = 'tests/models/compose/gantry_lab_slow.csv';
const kEvery = 500;

// Runs in the page: the rollout, records every kEvery steps, the best of three timings.
async function rolloutInPage({ model, rows, every }) {
  const { default: createSimlab } = await import('/dist/simlab.mjs');
  const simlab = await createSimlab();
  // The model and every file it refers to, found as the lab's loader finds them.
  const { gatherModelFiles } = await import('/lab/model_files.mjs');
  const folder = '/' + model.slice(0, model.lastIndexOf('/') + 1);
  const name = model.slice(folder.length - 1);
  const fetchOk = async (p) => {
    const response = await fetch(folder + p);
    if (!response.ok) throw new Error(`${folder + p}: HTTP ${response.status}`);
    return response;
  };
  const xml = await (await fetchOk(name)).text();
  const files = await gatherModelFiles(name, xml, async (p) => (await fetchOk(p)).text(),
                                       async (p) => new Uint8Array(await (await fetchOk(p)).arrayBuffer()));
  const sim = new simlab.Simulation(name, xml, files);
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

async function main() {
  await openBuilds(options);
  const session = await openLabSession(options);
  try {
    const page = await session.browser.newPage();
    // Any page of the server will do; the plain lesson text loads nothing else.
    await page.goto(`${session.url}lesson.txt`);
    const rows = readControls(path.join(repoRoot, kCtrl));
    const result = await page.evaluate(rolloutInPage, { model: kModel, rows, every: kEvery });
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
    await session.close();
  }
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

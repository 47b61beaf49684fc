// Step speed of the WebAssembly build in node against the native build, on the lab's
// workload: the gantry gripper from keyframe 0 under the slow-lift controls (contacts
// from the grasp on). Prints microseconds per step of each and their ratio.
//
//   node web/test/step_speed.mjs --simlab build/simlab [--dist web/dist] [--repeats 5]
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import {
  openBuilds, openModel, parseOptions, readControls, repoRoot, wasmRollout,
} from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  repeats: '5',
});
const model = path.join(repoRoot, 'models/gantry_gripper.xml');
const ctrlCsv = path.join(repoRoot, 'tests/models/compose/gantry_lab_slow.csv');
const controls = readControls(ctrlCsv);
const steps = controls.length;

// Best of the repeats, in seconds.
function best(repeats, run) {
  let fastest = Infinity;
  for (let r = 0; r < repeats; r++) {
    const t0 = process.hrtime.bigint();
    run();
    fastest = Math.min(fastest, Number(process.hrtime.bigint() - t0) / 1e9);
  }
  return fastest;
}

// Native: a whole rollout that records only its last step, less the same command with
// no steps (loading, compiling, writing).
function nativeSeconds(repeats) {
  const run = (n) => () => {
    const r = spawnSync(options.simlab, ['rollout', model, '--key', '0', '--ctrl', ctrlCsv,
      '--steps', String(n), '--every', String(Math.max(n, 1)), '--out', '/dev/null']);
    if (r.status !== 0) throw new Error(`${options.simlab} rollout failed: ${r.stderr}`);
  };
  return best(repeats, run(steps)) - best(repeats, run(0));
}

async function main() {
  const repeats = Number(options.repeats);
  const simlab = await openBuilds(options);
  const sim = await openModel(simlab, model);
  const wasm = best(repeats, () => wasmRollout(sim, { key: 0, controls, steps, fields: [], record: false }));
  const timestep = sim.option().timestep;
  sim.delete();
  const native = nativeSeconds(repeats);
  const us = (s) => (1e6 * s / steps).toFixed(2);
  console.log(`gantry_gripper slow lift, ${steps} steps, best of ${repeats}:`);
  console.log(`  wasm (node ${process.version}): ${us(wasm)} us/step`);
  console.log(`  native (${path.relative(repoRoot, options.simlab)}): ${us(native)} us/step`);
  console.log(`  wasm / native: ${(wasm / native).toFixed(2)}`);
  console.log(`  real-time factor of wasm alone: ${(timestep * steps / wasm).toFixed(0)}x ` +
              `(timestep ${timestep} s)`);
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

// The WebAssembly build is the same engine: rollouts in web/dist/simlab.mjs equal
// `simlab rollout` (native) of the same inputs, field by field, and the JS API keeps
// its promises (names, keyframes by name, errors as JS exceptions with file:line).
//
//   node web/test/rollout_equivalence.mjs --simlab build/simlab [--dist web/dist]
//        [--tol 1e-12] [--steps 3500]
//
// Exits 77 (ctest: skipped) with the reason when the WASM build is missing or older
// than the engine's sources.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  nativeRollout, openBuilds, openModel, parseOptions, readControls, repoRoot, wasmRollout,
} from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  tol: '1e-12',
  steps: '3500',
});
const tol = Number(options.tol);

// Every array the native rollout records, plus time and ncon.
const kFields = ['qpos', 'qvel', 'qacc', 'act', 'ctrl', 'actuator_force', 'actuator_length',
  'actuator_velocity', 'qfrc_actuator', 'qfrc_passive', 'qfrc_constraint', 'sensordata',
  'ten_length', 'ten_velocity'];

// Worst |wasm - native| / max(1, |native|) per field, and how many numbers differ at all.
function compareRollouts(native, wasm) {
  assert.equal(wasm.length, native.length, 'number of records');
  const report = {};
  for (const name of ['time', 'ncon', ...kFields]) report[name] = { worst: 0, at: -1, differ: 0, count: 0 };
  for (let s = 0; s < native.length; s++) {
    for (const name of Object.keys(report)) {
      const a = [].concat(native[s][name] ?? []);
      const b = Array.from([].concat(wasm[s][name] ?? []).flatMap((x) => (ArrayBuffer.isView(x) ? Array.from(x) : [x])));
      assert.equal(b.length, a.length, `${name} size at step ${s}`);
      const r = report[name];
      for (let i = 0; i < a.length; i++) {
        r.count++;
        if (a[i] === b[i]) continue;
        r.differ++;
        const err = Math.abs(a[i] - b[i]) / Math.max(1, Math.abs(a[i]));
        if (!(err <= r.worst)) { r.worst = err; r.at = s; }
      }
    }
  }
  return report;
}

// One model: both rollouts, the per-field report, and the verdict.
async function checkCase(simlab, name, modelPath, { key, ctrlCsv, steps }) {
  const sim = await openModel(simlab, modelPath);
  try {
    const controls = ctrlCsv ? readControls(ctrlCsv) : null;
    const native = nativeRollout(options.simlab, modelPath, { key, ctrl: ctrlCsv, steps });
    const wasm = wasmRollout(sim, { key, controls, steps, fields: kFields });
    const report = compareRollouts(native, wasm);
    let worst = 0;
    console.log(`${name}: ${steps} steps (nq ${sim.sizes().nq}, nu ${sim.sizes().nu}, ` +
                `nsensordata ${sim.sizes().nsensordata}, last ncon ${native.at(-1).ncon})`);
    for (const [field, r] of Object.entries(report)) {
      if (r.count === 0) continue;
      worst = Math.max(worst, r.worst);
      const where = r.differ ? ` (worst at step ${r.at})` : '';
      console.log(`  ${field.padEnd(18)} ${r.differ ? `${r.differ}/${r.count} differ, worst ${r.worst.toExponential(2)}${where}` : `bit-identical (${r.count} numbers)`}`);
    }
    assert.ok(worst <= tol, `${name}: worst difference ${worst} exceeds ${tol}`);
  } finally {
    sim.delete();
  }
}

// Smooth controls for the actuator bench, written as a CSV both engines read.
function benchControls(nu, steps) {
  const lines = ['# actuator bench controls (rollout_equivalence.mjs)'];
  for (let k = 0; k < steps; k++) {
    const row = [];
    for (let i = 0; i < nu; i++) row.push(String(0.8 * Math.sin(0.004 * (k + 1) * (i + 1) + i)));
    lines.push(row.join(','));
  }
  const file = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'simlab-wasm-')), 'bench.csv');
  fs.writeFileSync(file, lines.join('\n') + '\n');
  return file;
}

// Views by id (no name string crosses into wasm), efc_* views sized by the current rows
// (efc_J nefc x nv), and contactData() holding the same numbers as contacts().
function checkViewsAndContacts(simlab, sim) {
  const id = sim.dataId('qpos');
  assert.equal(sim.dataId('no_such_field'), -1);
  assert.deepEqual(Array.from(sim.dataViewAt(id)), Array.from(sim.data('qpos')));
  assert.throws(() => sim.dataViewAt(-1), /Data array id -1 out of range/);
  sim.setData('ctrl', [0.12, -0.1, -0.33, 0]);
  let { ncon, nefc } = sim.counts();
  for (let k = 0; k < 2000 && ncon === 0; k++) {
    sim.step(10);
    ({ ncon, nefc } = sim.counts());
  }
  assert.ok(ncon > 0, 'the gripper touches something');
  assert.equal(sim.dataView('efc_J').length, nefc * sim.sizes().nv, 'efc_J is nefc x nv');
  assert.equal(sim.dataViewAt(sim.dataId('efc_force')).length, nefc);
  const stride = simlab.contactStride;
  assert.equal(stride, 22);
  const flat = sim.contactData();
  const objects = sim.contacts();
  assert.equal(flat.length, ncon * stride);
  objects.forEach((c, i) => {
    const row = Array.from(flat.subarray(i * stride, (i + 1) * stride));
    assert.deepEqual(row, [...c.pos, ...c.frame, ...c.force, c.geom1, c.geom2, c.dist, c.dim]);
  });
  console.log(`  views by id; efc_J ${nefc} x ${sim.sizes().nv}; contactData ${ncon} x ${stride} = contacts()`);
}

// The API beyond stepping: names, shapes, keyframes by name, views, errors.
async function checkApi(simlab) {
  const models = path.join(repoRoot, 'models');
  const sim = await openModel(simlab, path.join(models, 'gantry_gripper.xml'));
  try {
    assert.equal(sim.nameToId('key', 'home'), 0);
    assert.equal(sim.nameToId('actuator', 'no such actuator'), -1);
    const grip = sim.idToName('actuator', sim.sizes().nu - 1);
    assert.equal(sim.nameToId('actuator', grip), sim.sizes().nu - 1);
    assert.ok(sim.nameToId('body', 'gripper/palm') >= 0, 'attached bodies carry the prefix');
    assert.equal(sim.nameToId('joint', sim.idToName('jnt', 0)), 0, 'mjtObj keyword and field prefix');
    assert.throws(() => sim.nameToId('widget', 'x'), /unknown object kind 'widget'/);
    sim.resetKeyframe('home');
    const keyQpos = sim.model('key_qpos');
    assert.deepEqual(Array.from(sim.data('qpos')), Array.from(keyQpos.slice(0, sim.sizes().nq)));
    assert.deepEqual(sim.dataShape('xpos'), { rows: sim.sizes().nbody, cols: 3, type: 'double' });
    assert.ok(sim.dataNames().includes('efc_force') && sim.modelNames().includes('body_mass'));
    sim.setDataAt('ctrl', 0, 0.25);
    assert.equal(sim.dataView('ctrl')[0], 0.25, 'views see writes');
    assert.throws(() => sim.setDataAt('ctrl', 99, 1), /ctrl\[99\]: index out of range/);
    assert.throws(() => sim.data('no_such_field'), /no Data array named 'no_such_field'/);
    assert.throws(() => sim.resetKeyframe('nope'), /no keyframe named 'nope'/);
    assert.throws(() => sim.setData('ctrl', [1, 2]), /ctrl needs \d+ numbers, got 2/);
    sim.step(5);
    assert.ok(Math.abs(sim.time - 5 * sim.option().timestep) < 1e-15);
    checkViewsAndContacts(simlab, sim);
  } finally {
    sim.delete();
  }
  // A bad file: a JS Error with simlab's file:line: element: problem message.
  const bad = '<mujoco>\n  <worldbody>\n    <geom type="sphere" size="-1"/>\n  </worldbody>\n</mujoco>\n';
  assert.throws(() => new simlab.Simulation('bad.xml', bad), (e) => {
    assert.ok(e instanceof Error);
    assert.match(e.message, /^bad\.xml:3: <geom>: /);
    console.log(`  bad model error: ${e.message}`);
    return true;
  });
  assert.throws(() => new simlab.Simulation('a.xml', '<mujoco><include file="missing.xml"/></mujoco>'),
                /missing\.xml/);
  console.log('api: names, shapes, keyframes by name, views and errors as expected');
}

async function main() {
  const simlab = await openBuilds(options);
  const models = path.join(repoRoot, 'models');
  const steps = Number(options.steps);
  await checkCase(simlab, 'gantry_gripper (lab slow lift)', path.join(models, 'gantry_gripper.xml'), {
    key: 0, steps, ctrlCsv: path.join(repoRoot, 'tests/models/compose/gantry_lab_slow.csv'),
  });
  const benchPath = path.join(models, 'actuator_bench.xml');
  if (fs.existsSync(benchPath)) {
    const bench = await openModel(simlab, benchPath);
    const nu = bench.sizes().nu;
    bench.delete();
    await checkCase(simlab, 'actuator_bench', benchPath, { key: -1, steps: 1000,
              ctrlCsv: benchControls(nu, 1000) });
  }
  await checkApi(simlab);
  console.log('PASS');
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

// Camera poses (cam_xpos, cam_xmat) along a rollout in MuJoCo itself (the oracle): the
// golden of tests/camera_test.cc.
//
//   node tools/dump_cameras.mjs MODEL.xml --key K --steps N --every M [--out OUT.json]
//
// Regenerate (from the repository root):
//   node tools/dump_cameras.mjs tests/compiler_models/cameras.xml --key 0 --steps 400 \
//     --every 50 --out tests/compiler_goldens/cameras_rollout.json
import fs from 'node:fs';

import { loadOracleModel } from './oracle_model.mjs';

// --key K --steps N --every M --out FILE after the model path.
function parseArgs(argv) {
  const opts = { model: argv[0], key: -1, steps: 0, every: 1, out: null };
  for (let i = 1; i < argv.length; i += 2) {
    const name = argv[i].replace(/^--/, '');
    if (!(name in opts)) throw new Error(`unknown option ${argv[i]}`);
    opts[name] = name === 'out' ? argv[i + 1] : Number(argv[i + 1]);
  }
  if (!opts.model) throw new Error('usage: node dump_cameras.mjs MODEL.xml [--key K] [--steps N]');
  return opts;
}

const opts = parseArgs(process.argv.slice(2));
const { mj, model } = await loadOracleModel(opts.model);
const data = new mj.MjData(model);
if (opts.key >= 0) mj.mj_resetDataKeyframe(model, data, opts.key);

// Step 0 after mj_forward, then every M-th step after mj_step.
const out = { engine: `mujoco ${mj.mj_versionString()}`, key: opts.key, records: [] };
const record = (step) => out.records.push({
  step, cam_xpos: Array.from(data.cam_xpos), cam_xmat: Array.from(data.cam_xmat),
});
mj.mj_forward(model, data);
record(0);
for (let step = 1; step <= opts.steps; step++) {
  mj.mj_step(model, data);
  if (step % opts.every === 0) record(step);
}

const text = JSON.stringify(out) + '\n';
if (opts.out) fs.writeFileSync(opts.out, text); else process.stdout.write(text);
data.delete();

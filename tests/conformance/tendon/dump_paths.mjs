// Tendon paths as MuJoCo 3.5.1 computes them, the goldens of tests/spatial_tendon_test.cc.
//
//   node tests/conformance/tendon/dump_paths.mjs    (from the repository root)
//
// For every base/<name>.xml: reset, apply base/<name>.state.json if present, mj_forward,
// record; then 5 times: 100 x mj_step, mj_forward, record. A record holds ten_wrapadr,
// ten_wrapnum, wrap_obj, wrap_xpos, ten_length, ten_J (dense: nv < 60), qM and qfrc_bias.
// Writes paths/<name>.json. MuJoCo comes from ../shared/oracle/node_modules.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const FIELDS = ['qpos', 'qvel', 'ten_wrapadr', 'ten_wrapnum', 'wrap_obj', 'wrap_xpos', 'ten_length',
  'ten_J', 'qM', 'qfrc_bias'];
const here = path.dirname(fileURLToPath(import.meta.url));
const oracle = process.env.SIMLAB_ORACLE || path.join(here, '..', '..', '..', '..', 'shared', 'oracle');
const { default: loadMujoco } = await import(
  pathToFileURL(path.join(oracle, 'node_modules', 'mujoco', 'mujoco.js')).href);
const mj = await loadMujoco();
try { mj.FS.mkdir('/model'); } catch { /* exists */ }
fs.mkdirSync(path.join(here, 'paths'), { recursive: true });

for (const file of fs.readdirSync(path.join(here, 'base')).filter((f) => f.endsWith('.xml'))) {
  const name = path.basename(file, '.xml');
  mj.FS.writeFile(`/model/${file}`, fs.readFileSync(path.join(here, 'base', file)));
  const model = mj.MjModel.mj_loadXML(`/model/${file}`);
  if (model.nv >= 60) throw new Error(`${file}: ten_J would be sparse`);
  const data = new mj.MjData(model);
  const statePath = path.join(here, 'base', `${name}.state.json`);
  if (fs.existsSync(statePath)) {
    for (const [k, v] of Object.entries(JSON.parse(fs.readFileSync(statePath, 'utf8')))) data[k].set(v);
  }
  const records = [];
  const record = () => {
    const r = {};
    for (const f of FIELDS) r[f] = Array.from(data[f], Number);
    records.push(r);
  };
  mj.mj_forward(model, data);
  record();
  for (let k = 0; k < 5; k++) {
    for (let s = 0; s < 100; s++) mj.mj_step(model, data);
    mj.mj_forward(model, data);
    record();
  }
  const out = { engine: `mujoco ${mj.mj_versionString()}`, model: `tests/conformance/tendon/base/${file}`,
    state: fs.existsSync(statePath) ? `tests/conformance/tendon/base/${name}.state.json` : null, records };
  fs.writeFileSync(path.join(here, 'paths', `${name}.json`), JSON.stringify(out) + '\n');
  data.delete();
  model.delete();
}

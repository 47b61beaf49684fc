// Goldens of tests/collision_convex_test.cc: for every keyframe of a model, MuJoCo's
// geom poses after mj_forward and the contacts it found (the fields a narrow-phase
// function sets). The poses let the test run the narrow phase on MuJoCo's own numbers,
// so a last-bit difference in kinematics cannot flip a tolerance-based GJK stop.
//
//   node tests/collision_convex/dump_keys.mjs MODEL.xml OUT.json
//
// MuJoCo comes from the oracle's node_modules: $SIMLAB_ORACLE, else ../shared/oracle
// beside the repository.
import fs from 'node:fs';

import { loadOracleModel } from '../../tools/oracle_model.mjs';

const [modelFile, outFile] = process.argv.slice(2);
if (!modelFile || !outFile) throw new Error('usage: node dump_keys.mjs MODEL.xml OUT.json');
const { mj, model } = await loadOracleModel(modelFile);
const data = new mj.MjData(model);

const keys = [];
for (let k = 0; k < model.nkey; k++) {
  mj.mj_resetDataKeyframe(model, data, k);
  mj.mj_forward(model, data);
  const contact = [];
  for (let i = 0; i < data.ncon; i++) {
    const c = data.contact.get(i);
    contact.push({ dist: c.dist, pos: Array.from(c.pos), normal: Array.from(c.frame).slice(0, 3),
      geom: Array.from(c.geom) });
    c.delete();
  }
  keys.push({ key: k, geom_xpos: Array.from(data.geom_xpos), geom_xmat: Array.from(data.geom_xmat),
    contact });
}
const head = `{"engine": "mujoco ${mj.mj_versionString()}", "keys": [\n`;
fs.writeFileSync(outFile, head + keys.map((k) => JSON.stringify(k)).join(',\n') + '\n]}\n');
data.delete();
model.delete();

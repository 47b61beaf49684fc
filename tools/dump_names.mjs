// Object names by kind (body, joint, geom, site, equality, tendon, actuator, key) from MuJoCo
// itself (the oracle): the name goldens of tests/composition_test.cc (ExpectNames).
//
//   node tools/dump_names.mjs MODEL.xml OUT.json
//
// Regenerate (from the repository root), for example:
//   node tools/dump_names.mjs tests/compiler_models/compose_attach.xml \
//     tests/models/compose/compose_attach.names.json
//
// MuJoCo comes from the oracle's node_modules: $SIMLAB_ORACLE, else ../shared/oracle.
import fs from 'node:fs';

import { loadOracleModel } from './oracle_model.mjs';

const [modelPath, outPath] = process.argv.slice(2);
if (!modelPath || !outPath) throw new Error('usage: node dump_names.mjs MODEL.xml OUT.json');
const { mj, model } = await loadOracleModel(modelPath);
// Kinds as the golden names them, MuJoCo's object types, and their counts.
const KINDS = [['body', 'mjOBJ_BODY', 'nbody'], ['joint', 'mjOBJ_JOINT', 'njnt'], ['geom', 'mjOBJ_GEOM', 'ngeom'],
  ['site', 'mjOBJ_SITE', 'nsite'], ['equality', 'mjOBJ_EQUALITY', 'neq'], ['tendon', 'mjOBJ_TENDON', 'ntendon'],
  ['actuator', 'mjOBJ_ACTUATOR', 'nu'], ['key', 'mjOBJ_KEY', 'nkey']];
const out = { engine: `mujoco ${mj.mj_versionString()}` };
for (const [kind, type, count] of KINDS) {
  out[kind] = [];
  for (let i = 0; i < model[count]; i++) out[kind].push(mj.mj_id2name(model, mj.mjtObj[type].value, i) ?? '');
}
fs.writeFileSync(outPath, JSON.stringify(out) + '\n');

// Dump every array of a compiled mjModel and the names of every named object kind, from
// MuJoCo itself (the oracle), as JSON: the goldens of tests/replicate_test.cc.
//
//   node tools/dump_fields_names.mjs MODEL.xml [OUT.json]
//
// Regenerate the replicate goldens (from the repository root):
//   for f in tests/replicate/*.xml; do
//     node tools/dump_fields_names.mjs $f tests/replicate/goldens/$(basename $f .xml).json; done
import fs from 'node:fs';

import { loadOracleModel } from './oracle_model.mjs';

const [modelPath, outPath] = process.argv.slice(2);
if (!modelPath) throw new Error('usage: node dump_fields_names.mjs MODEL.xml [OUT.json]');
const { mj, model } = await loadOracleModel(modelPath);

// Names by simlab's kind (the prefix of its *_names vectors) and MuJoCo object type.
const KINDS = [['body', 'mjOBJ_BODY', 'nbody'], ['jnt', 'mjOBJ_JOINT', 'njnt'],
  ['geom', 'mjOBJ_GEOM', 'ngeom'], ['site', 'mjOBJ_SITE', 'nsite'],
  ['cam', 'mjOBJ_CAMERA', 'ncam'], ['mesh', 'mjOBJ_MESH', 'nmesh'],
  ['hfield', 'mjOBJ_HFIELD', 'nhfield'], ['light', 'mjOBJ_LIGHT', 'nlight'],
  ['tex', 'mjOBJ_TEXTURE', 'ntex'], ['mat', 'mjOBJ_MATERIAL', 'nmat'], ['pair', 'mjOBJ_PAIR', 'npair'],
  ['exclude', 'mjOBJ_EXCLUDE', 'nexclude'], ['eq', 'mjOBJ_EQUALITY', 'neq'],
  ['tendon', 'mjOBJ_TENDON', 'ntendon'], ['actuator', 'mjOBJ_ACTUATOR', 'nu'],
  ['sensor', 'mjOBJ_SENSOR', 'nsensor'], ['key', 'mjOBJ_KEY', 'nkey']];
const out = { engine: `mujoco ${mj.mj_versionString()}`, names: {}, arrays: {} };
for (const [kind, type, count] of KINDS) {
  out.names[kind] = [];
  for (let i = 0; i < model[count]; i++) {
    out.names[kind].push(mj.mj_id2name(model, mj.mjtObj[type].value, i) ?? '');
  }
}

// Every typed array of the model (the test compares those simlab has).
for (const key of Object.getOwnPropertyNames(Object.getPrototypeOf(model))) {
  let v;
  try { v = model[key]; } catch { continue; }
  if (ArrayBuffer.isView(v)) out.arrays[key] = Array.from(v, Number);
}
const text = JSON.stringify(out);
if (outPath) fs.writeFileSync(outPath, text + '\n'); else process.stdout.write(text + '\n');

// Names of a compiled model's elements, from MuJoCo itself (the oracle), as JSON:
// the golden of tests/composition_test.cc for names given by <attach> prefixes.
//
//   node tests/models/compose/dump_names.mjs MODEL.xml [OUT.json]
//
// MuJoCo comes from the oracle's node_modules: $SIMLAB_ORACLE, else ../shared/oracle
// beside the repository.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

// mjtObj values and the size that counts each kind.
const KINDS = [['body', 1, 'nbody'], ['joint', 3, 'njnt'], ['geom', 5, 'ngeom'],
  ['site', 6, 'nsite'], ['equality', 17, 'neq'], ['tendon', 18, 'ntendon'],
  ['actuator', 19, 'nu'], ['key', 24, 'nkey']];

const [modelPath, outPath] = process.argv.slice(2);
if (!modelPath) throw new Error('usage: node dump_names.mjs MODEL.xml [OUT.json]');
const here = path.dirname(fileURLToPath(import.meta.url));
const oracle = process.env.SIMLAB_ORACLE ||
  path.join(here, '..', '..', '..', '..', 'shared', 'oracle');
const entry = path.join(oracle, 'node_modules', 'mujoco', 'mujoco.js');
const { default: loadMujoco } = await import(pathToFileURL(entry).href);
const mj = await loadMujoco();
try { mj.FS.mkdir('/model'); } catch { /* exists */ }
// The model's folder, recursively, in MuJoCo's virtual file system.
const folder = path.dirname(path.resolve(modelPath));
for (const relative of fs.readdirSync(folder, { recursive: true })) {
  const host = path.join(folder, relative);
  if (fs.statSync(host).isDirectory()) mj.FS.mkdirTree(`/model/${relative}`);
  else mj.FS.writeFile(`/model/${relative}`, fs.readFileSync(host));
}
const model = mj.MjModel.mj_loadXML(`/model/${path.basename(modelPath)}`);

const out = { engine: `mujoco ${mj.mj_versionString()}` };
for (const [kind, type, size] of KINDS) {
  out[kind] = [];
  for (let i = 0; i < model[size]; i++) out[kind].push(mj.mj_id2name(model, type, i) ?? '');
}
const text = JSON.stringify(out, null, 1);
if (outPath) fs.writeFileSync(outPath, text + '\n'); else process.stdout.write(text + '\n');

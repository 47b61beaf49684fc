// Dump MuJoCo's (the oracle's) acceleration-stage quantities on demand at chosen steps:
// cacc, cfrc_int, cfrc_ext (mj_rnePostConstraint), subtree_linvel, subtree_angmom
// (mj_subtreeVel) and energy (mj_energyPos, mj_energyVel). The goldens of
// tests/rne_post_test.cc.
//
//   node tools/dump_rnepost.mjs MODEL.xml [--key K] [--ctrl CTRL.csv] [--at 0,50,200]
//                               [--xfrc BODY:fx,fy,fz,tx,ty,tz] [OUT.json]
//
// Each dump: reset (keyframe K), xfrc_applied set, then mj_step with the control rows
// (row k before step k+1, the last row held) up to the step, then mj_forward and the
// on-demand functions. Regenerate all: tests/rne_post/make_goldens.sh
import fs from 'node:fs';

import { loadOracleModel } from './oracle_model.mjs';

const FIELDS = ['cacc', 'cfrc_int', 'cfrc_ext', 'subtree_linvel', 'subtree_angmom', 'energy'];

function parseArgs(argv) {
  const opts = { model: null, key: -1, ctrl: null, at: [0], xfrc: [], out: null };
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--key') opts.key = parseInt(argv[++i], 10);
    else if (argv[i] === '--ctrl') opts.ctrl = argv[++i];
    else if (argv[i] === '--at') opts.at = argv[++i].split(',').map(Number);
    else if (argv[i] === '--xfrc') opts.xfrc.push(argv[++i]);
    else if (!opts.model) opts.model = argv[i];
    else if (!opts.out) opts.out = argv[i];
    else throw new Error(`unexpected argument ${argv[i]}`);
  }
  if (!opts.model) throw new Error('usage: node dump_rnepost.mjs MODEL.xml [--key K] [--ctrl C.csv] [--at 0,50] [--xfrc BODY:f6] [OUT.json]');
  return opts;
}

// Rows of a control file; '#' lines are comments.
function readControls(file) {
  if (!file) return [];
  return fs.readFileSync(file, 'utf8').split('\n')
    .filter((l) => l.trim() && !l.startsWith('#'))
    .map((l) => l.split(',').map(Number));
}

const opts = parseArgs(process.argv.slice(2));
const { mj, model } = await loadOracleModel(opts.model);
const data = new mj.MjData(model);
if (opts.key >= 0) mj.mj_resetDataKeyframe(model, data, opts.key);
for (const spec of opts.xfrc) {
  const [body, values] = spec.split(':');
  const id = mj.mj_name2id(model, mj.mjtObj.mjOBJ_BODY.value, body);
  if (id < 0) throw new Error(`no body ${body}`);
  values.split(',').map(Number).forEach((v, k) => { data.xfrc_applied[6 * id + k] = v; });
}
const controls = readControls(opts.ctrl);

const out = { engine: `mujoco ${mj.mj_versionString()}`, key: opts.key, xfrc: opts.xfrc, dumps: [] };
let step = 0;
for (const at of [...opts.at].sort((a, b) => a - b)) {
  for (; step < at; step++) {
    const row = controls.length ? controls[Math.min(step, controls.length - 1)] : [];
    for (let u = 0; u < model.nu && u < row.length; u++) data.ctrl[u] = row[u];
    mj.mj_step(model, data);
  }
  mj.mj_forward(model, data);
  mj.mj_rnePostConstraint(model, data);
  mj.mj_subtreeVel(model, data);
  mj.mj_energyPos(model, data);
  mj.mj_energyVel(model, data);
  const dump = { step: at, ncon: data.ncon };
  for (const f of FIELDS) dump[f] = Array.from(data[f], Number);
  out.dumps.push(dump);
}
const lines = out.dumps.map((d) => '  ' + JSON.stringify(d));
const head = JSON.stringify({ engine: out.engine, key: out.key, xfrc: out.xfrc });
const text = `${head.slice(0, -1)},\n "dumps": [\n${lines.join(',\n')}\n]}`;
if (opts.out) fs.writeFileSync(opts.out, text + '\n'); else process.stdout.write(text + '\n');
data.delete();
model.delete();

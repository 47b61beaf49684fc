// Where simlab and MuJoCo part: both engines run mj_forward at one state of a rollout
// (MuJoCo, the oracle, here in node; simlab natively, through its Python module), and
// each named Data field is compared value by value. The first field of the pipeline that
// differs, at a state where both agree, is where to look.
//
//   node tools/fields_at_state.mjs MODEL.xml ROLLOUT.jsonl STEP [--ctrl CTRL.csv]
//        [--fields a,b,...] [--cold] [--python python3]
//
// The state is row STEP of a rollout (the format of ../shared/oracle/FORMAT.md, either
// engine's): its qpos, qvel and time, its qacc as the warm start (what the step after it
// starts from; --cold: no warm start, as the first forward after a reset), and control row
// STEP of CTRL.csv. MuJoCo comes from $SIMLAB_ORACLE (else ../shared/oracle); simlab from
// build/python. Prints, per field, how many values differ and the worst difference
// relative to max(1, |MuJoCo's value|).
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { loadOracleModel } from './oracle_model.mjs';

const kDefaultFields = [
  'xpos', 'xquat', 'cdof', 'cinert', 'crb', 'cvel', 'cdof_dot', 'qM', 'qfrc_bias', 'qfrc_passive',
  'qfrc_actuator', 'qfrc_smooth', 'qacc_smooth', 'efc_pos', 'efc_D', 'efc_R', 'efc_aref',
  'efc_b', 'efc_force', 'qfrc_constraint', 'qacc'];

// MODEL ROLLOUT STEP and the --name value options.
function parseArgs(argv) {
  const opts = { ctrl: '', fields: kDefaultFields.join(','), cold: false, python: 'python3' };
  const positional = [];
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--cold') opts.cold = true;
    else if (argv[i].startsWith('--')) opts[argv[i].slice(2)] = argv[++i];
    else positional.push(argv[i]);
  }
  if (positional.length !== 3) {
    throw new Error('usage: node tools/fields_at_state.mjs MODEL.xml ROLLOUT.jsonl STEP [--ctrl C.csv] [--fields a,b] [--cold]');
  }
  [opts.model, opts.rollout] = positional;
  opts.step = Number(positional[2]);
  return opts;
}

// { qpos, qvel, time, warm, ctrl } of the state.
function readState(opts) {
  const rows = fs.readFileSync(opts.rollout, 'utf8').trim().split('\n').slice(1).map(JSON.parse);
  const row = rows[opts.step];
  if (!row) throw new Error(`${opts.rollout} has no row ${opts.step}`);
  let ctrl = null;
  if (opts.ctrl) {
    const lines = fs.readFileSync(opts.ctrl, 'utf8').split('\n').filter((l) => l && l[0] !== '#');
    ctrl = lines[Math.min(opts.step, lines.length - 1)].split(',').map(Number);
  }
  return { qpos: row.qpos, qvel: row.qvel, time: row.time, warm: opts.cold ? null : row.qacc, ctrl };
}

// MuJoCo's fields after mj_forward at the state.
async function oracleFields(opts, state, fields) {
  const { mj, model } = await loadOracleModel(opts.model);
  const data = new mj.MjData(model);
  data.qpos.set(state.qpos);
  data.qvel.set(state.qvel);
  data.time = state.time;
  if (state.warm) data.qacc_warmstart.set(state.warm);
  if (state.ctrl && model.nu) data.ctrl.set(state.ctrl);
  mj.mj_forward(model, data);
  return Object.fromEntries(fields.map((f) => [f, data[f] === undefined ? null : Array.from(data[f])]));
}

// simlab's, from its Python module (the same state, as JSON on standard input).
function simlabFields(opts, state, fields) {
  const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
  const script = `
import json, sys
import numpy as np
import simlab as mujoco
job = json.load(sys.stdin)
m = mujoco.MjModel.from_xml_path(job['model'])
d = mujoco.MjData(m)
s = job['state']
d.qpos[:] = s['qpos']; d.qvel[:] = s['qvel']; d.time = s['time']
if s['warm'] is not None: d.qacc_warmstart[:] = s['warm']
if s['ctrl'] is not None and m.nu: d.ctrl[:] = s['ctrl']
mujoco.mj_forward(m, d)
out = {}
for f in job['fields']:
    out[f] = np.asarray(getattr(d, f)).ravel().tolist() if hasattr(d, f) else None
print(json.dumps(out))
`;
  const env = { ...process.env, PYTHONPATH: `${path.join(root, 'build/python')}:/usr/lib/python3/dist-packages` };
  const run = spawnSync(opts.python, ['-c', script], {
    input: JSON.stringify({ model: path.resolve(opts.model), state, fields }), env,
    encoding: 'utf8', maxBuffer: 1 << 30 });
  if (run.status !== 0) throw new Error(`simlab (python): ${run.stderr}`);
  return JSON.parse(run.stdout);
}

// One line per field: sizes, differing values, worst relative difference.
function report(fields, ours, theirs) {
  for (const f of fields) {
    const a = theirs[f], b = ours[f];
    if (!a || !b) {
      console.log(`${f.padEnd(18)} ${!a ? 'MuJoCo' : 'simlab'} has no such field`);
      continue;
    }
    if (a.length !== b.length) {
      console.log(`${f.padEnd(18)} ${a.length} values in MuJoCo, ${b.length} in simlab (another layout)`);
      continue;
    }
    let differ = 0, worst = 0, at = -1;
    for (let i = 0; i < a.length; i++) {
      if (a[i] === b[i]) continue;
      differ++;
      const e = Math.abs(a[i] - b[i]) / Math.max(1, Math.abs(a[i]));
      if (e > worst) [worst, at] = [e, i];
    }
    const where = differ ? ` (worst ${worst.toExponential(2)} at [${at}]: ${a[at]} vs ${b[at]})` : '';
    console.log(`${f.padEnd(18)} ${String(a.length).padStart(7)} values, ${String(differ).padStart(6)} differ${where}`);
  }
}

async function main() {
  const opts = parseArgs(process.argv.slice(2));
  const fields = opts.fields.split(',');
  const state = readState(opts);
  const theirs = await oracleFields(opts, state, fields);
  const ours = simlabFields(opts, state, fields);
  report(fields, ours, theirs);
}

main().catch((e) => {
  console.error(e.message ?? e);
  process.exit(1);
});

// The standing conformance sweep (issue 19): every complete model of a MuJoCo source tree
// (its model/ and test/ folders) that the oracle (MuJoCo 3.5.1, ../shared/oracle) loads,
// rolled out by both engines from keyframe 0 when there is one, under ctrlgen.mjs's
// controls, and compared field by field (1e-6, or 1e-4 when the reference has contacts).
// Prints a table of verdicts with each model's first failure, and a count per verdict.
//
//   node tools/sweep_vs_mujoco.mjs --mujoco /work/mujoco-native/src [--only SUBSTRING]
//        [--steps 200] [--timeout 120] [--out sweep.md] [--simlab build/simlab]
//        [--native /work/mujoco-oracle-era]
//
// --native: native MuJoCo at the oracle's commit with its plugins
// (tools/native/build_oracle_era.sh) is the reference for the models the npm oracle
// cannot load (those with plugins), without controls (ctrlgen.mjs cannot load them).
//
// A MuJoCo tree comes from `fetch` (github:google-deepmind/mujoco; ../shared/oracle/
// native/build.sh unpacks one). Nothing here is needed by the tests or CI.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
// (the oracle's scripts with its node_modules: $SIMLAB_ORACLE, else ../shared/oracle)
const oracle = process.env.SIMLAB_ORACLE ? path.resolve(process.env.SIMLAB_ORACLE)
                                         : path.resolve(root, '../shared/oracle');

// --name value options, with defaults.
function parseArgs(argv) {
  const opts = { mujoco: null, only: '', steps: 200, timeout: 120, out: null,
                 simlab: path.join(root, 'build/simlab'), native: null };
  for (let i = 0; i < argv.length; i += 2) {
    const name = argv[i].replace(/^--/, '');
    if (!(name in opts)) throw new Error(`unknown option ${argv[i]}`);
    opts[name] = typeof opts[name] === 'number' ? Number(argv[i + 1]) : argv[i + 1];
  }
  if (!opts.mujoco) throw new Error('usage: node tools/sweep_vs_mujoco.mjs --mujoco MUJOCO_SOURCE_TREE');
  return opts;
}

// Every .xml below `folder`.
function xmlFiles(folder) {
  const out = [];
  for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
    const full = path.join(folder, entry.name);
    if (entry.isDirectory()) out.push(...xmlFiles(full));
    else if (entry.name.endsWith('.xml')) out.push(full);
  }
  return out.sort();
}

// Runs a command with a time limit: {ok, out, err, timedOut}.
function run(command, args, timeout) {
  const done = spawnSync(command, args, { encoding: 'utf8', timeout: timeout * 1000, maxBuffer: 1 << 26 });
  return { ok: done.status === 0, out: done.stdout ?? '', err: (done.stderr ?? '').trim(),
           timedOut: done.error?.code === 'ETIMEDOUT' };
}

// The line of a message that says what went wrong (the first naming an error, else the
// first), shortened.
function firstLine(text) {
  const lines = text.split('\n').map((l) => l.trim()).filter(Boolean);
  const line = lines.find((l) => /error/i.test(l) && !/^at /.test(l)) ?? lines[0] ?? '';
  return line.length > 140 ? `${line.slice(0, 137)}...` : line;
}

// How many keyframes MuJoCo compiles for a model (0 when it cannot tell), from the
// oracle's dump of it (tools/dump_model.mjs, in a process of its own).
function keyframesOf(model, timeout) {
  const dumped = run('node', [path.join(root, 'tools', 'dump_model.mjs'), model], timeout);
  try {
    return dumped.ok ? JSON.parse(dumped.out).sizes.nkey ?? 0 : 0;
  } catch {
    return 0;
  }
}

// Both rollouts made (`ref` and `ours`): the verdict at the tolerance the reference's
// contacts call for.
function verdictOf(ref, ours, opts, note) {
  const contacts = fs.readFileSync(ref, 'utf8').split('\n').some((l) => /"ncon":[1-9]/.test(l));
  const tol = contacts ? '1e-4' : '1e-6';
  const compared = run('node', [path.join(oracle, 'compare.mjs'), ref, ours, '--tol', tol], opts.timeout);
  if (compared.ok) return { verdict: 'agrees', detail: `tol ${tol}${note}` };
  const fail = compared.out.split('\n').find((l) => l.startsWith('FAIL')) ?? compared.err;
  return { verdict: 'differs', detail: `tol ${tol}${note}: ${firstLine(fail).replace(/\s+/g, ' ')}` };
}

// A model the npm oracle cannot load, against native MuJoCo of the oracle's commit.
function sweepNative(model, opts, work, why) {
  const ref = path.join(work, 'ref.jsonl'), ours = path.join(work, 'ours.jsonl');
  const common = ['--steps', String(opts.steps), '--every', '10'];
  const env = { ...process.env, LD_PRELOAD: path.join(opts.native, 'musl_trig.so') };
  const reference = spawnSync(path.join(opts.native, 'rollout'), [model, ...common, '--out', ref],
                              { encoding: 'utf8', timeout: opts.timeout * 1000, env });
  if (reference.status !== 0) return { verdict: 'MuJoCo does not load', detail: why };
  const simulated = run(opts.simlab, ['rollout', model, ...common, '--out', ours], opts.timeout);
  if (simulated.timedOut) return { verdict: 'simlab times out', detail: `over ${opts.timeout} s` };
  if (!simulated.ok) return { verdict: 'simlab does not load', detail: firstLine(simulated.err) };
  return verdictOf(ref, ours, opts, ', native reference, no controls');
}

// One model's verdict: {verdict, detail}.
function sweepOne(model, opts, work) {
  const ctrl = path.join(work, 'ctrl.csv'), ref = path.join(work, 'ref.jsonl'), ours = path.join(work, 'ours.jsonl');
  const gen = run('node', [path.join(oracle, 'ctrlgen.mjs'), model, '--steps', String(opts.steps), '--out', ctrl], opts.timeout);
  if (!gen.ok && opts.native) return sweepNative(model, opts, work, firstLine(gen.err));
  if (!gen.ok) return { verdict: 'MuJoCo does not load', detail: firstLine(gen.err) };
  const key = keyframesOf(model, opts.timeout) > 0 ? ['--key', '0'] : [];
  const common = ['--steps', String(opts.steps), '--every', '10', '--ctrl', ctrl, ...key];
  const reference = run('node', [path.join(oracle, 'rollout.mjs'), model, ...common, '--out', ref], opts.timeout);
  if (!reference.ok) return { verdict: 'MuJoCo does not load', detail: firstLine(reference.err) };
  const simulated = run(opts.simlab, ['rollout', model, ...common, '--out', ours], opts.timeout);
  if (simulated.timedOut) return { verdict: 'simlab times out', detail: `over ${opts.timeout} s` };
  if (!simulated.ok) return { verdict: 'simlab does not load', detail: firstLine(simulated.err) };
  return verdictOf(ref, ours, opts, key.length ? ', key 0' : '');
}

function main() {
  const opts = parseArgs(process.argv.slice(2));
  const models = ['model', 'test'].flatMap((f) => xmlFiles(path.join(opts.mujoco, f)))
    .filter((m) => m.includes(opts.only));
  const work = fs.mkdtempSync(path.join(os.tmpdir(), 'simlab-sweep-'));
  const rows = ['| model | verdict | detail |', '|---|---|---|'];
  const counts = {};
  let deformable = 0;  // models simlab refuses for their flexes (issue 20 covers them)
  for (const model of models) {
    const { verdict, detail } = sweepOne(model, opts, work);
    counts[verdict] = (counts[verdict] ?? 0) + 1;
    if (verdict === 'simlab does not load' && /<flex|<flexcomp|<deformable/.test(detail)) deformable++;
    const row = `| ${path.relative(opts.mujoco, model)} | ${verdict} | ${detail.replaceAll('|', '/')} |`;
    rows.push(row);
    console.error(row);
  }
  fs.rmSync(work, { recursive: true, force: true });
  const summary = Object.entries(counts).map(([verdict, n]) => `${verdict}: ${n}`).join(', ');
  // The acceptance's share: of the models MuJoCo loads, flexes aside, those that agree.
  const loaded = models.length - (counts['MuJoCo does not load'] ?? 0) - deformable;
  const share = loaded ? (100 * (counts.agrees ?? 0) / loaded).toFixed(1) : '-';
  const text = `${rows.join('\n')}\n\n${models.length} models: ${summary}\n` +
    `flexes aside (${deformable} refused for them): ${counts.agrees ?? 0} of ${loaded} agree (${share}%)\n`;
  if (opts.out) fs.writeFileSync(opts.out, text);
  process.stdout.write(text);
}

main();

// Step speed of simlab's WebAssembly build against MuJoCo's own (the npm package `mujoco`,
// the oracle's), both in this node process, on testspeed's workload: from keyframe
// "test" when the model has one, under MuJoCo 3.12 testspeed's control noise (the
// Ornstein-Uhlenbeck process of apps/bench.cc, driven by the same Halton sequence).
// The rounds alternate the engines; each run's time is the process's CPU time
// (process.cpuUsage), and the least of the rounds is kept (a shared machine only adds
// time). Prints steps per second of each and the ratio simlab / MuJoCo.
//
//   node web/test/speed_vs_mujoco.mjs [--mujoco DIR] [--dist web/dist] [--rounds 9]
//
// DIR holds node_modules/mujoco (default ../shared/oracle; run `npm ci` there first).
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { loadSimlab, openModel, parseOptions, repoRoot } from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  mujoco: path.join(repoRoot, '../shared/oracle'),
  dist: path.join(repoRoot, 'web/dist'),
  rounds: '9',
});

const models = [
  { name: 'humanoid', file: 'tests/conformance/contact/models/humanoid.xml', steps: 20000 },
  { name: 'gantry-holding', file: 'tests/models/bench_gantry_holding.xml', steps: 20000 },
];

// Element `index` of the Halton sequence in `base` (MuJoCo's mju_Halton).
function halton(index, base) {
  let f = 1 / base, h = 0;
  for (let n = index; n > 0; n = Math.floor(n / base)) {
    h += f * (n % base);
    f /= base;
  }
  return h;
}

// testspeed 3.12's controls, `steps` rows of nu (see ControlNoise in apps/bench.cc).
function controlNoise({ nu, timestep, ctrlrange, limited, keyCtrl }, steps) {
  const rate = Math.exp(-timestep / 0.1), scale = 0.01 * Math.sqrt(1 - rate * rate);
  const rows = [];
  for (let s = 0; s < steps; s++) {
    const row = new Float64Array(nu);
    for (let i = 0; i < nu; i++) {
      const lo = ctrlrange[2 * i], hi = ctrlrange[2 * i + 1];
      let centre = limited[i] ? (hi + lo) / 2 : 0;
      const half = limited[i] ? (hi - lo) / 2 : 1;
      if (keyCtrl) centre = keyCtrl[i];
      let u = s > 0 ? rate * rows[s - 1][i] + (1 - rate) * centre : centre;
      u += scale * half * (2 * halton(s, i + 2) - 1);
      if (limited[i]) u = Math.min(Math.max(u, lo), hi);
      row[i] = u;
    }
    rows.push(row);
  }
  return rows;
}

// CPU seconds of run().
function cpuSeconds(run) {
  const before = process.cpuUsage();
  run();
  const used = process.cpuUsage(before);
  return (used.user + used.system) / 1e6;
}

// MuJoCo's engine on one model: its controls and a timed run. The model's folder is
// copied into MuJoCo's virtual file system, one folder per model.
let folders = 0;
function mujocoEngine(mj, file, steps) {
  const dir = `/bench${++folders}`;
  mj.FS.mkdir(dir);
  const copy = (from, to) => {
    for (const entry of fs.readdirSync(from, { withFileTypes: true })) {
      const src = path.join(from, entry.name), dst = `${to}/${entry.name}`;
      if (entry.isDirectory()) {
        mj.FS.mkdir(dst);
        copy(src, dst);
      } else {
        mj.FS.writeFile(dst, fs.readFileSync(src));
      }
    }
  };
  copy(path.dirname(file), dir);
  const model = mj.MjModel.mj_loadXML(`${dir}/${path.basename(file)}`);
  const data = new mj.MjData(model);
  let key = -1;
  for (let k = 0; k < model.nkey; k++) {
    if (mj.mj_id2name(model, mj.mjtObj.mjOBJ_KEY.value, k) === 'test') key = k;
  }
  const nu = model.nu;
  const controls = controlNoise({
    nu, timestep: model.opt.timestep, ctrlrange: model.actuator_ctrlrange,
    limited: model.actuator_ctrllimited,
    keyCtrl: key >= 0 ? model.key_ctrl.slice(key * nu, (key + 1) * nu) : null,
  }, steps);
  const run = () => {
    if (key >= 0) mj.mj_resetDataKeyframe(model, data, key); else mj.mj_resetData(model, data);
    const ctrl = data.ctrl;
    for (let s = 0; s < steps; s++) {
      ctrl.set(controls[s]);
      mj.mj_step(model, data);
    }
  };
  return { run, version: mj.mj_versionString() };
}

// simlab's engine on one model, with the same controls.
async function simlabEngine(simlab, file, steps) {
  const sim = await openModel(simlab, file);
  const { nu } = sim.sizes();
  const key = sim.nameToId('key', 'test');
  const controls = controlNoise({
    nu, timestep: sim.option().timestep, ctrlrange: sim.model('actuator_ctrlrange'),
    limited: sim.model('actuator_ctrllimited'),
    keyCtrl: key >= 0 ? sim.model('key_ctrl').slice(key * nu, (key + 1) * nu) : null,
  }, steps);
  const ctrlId = sim.dataId('ctrl');
  const run = () => {
    if (key >= 0) sim.resetKeyframe(key); else sim.reset();
    const ctrl = sim.dataViewAt(ctrlId);
    for (let s = 0; s < steps; s++) {
      ctrl.set(controls[s]);
      sim.step();
    }
  };
  return { run };
}

async function main() {
  const pkg = path.join(options.mujoco, 'node_modules/mujoco');
  if (!fs.existsSync(pkg)) {
    console.error(`no npm mujoco in ${pkg}: run \`npm ci\` in ${options.mujoco}`);
    process.exit(2);
  }
  const { default: loadMujoco } = await import(pathToFileURL(packageMain(pkg)).href);
  const mj = await loadMujoco();
  const simlab = await loadSimlab(options.dist);
  const rounds = Number(options.rounds);
  console.log(`simlab (${options.dist}) against MuJoCo ${mj.mj_versionString()} (npm mujoco), ` +
              `node ${process.version}, least CPU time of ${rounds} rounds`);
  console.log(`${'model'.padEnd(16)} ${'simlab'.padStart(10)} ${'MuJoCo'.padStart(10)} ${'ratio'.padStart(6)}`);
  for (const m of models) {
    const file = path.join(repoRoot, m.file);
    const engines = { simlab: await simlabEngine(simlab, file, m.steps),
                      mujoco: mujocoEngine(mj, file, m.steps) };
    const best = { simlab: Infinity, mujoco: Infinity };
    for (let r = 0; r < rounds; r++) {
      const order = r % 2 ? ['mujoco', 'simlab'] : ['simlab', 'mujoco'];
      for (const e of order) best[e] = Math.min(best[e], cpuSeconds(engines[e].run));
    }
    const sps = (e) => m.steps / best[e];
    console.log(`${m.name.padEnd(16)} ${sps('simlab').toFixed(0).padStart(10)} ` +
                `${sps('mujoco').toFixed(0).padStart(10)} ${(sps('simlab') / sps('mujoco')).toFixed(2).padStart(6)}`);
  }
}

// The package's entry file (its package.json "main").
function packageMain(pkg) {
  const json = JSON.parse(fs.readFileSync(path.join(pkg, 'package.json'), 'utf8'));
  return path.join(pkg, json.main || json.module || 'index.js');
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});

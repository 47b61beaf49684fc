// Shared by the WebAssembly tests: finding and loading web/dist/simlab.mjs in node,
// reading a model with its extra files, control CSVs, and rollouts on both engines.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { gatherModelFiles } from '../lab/model_files.mjs';

export const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

// Exit code ctest reads as "skipped" (SKIP_RETURN_CODE).
export const kSkip = 77;

// Ends the test as skipped, saying why; with `--require yes` (CI, where everything is
// installed and built fresh) a skip is a failure instead.
export function skipOrFail(reason, options = {}) {
  if (options.require === 'yes') {
    console.error(`FAIL: required, but ${reason}`);
    process.exit(1);
  }
  console.log(`SKIPPED: ${reason}`);
  process.exit(kSkip);
}

// Command-line options as {name: value} from "--name value" pairs.
export function parseOptions(argv, defaults) {
  const options = { ...defaults };
  for (let i = 0; i < argv.length; i += 2) {
    if (!argv[i].startsWith('--') || i + 1 >= argv.length) throw new Error(`bad option ${argv[i]}`);
    options[argv[i].slice(2)] = argv[i + 1];
  }
  return options;
}

// The engine sources' hash now (tools/source_hash.cmake; `wasm`: with the binding).
function sourceHash(wasm) {
  const args = [`-DROOT=${repoRoot}`, '-P', path.join(repoRoot, 'tools/source_hash.cmake')];
  if (wasm) args.unshift('-DWASM=ON');
  const run = spawnSync('cmake', args, { encoding: 'utf8' });
  if (run.status !== 0) throw new Error(`cmake -P tools/source_hash.cmake failed: ${run.stderr}`);
  return run.stdout.trim();
}

// Why a build is not of the sources now: its hash file missing or different, or ''.
function staleBuild(what, stampFile, wasm) {
  const how = wasm ? 'bash tools/build_wasm.sh' : 'cmake --build';
  if (!fs.existsSync(stampFile)) return `${what} has no ${path.basename(stampFile)} (${how} writes it)`;
  if (fs.readFileSync(stampFile, 'utf8').trim() !== sourceHash(wasm)) {
    return `${what} was built from other sources than src/ and include/ now (${how} rebuilds it)`;
  }
  return '';
}

// Why the WASM build cannot be tested (missing, or built from other sources unless
// `staleOk`), or ''.
export function whyNotTestable(dist, staleOk = false) {
  const wasm = path.join(dist, 'simlab.wasm');
  if (!fs.existsSync(wasm) || !fs.existsSync(path.join(dist, 'simlab.mjs'))) {
    const emscripten = spawnSync('em++', ['--version']).status === 0;
    return `no WebAssembly build in ${dist} (` +
           (emscripten ? 'bash tools/build_wasm.sh makes it' : 'emscripten is not installed') + ')';
  }
  return staleOk ? '' : staleBuild(wasm, path.join(dist, 'sources.sha256'), true);
}

// The module factory's result, with the binary read from disk (node has no fetch of file paths).
export async function loadSimlab(dist) {
  const { default: createSimlab } = await import(pathToFileURL(path.join(dist, 'simlab.mjs')).href);
  return createSimlab({ wasmBinary: fs.readFileSync(path.join(dist, 'simlab.wasm')) });
}

// Readers of a folder on disk, for gatherModelFiles: text, and bytes.
export function diskReaders(folder) {
  return [async (p) => fs.readFileSync(path.join(folder, p), 'utf8'),
    async (p) => new Uint8Array(fs.readFileSync(path.join(folder, p)))];
}

// A Simulation of the model at `modelPath` with every file it refers to (found as the
// lab's loader finds them, web/lab/model_files.mjs).
export async function openModel(simlab, modelPath) {
  const xml = fs.readFileSync(modelPath, 'utf8');
  const name = path.basename(modelPath);
  const files = await gatherModelFiles(name, xml, ...diskReaders(path.dirname(modelPath)));
  return new simlab.Simulation(name, xml, files);
}

// Control rows of a CSV as `simlab rollout --ctrl` reads it ('#' lines are comments).
export function readControls(csvPath) {
  return fs.readFileSync(csvPath, 'utf8').split('\n')
    .filter((line) => line.trim() !== '' && !line.trim().startsWith('#'))
    .map((line) => line.split(',').map(Number));
}

// The native rollout (JSON Lines) of the same inputs: one record per step.
export function nativeRollout(simlabExe, modelPath, { key = -1, ctrl, steps }) {
  const out = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'simlab-wasm-')), 'native.jsonl');
  const args = ['rollout', modelPath, '--steps', String(steps), '--out', out];
  if (key >= 0) args.push('--key', String(key));
  if (ctrl) args.push('--ctrl', ctrl);
  const run = spawnSync(simlabExe, args, { encoding: 'utf8' });
  if (run.status !== 0) throw new Error(`${simlabExe} ${args.join(' ')} failed: ${run.stderr}`);
  const lines = fs.readFileSync(out, 'utf8').trim().split('\n');
  fs.rmSync(path.dirname(out), { recursive: true });
  return lines.slice(1).map((line) => JSON.parse(line));
}

// The same order of work as `simlab rollout`: reset (keyframe), forward, record step 0;
// then per step: write the control row (the last one repeats), step, record.
export function wasmRollout(sim, { key = -1, controls, steps, fields, record = true }) {
  if (key >= 0) sim.resetKeyframe(key); else sim.reset();
  const records = [];
  const take = (step) => {
    if (!record) return;
    const r = { step, time: sim.time, ncon: sim.counts().ncon };
    for (const name of fields) r[name] = sim.data(name);
    records.push(r);
  };
  sim.forward();
  take(0);
  for (let step = 1; step <= steps; step++) {
    if (controls && controls.length) sim.setData('ctrl', controls[Math.min(step - 1, controls.length - 1)]);
    sim.step(1);
    take(step);
  }
  return records;
}

// The WASM module and the native simlab to compare it with; exits 77 (skipped) with the
// reason when the WASM build cannot be tested (`--stale ok`: test it even if older than
// the sources, e.g. while others edit them; `--require yes`: fail instead of skipping).
export async function openBuilds(options) {
  const reason = whyNotTestable(options.dist, options.stale === 'ok');
  if (reason) skipOrFail(reason, options);
  if (!fs.existsSync(options.simlab)) throw new Error(`no native simlab at ${options.simlab}`);
  // Both builds must come from the same sources (others may edit them meanwhile).
  const native = options.stale === 'ok' ? '' : staleBuild(options.simlab, `${options.simlab}.sources`, false);
  if (native) skipOrFail(native, options);
  return loadSimlab(options.dist);
}

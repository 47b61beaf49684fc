// The lab's model loader without a browser (web/lab/model_files.mjs): which files a model
// pulls in, where (includes, attached models, <compiler meshdir/texturedir/assetdir>,
// strippath), text for XML and bytes for the rest; then the fixture
// web/lab/fixtures/models/all_geoms.xml gathered from disk and, when web/dist is built,
// compiled by the WebAssembly engine with its mesh file. Convex hulls (qhull, compiled
// for the browser by tools/build_wasm.sh): the mesh models of tests/meshes give the same
// mesh arrays as MuJoCo's goldens (which the native build matches too), and the fixture
// mesh_drop.xml (colliding meshes falling on a plane) rolls out as natively
// (`--simlab`; skipped when a build is of other sources unless `--stale ok`).
//
//   node web/test/model_files.mjs [--dist web/dist] [--simlab build/simlab] [--stale ok]
//        [--require yes]
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { gatherModelFiles, normalizePath, startTags } from '../lab/model_files.mjs';
import {
  diskReaders, nativeRollout, parseOptions, wasmRollout, whyNotTestable,
} from './wasm_harness.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const options = parseOptions(process.argv.slice(2), {
  dist: path.join(repoRoot, 'web/dist'), simlab: '', stale: 'no', require: 'no',
});
const dist = path.resolve(options.dist);
const fixtures = path.join(repoRoot, 'web/lab/fixtures/models');

// Readers over a {path: content} object; every read is logged.
function memoryReaders(tree, log) {
  const read = (path) => {
    log.push(path);
    if (!(path in tree)) return Promise.reject(new Error(`${path}: HTTP 404`));
    return Promise.resolve(tree[path]);
  };
  return [read, async (path) => new TextEncoder().encode(await read(path))];
}


function checkTags() {
  const tags = startTags(`<mujoco><!-- <mesh file="no.stl"/> --><mesh name='a' file="x&amp;y.stl"/>
    <texture type="skybox" fileup = "up.png"/></mujoco>`);
  assert.deepEqual(tags.map((t) => t.tag), ['mujoco', 'mesh', 'texture']);
  assert.equal(tags[1].attrs.file, 'x&y.stl');
  assert.equal(tags[2].attrs.fileup, 'up.png');
  assert.equal(normalizePath('a/./b/../c.stl'), 'a/c.stl');
  assert.equal(normalizePath('../c.stl'), null);
  assert.equal(normalizePath('/abs/c.stl'), null);
  console.log('ok: start tags (comments skipped, entities decoded), paths normalised');
}

// A model with every kind of reference.
async function checkReferences() {
  const tree = {
    'parts/inc.xml': '<mujoco><include file="deeper.xml"/><asset><mesh file="inc.stl"/></asset></mujoco>',
    'parts/deeper.xml': '<mujoco><asset><hfield name="h" file="terrain.png"/></asset></mujoco>',
    'robot/arm.xml': `<mujoco><compiler assetdir="assets" strippath="true"/>
      <asset><mesh file="far/away/link.obj"/><skin file="arm.skn"/></asset></mujoco>`,
    'meshes/body.stl': 'solid', 'meshes/inc.stl': 'solid', 'meshes/terrain.png': 'png',
    'tex/sky_up.png': 'png', 'tex/sky_side.png': 'png', 'tex/grid.png': 'png',
    'robot/assets/link.obj': 'v', 'robot/assets/arm.skn': 'skin',
  };
  const main = `<mujoco>
    <asset>
      <mesh name="body" file="body.stl"/>
      <mesh name="inline" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/>
      <texture name="sky" type="skybox" fileup="sky_up.png" fileright="sky_side.png" fileleft="sky_side.png"/>
      <texture name="grid" file="grid.png"/>
      <model name="arm" file="robot/arm.xml"/>
    </asset>
    <include file="parts/inc.xml"/>
    <compiler meshdir="meshes" texturedir="tex/"/>
  </mujoco>`;
  const log = [];
  const [readText, readBytes] = memoryReaders(tree, log);
  const files = await gatherModelFiles('main.xml', main, readText, readBytes);
  const kinds = Object.fromEntries(Object.entries(files).map(([p, v]) => [p, typeof v === 'string' ? 'text' : 'bytes']));
  assert.deepEqual(kinds, {
    'parts/inc.xml': 'text', 'parts/deeper.xml': 'text', 'robot/arm.xml': 'text',
    'meshes/body.stl': 'bytes', 'meshes/inc.stl': 'bytes', 'meshes/terrain.png': 'bytes',
    'tex/sky_up.png': 'bytes', 'tex/sky_side.png': 'bytes', 'tex/grid.png': 'bytes',
    'robot/assets/link.obj': 'bytes', 'robot/assets/arm.skn': 'bytes',
  });
  assert.ok(files['meshes/body.stl'] instanceof Uint8Array);
  // deeper.xml is not in the model's folder: found beside the file that includes it.
  assert.deepEqual(log.filter((p) => p.endsWith('deeper.xml')), ['deeper.xml', 'parts/deeper.xml']);
  assert.equal(new Set(log).size, log.length, 'each file is read once');
  console.log(`ok: ${Object.keys(files).length} files of a model with includes, an attached model, ` +
              'meshdir, texturedir, assetdir and strippath');

  await assert.rejects(gatherModelFiles('m.xml', '<mujoco><asset><mesh file="gone.stl"/></asset></mujoco>',
    readText, readBytes), /gone\.stl: HTTP 404/);
  const skipped = await gatherModelFiles('m.xml', '<mujoco><asset><mesh file="../up.stl"/><mesh file="/abs.stl"/></asset></mujoco>',
    readText, readBytes);
  assert.deepEqual(skipped, {}, 'names outside the folder are left to the engine');
  console.log('ok: a missing file rejects with its name; names outside the model folder are not fetched');
}

// The lab's fixture and the lesson model, gathered from disk.
async function checkFixtures() {
  const allGeoms = fs.readFileSync(path.join(fixtures, 'all_geoms.xml'), 'utf8');
  const files = await gatherModelFiles('all_geoms.xml', allGeoms, ...diskReaders(fixtures));
  assert.deepEqual(Object.keys(files), ['meshes/wedge.stl']);
  assert.equal(files['meshes/wedge.stl'].length, 84 + 50 * 8, 'a binary STL of 8 triangles');
  const models = path.join(repoRoot, 'models');
  const gantry = await gatherModelFiles('gantry_gripper.xml',
    fs.readFileSync(path.join(models, 'gantry_gripper.xml'), 'utf8'), ...diskReaders(models));
  assert.deepEqual(Object.keys(gantry), ['gripper.xml']);
  console.log('ok: all_geoms.xml needs meshes/wedge.stl (bytes); gantry_gripper.xml needs gripper.xml');
  return { allGeoms, files };
}

// The fixture compiled by the WebAssembly engine with the gathered files.
async function checkWasm(simlab, { allGeoms, files }) {
  const sim = new simlab.Simulation('all_geoms.xml', allGeoms, files);
  try {
    assert.deepEqual(Array.from(sim.model('mesh_vertnum')), [6, 4], 'the STL wedge (6 vertices merged) and the inline tetrahedron');
    assert.deepEqual(Array.from(sim.model('mesh_facenum')), [8, 4]);
    assert.deepEqual(Array.from(sim.model('mesh_graphadr')), [-1, -1], 'visual meshes need no hull');
    const wedge = sim.nameToId('geom', 'wedge');
    assert.equal(sim.model('geom_type')[wedge], 7);
    assert.equal(sim.model('geom_dataid')[wedge], 0);
  } finally {
    sim.delete();
  }
  // The same wedge colliding: its convex hull, 6 vertices and 8 triangles.
  const colliding = allGeoms.replace(/(name="wedge" type="mesh"[^>]*?) contype="0" conaffinity="0"/, '$1');
  assert.notEqual(colliding, allGeoms);
  const hulled = new simlab.Simulation('all_geoms.xml', colliding, files);
  try {
    assert.equal(hulled.model('mesh_graphadr')[0], 0);
    assert.deepEqual(Array.from(hulled.model('mesh_graph').slice(0, 2)), [6, 8]);
  } finally {
    hulled.delete();
  }
  // qhull's errors reach the model's place (a flat mesh: qhull's longjmp in WebAssembly).
  const flat = '<mujoco>\n<asset><mesh name="flat" vertex="0 0 0  1 0 0  0 1 0  1 1 0"/></asset>\n' +
               '<worldbody><geom type="mesh" mesh="flat"/></worldbody></mujoco>';
  assert.throws(() => new simlab.Simulation('flat.xml', flat),
    /^Error: flat\.xml:2: <mesh name="flat">: qhull error while making the convex hull: QH6154 /);
  console.log('ok: the engine compiles the fixture with its STL mesh, and the same mesh colliding ' +
              'with its convex hull; a flat mesh gets qhull\'s error at the mesh\'s file:line');
}

// The model arrays of tests/meshes/NAME.xml (WebAssembly) against MuJoCo's golden, as
// tests/compiler_conformance_test.cc checks the native build: integers (hull graphs,
// faces) exactly, numbers to 1e-12.
async function checkMeshGolden(simlab, name, fields) {
  const folder = path.join(repoRoot, 'tests/meshes');
  const xml = fs.readFileSync(path.join(folder, `${name}.xml`), 'utf8');
  const files = await gatherModelFiles(`${name}.xml`, xml, ...diskReaders(folder));
  const golden = JSON.parse(fs.readFileSync(path.join(repoRoot, `tests/compiler_goldens/${name}.json`), 'utf8')).arrays;
  const sim = new simlab.Simulation(`${name}.xml`, xml, files);
  try {
    for (const field of fields) {
      const got = Array.from(sim.model(field));
      const want = golden[field];
      assert.equal(got.length, want.length, `${name}: ${field} size`);
      const integers = sim.modelShape(field).type === 'int';
      got.forEach((x, i) => {
        const ok = integers ? x === want[i] : Math.abs(x - want[i]) <= 1e-12 * Math.max(1, Math.abs(want[i]));
        assert.ok(ok, `${name}: ${field}[${i}] = ${x}, MuJoCo ${want[i]}`);
      });
    }
    return { nmesh: sim.sizes().nmesh, ngraph: golden.mesh_graph.length };
  } finally {
    sim.delete();
  }
}

// Hull-made arrays of the mesh test models equal MuJoCo's (and so the native build's).
async function checkHullArrays(simlab) {
  const fields = ['mesh_vertadr', 'mesh_vertnum', 'mesh_faceadr', 'mesh_facenum', 'mesh_graphadr',
    'mesh_graph', 'mesh_face', 'mesh_vert', 'mesh_pos', 'mesh_quat', 'geom_size', 'geom_rbound',
    'body_mass'];
  for (const name of ['mesh_assets', 'mesh_cloud']) {
    const { nmesh, ngraph } = await checkMeshGolden(simlab, name, fields);
    console.log(`ok: tests/meshes/${name}.xml in WebAssembly: ${nmesh} meshes, mesh_graph (${ngraph} ints), ` +
                'faces, vertices, geom sizes and masses as MuJoCo\'s golden');
  }
}

// The colliding meshes of mesh_drop.xml falling on a plane: WebAssembly against the
// native `simlab rollout`, every recorded number.
async function checkHullRollout(simlab) {
  const reason = !options.simlab ? 'no native simlab given (--simlab)'
    : !fs.existsSync(options.simlab) ? `no native simlab at ${options.simlab}`
      : whyNotTestable(dist, options.stale === 'ok');
  if (reason) {
    if (options.require === 'yes') throw new Error(`required, but ${reason}`);
    console.log(`skipped the native comparison of mesh_drop.xml: ${reason}`);
    return;
  }
  const modelPath = path.join(fixtures, 'mesh_drop.xml');
  const xml = fs.readFileSync(modelPath, 'utf8');
  const files = await gatherModelFiles('mesh_drop.xml', xml, ...diskReaders(fixtures));
  const fieldNames = ['qpos', 'qvel', 'qacc', 'qfrc_constraint'];
  const steps = 600;
  const sim = new simlab.Simulation('mesh_drop.xml', xml, files);
  let wasm;
  try {
    wasm = wasmRollout(sim, { steps, fields: fieldNames });
  } finally {
    sim.delete();
  }
  const native = nativeRollout(options.simlab, modelPath, { steps });
  assert.equal(wasm.length, native.length);
  let count = 0, differ = 0, worst = 0;
  native.forEach((record, s) => {
    assert.equal(wasm[s].ncon, record.ncon, `ncon at step ${s}`);
    for (const field of fieldNames) {
      Array.from(wasm[s][field]).forEach((x, i) => {
        const want = record[field][i];
        count++;
        if (x === want) return;
        differ++;
        worst = Math.max(worst, Math.abs(x - want) / Math.max(1, Math.abs(want)));
      });
    }
  });
  assert.ok(native.at(-1).ncon > 0, 'the meshes rest on the plane');
  assert.ok(worst <= 1e-12, `mesh_drop.xml: ${differ} of ${count} numbers differ, worst ${worst}`);
  console.log(`ok: mesh_drop.xml (colliding STL wedge and vertex-only box) ${steps} steps, ` +
              `${native.at(-1).ncon} contacts at the end: ` +
              (differ ? `${differ} of ${count} numbers differ, worst ${worst.toExponential(2)}`
                : `bit-identical to native (${count} numbers)`));
}

// The WebAssembly module, or null (skipped) when web/dist has none.
async function loadWasm() {
  if (!fs.existsSync(path.join(dist, 'simlab.mjs'))) {
    // With --require yes (CI) the WebAssembly build must be there.
    if (options.require === 'yes') throw new Error(`no WebAssembly build in ${dist}`);
    console.log(`skipped the WebAssembly checks: no build in ${dist}`);
    return null;
  }
  const createSimlab = (await import(path.join(dist, 'simlab.mjs'))).default;
  return createSimlab({ wasmBinary: fs.readFileSync(path.join(dist, 'simlab.wasm')) });
}

async function main() {
  checkTags();
  await checkReferences();
  const fixtureFiles = await checkFixtures();
  const simlab = await loadWasm();
  if (simlab) {
    await checkWasm(simlab, fixtureFiles);
    await checkHullArrays(simlab);
    await checkHullRollout(simlab);
  }
  console.log('PASS');
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

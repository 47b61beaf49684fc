// The lab's model loader without a browser (web/lab/model_files.mjs): which files a model
// pulls in, where (includes, attached models, <compiler meshdir/texturedir/assetdir>,
// strippath), text for XML and bytes for the rest; then the fixture
// web/lab/fixtures/models/all_geoms.xml gathered from disk and, when web/dist is built,
// compiled by the WebAssembly engine with its mesh file (and a colliding mesh refused,
// since the browser build has no qhull).
//
//   node web/test/model_files.mjs [--dist web/dist] [--require yes]
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { gatherModelFiles, normalizePath, startTags } from '../lab/model_files.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const distArg = process.argv.indexOf('--dist');
const dist = distArg > 0 ? path.resolve(process.argv[distArg + 1]) : path.join(repoRoot, 'web/dist');

// Readers over a {path: content} object; every read is logged.
function memoryReaders(tree, log) {
  const read = (path) => {
    log.push(path);
    if (!(path in tree)) return Promise.reject(new Error(`${path}: HTTP 404`));
    return Promise.resolve(tree[path]);
  };
  return [read, async (path) => new TextEncoder().encode(await read(path))];
}

// Readers over a folder on disk.
function diskReaders(folder) {
  return [async (p) => fs.readFileSync(path.join(folder, p), 'utf8'),
    async (p) => new Uint8Array(fs.readFileSync(path.join(folder, p)))];
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
  const fixtures = path.join(repoRoot, 'web/lab/fixtures/models');
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
async function checkWasm({ allGeoms, files }) {
  if (!fs.existsSync(path.join(dist, 'simlab.mjs'))) {
    // With --require yes (CI) the WebAssembly build must be there.
    if (process.argv.includes('--require')) throw new Error(`no WebAssembly build in ${dist}`);
    console.log(`skipped the WebAssembly check: no build in ${dist}`);
    return;
  }
  const createSimlab = (await import(path.join(dist, 'simlab.mjs'))).default;
  const simlab = await createSimlab({ wasmBinary: fs.readFileSync(path.join(dist, 'simlab.wasm')) });
  const sim = new simlab.Simulation('all_geoms.xml', allGeoms, files);
  try {
    assert.deepEqual(Array.from(sim.model('mesh_vertnum')), [6, 4], 'the STL wedge (6 vertices merged) and the inline tetrahedron');
    assert.deepEqual(Array.from(sim.model('mesh_facenum')), [8, 4]);
    const wedge = sim.nameToId('geom', 'wedge');
    assert.equal(sim.model('geom_type')[wedge], 7);
    assert.equal(sim.model('geom_dataid')[wedge], 0);
  } finally {
    sim.delete();
  }
  const colliding = allGeoms.replace(/(name="wedge" type="mesh"[^>]*?) contype="0" conaffinity="0"/, '$1');
  assert.notEqual(colliding, allGeoms);
  assert.throws(() => new simlab.Simulation('all_geoms.xml', colliding, files),
    /^Error: all_geoms\.xml:\d+: <mesh name="wedge">: convex hulls are not supported yet in this build$/);
  console.log('ok: the engine compiles the fixture with its STL mesh; a colliding mesh needs a convex hull, ' +
              'which the WebAssembly build refuses with the mesh\'s file:line');
}

async function main() {
  checkTags();
  await checkReferences();
  await checkWasm(await checkFixtures());
  console.log('PASS');
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

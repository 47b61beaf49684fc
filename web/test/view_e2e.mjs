// `simlab view` end to end in headless Chromium, on models the project did not write
// (MuJoCo's own, in ../shared/corpus/mujoco/model): each is served from its own folder
// (meshes and textures found there), loads, shows a picture that is not blank and a
// slider per control entry. On the humanoid: a slider moved with the mouse writes ctrl
// and changes the actuator's force; simulate's keys pause (time stops), single-step (one
// timestep), reset (time 0) and change the speed; the history goes back and forward
// (Left and Right arrows, its slider) and playing on from the past drops the newer
// states; body labels name the bodies; the lint panel lists its findings and marks a
// picked one's body; the info panel shows time, contacts and
// solver iterations; a click on a readout plots it and the
// CSV export holds the plotted series; the screenshot export is a PNG; the camera chooser
// tracks a body and draws from a model camera. On the mug (a
// free body): a double-click selects it and a Ctrl+drag pulls it up. Screenshots of each
// model go to --shots.
//
//   node web/test/view_e2e.mjs --simlab build/simlab [--shots DIR] [--require yes]
//
// Exits 77 (ctest: skipped) when the WASM build, Chromium or playwright-core is missing
// (with --require yes: fails).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { collectProblems, openLabSession, pictureStats } from './browser_harness.mjs';
import { openBuilds, parseOptions, repoRoot } from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  shots: path.join(os.tmpdir(), 'simlab-view-e2e'),
  corpus: path.resolve(repoRoot, '../shared/corpus/mujoco/model'),
  chromium: '/usr/bin/chromium',
});

function check(condition, message) {
  if (!condition) throw new Error(message);
  console.log(`ok: ${message}`);
}

// `simlab view MODEL` in Chromium: the page with its lab mounted, and the page's errors.
async function openViewer(model) {
  const session = await openLabSession(options, ['view', model]);
  const page = await session.browser.newPage({ viewport: { width: 1100, height: 1000 } });
  const problems = collectProblems(page);
  await page.goto(session.url);
  await page.waitForFunction(() => window.lab || document.querySelector('.simlab-lab-error'), null,
                             { timeout: 60000 });
  const error = await page.evaluate(() => (window.lab ? '' : document.querySelector('.simlab-lab-error').textContent));
  if (error) throw new Error(`${path.basename(model)} did not load: ${error}`);
  return { session, page, problems };
}

// Waits until the lab's simulation time is at least `seconds` past where it is now (at
// most a minute of wall time): physics checks wait for simulated time, so a busy machine
// drawing a few frames a second passes them as a fast one does.
async function waitForSimTime(page, seconds) {
  const start = await page.evaluate(() => window.lab.sim.time);
  await page.waitForFunction((t) => window.lab.sim.time >= t, start + seconds, { timeout: 60000 });
}

// Opens `model` in the viewer, runs `checks(page)`, then checks that the page logged no
// errors (named `name`) and closes it.
async function inViewer(model, name, checks) {
  const { session, page, problems } = await openViewer(model);
  try {
    await checks(page);
    check(problems.length === 0, `${name}: no page errors${problems.length ? `: ${problems.join('; ')}` : ''}`);
  } finally {
    await session.close();
  }
}

// Loads, draws, and has a slider per control entry; a screenshot of the page.
async function checkLoads(page, name) {
  await page.waitForTimeout(700);
  const stats = await page.evaluate(pictureStats);
  await page.screenshot({ path: path.join(options.shots, `view_${name}.png`) });
  check(stats.colours >= 8 && stats.unlike >= 0.002,
        `${name}: the picture has ${stats.colours} colours, ${(100 * stats.unlike).toFixed(1)}% unlike its corner`);
  const nu = await page.evaluate(() => window.lab.sim.sizes().nu);
  const sliders = await page.locator('.simlab-lab-control input[type=range]').count();
  check(sliders === nu, `${name}: ${sliders} sliders for nu = ${nu}`);
  await page.screenshot({ path: path.join(options.shots, `view_${name}.png`) });
  const info = await page.locator('.simlab-lab-info').textContent();
  const ncon = await page.evaluate(() => window.lab.sim.counts().ncon);
  check(/time +\d/.test(info) && /contacts +\d+/.test(info) && /solver +\d+ iterations/.test(info),
        `${name}: the info panel shows ${info.split('\n').length} lines (${info.split('\n').slice(0, 4).join('; ')}; ncon now ${ncon})`);
}

// The first slider clicked with the mouse near its top: ctrl follows, and so does the
// actuator's force (it changes from what it was; the humanoid's motors: gear * ctrl).
async function checkSlider(page, name) {
  const slider = page.locator('.simlab-lab-control input[type=range]').first();
  const box = await slider.boundingBox();
  const forceBefore = await page.evaluate(() => window.lab.sim.data('actuator_force')[0]);
  await page.mouse.click(box.x + box.width - 12, box.y + box.height / 2);
  await page.waitForTimeout(200);
  const [value, min, max, ctrl, force] = await page.evaluate(() => {
    const lab = window.lab, s = lab.controls[0].slider;
    return [Number(s.value), Number(s.min), Number(s.max), lab.sim.data('ctrl')[0], lab.sim.data('actuator_force')[0]];
  });
  check(value > min + 0.75 * (max - min) && ctrl === value && force !== forceBefore,
        `${name}: the mouse set slider 0 to ${value.toFixed(3)} (of ${min}..${max}): ctrl[0] = ${ctrl.toFixed(3)}, ` +
        `actuator_force[0] ${forceBefore.toFixed(3)} -> ${force.toFixed(3)}`);
}

// Playing, the page keeps real time (measured over 3 s of the lab's own clock): prints
// the frame rate and the engine's share of the wall time (stepping, against drawing).
async function checkRealTime(page, name) {
  await page.waitForTimeout(1000);
  const clock0 = await page.evaluate(() => window.lab.clock());
  await page.waitForTimeout(3000);
  const clock1 = await page.evaluate(() => window.lab.clock());
  const stats = await page.evaluate(() => window.lab.stats);
  const wall = (clock1.wall - clock0.wall) / 1000;
  const rtf = (clock1.time - clock0.time) / wall;
  const fps = (clock1.frames - clock0.frames) / wall;
  const share = stats.engineFactor > 0 ? stats.realTimeFactor / stats.engineFactor : 0;
  check(rtf >= 0.97 && rtf <= 1.03,
        `${name} keeps real time: real-time factor ${rtf.toFixed(3)} over ${wall.toFixed(1)} s at ${fps.toFixed(1)} fps; ` +
        `the engine takes ${(100 * share).toFixed(1)}% of the wall time (${stats.engineFactor.toFixed(0)}x real time)`);
}

// simulate's keys, pressed on the page (not in a form field).
async function checkKeys(page) {
  const time = () => page.evaluate(() => window.lab.sim.time);
  await page.locator('h1').click();
  await page.keyboard.press('Space');
  const paused = await time();
  await page.waitForTimeout(300);
  const later = await time();
  check(later === paused && paused > 0, `Space paused the simulation at t = ${paused.toFixed(3)} (still ${later.toFixed(3)} 300 ms later)`);
  const dt = await page.evaluate(() => window.lab.timestep);
  await page.keyboard.press('ArrowRight');
  const stepped = await time();
  check(Math.abs(stepped - paused - dt) < 1e-12, `Right arrow took one step of ${dt} s (t = ${stepped.toFixed(4)})`);
  await page.keyboard.press('Backspace');
  check(await time() === 0, 'Backspace reset the time to 0');
  await page.keyboard.press('-');
  await page.keyboard.press('-');
  const slow = await page.locator('select.simlab-lab-speed').inputValue();
  check(Number(slow) === 0.25, `'-' twice slowed to speed ${slow}`);
  await page.keyboard.press('=');
  await page.keyboard.press('=');
  await page.keyboard.press('Space');
  await page.waitForTimeout(1000);
  const rtf = await page.evaluate(() => window.lab.stats.realTimeFactor);
  check(rtf > 0.5, `'=' twice back to speed 1, Space plays again (real-time factor ${rtf.toFixed(2)})`);
}

// The history: paused, Left arrow goes back one state at a time (time by one timestep,
// the recorded qpos exactly), Right arrow forward again; the slider goes back to the
// oldest state kept; playing on from the past drops the states after it (the slider's
// newest end is the state played from).
async function checkHistory(page) {
  const now = () => page.evaluate(() => ({ time: window.lab.sim.time, qpos: Array.from(window.lab.sim.data('qpos')),
                                         history: window.lab.sim.history() }));
  await page.locator('h1').click();
  await page.waitForTimeout(1500);
  await page.keyboard.press('Space');
  const newest = await now();
  const dt = await page.evaluate(() => window.lab.timestep);
  await page.keyboard.press('ArrowLeft');
  await page.keyboard.press('ArrowLeft');
  const back2 = await now();
  check(back2.history.back === 2 && Math.abs(newest.time - back2.time - 2 * dt) < 1e-9,
        `Left arrow twice: 2 states back, t = ${back2.time.toFixed(4)} (was ${newest.time.toFixed(4)})`);
  const text = await page.locator('.simlab-lab-history-text').textContent();
  check(text === `-${(2 * dt).toFixed(3)} s`, `the history shows "${text}"`);
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowRight');
  const again = await now();
  check(again.history.back === 0 && again.time === newest.time && again.qpos.join() === newest.qpos.join(),
        'Right arrow twice: the newest state again, qpos equal to the bit');
  const slider = page.getByRole('slider', { name: 'history' });
  await slider.focus();
  await slider.press('Home');
  const oldest = await now();
  check(oldest.history.back === oldest.history.size - 1 && oldest.history.size > 100,
        `the slider's left end is the oldest state kept: t = ${oldest.time.toFixed(3)}, ` +
        `${oldest.history.size} states (${oldest.history.capacity} at most)`);
  await page.evaluate(() => document.activeElement.blur());
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('Space');
  // (until it has stepped: a loaded machine draws few frames)
  await page.waitForFunction((t) => window.lab.sim.time > t, oldest.time + 1.5 * dt, { timeout: 20000 });
  await page.keyboard.press('Space');
  const played = await now();
  check(played.history.back === 0 && played.time > oldest.time && played.history.size < oldest.history.size,
        `playing on from the past dropped the newer states: ${played.history.size} kept at t = ${played.time.toFixed(3)}`);
  await page.keyboard.press('Space');
}

// Labels: the label chooser names every body over the view, at its position.
async function checkLabels(page) {
  await page.locator('select.simlab-lab-label-kind').selectOption('body');
  await page.waitForTimeout(300);
  const shown = await page.evaluate(() => Array.from(document.querySelectorAll('.simlab-lab-label'))
    .filter((e) => e.style.display !== 'none').map((e) => e.textContent));
  const nbody = await page.evaluate(() => window.lab.sim.sizes().nbody);
  check(shown.includes('torso') && shown.length === nbody - 1, `body labels: ${shown.join(', ')}`);
  await page.screenshot({ path: path.join(options.shots, 'view_labels.png') });
  await page.locator('select.simlab-lab-label-kind').selectOption('');
  await page.waitForTimeout(200);
  const left = await page.evaluate(() => Array.from(document.querySelectorAll('.simlab-lab-label'))
    .filter((e) => e.style.display !== 'none').length);
  check(left === 0, 'no labels chosen: none shown');
}

// The lint panel: the humanoid's findings at its default state (a note for each of its
// 21 geared motors, and for the 4 joints its keyframes put slightly past their ranges), and
// a picked finding marks its body in the view (it glows and carries
// the check's name).
async function checkLint(page) {
  const summary = await page.locator('.simlab-lab-lint summary').textContent();
  check(summary === 'lint: 0 warnings, 25 notes', `the lint panel says "${summary}"`);
  await page.locator('.simlab-lab-lint summary').click();
  const row = page.locator('.simlab-lab-lint-finding', { hasText: '"abdomen_z" [gear-scales-force]' }).first();
  const head = await row.locator('.head').textContent();
  await row.click();
  await page.waitForTimeout(200);
  const marked = await page.evaluate(() => {
    const labels = Array.from(document.querySelectorAll('.simlab-lab-label')).filter((e) => e.style.display !== 'none');
    const glowing = window.lab.scene.geoms.filter(({ mesh }) => mesh.material.emissive.getHex() === 0x404000).length;
    return { labels: labels.map((e) => e.textContent), glowing };
  });
  check(/^note: actuator "abdomen_z" \[gear-scales-force\] \(humanoid.xml:\d+\)$/.test(head) && marked.glowing > 0 &&
        marked.labels.includes('gear-scales-force: actuator "abdomen_z"'),
        `picking "${head}" marks its body: ${marked.glowing} geoms glow, label "${marked.labels.at(-1)}"`);
  await page.screenshot({ path: path.join(options.shots, 'view_lint.png') });
  await page.locator('.simlab-lab-lint summary').click();
}

// A click on a readout plots it; the CSV export holds its series; the screenshot export
// is a PNG.
async function checkPlotAndExports(page) {
  const readout = page.locator('.simlab-lab-readout').first();
  const label = await readout.locator('.label').textContent();
  await readout.click();
  await page.waitForTimeout(1500);
  const traces = await page.evaluate(() => window.lab.plots.filter((p) => p.picked).map((p) => p.traces.length));
  check(traces.length === 1 && traces[0] === 1, `a click on readout "${label}" made a plot of it`);
  const [download] = await Promise.all([page.waitForEvent('download'), page.locator('button.simlab-lab-csv').click()]);
  const csv = fs.readFileSync(await download.path(), 'utf8').split('\n');
  const rows = csv.slice(1, csv.indexOf('')).map((line) => line.split(',').map(Number));
  check(csv[0] === `"time","${label}"` && rows.length >= 5 && rows.every((r) => r.length === 2 && r.every(Number.isFinite)),
        `the CSV export (${download.suggestedFilename()}) holds the plotted series: header ${csv[0]}, ${rows.length} rows`);
  const [shot] = await Promise.all([page.waitForEvent('download'), page.locator('button.simlab-lab-screenshot').click()]);
  const png = fs.readFileSync(await shot.path());
  check(png.subarray(1, 4).toString() === 'PNG' && png.length > 5000,
        `the screenshot export is a PNG of ${png.length} bytes (${shot.suggestedFilename()})`);
}

// A double-click on the free body selects it; a Ctrl+drag upwards pulls it up (its
// height while the drag is held), and letting go drops it again.
async function checkPerturbation(page, body) {
  const at = await page.evaluate((b) => {
    const lab = window.lab;
    const xpos = lab.sim.data('xipos').slice(3 * b, 3 * b + 3);
    const p = lab.scene.camera.position.clone().set(...xpos).project(lab.scene.camera);
    const box = lab.scene.renderer.domElement.getBoundingClientRect();
    return { x: box.left + (p.x + 1) / 2 * box.width, y: box.top + (1 - p.y) / 2 * box.height, z: xpos[2] };
  }, body);
  await page.mouse.dblclick(at.x, at.y);
  const selected = await page.evaluate(() => window.lab.sim.perturbState().select);
  check(selected === body, `a double-click at (${at.x.toFixed(0)}, ${at.y.toFixed(0)}) selected body ${selected}`);
  const height = () => page.evaluate((b) => window.lab.sim.data('xipos')[3 * b + 2], body);
  await page.keyboard.down('Control');
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  // (200 pixels up the screen: about half a metre at the mug's distance; the spring, 100 per
  // unit mass as MuJoCo's default, sags about 0.1 m under gravity)
  for (let k = 1; k <= 25; k++) await page.mouse.move(at.x, at.y - 8 * k);
  await waitForSimTime(page, 1);
  const [pulled, line] = [await height(), await page.evaluate(() => window.lab.scene.perturbLine.visible)];
  await page.screenshot({ path: path.join(options.shots, 'view_perturb.png') });
  await page.mouse.up();
  await page.keyboard.up('Control');
  await waitForSimTime(page, 1);
  const dropped = await height();
  check(pulled > at.z + 0.1 && line && dropped < pulled - 0.05,
        `a Ctrl+drag pulled it from z = ${at.z.toFixed(3)} to ${pulled.toFixed(3)} (line drawn: ${line}); ` +
        `let go, it fell to ${dropped.toFixed(3)}`);
}

// The camera chooser: ']' tracks the first moving body (the view's target is its subtree
// centre of mass), the model's camera "side" draws from cam_xpos with its field of view
// (a screenshot), and Escape returns to the free camera.
async function checkCameras(page) {
  const select = page.locator('select.simlab-lab-camera');
  const labels = await select.locator('option').allTextContents();
  check(labels.includes('track torso') && labels.includes('camera side'),
        `the camera chooser offers ${labels.length} cameras (${labels.slice(0, 3).join(', ')}, ...)`);
  await page.locator('.simlab-lab-canvas').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press(']');
  await page.waitForTimeout(300);
  const tracked = await page.evaluate(() => {
    const lab = window.lab, body = lab.sim.nameToId('body', 'torso');
    lab.scene.render();
    const com = Array.from(lab.sim.data('subtree_com').slice(3 * body, 3 * body + 3));
    return { value: lab.cameraSelect.value, target: [...lab.scene.view.target], com };
  });
  const gap = Math.max(...tracked.target.map((v, k) => Math.abs(v - tracked.com[k])));
  check(tracked.value === '1' && gap < 0.05,
        `']' tracks the torso: the view's target is ${gap.toExponential(1)} m from its centre of mass`);
  const side = labels.indexOf('camera side');
  await select.selectOption(String(side));
  await page.waitForTimeout(300);
  const fixed = await page.evaluate(() => {
    const lab = window.lab, cam = lab.sim.nameToId('camera', 'side');
    lab.scene.render();
    const pos = Array.from(lab.sim.data('cam_xpos').slice(3 * cam, 3 * cam + 3));
    return { pos, drawn: lab.scene.camera.position.toArray(), fov: lab.scene.camera.fov,
             fovy: lab.sim.model('cam_fovy')[cam] };
  });
  const off = Math.max(...fixed.pos.map((v, k) => Math.abs(v - fixed.drawn[k])));
  check(off < 1e-6 && fixed.fov === fixed.fovy,
        `the model camera "side" draws from cam_xpos (${off.toExponential(1)} m off) with fovy ${fixed.fov}`);
  await page.screenshot({ path: path.join(options.shots, 'view_camera_side.png') });
  await page.locator('.simlab-lab-canvas').click({ position: { x: 5, y: 5 } });
  await page.keyboard.press('Escape');
  const free = await page.evaluate(() => window.lab.cameraSelect.value);
  check(free === '0', 'Escape goes back to the free camera');
}

async function testModel(file, interactive) {
  const name = path.basename(file, '.xml');
  await inViewer(path.join(options.corpus, file), name, async (page) => {
    await checkLoads(page, name);
    if (await page.evaluate(() => window.lab.sim.sizes().nu) > 0) await checkSlider(page, name);
    if (interactive) {
      await checkRealTime(page, name);
      await checkKeys(page);
      await checkHistory(page);
      await checkLabels(page);
      await checkLint(page);
      await checkPlotAndExports(page);
      await checkCameras(page);
    }
    if (name === 'mug') await checkPerturbation(page, 1);
  });
}

// A model with skins (tests/compiler_models/skins.xml: a sleeve over a swinging arm and
// hand, a .skn tetrahedron, a triangle on the world): each skin is drawn, its vertices
// follow the bones (the sleeve moves as the arm swings) and stay finite; a screenshot.
async function testSkins() {
  await inViewer(path.join(repoRoot, 'tests/compiler_models/skins.xml'), 'skins', async (page) => {
    const sample = () => page.evaluate(() => window.lab.scene.skins.meshes.map(({ mesh }) =>
      Array.from(mesh.geometry.attributes.position.array)));
    await waitForSimTime(page, 0.3);
    const before = await sample();
    await waitForSimTime(page, 1.2);
    const after = await sample();
    await page.screenshot({ path: path.join(options.shots, 'view_skins.png') });
    check(before.length === 3, `skins: ${before.length} skins drawn`);
    check(after.flat().every(Number.isFinite) && after.flat().some((v) => v !== 0),
          'skins: their vertices are finite and placed');
    const moved = Math.max(...before[0].map((v, k) => Math.abs(v - after[0][k])));
    const still = Math.max(...before[2].map((v, k) => Math.abs(v - after[2][k])));
    check(moved > 1e-3 && still === 0,
          `skins: the sleeve follows the swinging arm (moved ${moved.toFixed(3)}), the world's triangle stays (${still})`);
  });
}

// sdf geoms (tests/conformance/corpus/sdf/sdf_drops.xml: shapes dropped on a static sdf
// icosahedron): the sdf geoms are drawn as their meshes, and the falling shapes come to
// rest on the rock (contacts with it) rather than falling through; a screenshot.
async function testSdf() {
  await inViewer(path.join(repoRoot, 'tests/conformance/corpus/sdf/sdf_drops.xml'), 'sdf', async (page) => {
    await page.waitForFunction(() => window.lab.sim.time > 0.5, null, { timeout: 30000 });
    const drawn = await page.evaluate(() => {
      const type = window.lab.sim.model('geom_type');
      return window.lab.scene.geoms.filter(({ g }) => type[g] === 8).length;
    });
    const onRock = await page.evaluate(() => {
      const sim = window.lab.sim;
      return sim.contacts().filter((c) => c.geom1 === 1 || c.geom2 === 1).length;
    });
    await page.screenshot({ path: path.join(options.shots, 'view_sdf.png') });
    check(drawn === 2, `sdf: ${drawn} of 2 sdf geoms drawn as their meshes`);
    check(onRock > 0, `sdf: ${onRock} contacts with the sdf rock at t > 0.5 s`);
  });
}

// Drags the mouse dx pixels across the middle of the scene (left button: orbit); returns
// how many degrees the free camera's azimuth turned.
async function dragOrbit(page, dx) {
  const at = await page.evaluate(() => {
    const box = window.lab.scene.renderer.domElement.getBoundingClientRect();
    return { x: box.left + box.width / 2, y: box.top + box.height / 2, az: window.lab.scene.view.azimuth };
  });
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) await page.mouse.move(at.x + dx * k / 8, at.y);
  await page.mouse.up();
  return await page.evaluate(() => window.lab.scene.view.azimuth) - at.az;
}

// Flexes (MuJoCo's flag.xml, a cloth flapping from one pinned corner, and softbox.xml, a
// soft box of radial sliders): each flex is drawn from flexvert_xpos, its drawn vertices
// are the engine's (finite), and the cloth deforms as it moves (its drawn shape is no
// longer the flat grid it starts as); a screenshot of each.
async function testFlexes() {
  for (const [file, name] of [['flex/flag.xml', 'flag'], ['flex/softbox.xml', 'softbox']]) {
    await inViewer(path.join(options.corpus, file), name, async (page) => {
      await page.waitForFunction(() => window.lab.sim.time > 0.6, null, { timeout: 60000 });
      const drawn = await page.evaluate(() => {
        const lab = window.lab, items = lab.scene.flexes.items;
        const xpos = lab.sim.data('flexvert_xpos');
        const position = items.length ? Array.from(items[0].object.geometry.attributes.position.array) : [];
        const off = Math.max(...position.map((v, k) => Math.abs(v - xpos[k])));
        // The spread of the drawn vertices along z: a flat horizontal grid has none.
        const z = position.filter((v, k) => k % 3 === 2);
        return { count: items.length, n: position.length / 3, off, finite: position.every(Number.isFinite),
                 zspread: Math.max(...z) - Math.min(...z) };
      });
      // The wind (5 5 0) streams the flag along x = y: a user drags the view round to face
      // it (112 pixels left, 45 degrees of azimuth) before the picture.
      if (name === 'flag') {
        const turned = await dragOrbit(page, -112);
        check(Math.abs(turned - 45) < 1, `flag: a drag turned the free camera by ${turned.toFixed(1)} degrees`);
      }
      await page.screenshot({ path: path.join(options.shots, `view_flex_${name}.png`) });
      check(drawn.count === 1 && drawn.n > 0 && drawn.finite,
            `${name}: the flex is drawn, ${drawn.n} vertices, all finite`);
      check(drawn.off < 1e-6, `${name}: drawn vertices are the engine's flexvert_xpos (${drawn.off.toExponential(1)} off)`);
      if (name === 'flag') check(drawn.zspread > 0.1, `flag: the cloth hangs and folds (z spread ${drawn.zspread.toFixed(2)} m)`);
    });
  }
}

async function main() {
  await openBuilds(options);
  fs.mkdirSync(options.shots, { recursive: true });
  await testModel('humanoid/humanoid.xml', true);
  for (const file of ['mug/mug.xml', 'cards/cards.xml', 'cube/cube_3x3x3.xml', 'car/car.xml']) {
    await testModel(file, false);
  }
  await testSkins();
  await testSdf();
  await testFlexes();
  console.log(`screenshots in ${options.shots}`);
  console.log('PASS');
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

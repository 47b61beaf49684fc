// The lab end to end in headless Chromium (Debian's, driven by playwright-core), on the
// lesson page as a student gets it: starts `simlab lab LESSON`, opens its page and finds
// the live lab in the lesson. Checks the lab against its block in the lesson (title,
// camera, sliders with labels, units, ranges, steps and initial values, readouts, plot
// traces, window and dashes, note, dock) and that its picture is not blank; turns the
// toggles on (contact points, force arrows and joint axes appear, and go again when
// turned off); drags the carriage z slider to -0.33 and the grip slider to 0 (mouse,
// then arrow keys for the exact value), waits for the grip force readout to reach the
// grip actuator's forcerange (read from model.actuator_forcerange) with both finger
// readouts equal, then raises z slowly with the arrow keys: the cube height readout must
// rise, and stay up. Saves screenshots before and after, checks the frame rate and
// real-time factor shown on the page, and finally drives the sliders through the lab's
// API with pacing off and compares every readout with the same expressions evaluated on
// `simlab rollout` of the same control sequence. A second page (web/lab/index.html with
// web/lab/fixtures/all_geoms.json) draws every geom type and shows bad expressions as
// errors.
//
//   node web/test/lab_e2e.mjs --simlab build/simlab [--lesson PATH] [--shots DIR]
//                             [--tol 1e-12] [--require yes]
//
// Exits 77 (ctest: skipped) when the WASM build, Chromium or playwright-core is missing
// (with --require yes: fails).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { evaluateExpr, parseExpr } from '../lab/expr.mjs';
import { parseLesson } from '../lesson/parse.mjs';
import { collectProblems, kDefaultLesson, openLabSession, pictureStats } from './browser_harness.mjs';
import {
  nativeRollout, openBuilds, parseOptions, repoRoot,
} from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  dist: path.join(repoRoot, 'web/dist'),
  lesson: kDefaultLesson,
  shots: path.join(os.tmpdir(), 'simlab-lab-e2e'),
  tol: '1e-12',
  chromium: '/usr/bin/chromium',
});

// A screenshot of the lab (on the lesson page: the lab's section) into --shots.
async function shoot(page, name) {
  await page.locator('section.lab-mount').screenshot({ path: path.join(options.shots, name) });
}

function check(condition, message) {
  if (!condition) throw new Error(message);
  console.log(`ok: ${message}`);
}

// The readouts shown on the page: {label: {value, text, error}}.
async function readouts(page) {
  const list = await page.evaluate(() => window.lab.readoutValues());
  return Object.fromEntries(list.map((r) => [r.label, r]));
}

// Drags slider `label` with the mouse to about `value`, then arrow keys to exactly it.
async function dragSlider(page, label, value) {
  const slider = page.getByRole('slider', { name: label });
  const box = await slider.boundingBox();
  const [min, max, step, current] = await slider.evaluate((s) => [s.min, s.max, s.step, s.value].map(Number));
  const x = (v) => box.x + 8 + (box.width - 16) * (v - min) / (max - min);
  await page.mouse.move(x(current), box.y + box.height / 2);
  await page.mouse.down();
  for (let k = 1; k <= 10; k++) await page.mouse.move(x(current + (value - current) * k / 10), box.y + box.height / 2);
  await page.mouse.up();
  const dragged = Number(await slider.inputValue());
  check(Math.abs(dragged - value) <= Math.max(3 * step, 0.05 * (max - min)),
        `the mouse moved slider "${label}" from ${current} to ${dragged} (aiming at ${value})`);
  for (let guard = 0; guard < 200; guard++) {
    const now = Number(await slider.inputValue());
    if (Math.abs(now - value) < step / 2) break;
    await slider.press(now < value ? 'ArrowRight' : 'ArrowLeft');
  }
  const final = Number(await slider.inputValue());
  check(Math.abs(final - value) < step / 2, `slider "${label}" dragged to ${final}`);
}

// Waits (real time, at most `seconds`) until `predicate(readouts)` holds (it may be
// async), checking `invariant` on the way; the readouts then, or null.
async function waitFor(page, seconds, predicate, invariant = () => {}) {
  const end = Date.now() + 1000 * seconds;
  for (;;) {
    const r = await readouts(page);
    invariant(r);
    if (await predicate(r)) return r;
    if (Date.now() > end) return null;
    await page.waitForTimeout(50);
  }
}

// Samples the readouts for `seconds` (real time), the finger readouts equal in each;
// returns how many samples were taken.
async function fingersStayEqual(page, seconds) {
  const end = Date.now() + 1000 * seconds;
  let samples = 0;
  do {
    fingersEqual(await readouts(page));
    samples++;
    await page.waitForTimeout(50);
  } while (Date.now() < end);
  return samples;
}

function fingersEqual(r) {
  if (r['left finger (m)'].text !== r['right finger (m)'].text) {
    throw new Error(`finger readouts differ: ${r['left finger (m)'].text} vs ${r['right finger (m)'].text}`);
  }
}

// The student's session, paced in real time.
async function interactive(page, spec) {
  const gripId = await page.evaluate(() => window.lab.sim.nameToId('actuator', 'gripper/grip'));
  const range = await page.evaluate((id) => Array.from(window.lab.sim.model('actuator_forcerange')).slice(2 * id, 2 * id + 2), gripId);
  check(gripId === 3 && range[0] < range[1], `grip actuator ${gripId} has forcerange [${range}]`);
  await page.waitForTimeout(1000);
  await shoot(page, 'lab_before.png');

  await dragSlider(page, 'ctrl[2]: carriage z target', -0.33);
  const carriageZ = () => page.evaluate(() => window.lab.sim.data('qpos')[2]);
  const lowered = await waitFor(page, 10, async () => Math.abs((await carriageZ()) + 0.33) < 0.006, fingersEqual);
  check(lowered !== null, 'the carriage came down to z = -0.33 (within 6 mm)');
  await dragSlider(page, 'ctrl[3]: grip half-opening', 0);
  // Closing pulls the fingers to lower qpos: the force saturates at the lower bound.
  const bound = range[0];
  const gripped = await waitFor(page, 5, (r) => Math.abs(r['grip force (N)'].value - bound) < 1e-9, fingersEqual);
  check(gripped !== null, `grip force readout reaches the forcerange bound ${bound}: ${gripped?.['grip force (N)'].text} N`);
  const samples = await fingersStayEqual(page, 0.3);
  check(samples > 0, `finger readouts stayed equal while the gripper closed (${samples} samples)`);
  await shoot(page, 'lab_gripped.png');
  await checkInset(page, 'the closed grip', true);
  const before = (await readouts(page))['cube z (m)'].value;
  const clock0 = await page.evaluate(() => window.lab.clock());

  // Raise z slowly, 5 mm at a time, from -0.33 to -0.18.
  const z = page.getByRole('slider', { name: 'ctrl[2]: carriage z target' });
  for (let k = 0; k < 30; k++) {
    await z.press('ArrowRight');
    await page.waitForTimeout(40);
    fingersEqual(await readouts(page));
  }
  await page.waitForTimeout(500);
  const after = await readouts(page);
  const clock1 = await page.evaluate(() => window.lab.clock());
  const stats = await page.evaluate(() => window.lab.stats);
  const dropped = await page.evaluate(() => window.lab.pacer.dropped);
  await shoot(page, 'lab_after.png');
  check(after['cube z (m)'].value > before + 0.1,
        `cube height readout rose from ${before.toFixed(4)} to ${after['cube z (m)'].text} m`);
  const cube = await page.evaluate(() => Array.from(window.lab.sim.data('qpos')).slice(5, 8));
  await checkPicture(page, cube, 'the lifted cube');
  await checkInset(page, 'the lifted cube', false);
  const rtf = (clock1.time - clock0.time) / ((clock1.wall - clock0.wall) / 1000);
  const shown = await page.locator('.simlab-lab-stats').textContent();
  console.log(`page shows "${shown}"; real-time factor over the raise ${rtf.toFixed(4)} ` +
              `(${(clock1.time - clock0.time).toFixed(3)} s simulated), frame rate ${stats.fps.toFixed(1)} fps, ` +
              `engine ${stats.engineFactor.toFixed(0)}x real time`);
  const [, fpsShown, rtfShown] = /^(\d+) fps, real-time factor (\d+\.\d\d)/.exec(shown) ?? [];
  check(Number(fpsShown) >= 1 && Math.abs(Number(rtfShown) - 1) <= 0.05,
        `the page shows its frame rate (${fpsShown} fps) and real-time factor (${rtfShown})`);
  const stepsPerFrame = (clock1.steps - clock0.steps) / (clock1.frames - clock0.frames);
  check(stepsPerFrame > 1, `several steps per frame: ${stepsPerFrame.toFixed(1)} on average over the raise`);
  check(rtf >= 0.97 && rtf <= 1.03 && stats.engineFactor >= 1,
        `the page keeps real time: ${rtf.toFixed(4)} over the raise, engine ${stats.engineFactor.toFixed(0)}x ` +
        `(${dropped.toFixed(3)} s of wall time dropped since mounting)`);
  // Held up, the cube stays in the grip (the model's hard elliptic friction stops the creep).
  await page.waitForTimeout(2000);
  const held = await readouts(page);
  check(Math.abs(held['cube z (m)'].value - after['cube z (m)'].value) < 2e-3,
        `two seconds later the cube is still held at ${held['cube z (m)'].text} m`);
  await checkPlotWindow(page, spec.plots[0].window);
  await orbit(page);
  await pauseAndReset(page, spec);
  return range;
}

// The pause button stops time; reset goes back to the keyframe with the sliders at their
// initial values.
async function pauseAndReset(page, spec) {
  await page.getByRole('button', { name: 'pause' }).click();
  const t0 = await page.evaluate(() => window.lab.sim.time);
  await page.waitForTimeout(300);
  const t1 = await page.evaluate(() => window.lab.sim.time);
  const samples = await page.evaluate(() => window.lab.plots.map(({ plot }) => plot.columns[0].length));
  await page.waitForTimeout(300);
  const samplesLater = await page.evaluate(() => window.lab.plots.map(({ plot }) => plot.columns[0].length));
  check(samples.join() === samplesLater.join(), `plots hold ${samples} samples while paused`);
  // Paused, a slider still acts at once: opening the grip turns its force from -5 N to +5 N.
  await page.getByRole('slider', { name: 'ctrl[3]: grip half-opening' }).evaluate((slider) => {
    slider.value = '0.04';
    slider.dispatchEvent(new Event('input', { bubbles: true }));
  });
  const opened = await waitFor(page, 5, (r) => r['grip force (N)'].text === '5.00');
  const tPaused = await page.evaluate(() => window.lab.sim.time);
  check(opened !== null && tPaused === t0,
        `paused, opening the grip shows ${opened?.['grip force (N)'].text} N at once (time still ${tPaused.toFixed(3)} s)`);
  await page.getByRole('button', { name: 'reset' }).click();
  const state = await page.evaluate(() => ({
    time: window.lab.sim.time, qpos: Array.from(window.lab.sim.data('qpos')),
    ctrl: Array.from(window.lab.sim.data('ctrl')),
    sliders: window.lab.controls.map(({ slider }) => Number(slider.value)),
  }));
  const key = await page.evaluate(() => Array.from(window.lab.sim.model('key_qpos') ?? []).slice(0, 12));
  check(t1 === t0 && state.time === 0 && state.sliders.join() === spec.controls.map((c) => c.value).join() &&
        state.ctrl.join() === '0.12,0,0,0.04' && (key.length === 0 || state.qpos.join() === key.join()),
        `pause holds time at ${t0.toFixed(3)} s; reset: time 0, sliders ${state.sliders}, ctrl ${state.ctrl}`);
  await page.getByRole('button', { name: 'play' }).click();
}

// The mouse orbits (dragging up lowers the elevation, as the camera rises) and zooms.
async function orbit(page) {
  const canvas = await page.locator('canvas.simlab-lab-canvas').boundingBox();
  const view0 = await page.evaluate(() => ({ ...window.lab.scene.view }));
  let [cx, cy] = [canvas.x + canvas.width / 2, canvas.y + canvas.height / 2];
  // Before the view is clicked, the wheel scrolls the page, not the camera.
  await page.mouse.move(cx, cy + 50);
  await page.mouse.wheel(0, -100);
  await page.waitForTimeout(200);
  const unfocused = await page.evaluate(() => window.lab.scene.view.distance);
  check(unfocused === view0.distance, `the wheel over an unclicked view leaves the camera at ${unfocused}`);
  // The page may have scrolled: where the view is now.
  const moved = await page.locator('canvas.simlab-lab-canvas').boundingBox();
  [cx, cy] = [moved.x + moved.width / 2, moved.y + moved.height / 2];
  await page.mouse.move(cx, cy + 50);
  await page.mouse.down();
  await page.mouse.move(cx + 30, cy - 50, { steps: 10 });
  await page.mouse.up();
  await page.mouse.wheel(0, -300);
  await page.waitForTimeout(300);
  const view1 = await page.evaluate(() => ({ ...window.lab.scene.view }));
  check(view1.elevation < view0.elevation - 30 && view1.azimuth !== view0.azimuth &&
        view1.distance < view0.distance,
        `mouse orbit and zoom: elevation ${view0.elevation} -> ${view1.elevation.toFixed(1)}, ` +
        `azimuth ${view0.azimuth} -> ${view1.azimuth.toFixed(1)}, distance ${view0.distance} -> ${view1.distance.toFixed(3)}`);
  await shoot(page, 'lab_orbit.png');
}

// The lab driven through its API with pacing off: slider moves at fixed steps. Returns
// the control rows per step and the readouts at checkpoints.
async function deterministic(page) {
  return page.evaluate(() => {
    const lab = window.lab;
    lab.pause();
    lab.reset();
    const rows = [];
    const checkpoints = [];
    // ctrl stays as the sliders left it between moves: one row per step, then the steps at once.
    const run = (steps) => {
      const ctrl = Array.from(lab.sim.data('ctrl'));
      for (let i = 0; i < steps; i++) rows.push(ctrl);
      lab.step(steps);
      checkpoints.push({ step: rows.length, readouts: lab.readoutValues().map((r) => r.value) });
    };
    lab.setControl(1, -0.33);
    run(500);
    lab.setControl(2, 0);
    run(500);
    for (let k = 1; k <= 30; k++) {
      lab.setControl(1, -0.33 + 0.01 * k);
      run(40);
    }
    run(200);
    return { rows, checkpoints, exprs: lab.spec.readouts.map((r) => r.expr),
             labels: lab.spec.readouts.map((r) => r.label) };
  });
}

// The API session did what the sliders asked: ctrl rows with z at -0.33 and the grip at
// 0, the grip force saturated once closed, the cube raised by the end.
function checkSliderSession(result, range) {
  const near = (x, y) => Math.abs(x - y) < 1e-12;
  const lowered = result.rows.findIndex((row) => near(row[2], -0.33));
  const closed = result.rows.findIndex((row) => near(row[2], -0.33) && row[3] === 0);
  check(lowered >= 0 && closed > lowered,
        `control rows hold z -0.33 from step ${lowered} and grip 0 from step ${closed}`);
  const readout = (checkpoint, label) => checkpoint.readouts[result.labels.indexOf(label)];
  const grip = result.checkpoints.map((c) => readout(c, 'grip force (N)'));
  const cube = result.checkpoints.map((c) => readout(c, 'cube z (m)'));
  const last = result.checkpoints.length - 1;
  check(Math.abs(grip[1] - range[0]) < 1e-9 && cube[last] > cube[1] + 0.1,
        `checkpoints: grip force ${grip[1]} N at the bound ${range[0]}, cube z ${cube[1].toFixed(4)} -> ` +
        `${cube[last].toFixed(4)} m`);
}

function compareWithNative(result) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'simlab-lab-'));
  const csv = path.join(dir, 'ctrl.csv');
  fs.writeFileSync(csv, result.rows.map((row) => row.map((x) => x.toPrecision(17)).join(',')).join('\n') + '\n');
  const native = nativeRollout(options.simlab, path.join(repoRoot, 'models/gantry_gripper.xml'),
                               { key: 0, ctrl: csv, steps: result.rows.length });
  fs.rmSync(dir, { recursive: true });
  const trees = result.exprs.map(parseExpr);
  let worst = 0;
  for (const { step, readouts: values } of result.checkpoints) {
    const record = native[step];
    if (record.step !== step) throw new Error(`native record ${step} is step ${record.step}`);
    const read = (source, name, i) => {
      if (source !== 'data' || !(name in record)) throw new Error(`native rollout has no ${source}.${name}`);
      return record[name][i];
    };
    trees.forEach((tree, k) => {
      const y = evaluateExpr(tree, read);
      worst = Math.max(worst, Math.abs(values[k] - y) / Math.max(1, Math.abs(y)));
    });
  }
  console.log(`readouts at ${result.checkpoints.length} checkpoints (${result.rows.length} steps) vs native ` +
              `simlab rollout: ${worst === 0 ? 'bit-identical' : `worst ${worst.toExponential(2)}`}`);
  check(worst <= Number(options.tol), `browser readouts equal native within ${options.tol}`);
}

// The lesson's lab block, as the lesson parser reads it in node.
function lessonLabSpec() {
  const blocks = parseLesson(fs.readFileSync(options.lesson, 'utf8')).blocks.filter((b) => b.type === 'lab');
  if (blocks.length !== 1 || blocks[0].error) throw new Error(`expected one good lab block in ${options.lesson}`);
  return blocks[0].spec;
}

// What the mounted lab shows, read from the page's DOM and its plot.
function shownLab() {
  const lab = window.lab;
  const root = lab.root;
  const texts = (selector) => Array.from(root.querySelectorAll(selector), (e) => e.textContent.trim());
  const chart = lab.plots[0]?.plot.chart;
  return {
    title: root.querySelector('h3')?.textContent ?? '',
    dock: root.closest('section.lab-mount').classList.contains('lab-docked'),
    controls: lab.controls.map(({ slider, shown }) => ({
      label: slider.getAttribute('aria-label'), min: Number(slider.min), max: Number(slider.max),
      step: Number(slider.step), value: Number(slider.value), shown: shown.textContent.trim(),
    })),
    readoutLabels: texts('.simlab-lab-readout .label'),
    readoutTexts: texts('.simlab-lab-readout .value'),
    note: texts('.simlab-lab-note')[0] ?? '',
    toggles: Array.from(root.querySelectorAll('input[data-toggle]'), (b) => b.dataset.toggle),
    plot: chart && {
      labels: chart.series.slice(1).map((series) => series.label),
      dashed: chart.series.slice(1).map((series) => Array.isArray(series.dash) && series.dash.length > 0),
      ylabel: chart.axes[1].label, window: lab.plots[0].plot.window,
    },
    view: { ...lab.scene.view },
    cameraZ: lab.scene.camera.position.z,
  };
}

// The lab as its block asks: every field of the spec shows up on the page.
async function checkAgainstSpec(page, spec) {
  const shown = await page.evaluate(shownLab);
  check(shown.title === spec.title && shown.dock === (spec.dock === true),
        `title "${shown.title}", docked: ${shown.dock}`);
  spec.controls.forEach((c, k) => {
    const s = shown.controls[k];
    check(s.label === c.label && s.min === c.min && s.max === c.max && s.step === c.step &&
          s.value === c.value && s.shown === `${c.value} ${c.unit}`,
          `slider "${s.label}": ${s.min}..${s.max} step ${s.step}, starts at "${s.shown}"`);
  });
  check(shown.readoutLabels.join('|') === spec.readouts.map((r) => r.label).join('|'),
        `readouts in the block's order: ${shown.readoutLabels.join(', ')}`);
  spec.readouts.forEach((r, k) => {
    const decimals = (shown.readoutTexts[k].split('.')[1] ?? '').length;
    check(decimals === (r.digits ?? 3), `readout "${r.label}" shows ${shown.readoutTexts[k]} (${r.digits} digits)`);
  });
  const plot = spec.plots[0];
  check(shown.plot.labels.join('|') === plot.traces.map((t) => t.label).join('|') &&
        shown.plot.dashed.join() === plot.traces.map((t) => t.dash === true).join() &&
        shown.plot.ylabel === plot.ylabel && shown.plot.window === plot.window,
        `plot "${shown.plot.ylabel}": traces ${shown.plot.labels} dashed ${shown.plot.dashed}, window ${shown.plot.window} s`);
  check(shown.note === spec.note, 'the note is shown');
  check(shown.toggles.join() === spec.toggles.join(), `toggles: ${shown.toggles}`);
  const cam = spec.camera;
  const v = shown.view;
  check(v.azimuth === cam.azimuth && v.elevation === -cam.elevation && v.distance === cam.distance &&
        v.target.join() === cam.target.join() && shown.cameraZ > cam.target[2],
        `camera: azimuth ${v.azimuth}, ${cam.elevation} degrees above the horizon (camera z ` +
        `${shown.cameraZ.toFixed(3)} m), distance ${v.distance}, target ${v.target}`);
}

// The picture is not blank, and the cube (yellow) is where the camera should see it (the
// main camera, or with `inset` the close-up's).
async function checkPicture(page, cubePosition, name, inset = false) {
  const stats = await page.evaluate(pictureStats, [cubePosition, inset]);
  // (most of the 7 x 7 pixels round it: a contact point drawn on the cube may cover a few)
  const yellow = stats.around.filter(([r, g, b]) => r > b + 60 && g > b + 40).length;
  check(stats.colours >= 16 && stats.unlike > 0.2 && yellow > stats.around.length / 2,
        `${name}: ${stats.colours} colours, ${(100 * stats.unlike).toFixed(0)}% of it not sky, ` +
        `the cube at pixel (${stats.x}, ${stats.y})${inset ? ' of the inset' : ''} is yellow ` +
        `(rgb ${stats.at} there, ${yellow} of ${stats.around.length} pixels round it yellow)`);
}

// The lesson's lab shows the gantry's close-up camera in an inset, captioned: the cube
// seen through it (yellow), the fingertip in it and, with `floor`, the floor beside the
// cube too.
async function checkInset(page, name, floor) {
  const caption = await page.locator('.simlab-lab-inset').textContent();
  const rect = await page.evaluate(() => window.lab.scene.insetRect());
  check(caption === 'camera grip' && rect.width >= 200 && rect.height >= 200,
        `the inset shows "${caption}" at ${rect.width} x ${rect.height} px`);
  const qpos = await page.evaluate(() => Array.from(window.lab.sim.data('qpos')));
  await checkPicture(page, qpos.slice(5, 8), `${name} (inset)`, true);
  const fingertip = await page.evaluate(() => {
    const sim = window.lab.sim, g = sim.nameToId('geom', 'gripper/finger_left');
    const p = sim.data('geom_xpos'), size = sim.model('geom_size');
    return [p[3 * g], p[3 * g + 1], p[3 * g + 2] - size[3 * g + 2]];
  });
  const tip = await page.evaluate(pictureStats, [fingertip, true]);
  check(tip.inside, `${name}: the fingertip is in the inset, at pixel (${tip.x}, ${tip.y})`);
  if (!floor) return;
  const ground = await page.evaluate(pictureStats, [[qpos[5], qpos[6] - 0.05, 0], true]);
  check(ground.inside, `${name}: the floor beside the cube is in the inset, at pixel (${ground.x}, ${ground.y})`);
}

// In the page: how many overlay objects the view shows (contact points, contact and
// actuator force arrows, joint axes), and the contacts now.
function overlayCounts() {
  const scene = window.lab.scene;
  const visible = (list) => list.filter((o) => o.visible).length;
  return {
    points: visible(scene.contactPoints), contactArrows: visible(scene.arrows.contact.arrows),
    actuatorArrows: visible(scene.arrows.actuator.arrows), axes: visible(scene.arrows.axis.arrows),
    ncon: window.lab.sim.counts().ncon,
  };
}

// The toggles draw their overlays: one point per contact, force arrows, one axis per
// slide or hinge joint (5 in the gantry); turned off, nothing.
async function checkToggles(page) {
  const boxes = await page.locator('input[data-toggle]').all();
  for (const box of boxes) await box.check();
  await page.waitForTimeout(300);
  const on = await page.evaluate(overlayCounts);
  check(on.points === on.ncon && on.ncon > 0 && on.contactArrows > 0 && on.actuatorArrows > 0 && on.axes === 5,
        `toggles on: ${on.points} contact points (ncon ${on.ncon}), ${on.contactArrows} contact force arrows, ` +
        `${on.actuatorArrows} actuator arrows, ${on.axes} joint axes`);
  for (const box of boxes) await box.uncheck();
  await page.waitForTimeout(200);
  const off = await page.evaluate(overlayCounts);
  check(off.points + off.contactArrows + off.actuatorArrows + off.axes === 0, 'toggles off: no overlays');
  for (const box of boxes) await box.check();
}

// The plot keeps the last `window` seconds, its x axis spanning exactly that.
async function checkPlotWindow(page, window) {
  const plot = await page.evaluate(() => {
    const { plot } = window.lab.plots[0];
    const t = plot.columns[0];
    return { first: t[0], last: t[t.length - 1], min: plot.chart.scales.x.min, max: plot.chart.scales.x.max };
  });
  check(plot.last > window && Math.abs(plot.max - plot.min - window) < 1e-9 && plot.first >= plot.last - window,
        `the plot spans ${plot.min.toFixed(2)}..${plot.max.toFixed(2)} s, samples ${plot.first.toFixed(2)}..` +
        `${plot.last.toFixed(2)} s (window ${window} s)`);
}

// Lesson 2.3's page, served by `simlab lab`: its lab, found in the lesson.
async function testLessonLab(session) {
  const spec = lessonLabSpec();
  const page = await session.browser.newPage({ viewport: { width: 1000, height: 1000 } });
  const problems = collectProblems(page);
  await page.goto(session.url);
  await page.waitForSelector('section.lab-mount[data-mounted]', { timeout: 60000 });
  const mounted = await page.getAttribute('section.lab-mount', 'data-mounted');
  check(mounted === 'true', `the lesson's lab mounted in place (data-mounted="${mounted}")`);
  // The lab's controller, by the name the rest of this test uses.
  await page.evaluate(() => { window.lab = document.querySelector('section.lab-mount').simlabLab; });
  await page.locator('section.lab-mount').scrollIntoViewIfNeeded();
  await checkAgainstSpec(page, spec);
  // (the lesson's gantry lints clean at its keyframe: simlab lint finds none of the traps)
  const lint = await page.locator('.simlab-lab-lint summary').textContent();
  check(lint === 'lint: no findings', `the lint panel says "${lint}"`);
  await page.waitForTimeout(500);
  await checkPicture(page, [0.12, 0, 0.02], 'the first picture');
  await checkToggles(page);
  const range = await interactive(page, spec);
  const apiSession = await deterministic(page);
  checkSliderSession(apiSession, range);
  compareWithNative(apiSession);
  check(problems.length === 0, `no page errors${problems.length ? `: ${problems.join('; ')}` : ''}`);
  await page.close();
}

// web/lab/fixtures/all_geoms.json on the lab's own page: every geom type drawn, bad
// expressions and a bad control target shown as errors while the rest keeps running.
async function testAllGeoms(session) {
  const page = await session.browser.newPage({ viewport: { width: 900, height: 900 } });
  const problems = collectProblems(page);
  await page.goto(`${session.url}lab/index.html?spec=fixtures/all_geoms.json&base=fixtures/`);
  await page.waitForFunction(() => window.lab?.sim || document.getElementById('error').textContent, null,
                             { timeout: 60000 });
  const error = await page.locator('#error').textContent();
  check(!error, `the fixture's lab mounted${error ? `: ${error}` : ''}`);
  const drawn = await page.evaluate(() => window.lab.scene.geoms.map(({ g }) => g));
  const types = await page.evaluate(() => Array.from(window.lab.sim.model('geom_type')));
  check(drawn.length === types.length && [0, 1, 2, 3, 4, 5, 6, 7].every((t) => types.includes(t)),
        `all ${types.length} geoms drawn (types ${[...new Set(types)].sort()})`);
  for (const box of await page.locator('input[data-toggle]').all()) await box.check();
  await page.waitForTimeout(1500);
  const r = await readouts(page);
  check(/no data array named 'qpoz'/.test(r.unknown.text), `unknown name: "${r.unknown.text}"`);
  check(/model\.body_mass\[99\]: index out of range/.test(r['out of range'].text),
        `index out of range: "${r['out of range'].text}"`);
  check(/column 16: expected a number/.test(r.syntax.text), `syntax error: "${r.syntax.text}"`);
  check(r['slide (m)'].value > 0.01 && r.arithmetic.value === 1,
        `the other readouts keep working: slide ${r['slide (m)'].text}, arithmetic ${r.arithmetic.text}`);
  const bad = page.getByRole('slider', { name: 'bad target' });
  const message = await page.locator('.simlab-lab-control', { has: bad }).locator('.simlab-lab-error').textContent();
  check(await bad.isDisabled() && /ctrl\[7\]: index out of range/.test(message), `bad control target: "${message}"`);
  await page.screenshot({ path: path.join(options.shots, 'lab_all_geoms.png'), fullPage: true });
  // A state that diverges is reset by the engine and shown as a warning in the toolbar.
  await page.evaluate(() => { window.lab.sim.setDataAt('qvel', 0, 1e300); window.lab.sim.step(); });
  await page.waitForTimeout(300);
  const warned = await page.locator('.simlab-lab-toolbar .simlab-lab-warning').textContent();
  check(/^warning: bad qvel \(NaN or too large\): simulation reset \(1x\)$/.test(warned),
        `a diverging state shows "${warned}"`);
  await page.locator('.simlab-lab-toolbar').first().screenshot({ path: path.join(options.shots, 'lab_warning.png') });
  // An error while stepping stops the lab and says so in its toolbar; the page lives on.
  await page.evaluate(() => { window.lab.sim.step = () => { throw new Error('the engine failed'); }; });
  await page.waitForTimeout(500);
  const stopped = await page.locator('.simlab-lab-toolbar .simlab-lab-error').textContent();
  const button = await page.locator('button.simlab-lab-play').textContent();
  check(stopped === 'stopped: the engine failed' && button === 'play', `a failing step shows "${stopped}" and pauses`);
  check(problems.length === 0, `no page errors${problems.length ? `: ${problems.join('; ')}` : ''}`);
  await page.close();
}

async function main() {
  await openBuilds(options);
  fs.mkdirSync(options.shots, { recursive: true });
  const session = await openLabSession(options);
  try {
    await testLessonLab(session);
    await testAllGeoms(session);
  } finally {
    await session.close();
  }
  console.log(`screenshots in ${options.shots}`);
  console.log('PASS');
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

// Unit tests, in node, of the viewer's parts that need no browser: the panels generated
// from a model (web/lab/panels.mjs), the pacer with a clock of the test's own
// (web/lab/pacer.mjs), the history slider (history.mjs), the labels (labels.mjs), and the choice of the main model among files a user gives
// (web/view/files.mjs).
//
//   node web/test/view_units.mjs
import assert from 'node:assert/strict';
import { HistoryScrubber } from '../lab/history.mjs';
import { actuatorPoint, kMaxLabels, labelPoint, labelTexts } from '../lab/labels.mjs';
import { lintBody, lintSummary } from '../lab/lint_panel.mjs';
import { Pacer, kSpeeds, nextSpeed } from '../lab/pacer.mjs';
import { tickTexts } from '../lab/plot.mjs';
import { specFromModel } from '../lab/panels.mjs';
import { draggedPoint, draggedQuat, toBodyFrame } from '../lab/perturb.mjs';
import { pickMainModel, withPaths } from '../view/files.mjs';

// A model of 3 actuators (a limited motor, an unlimited one, a 4-control orientation
// servo with 3 outputs), a free joint, a hinge and a slide, two sensors, one keyframe.
const info = {
  sizes: { nactuator: 3, njnt: 3, nsensor: 2, nkey: 1 },
  statistic: { extent: 2, center: [0, 0, 1] },
  visual: { azimuth: 120, elevation: -20 },
  names: { actuator: ['lift', '', 'wrist'], jnt: ['root', 'elbow', ''], sensor: ['touch', 'acc'], key: ['home'] },
  actuator_ctrladr: [0, 1, 2], actuator_ctrlnum: [1, 1, 4],
  actuator_outadr: [0, 1, 2], actuator_outnum: [1, 1, 3],
  actuator_ctrlrange: [0.5, 2, 0, 0, -1, 1, -1, 1, -1, 1, -1, 1],
  actuator_ctrllimited: [1, 0, 1, 1, 1, 1],
  jnt_type: [0, 3, 2], jnt_qposadr: [0, 7, 8],
  sensor_adr: [0, 1], sensor_dim: [1, 3],
};

// A File of the browser's, as far as files.mjs uses it.
function fakeFile(name, text, relative = '') {
  return { name, webkitRelativePath: relative, text: async () => text,
           arrayBuffer: async () => new TextEncoder().encode(text).buffer };
}

const tests = {
  'a slider per control entry, in ctrlrange or -1..1': () => {
    const spec = specFromModel(info, 'm.xml');
    assert.deepEqual(spec.controls.map((c) => [c.label, c.set, c.min, c.max, c.value]), [
      ['lift', 'data.ctrl[0]', 0.5, 2, 0.5],
      ['actuator 1', 'data.ctrl[1]', -1, 1, 0],
      ['wrist[0]', 'data.ctrl[2]', -1, 1, 0],
      ['wrist[1]', 'data.ctrl[3]', -1, 1, 0],
      ['wrist[2]', 'data.ctrl[4]', -1, 1, 0],
      ['wrist[3]', 'data.ctrl[5]', -1, 1, 0],
    ]);
    assert.equal(spec.title, 'm.xml');
    assert.deepEqual(spec.camera, { target: [0, 0, 1], distance: 3, azimuth: 120, elevation: 20 });
    assert.deepEqual(spec.keys, ['home']);
  },
  'readouts of scalar joints, every force output and every sensor number': () => {
    const spec = specFromModel(info);
    assert.deepEqual(spec.readouts.map((r) => [r.group, r.label, r.expr]), [
      ['joint positions', 'elbow', 'data.qpos[7]'],
      ['joint positions', 'joint 2', 'data.qpos[8]'],
      ['actuator forces', 'lift', 'data.actuator_force[0]'],
      ['actuator forces', 'actuator 1', 'data.actuator_force[1]'],
      ['actuator forces', 'wrist[0]', 'data.actuator_force[2]'],
      ['actuator forces', 'wrist[1]', 'data.actuator_force[3]'],
      ['actuator forces', 'wrist[2]', 'data.actuator_force[4]'],
      ['sensors', 'touch', 'data.sensordata[0]'],
      ['sensors', 'acc[0]', 'data.sensordata[1]'],
      ['sensors', 'acc[1]', 'data.sensordata[2]'],
      ['sensors', 'acc[2]', 'data.sensordata[3]'],
    ]);
  },
  'a large model shows at most 60 readouts a group': () => {
    const n = 100;
    const big = { ...info, sizes: { ...info.sizes, njnt: n }, names: { ...info.names, jnt: Array(n).fill('') },
                  jnt_type: Array(n).fill(3), jnt_qposadr: [...Array(n).keys()] };
    assert.equal(specFromModel(big).readouts.filter((r) => r.group === 'joint positions').length, 60);
  },
  'the pacer keeps real time with a clock of its own': () => {
    let clock = 0, steps = 0;
    const pacer = new Pacer({ timestep: 0.002, step: (n) => { steps += n; clock += 0.01 * n; }, now: () => clock });
    for (let frame = 0; frame <= 600; frame++) pacer.frame(frame * 1000 / 60, true);
    assert.ok(Math.abs(steps * 0.002 - 10) < 0.01, `${steps} steps in 10 s`);
    assert.ok(pacer.dropped < 1e-9);
  },
  'slow frames of a busy machine are caught up; a stall or a hidden tab is not': () => {
    let steps = 0;
    const pacer = new Pacer({ timestep: 0.002, step: (n) => { steps += n; }, now: () => 0 });
    // 5 fps with every third frame 400 ms late: 10 s of wall time, all of it simulated
    let wall = 0;
    for (let frame = 0; wall < 10000; frame++) {
      wall += frame % 3 === 2 ? 400 : 200;
      pacer.frame(wall, true);
    }
    assert.ok(Math.abs(steps * 0.002 - (wall - 200) / 1000) < 0.01, `${steps} steps in ${wall} ms`);
    assert.ok(pacer.dropped < 1e-9);
    // a 3 s stall drops all but a second of it; after resync (the tab was hidden) the
    // next frame's gap is dropped entirely
    const before = steps;
    pacer.frame(wall + 3000, true);
    assert.equal(steps - before, 500);
    pacer.resync();
    pacer.frame(wall + 8000, true);
    assert.equal(steps - before, 500);
    pacer.frame(wall + 8100, true);
    assert.equal(steps - before, 550);
  },
  'slow motion steps at the chosen fraction of real time': () => {
    for (const speed of kSpeeds) {
      let steps = 0;
      const pacer = new Pacer({ timestep: 0.001, step: (n) => { steps += n; }, now: () => 0 });
      pacer.speed = speed;
      for (let frame = 0; frame <= 640; frame++) pacer.frame(frame * 1000 / 64, true);
      assert.ok(Math.abs(steps * 0.001 - 10 * speed) <= 0.001 + 1e-12, `speed ${speed}: ${steps} steps`);
    }
  },
  'a slow engine drops what it cannot catch; a paused one takes no steps': () => {
    let clock = 0, steps = 0;
    const pacer = new Pacer({ timestep: 0.001, step: (n) => { steps += n; clock += 1 * n; }, now: () => clock });
    for (let frame = 0; frame <= 60; frame++) pacer.frame(frame * 1000 / 60, true);
    // (a 10 ms budget of a 16.7 ms frame: about 60% of real time, the rest dropped)
    assert.ok(steps * 0.001 > 0.55 && steps * 0.001 < 0.7, `${steps} steps`);
    assert.ok(Math.abs(steps * 0.001 + pacer.dropped - 1) < 0.002, `dropped ${pacer.dropped}`);
    const before = steps;
    for (let frame = 61; frame <= 120; frame++) pacer.frame(frame * 1000 / 60, false);
    assert.equal(steps, before);
  },
  "'-' and '=' step through the speeds and stop at the ends": () => {
    assert.equal(nextSpeed(1, 1), 1);
    assert.equal(nextSpeed(1, -1), 1 / 2);
    let speed = 1;
    for (let k = 0; k < 10; k++) speed = nextSpeed(speed, -1);
    assert.equal(speed, 1 / 64);
    assert.equal(nextSpeed(speed, 1), 1 / 32);
  },
  'a pulled point follows the mouse across the image plane at its depth': () => {
    // Camera at the origin looking along +y, right +x, up +z, 90 degree field of view,
    // 200 pixels high: at depth 2 one pixel is 2 * 2 * tan(45) / 200 = 0.02.
    const camera = { position: [0, 0, 0], forward: [0, 1, 0], right: [1, 0, 0], up: [0, 0, 1], fovy: 90, height: 200 };
    const moved = draggedPoint([0.5, 2, 0.1], 10, -5, camera);
    [0.7, 2, 0.2].forEach((v, k) => assert.ok(Math.abs(moved[k] - v) < 1e-12, `${moved}`));
  },
  'a turned body turns about the view axes, a point goes into its body frame': () => {
    const camera = { right: [1, 0, 0], up: [0, 0, 1] };
    const q = draggedQuat([1, 0, 0, 0], 157.07963267948966, 0, camera);  // 1.5708 rad about z
    [Math.SQRT1_2, 0, 0, Math.SQRT1_2].forEach((v, k) => assert.ok(Math.abs(q[k] - v) < 1e-9, `${q}`));
    // A body at (1, 2, 3) turned 90 degrees about z: world (1, 3, 3) is its local (1, 0, 0).
    const local = toBodyFrame([1, 3, 3], [1, 2, 3], [0, -1, 0, 1, 0, 0, 0, 0, 1]);
    [1, 0, 0].forEach((v, k) => assert.ok(Math.abs(local[k] - v) < 1e-12, `${local}`));
  },
  'the history scrubs within the states kept and says how far back it is': () => {
    // (a stand-in engine: 5 states kept, at times 0.00 .. 0.04)
    const sim = { size: 5, backNow: 0, history() { return { size: this.size, back: this.backNow, newest: 0.04 }; },
                  scrub(back) { this.backNow = back; } };
    const history = new HistoryScrubber(sim);
    assert.deepEqual(history.sliderState(0.04), { slider: { max: '4', value: '4' }, text: '0.000 s' });
    assert.equal(history.scrubTo(2), true);
    assert.equal(history.back(), 2);
    assert.deepEqual(history.sliderState(0.02), { slider: { max: '4', value: '2' }, text: '-0.020 s' });
    assert.equal(history.scrubTo(2), false, 'already there');
    assert.equal(history.scrubTo(99), true);
    assert.equal(history.back(), 4, 'clamped to the oldest state kept');
    assert.equal(history.scrubTo(-3), true);
    assert.equal(history.back(), 0, 'clamped to the newest');
    sim.size = 0;
    assert.equal(history.scrubTo(1), false, 'nothing kept');
  },
  'labels name each object, or number it; actuators sit at their transmission': () => {
    const names = { body: ['world', 'torso', ''], joint: ['hip'] };
    const nameOf = (kind, id) => names[kind]?.[id] ?? '';
    assert.deepEqual(labelTexts('body', { nbody: 3 }, nameOf), [{ id: 1, text: 'torso' }, { id: 2, text: 'body 2' }]);
    assert.deepEqual(labelTexts('joint', { njnt: 1 }, nameOf), [{ id: 0, text: 'hip' }]);
    assert.equal(labelTexts('geom', { ngeom: 5000 }, nameOf).length, kMaxLabels);
    // (trntype joint, tendon, site, body)
    const model = { actuator_trntype: [0, 3, 4, 5], actuator_trnid: [2, -1, 0, -1, 1, -1, 3, -1] };
    assert.deepEqual([0, 1, 2, 3].map((a) => actuatorPoint(model, a)),
                     [['xanchor', 2], null, ['site_xpos', 1], ['xpos', 3]]);
  },
  'a label sits where its point projects, and not off the view or behind the camera': () => {
    assert.deepEqual(labelPoint([0, 0, 0.5], 200, 100), [100, 50]);
    assert.deepEqual(labelPoint([-1, 1, 0.5], 200, 100), [0, 0]);
    assert.equal(labelPoint([0, 0, 1.2], 200, 100), null);
    assert.equal(labelPoint([1.5, 0, 0.5], 200, 100), null);
  },
  'a lint finding marks the body its element acts on; the summary counts': () => {
    // (geom 0 on body 2; equality 0 couples joint 1 (body 3); actuators on joint 1, site 0
    // (body 4), a tendon)
    const model = { geom_bodyid: [2], eq_type: [2], eq_obj1id: [1], jnt_bodyid: [1, 3], site_bodyid: [4],
                    actuator_trntype: [0, 4, 3], actuator_trnid: [1, -1, 0, -1, 0, -1] };
    const body = (kind, id) => lintBody(model, { kind, id });
    assert.deepEqual([body('geom', 0), body('equality', 0), body('actuator', 0), body('actuator', 1),
                      body('actuator', 2), body('keyframe', 0), body('', -1)], [2, 3, 3, 4, -1, -1, -1]);
    assert.equal(lintSummary([]), 'no findings');
    assert.equal(lintSummary([{ severity: 'warning' }, { severity: 'note' }, { severity: 'note' }]), '1 warning, 2 notes');
  },
  'plot ticks have the decimals their spacing needs, and no "-0"': () => {
    assert.deepEqual(tickTexts(null, [0, -0.01, -0.02]), ['0.00', '-0.01', '-0.02']);
    assert.deepEqual(tickTexts(null, [-0, 5, 10]), ['0', '5', '10']);
    assert.deepEqual(tickTexts(null, [-1e-9, 0.5, 1]), ['0.0', '0.5', '1.0']);
  },
  'the main model is the .xml no other names': async () => {
    const files = [fakeFile('arm.xml', '<mujoco/>', 'robot/parts/arm.xml'),
                   fakeFile('scene.xml', '<mujoco><include file="parts/arm.xml"/></mujoco>', 'robot/scene.xml'),
                   fakeFile('a.stl', 'solid', 'robot/meshes/a.stl')];
    assert.deepEqual(withPaths(files).map((e) => e.path), ['parts/arm.xml', 'scene.xml', 'meshes/a.stl']);
    const source = await pickMainModel(files);
    assert.equal(source.filename, 'scene.xml');
    assert.equal(await source.readText('parts/arm.xml'), '<mujoco/>');
    assert.equal((await source.readBytes('./meshes/a.stl')).length, 5);
    await assert.rejects(source.readText('missing.xml'), /not among the files given/);
    assert.equal(await pickMainModel([fakeFile('a.stl', 'solid')]), null);
  },
};

let failed = 0;
for (const [name, test] of Object.entries(tests)) {
  try {
    await test();
    console.log(`ok: ${name}`);
  } catch (error) {
    failed++;
    console.log(`FAIL: ${name}\n${error.stack}`);
  }
}
console.log(failed ? `${failed} failed` : 'PASS');
process.exit(failed ? 1 : 0);

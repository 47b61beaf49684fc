// Unit tests of the lab's expression parser (web/lab/expr.mjs) and lab-block reader
// (web/lab/spec.mjs), in node:
//
//   node web/test/lab_expr.mjs
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import {
  ExprError, arrayReader, arraysOf, evaluateExpr, parseExpr, parseTarget,
} from '../lab/expr.mjs';
import { parseLabSpec } from '../lab/spec.mjs';
import { parseLesson } from '../lesson/parse.mjs';
import { repoRoot } from './wasm_harness.mjs';

const arrays = {
  data: { qpos: [0.5, -1, 2, 4], actuator_force: [1, 2, 3, -5] },
  model: { actuator_forcerange: [0, 0, -5, 5] },
};
const read = arrayReader((source, name) => arrays[source][name] ?? null);
const value = (text) => evaluateExpr(parseExpr(text), read);

const tests = {
  'numbers and precedence': () => {
    assert.equal(value('1 + 2 * 3'), 7);
    assert.equal(value('(1 + 2) * 3'), 9);
    assert.equal(value('8 / 4 / 2'), 1);
    assert.equal(value('10 - 4 - 3'), 3);
    assert.equal(value('-2 * -3'), 6);
    assert.equal(value('--1'), 1);
    assert.equal(value('1.5e1 + .5 + 2.'), 17.5);
  },
  'array references': () => {
    assert.equal(value('data.qpos[3]'), 4);
    assert.equal(value('data.actuator_force[3] / model.actuator_forcerange[2]'), 1);
    assert.equal(value('data.qpos[1 + 2] - data.qpos[0]'), 3.5);
    assert.equal(value('data.qpos[data.qpos[2]]'), 2);
  },
  'unknown names and indices out of range are errors naming them': () => {
    assert.throws(() => value('data.qpoz[0]'), /no data array named 'qpoz'/);
    assert.throws(() => value('model.nothing[0]'), /no model array named 'nothing'/);
    assert.throws(() => value('data.qpos[4]'), /data\.qpos\[4\]: index out of range \(qpos has 4 numbers\)/);
    assert.throws(() => value('data.qpos[-1]'), /index out of range/);
    assert.throws(() => value('data.qpos[0.5]'), /whole number/);
  },
  'syntax errors say where': () => {
    const cases = [['', /empty expression/], ['1 +', /column 4: expected a number/],
      ['(1 + 2', /expected '\)'/], ['data.qpos[1', /expected '\]'/], ['data.qpos', /expected '\['/],
      ['data[0]', /expected '\.'/], ['1 2', /column 3: unexpected '2'/],
      ['window.alert(1)', /column 1: expected a number/], ['data.qpos[0]; 1', /unexpected ';'/],
      ['qpos[0]', /expected a number, data.NAME/], ['2 ** 3', /column 4/]];
    for (const [text, pattern] of cases) {
      assert.throws(() => parseExpr(text), (e) => e instanceof ExprError && pattern.test(e.message), text);
    }
  },
  'nothing is evaluated as JavaScript': () => {
    globalThis.labExprTouched = false;
    assert.throws(() => parseExpr('globalThis.labExprTouched = true'), ExprError);
    assert.equal(globalThis.labExprTouched, false);
    // Object prototype names are not arrays.
    const safe = arrayReader((source, name) => (Object.hasOwn(arrays[source], name) ? arrays[source][name] : null));
    assert.throws(() => evaluateExpr(parseExpr('data.constructor[0]'), safe), /no data array named 'constructor'/);
  },
  'control targets': () => {
    assert.deepEqual(parseTarget('data.ctrl[3]'), { name: 'ctrl', index: 3 });
    assert.deepEqual(parseTarget(' data.ctrl[1 + 1] '), { name: 'ctrl', index: 2 });
    assert.throws(() => parseTarget('model.ctrl[0]'), /must set one element/);
    assert.throws(() => parseTarget('data.ctrl[0] + 1'), /must set one element/);
    assert.throws(() => parseTarget('data.ctrl[data.qpos[0]]'), /constant/);
  },
  'the reader reads the live arrays, and arraysOf lists what an expression reads': () => {
    const live = { qpos: [1] };
    const reader = arrayReader((source, name) => live[name] ?? null);
    assert.equal(evaluateExpr(parseExpr('data.qpos[0]'), reader), 1);
    live.qpos = [2];
    assert.equal(evaluateExpr(parseExpr('data.qpos[0]'), reader), 2);
    assert.deepEqual(arraysOf(parseExpr('-(data.qpos[model.jnt_qposadr[1]] + 2) * data.ctrl[0]')),
                     [['data', 'qpos'], ['model', 'jnt_qposadr'], ['data', 'ctrl']]);
    assert.throws(() => parseTarget('data.ctrl[0.5]'), /whole number/);
  },
  "the lesson's lab block, typographic quotes normalised": () => {
    const lesson = path.resolve(repoRoot, '../shared/lesson/lesson-2.3-actuators.txt');
    const text = fs.readFileSync(lesson, 'utf8');
    assert.match(text, /\u201C/);
    const [block] = parseLesson(text).blocks.filter((b) => b.type === 'lab');
    assert.equal(block.line, 21);
    assert.equal(block.error, undefined);
    // The dev page's copy of the block reads the same.
    const copy = fs.readFileSync(path.join(repoRoot, 'web/lab/fixtures/lesson-2.3-lab.txt'), 'utf8');
    assert.deepEqual(parseLabSpec(copy), block.spec);
    const spec = block.spec;
    assert.equal(spec.model, 'gantry_gripper');
    assert.deepEqual(spec.camera, { azimuth: -60, elevation: 20, distance: 0.9, target: [0.1, 0, 0.15] });
    assert.equal(spec.controls.length, 3);
    assert.deepEqual(parseTarget(spec.controls[2].set), { name: 'ctrl', index: 3 });
    for (const r of spec.readouts) parseExpr(r.expr);
    assert.equal(spec.plots[0].traces[1].dash, true);
    assert.throws(() => parseLabSpec('{"model": "../etc/passwd"}'), /needs "model"/);
    assert.throws(() => parseLabSpec('{“model”: 1'), /not valid JSON/);
    assert.throws(() => parseLabSpec('[1, 2]'), /must be a JSON object/);
    const bad = parseLesson('```lab simlab {“title”: “no model”}').blocks[0];
    assert.match(bad.error, /needs "model"/);
  },
};

let failed = 0;
for (const [name, test] of Object.entries(tests)) {
  try {
    test();
    console.log(`ok: ${name}`);
  } catch (error) {
    failed++;
    console.log(`FAIL: ${name}: ${error.message}`);
  }
}
console.log(failed ? `${failed} failed` : 'PASS');
process.exit(failed ? 1 : 0);

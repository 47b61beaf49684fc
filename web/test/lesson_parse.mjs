// The lesson parser, quote normalisation, math and the knowledge check's grading, in node
// (no WebAssembly, no browser): every block of ../shared/lesson/lesson-2.3-actuators.txt.
//
//   node web/test/lesson_parse.mjs [--lesson PATH]
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { texError } from '../lesson/math.mjs';
import { normalizeQuotes, parseLenientJson } from '../lab/spec.mjs';
import { parseHtmlSubset, parseInline, parseLesson } from '../lesson/parse.mjs';
import { grade, readNumber } from '../lesson/quiz.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const argv = process.argv.slice(2);
const lessonPath = argv[0] === '--lesson' ? argv[1]
  : path.resolve(repoRoot, '../shared/lesson/lesson-2.3-actuators.txt');

const checks = [];
const check = (name, fn) => checks.push({ name, fn });

const text = fs.readFileSync(lessonPath, 'utf8');
const { blocks } = parseLesson(text);
const ofType = (type) => blocks.filter((b) => b.type === type);

check('block sequence of the lesson', () => {
  const kinds = blocks.map((b) => (b.type === 'code' ? `code:${b.lang}` : b.type)).join(' ');
  assert.equal(kinds, [
    'paragraph table paragraph paragraph lab heading callout paragraph table paragraph',
    'code:io code:python paragraph code:text paragraph paragraph paragraph paragraph callout',
    'paragraph table paragraph paragraph paragraph callout paragraph paragraph paragraph',
    'paragraph exercise exercise paragraph quiz paragraph'].join(' '));
});

check('the two exercises, numbered', () => {
  const exercises = ofType('exercise');
  assert.deepEqual(exercises.map((b) => b.number), [1, 2]);
  assert.match(exercises[0].text, /^Replace the gripper/);
  assert.match(exercises[1].text, /^Add a force and a torque sensor/);
});

check('every non-empty line belongs to a block', () => {
  const starts = blocks.map((b) => b.line);
  assert.equal(starts[0], 1);
  assert.ok(starts.every((s, i) => i === 0 || s > starts[i - 1]));
  const lines = text.split('\n');
  const words = (s) => s.replace(/[^A-Za-z0-9]+/g, ' ').trim().split(' ').filter(Boolean).length;
  const inBlocks = JSON.stringify(blocks.map(({ line, ...b }) => b));
  for (const [i, line] of lines.entries()) {
    if (words(line) < 3 || /^```/.test(line)) continue;
    const text0 = line.replace(/^(>|#+)\s*/, '').replace(/^\[!\w+\]\s*/, '').replace(/^\$\$/, '');
    const probe = text0.split('|').map((c) => c.trim()).find((c) => c).slice(0, 25);
    const found = inBlocks.includes(JSON.stringify(probe).slice(1, -1)) ||
                  inBlocks.includes(normalizeQuotes(probe)) || inBlocks.includes(probe.replace(/\\\\/g, '\\'));
    if (!found && !/^[{"\]]/.test(line)) assert.fail(`line ${i + 1} lost: ${line.slice(0, 60)}`);
  }
});

check('heading', () => {
  assert.deepEqual(ofType('heading').map((h) => [h.level, h.text]), [[2, 'The actuator model']]);
});

check('tables, including rows wrapped over several lines', () => {
  const tables = ofType('table');
  assert.deepEqual(tables.map((t) => t.header.length), [3, 4, 3]);
  assert.deepEqual(tables.map((t) => t.rows.length), [5, 4, 6]);
  for (const t of tables) {
    for (const row of t.rows) {
      assert.equal(row.length, t.header.length);
      assert.ok(row.every((cell) => cell.length > 0 && !cell.includes('|')), JSON.stringify(row));
    }
  }
  assert.deepEqual(tables[0].rows[0], ['<actuator>',
    'general, motor, position, velocity, intvelocity, damper, cylinder, muscle, adhesion, pid, orientation, dcmotor, plugin',
    'turn data.ctrl into forces']);
  assert.deepEqual(tables[0].rows[4], ['<keyframe>', 'key', 'named states to reset to']);
  assert.equal(tables[1].rows[3][0], '`general dyntype="filter" dynprm="τ" gainprm="a"`');
  assert.deepEqual(tables[2].rows[5], ['bookkeeping', 'clock, e_potential, e_kinetic, subtreecom', 'various']);
  assert.equal(tables[2].rows[0][2], 'position, velocity or acceleration stage, depending on the quantity');
});

check('callouts: > form and one-line form with wrapped text', () => {
  const callouts = ofType('callout');
  assert.deepEqual(callouts.map((c) => [c.kind, c.title]), [
    ['established', 'One force law for SISO actuators'],
    ['implementation', 'Actuators with more than one input'],
    ['recommendation', 'Drive the average, constrain the difference']]);
  assert.deepEqual(callouts[0].body.map((b) => b.type), ['paragraph', 'math', 'paragraph']);
  assert.equal(callouts[0].body[1].tex, 'p = a\\,u + b_0 + b_1\\, l + b_2\\, \\dot l,');
  assert.match(callouts[1].body[0].text, /^Since 3\.11, an actuator can take several controls: an orientationservo/);
  assert.match(callouts[1].body[0].text, /all three are equal\.$/);
  assert.match(callouts[2].body[0].text, /^The gripper pattern/);
});

check('code blocks: io, python with file=, text output', () => {
  const [io, python, output] = ofType('code');
  assert.deepEqual(io.text.split('\n').map((l) => l.split(':')[0]), ['INPUT', 'PROCESS', 'OUTPUT']);
  assert.equal(python.attrs.file, 'examples/l2_3_actuators.py');
  assert.match(python.text, /^“"”Lesson 2\.3: actuator force laws/);
  assert.match(python.text.split('\n').at(-1), /^if name == “main”:/);
  assert.equal(output.text.split('\n')[0], 'force laws at q = 0.3 rad, qdot = -0.5 rad/s:');
  assert.match(output.text.split('\n').at(-1), /^grip command 0\.03 m/);
  assert.equal(output.text.split('\n').length, 17);
  assert.equal(blocks[blocks.indexOf(output) - 1].text, 'Output:');
});

check('lab block: JSON with typographic quotes, never rejected', () => {
  const [lab] = ofType('lab');
  assert.equal(lab.error, undefined);
  assert.equal(lab.engine, 'simlab');
  const spec = lab.spec;
  assert.equal(spec.model, 'gantry_gripper');
  assert.equal(spec.title, 'Four actuators, one tendon, one equality');
  assert.deepEqual([spec.key, spec.height, spec.autoplay, spec.dock], [0, 250, true, true]);
  assert.deepEqual(spec.camera, { azimuth: -60, elevation: 20, distance: 0.9, target: [0.1, 0, 0.15] });
  assert.deepEqual(spec.toggles, ['contacts', 'forces', 'joints']);
  assert.deepEqual(spec.controls.map((c) => c.set), ['data.ctrl[0]', 'data.ctrl[2]', 'data.ctrl[3]']);
  assert.deepEqual(spec.readouts.map((r) => r.expr), ['data.actuator_force[2]', 'data.actuator_force[3]',
    'data.qpos[3]', 'data.qpos[4]', 'data.ten_length[0]', 'data.qpos[7]']);
  assert.equal(spec.plots[0].traces[1].dash, true);
  assert.match(spec.note, /^Lower the carriage to about -0\.33 m/);
});

check('quote normalisation', () => {
  const value = (s) => {
    const r = parseLenientJson(s);
    assert.equal(r.error, undefined, `${s}: ${r.error}`);
    return r.value;
  };
  assert.deepEqual(value('{“a”: “b”, “n”: [1, 2]}'), { a: 'b', n: [1, 2] });
  assert.deepEqual(value('{"note": "the gripper’s cube ‘here’"}'), { note: "the gripper's cube 'here'" });
  assert.deepEqual(value('{“note”: “say “hi” now”, “x”: 1}'), { note: 'say "hi" now', x: 1 });
  assert.deepEqual(value('{"a": “b”, “c”:"d"}'), { a: 'b', c: 'd' });
  assert.deepEqual(value('{“a”: “escaped \\” stays”}'), { a: 'escaped " stays' });
  assert.equal(normalizeQuotes('{“k”: ‘v’}'), "{\"k\": 'v'}");
  const closed = parseLesson('```lab simlab {“model”: “m”, “key”: 1}```\nafter');
  assert.deepEqual(closed.blocks.map((b) => b.type), ['lab', 'paragraph']);
  assert.deepEqual(closed.blocks[0].spec, { model: 'm', key: 1 });
  const multi = parseLesson('```lab simlab {\n  “model”: “m”,\n  “controls”: []\n}\n```\n## Next');
  assert.deepEqual(multi.blocks.map((b) => b.type), ['lab', 'heading']);
  assert.deepEqual(multi.blocks[0].spec, { model: 'm', controls: [] });
  const broken = parseLesson('```lab simlab {“model”: m}\ntext here');
  assert.equal(broken.blocks[0].type, 'lab');
  assert.ok(broken.blocks[0].error);
  assert.equal(broken.blocks[0].raw, '{“model”: m}');
});

check('inline pieces and the HTML subset', () => {
  assert.deepEqual(parseInline('a `b` $c$ d $$e$$'), [{ t: 'text', v: 'a ' }, { t: 'code', v: 'b' },
    { t: 'text', v: ' ' }, { t: 'math', v: 'c' }, { t: 'text', v: ' d ' }, { t: 'displaymath', v: 'e' }]);
  const open = ofType('quiz')[0].quiz.questions[3];
  const question = parseHtmlSubset(open.q);
  assert.deepEqual(question[0].at(-2), { t: 'code', v: '<velocity joint="j" kv="4"/>' });
  const reference = parseHtmlSubset(open.reference);
  assert.deepEqual(reference[0][0], { t: 'code', v: '<general joint="j" gainprm="4" biastype="affine" biasprm="0 0 -4"/>' });
  assert.ok(reference[0].some((p) => p.t === 'math' && p.v === 'p = 4u - 4\\dot l'));
});

check('every $math$ of the lesson typesets with KaTeX', () => {
  const sources = [...text.matchAll(/\$\$(.+?)\$\$|\$([^$\n]+?)\$/g)].map((m) => (m[1] ?? m[2]).replace(/\\\\/g, '\\'));
  assert.ok(sources.length >= 25, `${sources.length} math pieces`);
  for (const tex of sources) assert.equal(texError(tex), null, tex);
  assert.equal(texError('\\tfrac12(q_\\text{left} + q_\\text{right})'), null);
  assert.match(texError('\\foo x'), /Undefined control sequence/);
  assert.match(texError('\\frac{1}{2'), /end of input/);
});

check('knowledge check: the four questions and their grading', () => {
  const { quiz } = ofType('quiz')[0];
  assert.equal(quiz.title, 'Knowledge check');
  const [numeric, gear, clamp, open] = quiz.questions;
  assert.deepEqual(quiz.questions.map((q) => q.kind), ['numeric', 'mcq', 'mcq', 'open']);
  assert.deepEqual([numeric.answer, numeric.tol, numeric.unit], [13, 0.001, 'N m']);
  assert.equal(grade(numeric, '13').status, 'right');
  assert.equal(grade(numeric, 13).status, 'right');
  assert.equal(grade(numeric, '13.001').status, 'right');
  assert.equal(grade(numeric, '12.999 N m').status, 'right');
  assert.equal(grade(numeric, '12').status, 'wrong');
  assert.equal(grade(numeric, '13.002').status, 'wrong');
  assert.equal(grade(numeric, 'thirteen').status, 'invalid');
  assert.equal(grade(numeric, '').status, 'invalid');
  assert.equal(readNumber('13,0'), 13);
  assert.equal(grade(gear, gear.options.indexOf('15')).status, 'right');
  assert.equal(grade(gear, '15').status, 'right');
  assert.equal(grade(gear, '1.5').status, 'wrong');
  assert.equal(grade(gear, -1).status, 'invalid');
  assert.equal(grade(clamp, '3').status, 'right');
  assert.equal(grade(clamp, '1').status, 'wrong');
  const revealed = grade(open, 'gainprm="4"');
  assert.equal(revealed.status, 'revealed');
  assert.match(open.reference, /biastype=\\?"affine\\?"/);
});

let failed = 0;
for (const { name, fn } of checks) {
  try {
    fn();
    console.log(`ok   ${name}`);
  } catch (e) {
    failed++;
    console.log(`FAIL ${name}\n     ${e.message.split('\n').join('\n     ')}`);
  }
}
console.log(failed ? `${failed} of ${checks.length} checks failed` : `PASS (${checks.length} checks)`);
process.exit(failed ? 1 : 0);

// The lesson page end to end in headless Chromium (Debian's, driven by playwright-core):
// starts `simlab lab LESSON --port 0`, opens the page it prints, checks that headings,
// tables, callouts, math, code are rendered and the lab is live in place (mounted, with
// its 3D view, sliders and readouts), answers the knowledge
// check (13 -> right, 12 -> wrong, option "15" -> right, the open question reveals its
// reference) and saves screenshots (lesson_page_top.png, lesson_page_model.png,
// lesson_page_quiz.png, lesson_page_full.png) into --out.
//
//   node web/test/lesson_page_e2e.mjs --simlab build/simlab [--lesson PATH] [--out DIR] [--require yes]
//
// Exits 77 (ctest: skipped) when Chromium or playwright-core is missing (with --require
// yes: fails).
import assert from 'node:assert/strict';
import path from 'node:path';
import { collectProblems, kDefaultLesson, openLabSession } from './browser_harness.mjs';
import { parseOptions, repoRoot } from './wasm_harness.mjs';

const options = parseOptions(process.argv.slice(2), {
  simlab: path.join(repoRoot, 'build/simlab'),
  lesson: kDefaultLesson,
  chromium: '/usr/bin/chromium',
  out: '',
});
const outDir = options.out || path.dirname(path.resolve(options.simlab));

// What the page shows, counted in the page.
function inventory() {
  const texts = (selector) => [...document.querySelectorAll(selector)].map((e) => e.textContent.trim());
  return {
    title: document.getElementById('title').textContent,
    headings: texts('main .lesson-heading'),
    tables: [...document.querySelectorAll('table.lesson-table')].map((t) => ({
      columns: t.querySelectorAll('thead th').length,
      rows: t.querySelectorAll('tbody tr').length,
      firstCell: t.querySelector('tbody td').textContent,
    })),
    callouts: [...document.querySelectorAll('aside.callout')].map((a) => ({
      kind: a.querySelector('.callout-kind').textContent,
      title: a.querySelector('.callout-title')?.textContent ?? '',
    })),
    math: document.querySelectorAll('.math').length,
    displayMath: document.querySelectorAll('.math-display').length,
    fractions: document.querySelectorAll('.math .katex .mfrac').length,
    subscripts: document.querySelectorAll('.math .katex .msupsub').length,
    unknownMath: texts('.math[data-error]'),
    katexFont: getComputedStyle(document.querySelector('.math .katex')).fontFamily,
    mathLeftAsDollars: texts('main p, main td').filter((t) => /\$[^$]+\$/.test(t)),
    codeCaptions: texts('figure.code figcaption'),
    programLines: document.querySelector('figure.code-python pre code').textContent.split('\n').length,
    programSource: document.querySelector('figure.code-python').dataset.source ?? '',
    outputTables: [...document.querySelectorAll('.output-table')].map((t) => [
      t.querySelectorAll('th').length, t.querySelectorAll('tbody tr').length]),
    exercises: texts('section.exercise h4'),
    ioTerms: texts('dl.io dt'),
    labs: [...document.querySelectorAll('section.lab-mount')].map((s) => ({
      model: s.dataset.model, mounted: s.dataset.mounted ?? '',
      canvases: s.querySelectorAll('canvas.simlab-lab-canvas').length,
      sliders: s.querySelectorAll('.simlab-lab-control input[type=range]').length,
      readouts: s.querySelectorAll('.simlab-lab-readout').length,
    })),
    questions: document.querySelectorAll('.quiz .question').length,
  };
}

// Answers question `index` (numeric text or option text) and returns its result attribute.
async function answer(page, index, response) {
  const question = page.locator(`.quiz .question[data-index="${index}"]`);
  if (typeof response === 'string' && (await question.locator('input.answer-input').count())) {
    await question.locator('input.answer-input').fill(response);
  } else if (typeof response === 'string') {
    await question.locator('label.option', { hasText: new RegExp(`^\\s*${response.replace('.', '\\.')}\\s*$`) })
      .locator('input').check();
  }
  await question.locator('button.check').click();
  return question.getAttribute('data-result');
}

async function checkPage(page) {
  await page.waitForSelector('figure.code-python[data-source="repository"]', { timeout: 15000 });
  await page.waitForFunction(() => document.querySelector('figure.code-python figcaption').textContent.includes('C++'),
                             null, { timeout: 15000 });
  const seen = await page.evaluate(inventory);
  console.log(JSON.stringify(seen));
  assert.equal(seen.title, 'Lesson 2.3: actuators');
  assert.deepEqual(seen.headings, ['The actuator model', 'Knowledge check']);
  assert.deepEqual(seen.tables.map((t) => [t.columns, t.rows]), [[3, 5], [4, 4], [3, 6]]);
  assert.equal(seen.tables[0].firstCell, '<actuator>');
  assert.deepEqual(seen.callouts.map((c) => c.kind), ['Established', 'Implementation', 'Recommendation']);
  assert.equal(seen.callouts[1].title, 'Actuators with more than one input');
  assert.ok(seen.math >= 25 && seen.displayMath >= 1 && seen.fractions >= 1 && seen.subscripts >= 10,
            `math ${seen.math}, display ${seen.displayMath}, fractions ${seen.fractions}, subs ${seen.subscripts}`);
  assert.deepEqual(seen.unknownMath, []);
  assert.match(seen.katexFont, /KaTeX_Main/, 'KaTeX stylesheet applied');
  assert.deepEqual(seen.mathLeftAsDollars, []);
  assert.deepEqual(seen.codeCaptions, ['examples/l2_3_actuators.py · run: python3 examples/l2_3_actuators.py · ' +
    'C++: examples/l2_3_actuators.cpp (build/l2_3_actuators)', 'output']);
  assert.ok(seen.programSource === 'repository' && seen.programLines > 50,
            `the program from the repository, ${seen.programLines} lines`);
  assert.deepEqual(seen.outputTables, [[6, 4]]);
  assert.deepEqual(seen.exercises, ['Exercise 1', 'Exercise 2']);
  assert.deepEqual(seen.ioTerms, ['INPUT', 'PROCESS', 'OUTPUT']);
  assert.deepEqual(seen.labs, [{ model: 'gantry_gripper', mounted: 'true', canvases: 1, sliders: 3, readouts: 6 }]);
  assert.equal(seen.questions, 4);
}

async function checkQuiz(page) {
  assert.equal(await answer(page, 0, '12'), 'wrong');
  assert.equal(await answer(page, 0, '13'), 'right');
  assert.equal(await answer(page, 1, '1.5'), 'wrong');
  assert.equal(await answer(page, 1, '15'), 'right');
  assert.equal(await answer(page, 2, '3'), 'right');
  assert.equal(await answer(page, 3, null), 'revealed');
  const reference = page.locator('.quiz .question[data-index="3"] .explain');
  assert.ok(await reference.isVisible());
  assert.match(await reference.textContent(), /<general joint="j" gainprm="4" biastype="affine"/);
  console.log('knowledge check: 12 wrong, 13 right, "1.5" wrong, "15" right, "3" right, open reference shown');
}

// On a wide screen the docked lab stays in view at the right of the text while the page
// scrolls to the knowledge check; screenshot lesson_page_docked.png.
async function checkDocked(browser, url) {
  const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
  await page.goto(url);
  await page.waitForSelector('section.lab-mount[data-mounted="true"]', { timeout: 60000 });
  await page.evaluate(() => document.querySelector('.quiz').scrollIntoView());
  await page.waitForTimeout(300);
  const boxes = await page.evaluate(() => {
    const box = (e) => e.getBoundingClientRect().toJSON();
    return { lab: box(document.querySelector('section.lab-mount')), main: box(document.querySelector('main')),
             quiz: box(document.querySelector('.quiz')), scrolled: window.scrollY };
  });
  const { lab, main, quiz } = boxes;
  assert.ok(boxes.scrolled > 2000 && quiz.top < 900, `scrolled to the quiz: ${JSON.stringify(boxes)}`);
  assert.ok(lab.top >= 0 && lab.top < 50 && lab.left >= main.right && lab.width > 400 && lab.right <= 1600,
            `the docked lab stays in view beside the text: ${JSON.stringify(boxes)}`);
  await page.screenshot({ path: path.join(outDir, 'lesson_page_docked.png') });
  await page.close();
  console.log(`docked: the lab stays at x ${lab.left.toFixed(0)}..${lab.right.toFixed(0)}, text ends at ${main.right.toFixed(0)}`);
}

// Without web/lab/lab.mjs (the request refused here), the lab section shows the parsed spec.
async function checkPlaceholder(browser, url) {
  const page = await browser.newPage();
  await page.route('**/lab/lab.mjs', (route) => route.fulfill({ status: 404, body: 'missing' }));
  await page.goto(url);
  await page.waitForSelector('section.lab-mount[data-mounted="placeholder"]', { timeout: 15000 });
  const spec = JSON.parse(await page.locator('section.lab-mount pre.lab-spec').textContent());
  assert.equal(spec.model, 'gantry_gripper');
  assert.equal(spec.controls.length, 3);
  assert.equal(await page.locator('.quiz .question').count(), 4);
  await page.close();
  console.log('without /lab/lab.mjs: the lab section shows the parsed spec, the rest of the page works');
}

async function main() {
  const { browser, url, close } = await openLabSession(options);
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 900 } });
    const lessonErrors = collectProblems(page);
    await page.goto(url);
    await page.waitForSelector('body[data-ready]', { timeout: 15000 });
    assert.equal(await page.getAttribute('body', 'data-ready'), 'true');
    // The lab mounts live (its engine and model load) or the page says why not.
    await page.waitForSelector('section.lab-mount[data-mounted]', { timeout: 60000 });
    await checkPage(page);
    await page.screenshot({ path: path.join(outDir, 'lesson_page_top.png') });
    await page.screenshot({ path: path.join(outDir, 'lesson_page_full.png'), fullPage: true });
    await page.evaluate(() => document.getElementById('the-actuator-model').scrollIntoView());
    await page.screenshot({ path: path.join(outDir, 'lesson_page_model.png') });
    await checkQuiz(page);
    await page.locator('.quiz').screenshot({ path: path.join(outDir, 'lesson_page_quiz.png') });
    assert.deepEqual(lessonErrors, []);
    await checkDocked(browser, url);
    await checkPlaceholder(browser, url);
    console.log(`screenshots in ${outDir}: lesson_page_top.png lesson_page_model.png lesson_page_full.png lesson_page_quiz.png lesson_page_docked.png`);
    console.log('PASS');
  } finally {
    await close();
  }
}

main().catch((e) => {
  console.error(`FAIL: ${e.stack ?? e}`);
  process.exit(1);
});

// The lesson's document model (parse.mjs) as DOM. No innerHTML anywhere: lesson text
// is always text, so "<actuator>" or "<code><general .../></code>" show as written.
//
// renderLesson(doc, container, {baseUrl, loadLab, fetchText}) appends one element per
// block. Each lab block becomes a <section class="lab-mount"> handed to mountLab(element,
// spec, {baseUrl}) from web/lab/lab.mjs (loaded by `loadLab`, dynamically); if that module
// is missing or fails, the section shows the parsed spec instead. A program block shows
// the program from the repository (fetchText(url) -> its text), printed output becomes
// tables where its columns line up, and exercises are set apart.
import { mathToDom } from './math.mjs';
import { parseHtmlSubset, parseInline } from './parse.mjs';
import { grade } from './quiz.mjs';

// document.createElement with a class and children (strings become text).
function make(doc, tag, className, children = []) {
  const e = doc.createElement(tag);
  if (className) e.className = className;
  for (const child of children) e.append(child);
  return e;
}

// Inline pieces ({t, v}) as nodes.
function inlineNodes(doc, pieces) {
  return pieces.map((p) => {
    if (p.t === 'code') return make(doc, 'code', '', [p.v]);
    if (p.t === 'math') return mathToDom(p.v, doc, false);
    if (p.t === 'displaymath') return mathToDom(p.v, doc, true);
    if (p.t === 'strong') return make(doc, 'strong', '', [p.v]);
    return doc.createTextNode(p.v);
  });
}

const inline = (doc, text) => inlineNodes(doc, parseInline(text));

// The knowledge check's HTML subset as <p> elements.
function htmlParagraphs(doc, html, className) {
  return make(doc, 'div', className, parseHtmlSubset(html ?? '').map((pieces) =>
    make(doc, 'p', '', inlineNodes(doc, pieces))));
}

function slug(text) {
  return text.toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '');
}

function renderHeading(doc, block) {
  const h = make(doc, `h${Math.min(block.level + 1, 6)}`, 'lesson-heading', inline(doc, block.text));
  h.id = slug(block.text);
  return h;
}

function renderTable(doc, block) {
  const row = (cells, tag) => make(doc, 'tr', '', cells.map((c) => make(doc, tag, '', inline(doc, c))));
  return make(doc, 'div', 'table-wrap', [make(doc, 'table', 'lesson-table', [
    make(doc, 'thead', '', [row(block.header, 'th')]),
    make(doc, 'tbody', '', block.rows.map((r) => row(r, 'td'))),
  ])]);
}

const kCalloutNames = { established: 'Established', implementation: 'Implementation',
  recommendation: 'Recommendation', warning: 'Warning', note: 'Note' };

function renderCallout(doc, block) {
  const kind = kCalloutNames[block.kind] ?? block.kind;
  const aside = make(doc, 'aside', `callout callout-${block.kind}`, [
    make(doc, 'div', 'callout-kind', [kind]),
  ]);
  if (block.title) aside.append(make(doc, 'div', 'callout-title', inline(doc, block.title)));
  for (const b of block.body) aside.append(renderBlock(doc, b, {}));
  return aside;
}

// ```io: INPUT / PROCESS / OUTPUT lines as a definition list.
function renderIo(doc, block) {
  const dl = make(doc, 'dl', 'io');
  for (const line of block.text.split('\n')) {
    const m = /^([A-Z]+):\s*(.*)$/.exec(line);
    if (m) dl.append(make(doc, 'dt', '', [m[1]]), make(doc, 'dd', '', inline(doc, m[2])));
    else if (line.trim()) dl.append(make(doc, 'dd', '', inline(doc, line)));
  }
  return dl;
}

// Words of a line of printed output, a bracketed group ([0. -10. -1.]) counting as one.
function outputWords(line) {
  return line.match(/\[[^\]]*\]|\S+/g) ?? [];
}

// Printed output: a line of 3 or more words none of which is a number, followed by at
// least 2 lines of as many words, is a table (that line its header); the other lines
// stay as printed.
function renderOutput(doc, text) {
  const box = make(doc, 'div', 'output');
  const lines = text.split('\n');
  let plain = [];
  const flush = () => {
    if (plain.length) box.append(make(doc, 'pre', '', [make(doc, 'code', 'language-text', [plain.join('\n')])]));
    plain = [];
  };
  const isHeader = (words) => words.length >= 3 && words.every((w) => !Number.isFinite(Number(w)));
  for (let i = 0; i < lines.length;) {
    const width = isHeader(outputWords(lines[i])) ? outputWords(lines[i]).length : 0;
    let end = i + 1;
    while (end < lines.length && width >= 3 && outputWords(lines[end]).length === width) end++;
    if (end - i < 3) {
      plain.push(lines[i++]);
      continue;
    }
    flush();
    const [header, ...rows] = lines.slice(i, end).map(outputWords);
    box.append(make(doc, 'table', 'output-table', [
      make(doc, 'thead', '', [make(doc, 'tr', '', header.map((h) => make(doc, 'th', '', [h])))]),
      make(doc, 'tbody', '', rows.map((r) => make(doc, 'tr', '', r.map((c) => make(doc, 'td', '', [c]))))),
    ]));
    i = end;
  }
  flush();
  return box;
}

// A program block names its file in the repository (```python file=examples/x.py): the
// caption links to it and says how to run it; the program itself is fetched from the
// repository (`fetchText`), since the lesson's copy lost its line breaks, and a C++
// program of the same name, if the repository has one, is linked too.
function renderProgram(doc, block, figure, options) {
  const file = block.attrs.file;
  const link = make(doc, 'a', 'program-link', [file]);
  link.href = `/${file}`;
  const caption = make(doc, 'figcaption', '', [link, ' · run: ', make(doc, 'code', '', [`python3 ${file}`])]);
  const code = make(doc, 'code', `language-${block.lang}`, [block.text]);
  figure.append(caption, make(doc, 'pre', '', [code]));
  if (!options.fetchText) return;
  options.fetchText(`/${file}`).then((text) => {
    code.textContent = text;
    figure.dataset.source = 'repository';
  }).catch(() => {});
  const cpp = file.replace(/\.py$/, '.cpp');
  if (cpp === file) return;
  options.fetchText(`/${cpp}`).then(() => {
    const other = make(doc, 'a', 'program-link', [cpp]);
    other.href = `/${cpp}`;
    const target = cpp.replace(/^examples\//, 'build/').replace(/\.cpp$/, '');
    caption.append(' · C++: ', other, ' (', make(doc, 'code', '', [target]), ')');
  }).catch(() => {});
}

function renderCode(doc, block, options = {}) {
  if (block.lang === 'io') return renderIo(doc, block);
  const figure = make(doc, 'figure', `code code-${block.lang}`);
  if (block.attrs.file) {
    renderProgram(doc, block, figure, options);
  } else if (block.lang === 'text') {
    figure.append(make(doc, 'figcaption', '', ['output']), renderOutput(doc, block.text));
  } else {
    figure.append(make(doc, 'figcaption', '', [block.lang]),
                  make(doc, 'pre', '', [make(doc, 'code', `language-${block.lang}`, [block.text])]));
  }
  return figure;
}

// An exercise, set apart and numbered.
function renderExercise(doc, block) {
  return make(doc, 'section', 'exercise', [make(doc, 'h4', 'exercise-title', [`Exercise ${block.number}`]),
    make(doc, 'p', '', inline(doc, block.text))]);
}

// The lab's title and why it is not live (yet); with `showSpec`, the parsed spec too,
// where the live lab cannot run.
function labPlaceholder(doc, element, block, reason, showSpec = true) {
  element.classList.add('lab-placeholder');
  element.replaceChildren(
    make(doc, 'div', 'lab-title', [block.spec?.title ?? 'Lab']),
    make(doc, 'p', 'lab-reason', [reason]));
  if (showSpec) {
    element.append(make(doc, 'pre', 'lab-spec', [block.spec ? JSON.stringify(block.spec, null, 2) : block.raw]));
  }
}

function renderLab(doc, block, options) {
  const section = make(doc, 'section', 'lab-mount');
  section.dataset.model = block.spec?.model ?? '';
  // "dock": true keeps the lab in view beside the text on wide screens (lesson.css).
  // Only the first docked lab of a page docks (two would cover each other).
  if (block.spec?.dock === true && !doc.querySelector('.lab-docked')) {
    section.classList.add('lab-docked');
    doc.body?.classList.add('has-docked-lab');
  }
  if (block.error) {
    labPlaceholder(doc, section, block, `The lab block's JSON could not be read: ${block.error}`);
    return section;
  }
  labPlaceholder(doc, section, block, 'Loading the live lab…', false);
  const load = options.loadLab ?? (() => Promise.reject(new Error('no lab loader')));
  load().then(async (module) => {
    section.classList.remove('lab-placeholder');
    section.replaceChildren();
    // A lab that cannot start (its model fails to load) says why in place.
    await module.mountLab(section, block.spec, { baseUrl: options.baseUrl })
      .then(() => { section.dataset.mounted = 'true'; }, () => { section.dataset.mounted = 'error'; });
  }).catch((e) => {
    labPlaceholder(doc, section, block, `The live lab is not available here (${e.message}); its specification:`);
    section.dataset.mounted = 'placeholder';
  });
  return section;
}

// One question: its text, an answer control, a Check button and the feedback.
function renderQuestion(doc, question, index) {
  const box = make(doc, 'div', `question question-${question.kind}`);
  box.dataset.index = String(index);
  box.append(make(doc, 'div', 'question-number', [`Question ${index + 1}`]),
             htmlParagraphs(doc, question.q, 'question-text'));
  const feedback = make(doc, 'div', 'feedback');
  feedback.setAttribute('aria-live', 'polite');
  const explain = htmlParagraphs(doc, question.explain ?? question.reference, 'explain');
  explain.hidden = true;
  let response = () => null;
  if (question.kind === 'numeric') {
    const input = make(doc, 'input', 'answer-input');
    input.type = 'text';
    input.inputMode = 'decimal';
    input.setAttribute('aria-label', `answer to question ${index + 1}`);
    box.append(make(doc, 'label', 'answer', [input, ` ${question.unit ?? ''}`]));
    response = () => input.value;
  } else if (question.kind === 'mcq') {
    const name = `q${index}`;
    const list = make(doc, 'div', 'options', (question.options ?? []).map((option, k) => {
      const radio = make(doc, 'input');
      radio.type = 'radio';
      radio.name = name;
      radio.value = String(k);
      return make(doc, 'label', 'option', [radio, ' ', ...inline(doc, option)]);
    }));
    box.append(list);
    response = () => {
      const checked = list.querySelector('input:checked');
      return checked ? Number(checked.value) : -1;
    };
  } else {
    box.append(make(doc, 'textarea', 'open-answer'));
  }
  const button = make(doc, 'button', 'check', [question.kind === 'open' ? 'Show the reference answer' : 'Check']);
  button.type = 'button';
  button.addEventListener('click', () => {
    const result = grade(question, response());
    box.dataset.result = result.status;
    feedback.textContent = result.message;
    explain.hidden = result.status === 'invalid';
  });
  box.append(button, feedback, explain);
  return box;
}

function renderQuiz(doc, block) {
  const quiz = block.quiz;
  const section = make(doc, 'section', 'quiz', [make(doc, 'h2', 'lesson-heading', [quiz.title ?? 'Knowledge check'])]);
  section.id = quiz.id ? `quiz-${slug(quiz.id)}` : 'quiz';
  quiz.questions.forEach((q, i) => section.append(renderQuestion(doc, q, i)));
  return section;
}

function renderBlock(doc, block, options) {
  switch (block.type) {
    case 'heading': return renderHeading(doc, block);
    case 'paragraph': return make(doc, 'p', '', inline(doc, block.text));
    case 'math': return mathToDom(block.tex, doc, true);
    case 'table': return renderTable(doc, block);
    case 'callout': return renderCallout(doc, block);
    case 'code': return renderCode(doc, block, options);
    case 'exercise': return renderExercise(doc, block);
    case 'lab': return renderLab(doc, block, options);
    case 'quiz': return renderQuiz(doc, block);
    default: return make(doc, 'p', 'unknown-block', [`(a ${block.type} block is not supported yet)`]);
  }
}

// Appends the lesson to `container`; returns the lab sections (for whoever waits on them).
export function renderLesson(lesson, container, options = {}) {
  const doc = container.ownerDocument;
  const labs = [];
  for (const block of lesson.blocks) {
    const element = renderBlock(doc, block, options);
    element.dataset.line = String(block.line ?? '');
    if (block.type === 'lab') labs.push(element);
    container.append(element);
  }
  return labs;
}

// The lesson parser: lesson text (taken verbatim) -> a document model, a list of blocks.
//
//   {type: 'heading', level, text}            # and ## lines
//   {type: 'paragraph', text}                 one line of prose (inline `code`, $math$)
//   {type: 'math', tex}                       a $$...$$ line
//   {type: 'table', header: [..], rows: [[..]]}   rows may be wrapped over several lines
//   {type: 'callout', kind, title, body: [blocks]} > [!kind] Title / [!kind] Title text...
//   {type: 'code', lang, attrs, text, closed}  ```python file=..., ```text, ```io
//   {type: 'exercise', number, text}         a paragraph that sets an exercise
//   {type: 'lab', engine, spec, raw, error}    ```lab simlab {...} (JSON, typographic quotes ok)
//   {type: 'quiz', quiz: {id, title, questions}} the knowledge check's JSON object
//
// Every block carries `line` (1-based) for messages. The parser never throws: a lab
// block whose JSON cannot be read keeps its raw text and an `error`.
//
// The lesson files come from a copy that lost blank lines and most closing fences, so a
// fence without its closing ``` ends at the next block that is clearly not its content
// (another fence, a heading, a callout, the knowledge check, or a prose sentence).

import { checkLabSpec, isDoubleQuote, parseLenientJson } from '../lab/spec.mjs';

// ---------------------------------------------------------------- JSON objects over lines

// End index (exclusive) of the balanced {...} starting at `start` in `text`, honouring
// strings with any kind of double quote; -1 when it never closes.
function balancedEnd(text, start) {
  let depth = 0;
  let inString = false;
  for (let i = start; i < text.length; i++) {
    const c = text[i];
    if (inString) {
      if (c === '\\') i++;
      else if (isDoubleQuote(c)) inString = false;
    } else if (isDoubleQuote(c)) {
      inString = true;
    } else if (c === '{' || c === '[') {
      depth++;
    } else if ((c === '}' || c === ']') && --depth === 0) {
      return i + 1;
    }
  }
  return -1;
}

// The JSON object that starts at lines[i] (column `column`), possibly over several
// lines: {json, next (line index after it), rest (text after the object on its last line)}.
function readJsonObject(lines, i, column) {
  let text = lines[i].slice(column);
  for (let j = i; j < lines.length; j++) {
    if (j > i) text += '\n' + lines[j];
    const end = balancedEnd(text, text.indexOf('{'));
    if (end >= 0) return { json: text.slice(0, end), next: j + 1, rest: text.slice(end).trim() };
  }
  return { json: text, next: lines.length, rest: '' };
}

// ---------------------------------------------------------------- inline text

// `code`, $$display$$ and $inline$ math in a line of prose:
// [{t: 'text' | 'code' | 'math' | 'displaymath', v}].
export function parseInline(text) {
  const out = [];
  const pattern = /`([^`]+)`|\$\$(.+?)\$\$|\$([^$]+?)\$/g;
  let last = 0;
  for (const m of text.matchAll(pattern)) {
    if (m.index > last) out.push({ t: 'text', v: text.slice(last, m.index) });
    if (m[1] !== undefined) out.push({ t: 'code', v: m[1] });
    else if (m[2] !== undefined) out.push({ t: 'displaymath', v: m[2] });
    else out.push({ t: 'math', v: m[3] });
    last = m.index + m[0].length;
  }
  if (last < text.length) out.push({ t: 'text', v: text.slice(last) });
  return out;
}

const kHtmlEntities = { '&lt;': '<', '&gt;': '>', '&amp;': '&', '&quot;': '"', '&#39;': "'" };

function decodeEntities(text) {
  return text.replace(/&(lt|gt|amp|quot|#39);/g, (e) => kHtmlEntities[e]);
}

// The small HTML subset of the knowledge check (<p>, <code>, <b>, <i>, <em>, <strong>,
// <br>) as paragraphs of inline pieces. The inside of <code> is literal text (the lesson
// writes <code><general .../></code>); any other tag is shown as text, never as markup.
export function parseHtmlSubset(html) {
  const paragraphs = [];
  let current = [];
  const flush = () => {
    if (current.length) paragraphs.push(current);
    current = [];
  };
  const emphasis = [];
  const tag = /<code>([\s\S]*?)<\/code>|<(\/?)(p|b|i|em|strong|br\s*\/?)>/g;
  let last = 0;
  const pushText = (text) => {
    for (const piece of parseInline(decodeEntities(text))) {
      if (piece.t === 'text' && emphasis.length) piece.t = 'strong';
      current.push(piece);
    }
  };
  for (const m of html.matchAll(tag)) {
    if (m.index > last) pushText(html.slice(last, m.index));
    last = m.index + m[0].length;
    if (m[1] !== undefined) {
      current.push({ t: 'code', v: decodeEntities(m[1]) });
    } else if (m[3] === 'p' || m[3].startsWith('br')) {
      flush();
    } else if (m[2]) {
      emphasis.pop();
    } else {
      emphasis.push(m[3]);
    }
  }
  if (last < html.length) pushText(html.slice(last));
  flush();
  return paragraphs;
}

// ---------------------------------------------------------------- line classes

const kFence = /^```\s*([A-Za-z0-9_-]*)\s*(.*)$/;
const kHeading = /^(#{1,6})\s+(.+)$/;
const kCallout = /^(>\s*)?\[!([A-Za-z-]+)\]\s*(.*)$/;
const kDisplayMath = /^\$\$(.+)\$\$\s*$/;
const kTableSeparator = /^\|?\s*:?-{3,}:?\s*(\|\s*:?-{3,}:?\s*)*\|?\s*$/;

// A sentence of prose: capitalised word, at least five words, ends with a full stop.
function isProse(line) {
  return /^[A-Z][a-z']/.test(line) && line.trim().split(/\s+/).length >= 5 && /[.!?]$/.test(line.trim());
}

// A short label that introduces the next block ("Output:").
function isLabel(line) {
  return /^[A-Z][a-z]+( [a-z]+){0,2}:$/.test(line.trim());
}

// The knowledge check: a JSON object whose first line names its questions or id.
function startsQuiz(line) {
  return /^\s*\{\s*"(id|questions|title)"\s*:/.test(line) && /"questions"|"id"/.test(line);
}

// A line that starts a block of its own (ends an unclosed fence or a wrapped callout).
function startsBlock(line) {
  return kFence.test(line) || kHeading.test(line) || kCallout.test(line) || startsQuiz(line) ||
         (line.startsWith('|') && line.trim().endsWith('|'));
}

// ---------------------------------------------------------------- block readers

// `| a | b |` or a wrapped piece `b |` -> its cells, trimmed (| inside `code` or $math$ kept).
function splitCells(line) {
  let text = line.trim();
  if (text.startsWith('|')) text = text.slice(1);
  if (text.endsWith('|')) text = text.slice(0, -1);
  const cells = [];
  let cell = '';
  let quote = '';
  for (const c of text) {
    if (quote) {
      if (c === quote) quote = '';
    } else if (c === '`' || c === '$') {
      quote = c;
    } else if (c === '|') {
      cells.push(cell.trim());
      cell = '';
      continue;
    }
    cell += c;
  }
  cells.push(cell.trim());
  return cells;
}

// A table: header line, separator, then rows; a row's cells may continue on the next
// lines (each piece ending with |) until the row has as many cells as the header.
function readTable(lines, i) {
  const header = splitCells(lines[i]);
  const rows = [];
  let pending = [];
  let j = i + 2;
  for (; j < lines.length; j++) {
    const line = lines[j].trim();
    if (!line || kFence.test(line) || !(line.startsWith('|') || line.endsWith('|'))) break;
    pending.push(...splitCells(line));
    while (pending.length >= header.length) rows.push(pending.splice(0, header.length));
  }
  if (pending.length) rows.push([...pending, ...Array(header.length - pending.length).fill('')]);
  return { block: { type: 'table', header, rows }, next: j };
}

// `key=value` words at the start of a fence's info string; the rest is content.
function fenceAttributes(info) {
  const attrs = {};
  let rest = info;
  for (let m; (m = /^([A-Za-z_][\w-]*)=("[^"]*"|\S+)\s*/.exec(rest));) {
    attrs[m[1]] = m[2].replace(/^"|"$/g, '');
    rest = rest.slice(m[0].length);
  }
  return { attrs, rest };
}

// Where an unclosed fence's content stops: before the next block or prose sentence
// (and before a label such as "Output:" that introduces the next fence).
function unclosedEnd(lines, j) {
  for (let k = j; k < lines.length; k++) {
    const line = lines[k];
    if (startsBlock(line) || isProse(line)) return k;
    if (isLabel(line) && k + 1 < lines.length && kFence.test(lines[k + 1])) return k;
  }
  return lines.length;
}

// Why a lab block's JSON is not a usable spec ('' when it is).
function labSpecProblem(spec) {
  try {
    checkLabSpec(spec);
    return '';
  } catch (e) {
    return e.message;
  }
}

// A lab block: ```lab ENGINE {json} (``` optional), the JSON possibly over several lines.
function readLab(lines, i, info) {
  const engine = /^[A-Za-z]\w*/.exec(info)?.[0] ?? '';
  const column = lines[i].indexOf('{');
  if (column < 0) return { block: { type: 'lab', engine, spec: null, raw: '', error: 'no JSON object' }, next: i + 1 };
  const { json, next, rest } = readJsonObject(lines, i, column);
  const parsed = parseLenientJson(json);
  const block = { type: 'lab', engine, spec: parsed.value ?? null, raw: json };
  if (parsed.error) block.error = parsed.error;
  else block.error = labSpecProblem(parsed.value);
  if (!block.error) delete block.error;
  const closedAfter = rest.startsWith('```') || (next < lines.length && lines[next].trim() === '```');
  return { block, next: !rest.startsWith('```') && closedAfter ? next + 1 : next };
}

// A fenced block: content until the closing ``` (or where an unclosed one evidently ends).
function readFence(lines, i) {
  const [, lang, info] = kFence.exec(lines[i]);
  if (lang === 'lab') return readLab(lines, i, info);
  const { attrs, rest } = fenceAttributes(info);
  const content = rest ? [rest] : [];
  let j = i + 1;
  const close = lines.findIndex((line, k) => k > i && line.trim() === '```');
  const nextFence = lines.findIndex((line, k) => k > i && kFence.test(line) && line.trim() !== '```');
  const closed = close >= 0 && (nextFence < 0 || close < nextFence);
  const end = closed ? close : unclosedEnd(lines, j);
  for (; j < end; j++) content.push(lines[j]);
  return { block: { type: 'code', lang: lang || 'text', attrs, text: content.join('\n'), closed },
           next: closed ? end + 1 : end };
}

// Splits "Title words Body text..." where the body's first sentence begins: the first
// capitalised word that follows a lower-case word.
function splitCalloutTitle(text) {
  const words = text.split(' ');
  for (let k = 2; k < words.length; k++) {
    if (/^[A-Z][a-z]/.test(words[k]) && /[a-z0-9,]$/.test(words[k - 1])) {
      return { title: words.slice(0, k).join(' '), body: words.slice(k).join(' ') };
    }
  }
  return { title: '', body: text };
}

// Body lines of a callout as paragraphs and display math.
function calloutBody(lines) {
  return lines.filter((line) => line.trim()).map((line) => {
    const math = kDisplayMath.exec(line.trim());
    return math ? { type: 'math', tex: math[1].trim() } : { type: 'paragraph', text: line.trim() };
  });
}

// A callout: "> [!kind] Title" with "> " body lines, or "[!kind] Title Body ..." on one
// line whose text may wrap onto the next lines until a sentence ends.
function readCallout(lines, i) {
  const [, marker, kind, rest] = kCallout.exec(lines[i]);
  let j = i + 1;
  const body = [];
  let title = rest.trim();
  if (marker && j < lines.length && lines[j].startsWith('>')) {
    for (; j < lines.length && lines[j].startsWith('>'); j++) body.push(lines[j].replace(/^>\s?/, ''));
  } else {
    let text = rest.trim();
    for (; j < lines.length && !/[.!?:)]$/.test(text) && !startsBlock(lines[j]); j++) {
      text += (/[A-Za-z]$/.test(text) ? ' ' : '') + lines[j].trim();
    }
    const split = splitCalloutTitle(text);
    title = split.title;
    body.push(split.body);
  }
  return { block: { type: 'callout', kind: kind.toLowerCase(), title, body: calloutBody(body) }, next: j };
}

// The knowledge check's JSON object (or, if it does not parse, its lines as paragraphs).
function readQuiz(lines, i) {
  const { json, next } = readJsonObject(lines, i, lines[i].indexOf('{'));
  const parsed = parseLenientJson(json);
  if (parsed.value && Array.isArray(parsed.value.questions)) {
    return { block: { type: 'quiz', quiz: parsed.value }, next };
  }
  return { block: { type: 'paragraph', text: lines[i].trim() }, next: i + 1 };
}

// One block starting at line i: {block, next}.
function readBlock(lines, i) {
  const line = lines[i];
  const heading = kHeading.exec(line);
  if (heading) return { block: { type: 'heading', level: heading[1].length, text: heading[2].trim() }, next: i + 1 };
  if (kFence.test(line)) return readFence(lines, i);
  if (kCallout.test(line)) return readCallout(lines, i);
  if (startsQuiz(line)) return readQuiz(lines, i);
  if (line.trim().startsWith('|') && i + 1 < lines.length && kTableSeparator.test(lines[i + 1].trim())) {
    return readTable(lines, i);
  }
  const math = kDisplayMath.exec(line.trim());
  if (math) return { block: { type: 'math', tex: math[1].trim() }, next: i + 1 };
  return { block: { type: 'paragraph', text: line.trim() }, next: i + 1 };
}

// The whole lesson: {blocks}. Blank lines separate nothing (each line is a block).
export function parseLesson(text) {
  const lines = text.replace(/\r\n?/g, '\n').split('\n');
  const blocks = [];
  for (let i = 0; i < lines.length;) {
    if (!lines[i].trim()) {
      i++;
      continue;
    }
    const { block, next } = readBlock(lines, i);
    block.line = i + 1;
    blocks.push(block);
    i = Math.max(next, i + 1);
  }
  markExercises(blocks);
  return { blocks };
}

// The copy lost the exercises' heading: an exercise is a paragraph of at least
// kExerciseLength characters that opens with an instruction (Replace, Add, Write ...);
// they become {type: 'exercise', number, text}, numbered in order.
const kExerciseStart = /^(Replace|Add|Write|Modify|Extend|Build|Change|Implement|Derive|Measure)\s/;
const kExerciseLength = 120;
function markExercises(blocks) {
  let number = 0;
  for (const block of blocks) {
    if (block.type !== 'paragraph' || block.text.length < kExerciseLength || !kExerciseStart.test(block.text)) continue;
    block.type = 'exercise';
    block.number = ++number;
  }
}

// Lab blocks' JSON: "```lab simlab {JSON}" specs whose JSON may be written with
// typographic quotes (“ ” ‘ ’), normalised to ASCII before parsing. The lesson parser
// (web/lesson/parse.mjs) reads lab blocks with the same functions.

const kBlockStart = /^```lab\s+simlab\s*/;
const kOpenDouble = '\u201c';
const kCloseDouble = '\u201d';
const kSingles = /[\u2018\u2019]/g;

// True for the three double quotes a lesson writes: " “ ”.
export function isDoubleQuote(c) {
  return c === '"' || c === kOpenDouble || c === kCloseDouble;
}

// The next character after position i that is not white space ('' at the end).
function nextVisible(text, i) {
  while (i < text.length && /\s/.test(text[i])) i++;
  return i < text.length ? text[i] : '';
}

// Typographic quotes -> ASCII: a double quote that opens or closes a JSON string becomes
// ", one inside a string (followed by more text) becomes \", and ‘ ’ become '.
export function normalizeQuotes(text) {
  let out = '';
  let inString = false;
  for (let i = 0; i < text.length; i++) {
    const c = text[i];
    if (inString && c === '\\' && i + 1 < text.length) {
      const escaped = text[++i];
      out += isDoubleQuote(escaped) ? '\\"' : c + escaped;
    } else if (isDoubleQuote(c) && !inString) {
      out += '"';
      inString = true;
    } else if (isDoubleQuote(c)) {
      const after = nextVisible(text, i + 1);
      const closes = after === '' || ',:}]'.includes(after);
      out += closes ? '"' : '\\"';
      inString = !closes;
    } else {
      out += c.replace(kSingles, "'");
    }
  }
  return out;
}

// JSON with typographic quotes: the careful normalisation first, then a plain
// replacement. Returns {value} or {error} (the first attempt's message).
export function parseLenientJson(text) {
  const attempts = [normalizeQuotes(text),
    text.replace(/[\u201c\u201d]/g, '"').replace(kSingles, "'")];
  let firstError = null;
  for (const candidate of attempts) {
    try {
      return { value: JSON.parse(candidate) };
    } catch (e) {
      firstError ??= e.message;
    }
  }
  return { error: firstError };
}

// Throws an Error naming the problem unless `spec` is an object naming a model.
export function checkLabSpec(spec) {
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) {
    throw new Error('lab block must be a JSON object');
  }
  if (typeof spec.model !== 'string' || !/^[\w.-]+$/.test(spec.model)) {
    throw new Error('lab block needs "model": the name of a file in models/ (without .xml)');
  }
  return spec;
}

// A lab spec from a block's JSON (or the whole "```lab simlab {...}" line); throws an
// Error naming the problem when it is not a JSON object with a model.
export function parseLabSpec(text) {
  const parsed = parseLenientJson(text.trim().replace(kBlockStart, '').replace(/```\s*$/, ''));
  if (parsed.error) throw new Error(`lab block is not valid JSON: ${parsed.error}`);
  return checkLabSpec(parsed.value);
}

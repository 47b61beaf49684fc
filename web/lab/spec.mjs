// Lab blocks of a lesson: "```lab simlab {JSON}" lines whose JSON may be written with
// typographic quotes (“ ”), which are normalised to ASCII quotes before parsing.

const kBlockStart = /^```lab\s+simlab\s*/;

// The JSON of one lab block with typographic double quotes made ASCII.
export function normalizeQuotes(text) {
  return text.replace(/[\u201C\u201D\u201E\u201F\u2033]/g, '"');
}

// A lab spec from a block's JSON (or the whole "```lab simlab {...}" line); throws an
// Error naming the problem when it is not a JSON object with a model.
export function parseLabSpec(text) {
  const json = normalizeQuotes(text.trim().replace(kBlockStart, ''));
  let spec;
  try {
    spec = JSON.parse(json);
  } catch (error) {
    throw new Error(`lab block is not valid JSON: ${error.message}`);
  }
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) {
    throw new Error('lab block must be a JSON object');
  }
  if (typeof spec.model !== 'string' || !/^[\w.-]+$/.test(spec.model)) {
    throw new Error('lab block needs "model": the name of a file in models/ (without .xml)');
  }
  return spec;
}

// Every lab block of a lesson's text: [{line (1-based), spec}].
export function extractLabSpecs(lessonText) {
  const blocks = [];
  lessonText.split('\n').forEach((line, i) => {
    if (kBlockStart.test(line.trim())) blocks.push({ line: i + 1, spec: parseLabSpec(line) });
  });
  return blocks;
}

// Grading the knowledge check. Question kinds (the lesson's JSON):
//   numeric: {q, answer, tol, unit, explain}   right when |response - answer| <= tol
//   mcq:     {q, options, answer (index), explain}
//   open:    {q, reference}                   nothing to grade: the reference is revealed
// grade(question, response) -> {status: 'right' | 'wrong' | 'invalid' | 'revealed', message}.

// Room for the decimal representation of the tolerance itself (13.001 vs 13 with 0.001).
const kRoundoff = 1e-9;

// A number typed by a person: decimal comma accepted, a trailing unit ignored.
export function readNumber(text) {
  const m = /^\s*([-+\u2212]?(\d+([.,]\d*)?|[.,]\d+)([eE][-+]?\d+)?)/.exec(String(text ?? ''));
  if (!m) return NaN;
  return Number(m[1].replace(',', '.').replace('\u2212', '-'));
}

function gradeNumeric(question, response) {
  const value = typeof response === 'number' ? response : readNumber(response);
  if (!Number.isFinite(value)) return { status: 'invalid', message: 'Enter a number.' };
  const tol = Number(question.tol ?? 0);
  const ok = Math.abs(value - Number(question.answer)) <= tol * (1 + kRoundoff) + 1e-12;
  return { status: ok ? 'right' : 'wrong', message: ok ? 'Right.' : 'Not quite.' };
}

// The response is an option index, or the option's text.
function gradeChoice(question, response) {
  const options = question.options ?? [];
  const index = typeof response === 'number' ? response : options.indexOf(String(response));
  if (!(index >= 0 && index < options.length)) return { status: 'invalid', message: 'Choose an option.' };
  const ok = index === Number(question.answer);
  return { status: ok ? 'right' : 'wrong', message: ok ? 'Right.' : 'Not quite.' };
}

export function grade(question, response) {
  switch (question.kind) {
    case 'numeric': return gradeNumeric(question, response);
    case 'mcq': return gradeChoice(question, response);
    case 'open': return { status: 'revealed', message: 'Compare your answer with the reference.' };
    default: return { status: 'invalid', message: `question kind "${question.kind}" is not supported yet` };
  }
}

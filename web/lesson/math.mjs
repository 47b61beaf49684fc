// The lessons' math, typeset by KaTeX (npm): mathToDom(tex, document, display) returns a
// <span class="math"> (or a display <div class="math math-display">) that KaTeX fills with
// its own DOM nodes (no HTML strings: lesson text stays text). TeX that KaTeX cannot read is
// shown as its source, marked data-error with KaTeX's message, never dropped.
// texError(tex) is that message, or null when the TeX typesets (usable without a DOM).
import katex from '../node_modules/katex/dist/katex.mjs';

// KaTeX's options: errors thrown (so they can be shown and tested), no \href or
// \includegraphics from lesson text.
function options(display) {
  return { displayMode: display, throwOnError: true, trust: false, output: 'htmlAndMathml' };
}

export function texError(tex) {
  try {
    katex.renderToString(tex, options(false));
    return null;
  } catch (e) {
    return e.message;
  }
}

export function mathToDom(tex, doc, display = false) {
  const element = doc.createElement(display ? 'div' : 'span');
  element.className = display ? 'math math-display' : 'math';
  try {
    katex.render(tex, element, options(display));
  } catch (e) {
    element.textContent = tex;
    element.dataset.error = e.message;
  }
  return element;
}

// A small TeX renderer for the math the lessons use: letters (italic), numbers,
// operators, subscripts and superscripts, \frac \tfrac \dfrac, accents (\dot \ddot \hat
// \bar \vec), \text, Greek letters, \sum \nabla \times and friends, spacing commands.
//
// parseTex(tex) -> {nodes, unknown}: a tree of
//   {k: 'mi' | 'mn' | 'mo' | 'mtext', v}   identifier, number, operator, upright text
//   {k: 'space', v}                        a space of width v em
//   {k: 'group', c: [nodes]}
//   {k: 'script', base, sub, sup}          sub/sup are nodes or null
//   {k: 'frac', num, den}
//   {k: 'accent', mark, base}              mark is a combining character
// `unknown` lists commands it does not know (rendered as their name, never dropped).
// mathToDom(nodes, document, display) builds the DOM; mathToText gives a readable line.

const kGreek = {
  alpha: 'α', beta: 'β', gamma: 'γ', delta: 'δ', epsilon: 'ε', varepsilon: 'ε', zeta: 'ζ',
  eta: 'η', theta: 'θ', iota: 'ι', kappa: 'κ', lambda: 'λ', mu: 'μ', nu: 'ν', xi: 'ξ', pi: 'π',
  rho: 'ρ', sigma: 'σ', tau: 'τ', phi: 'φ', varphi: 'φ', chi: 'χ', psi: 'ψ', omega: 'ω',
  Gamma: 'Γ', Delta: 'Δ', Theta: 'Θ', Lambda: 'Λ', Pi: 'Π', Sigma: 'Σ', Phi: 'Φ', Omega: 'Ω',
};
const kSymbols = {
  sum: '∑', prod: '∏', int: '∫', nabla: '∇', partial: '∂', times: '×', cdot: '·', pm: '±',
  le: '≤', leq: '≤', ge: '≥', geq: '≥', ne: '≠', neq: '≠', approx: '≈', infty: '∞', to: '→',
  rightarrow: '→', leftarrow: '←', ldots: '…', dots: '…', cdots: '⋯', in: '∈', sim: '∼',
  min: 'min', max: 'max', exp: 'exp', log: 'log', sin: 'sin', cos: 'cos', quad: ' ',
};
const kAccents = { dot: '\u0307', ddot: '\u0308', hat: '\u0302', bar: '\u0304', vec: '\u20d7', tilde: '\u0303' };
const kSpaces = { ',': 0.17, ':': 0.22, ';': 0.28, '!': 0, ' ': 0.25, quad: 1, qquad: 2 };
const kFractions = new Set(['frac', 'tfrac', 'dfrac']);
const kTextCommands = new Set(['text', 'mathrm', 'textrm', 'operatorname', 'mathbf']);
const kIgnored = new Set(['left', 'right', 'displaystyle', 'big', 'Big', 'bigl', 'bigr']);

// Recursive descent over the TeX source.
class TexReader {
  constructor(tex) {
    this.tex = tex;
    this.i = 0;
    this.unknown = [];
  }

  skipSpace() {
    while (this.i < this.tex.length && /\s/.test(this.tex[this.i])) this.i++;
  }

  // Nodes until '}' or the end.
  row() {
    const nodes = [];
    for (this.skipSpace(); this.i < this.tex.length && this.tex[this.i] !== '}'; this.skipSpace()) {
      const node = this.scripted();
      if (node) nodes.push(node);
    }
    return nodes;
  }

  // An atom with its _ and ^ scripts.
  scripted() {
    let base = this.atom();
    for (this.skipSpace(); this.tex[this.i] === '_' || this.tex[this.i] === '^'; this.skipSpace()) {
      const which = this.tex[this.i++] === '_' ? 'sub' : 'sup';
      if (!base || base.k !== 'script') base = { k: 'script', base: base ?? { k: 'group', c: [] }, sub: null, sup: null };
      base[which] = this.argument();
    }
    return base;
  }

  // One argument: a {group} or a single character / command.
  argument() {
    this.skipSpace();
    if (this.tex[this.i] === '{') return this.atom();
    if (/[0-9A-Za-z]/.test(this.tex[this.i] ?? '')) return this.charNode(this.tex[this.i++]);
    return this.atom() ?? { k: 'group', c: [] };
  }

  charNode(c) {
    if (/[0-9.]/.test(c)) return { k: 'mn', v: c };
    if (/[A-Za-z]/.test(c)) return { k: 'mi', v: c };
    return { k: 'mo', v: c === '-' ? '−' : c === '*' ? '∗' : c };
  }

  // Raw text up to the matching '}' (after '{').
  rawGroup() {
    this.skipSpace();
    if (this.tex[this.i] !== '{') return '';
    let depth = 0;
    const start = ++this.i;
    for (; this.i < this.tex.length; this.i++) {
      if (this.tex[this.i] === '{') depth++;
      else if (this.tex[this.i] === '}' && depth-- === 0) break;
    }
    return this.tex.slice(start, this.i++);
  }

  atom() {
    const c = this.tex[this.i];
    if (c === '{') {
      this.i++;
      const c2 = this.row();
      this.i++;
      return { k: 'group', c: c2 };
    }
    if (c === '\\') return this.command();
    this.i++;
    if (/[0-9]/.test(c)) {
      let v = c;
      while (/[0-9.]/.test(this.tex[this.i] ?? '')) v += this.tex[this.i++];
      return { k: 'mn', v };
    }
    return this.charNode(c);
  }

  command() {
    this.i++;
    const name = /^[A-Za-z]+/.exec(this.tex.slice(this.i))?.[0] ?? this.tex[this.i] ?? '';
    this.i += name.length;
    if (name in kSpaces) return { k: 'space', v: kSpaces[name] };
    if (name in kGreek) return { k: 'mi', v: kGreek[name] };
    if (name in kSymbols) return { k: 'mo', v: kSymbols[name] };
    if (name in kAccents) return { k: 'accent', mark: kAccents[name], base: this.argument() };
    if (kFractions.has(name)) return { k: 'frac', num: this.argument(), den: this.argument() };
    if (kTextCommands.has(name)) return { k: 'mtext', v: this.rawGroup() };
    if (kIgnored.has(name)) return null;
    if ('{}_%#&$'.includes(name)) return { k: 'mo', v: name };
    this.unknown.push(name);
    return { k: 'mtext', v: name };
  }
}

export function parseTex(tex) {
  const reader = new TexReader(tex);
  const nodes = [];
  while (reader.i < tex.length) {
    nodes.push(...reader.row());
    if (reader.i < tex.length) reader.i++;  // a stray '}'
  }
  return { nodes, unknown: reader.unknown };
}

const kBinary = new Set(['=', '+', '−', '×', '≤', '≥', '≠', '≈', '→', '·', '±', '<', '>']);

// Readable plain text (sub/superscripts as _x and ^x), e.g. for aria-label and tests.
export function mathToText(nodes) {
  const one = (n) => {
    if (!n) return '';
    switch (n.k) {
      case 'group': return mathToText(n.c);
      case 'script': return `${one(n.base)}${n.sub ? `_${one(n.sub)}` : ''}${n.sup ? `^${one(n.sup)}` : ''} `;
      case 'frac': return `(${one(n.num)})/(${one(n.den)})`;
      case 'accent': return one(n.base) + n.mark;
      case 'space': return ' ';
      case 'mo': return kBinary.has(n.v) ? ` ${n.v} ` : n.v;
      default: return n.v;
    }
  };
  return nodes.map(one).join('').replace(/\s+/g, ' ').replace(/ ([),;])/g, '$1').trim();
}

// A minus or plus sign is unary at the start of a row or after an operator or comma.
function markUnary(nodes) {
  nodes.forEach((n, i) => {
    const before = nodes[i - 1];
    if (n.k === 'mo' && (n.v === '−' || n.v === '+') && (!before || (before.k === 'mo' && before.v !== ')'))) {
      n.unary = true;
    }
  });
  return nodes;
}

// A row of nodes as DOM nodes.
function rowToDom(nodes, doc) {
  return markUnary(nodes).map((n) => nodeToDom(n, doc));
}

// One node as DOM.
function nodeToDom(n, doc) {
  const el = (tag, cls, children = []) => {
    const e = doc.createElement(tag);
    if (cls) e.className = cls;
    for (const child of children) e.append(child);
    return e;
  };
  switch (n.k) {
    case 'mi': return el('i', 'mi', [n.v]);
    case 'mn': return el('span', 'mn', [n.v]);
    case 'mtext': return el('span', 'mtext', [n.v]);
    case 'mo': return el('span', kBinary.has(n.v) && !n.unary ? 'mo mo-binary' : 'mo', [n.v]);
    case 'space': {
      const s = el('span', 'mspace');
      s.style.marginRight = `${n.v}em`;
      return s;
    }
    case 'group': return el('span', 'mrow', rowToDom(n.c, doc));
    case 'accent': {
      const base = nodeToDom(n.base, doc);
      base.append(n.mark);
      return el('span', 'maccent', [base]);
    }
    case 'frac': return el('span', 'mfrac', [el('span', 'mnum', [nodeToDom(n.num, doc)]),
                                             el('span', 'mden', [nodeToDom(n.den, doc)])]);
    case 'script': {
      const parts = [nodeToDom(n.base, doc)];
      if (n.sub) parts.push(el('sub', 'msub', [nodeToDom(n.sub, doc)]));
      if (n.sup) parts.push(el('sup', 'msup', [nodeToDom(n.sup, doc)]));
      return el('span', 'mscript', parts);
    }
    default: return doc.createTextNode('');
  }
}

// A <span class="math"> (or <div class="math math-display">) for a TeX string.
export function mathToDom(tex, doc, display = false) {
  const { nodes, unknown } = parseTex(tex);
  const root = doc.createElement(display ? 'div' : 'span');
  root.className = display ? 'math math-display' : 'math';
  root.setAttribute('data-tex', tex);
  root.setAttribute('aria-label', mathToText(nodes));
  if (unknown.length) root.setAttribute('data-unknown', unknown.join(' '));
  root.append(...rowToDom(nodes, doc));
  return root;
}

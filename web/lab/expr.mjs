// Readout and control expressions of a lab block, parsed (never evaluated as JavaScript).
//
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := '-' unary | primary
//   primary := NUMBER | ('data' | 'model') '.' NAME '[' expr ']' | '(' expr ')'
//
// parseExpr(text) returns a tree; evaluateExpr(tree, read) computes it, where
// read(kind, name, index) returns the number (and throws for an unknown name or an index
// out of range). Errors are ExprError with the column where parsing stopped.

export class ExprError extends Error {}

// Splits text into numbers, names and one-character symbols, each with its column.
function tokenize(text) {
  const tokens = [];
  const pattern = /\s*(?:(\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?)|([A-Za-z_][A-Za-z0-9_]*)|(\S))/y;
  let match;
  while (pattern.lastIndex < text.length && (match = pattern.exec(text))) {
    const column = match.index + match[0].length - (match[1] ?? match[2] ?? match[3] ?? '').length + 1;
    if (match[1] !== undefined) tokens.push({ kind: 'number', value: Number(match[1]), column });
    else if (match[2] !== undefined) tokens.push({ kind: 'name', value: match[2], column });
    else if (match[3] !== undefined) tokens.push({ kind: 'symbol', value: match[3], column });
  }
  tokens.push({ kind: 'end', value: '', column: text.length + 1 });
  return tokens;
}

// A recursive-descent parser over the tokens of one expression.
class Parser {
  constructor(text) {
    this.text = text;
    this.tokens = tokenize(text);
    this.at = 0;
  }

  peek() { return this.tokens[this.at]; }
  next() { return this.tokens[this.at++]; }

  fail(message, token = this.peek()) {
    throw new ExprError(`'${this.text}' column ${token.column}: ${message}`);
  }

  // Consumes the symbol `value` or fails saying what was expected.
  expect(value) {
    const token = this.peek();
    if (token.kind !== 'symbol' || token.value !== value) {
      this.fail(`expected '${value}' but found ${describe(token)}`);
    }
    return this.next();
  }

  isSymbol(...values) {
    const token = this.peek();
    return token.kind === 'symbol' && values.includes(token.value);
  }

  // Left-associative chains of binary operators.
  binary(operators, operand) {
    let left = operand();
    while (this.isSymbol(...operators)) {
      const op = this.next().value;
      left = { op, left, right: operand() };
    }
    return left;
  }

  expression() { return this.binary(['+', '-'], () => this.term()); }
  term() { return this.binary(['*', '/'], () => this.unary()); }

  unary() {
    if (this.isSymbol('-')) {
      this.next();
      return { op: 'neg', operand: this.unary() };
    }
    if (this.isSymbol('+')) {
      this.next();
      return this.unary();
    }
    return this.primary();
  }

  primary() {
    const token = this.peek();
    if (token.kind === 'number') return { number: this.next().value };
    if (this.isSymbol('(')) {
      this.next();
      const inner = this.expression();
      this.expect(')');
      return inner;
    }
    if (token.kind === 'name' && (token.value === 'data' || token.value === 'model')) {
      return this.reference();
    }
    return this.fail(`expected a number, data.NAME[i], model.NAME[i] or '(' but found ${describe(token)}`);
  }

  // data.NAME[index] or model.NAME[index]; the index is itself an expression.
  reference() {
    const source = this.next().value;
    this.expect('.');
    const name = this.peek();
    if (name.kind !== 'name') this.fail(`expected an array name after '${source}.'`);
    this.next();
    this.expect('[');
    const index = this.expression();
    this.expect(']');
    return { source, name: name.value, index };
  }

  parseAll() {
    if (this.peek().kind === 'end') this.fail('empty expression');
    const tree = this.expression();
    if (this.peek().kind !== 'end') this.fail(`unexpected ${describe(this.peek())}`);
    return tree;
  }
}

function describe(token) {
  return token.kind === 'end' ? 'the end' : `'${token.value}'`;
}

// The tree of `text`; throws ExprError on a syntax error.
export function parseExpr(text) {
  if (typeof text !== 'string') throw new ExprError('expression must be a string');
  return new Parser(text).parseAll();
}

// The value of a tree; read(source, name, index) supplies array elements.
export function evaluateExpr(tree, read) {
  if ('number' in tree) return tree.number;
  if ('source' in tree) {
    const index = evaluateExpr(tree.index, read);
    if (!Number.isInteger(index)) {
      throw new ExprError(`${tree.source}.${tree.name}[${index}]: index must be a whole number`);
    }
    return read(tree.source, tree.name, index);
  }
  if (tree.op === 'neg') return -evaluateExpr(tree.operand, read);
  const a = evaluateExpr(tree.left, read);
  const b = evaluateExpr(tree.right, read);
  switch (tree.op) {
    case '+': return a + b;
    case '-': return a - b;
    case '*': return a * b;
    default: return a / b;
  }
}

// The single array element a control writes ("data.ctrl[3]" -> {name: 'ctrl', index: 3}).
export function parseTarget(text) {
  const tree = parseExpr(text);
  if (!('source' in tree) || tree.source !== 'data') {
    throw new ExprError(`'${text}': a control must set one element, data.NAME[i]`);
  }
  const index = evaluateExpr(tree.index, () => {
    throw new ExprError(`'${text}': the index of a control target must be a constant`);
  });
  if (!Number.isInteger(index)) throw new ExprError(`'${text}': the index must be a whole number`);
  return { name: tree.name, index };
}

// A reader over arrays fetched by `fetchArray(source, name)` (null for an unknown name;
// the caller keeps its own arrays, so nothing is cached here); it checks names and indices
// and says which one is wrong.
export function arrayReader(fetchArray) {
  return (source, name, index) => {
    const array = fetchArray(source, name);
    if (!array) throw new ExprError(`no ${source} array named '${name}'`);
    if (index < 0 || index >= array.length) {
      throw new ExprError(`${source}.${name}[${index}]: index out of range (${name} has ${array.length} numbers)`);
    }
    return array[index];
  };
}

// Every array an expression reads: [[source, name], ...] (repeats included).
export function arraysOf(tree, out = []) {
  if (!tree || typeof tree !== 'object') return out;
  if ('source' in tree) {
    out.push([tree.source, tree.name]);
    return arraysOf(tree.index, out);
  }
  for (const key of ['left', 'right', 'operand']) arraysOf(tree[key], out);
  return out;
}

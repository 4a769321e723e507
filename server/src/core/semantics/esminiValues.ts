import { EsminiEvaluationFailure, EsminiStop } from '../diagnostics/expressionFacts';
import { ValueRule } from '../profiles/facts';
import { ExpressionNode } from './expressionParser';
import { ParameterType, ParameterValue, SHARED_MATH_FUNCTIONS, SharedMathFunction } from './values';

/**
 * Values as esmini (release 3.6.0) computes them. esmini keeps every parameter value as text; a
 * `${...}` is its body with each `$name` replaced by that text and a few words rewritten, then
 * evaluated by zserge/expr with doubles throughout, or glued as text when it holds a word the
 * evaluator does not know. Each step names its rule in the esmini profile (core/profiles/esmini.ts),
 * where the lines of esmini's sources are given.
 */

/** What esmini makes of a value: the text it keeps, or why it stops the scenario. */
export type EsminiText =
  | {
      ok: true;
      text: string;
      rules: ValueRule[];
      /** The number the text reads as when esmini's tokenizer reads it as one number (kept to compute on trees). */ number?: number;
    }
  | { ok: false; stop: EsminiStop; rules: ValueRule[] };

/** The text of a parameter as esmini holds it; undefined when esmini cannot find it (it stops). */
export type EsminiParameterText = (name: string) => EsminiText | undefined;

const DELIMITERS = ' ({)}-+*/%^!|&<>=,';

function addRule(rules: ValueRule[], rule: ValueRule): void {
  if (!rules.includes(rule)) rules.push(rule);
}

/** Replaces each `$name` by its text, as Parameters::ResolveParametersInString does. */
function substitute(body: string, lookup: EsminiParameterText, rules: ValueRule[]): { text: string } | { stop: EsminiStop } {
  let text = body;
  // A value that holds a `$` is substituted again; esmini would loop for ever on a value naming itself.
  for (let round = 0; round < 1000; round++) {
    const found = text.indexOf('$');
    if (found < 0) return { text };
    let end = found + 1;
    while (end < text.length && !DELIMITERS.includes(text[end])) end++;
    const name = text.slice(found + 1, end);
    const value = lookup(name);
    if (!value) return { stop: { stop: 'unresolved-parameter', name } };
    if (!value.ok) return { stop: value.stop };
    for (const rule of value.rules) addRule(rules, rule);
    addRule(rules, 'substitution');
    text = text.slice(0, found) + value.text + text.slice(end);
  }
  return { stop: { stop: 'names-itself' } };
}

function replaceAll(text: string, search: string, replacement: string): string {
  return text.includes(search) ? text.split(search).join(replacement) : text;
}

const isSpace = (c: string) => c === ' ' || c === '\t' || c === '\n' || c === '\v' || c === '\f' || c === '\r';
const isDigit = (c: string) => c >= '0' && c <= '9';
const isFirstVarChar = (c: string) => (c.charCodeAt(0) >= 64 && c !== '^' && c !== '|') || c === '$';
const isVarChar = (c: string) => isFirstVarChar(c) || c === '#' || isDigit(c);

const BINARY_PRECEDENCE: Record<string, number> = {
  '**': 2,
  '*': 2,
  '/': 2,
  '%': 2,
  '+': 3,
  '-': 3,
  '<<': 4,
  '>>': 4,
  '<': 5,
  '<=': 5,
  '>': 5,
  '>=': 5,
  '==': 5,
  '!=': 5,
  '&': 6,
  '|': 7,
  '^': 8,
  '&&': 9,
  '||': 10,
  '=': 11,
  ',': 12,
};
const RIGHT_ASSOCIATIVE = new Set(['**', '=', ',']);
const ESMINI_FUNCTIONS: Record<string, number> = {
  round: 1,
  floor: 1,
  ceil: 1,
  sqrt: 1,
  pow: 2,
  sin: 1,
  cos: 1,
  tan: 1,
  asin: 1,
  acos: 1,
  atan: 1,
  sign: 1,
  abs: 1,
  max: 2,
  min: 2,
};
const CONSTANTS: Record<string, number> = { pi: 3.14159265358979323846, e: 2.718281828459045 };

type Token =
  | { kind: 'number'; text: string }
  | { kind: 'word'; text: string }
  | { kind: 'open' }
  | { kind: 'close' }
  | { kind: 'operator'; text: string; unary: boolean };

type Scan = { tokens: Token[] } | { text: true } | { failure: EsminiEvaluationFailure };

const TOP = 1;
const TOPEN = 2;
const TCLOSE = 4;
const TNUMBER = 8;
const TWORD = 16;

/** zserge/expr's expr_next_token and the identifier handling of expr_create, in the order esmini meets them. */
function scan(source: string): Scan {
  const tokens: Token[] = [];
  let flags = TOPEN | TNUMBER | TWORD;
  let pending: string | undefined;
  let i = 0;
  const takePending = (next: Token | undefined): Scan | undefined => {
    if (pending === undefined) return undefined;
    const word = pending;
    pending = undefined;
    if (next?.kind === 'open') {
      if (ESMINI_FUNCTIONS[word] === undefined) return { failure: { failure: 'unknown-function', word } };
      tokens.push({ kind: 'word', text: word });
      return undefined;
    }
    if (CONSTANTS[word] !== undefined) {
      tokens.push({ kind: 'word', text: word });
      return undefined;
    }
    return { text: true };
  };
  while (i < source.length) {
    const c = source[i];
    let token: Token | undefined;
    if (c === '#') {
      while (i < source.length && source[i] !== '\n') i++;
      continue;
    }
    if (isSpace(c)) {
      i++;
      continue;
    }
    if (isDigit(c)) {
      if ((flags & TNUMBER) === 0) return { failure: { failure: 'number-where-operator', rest: source.slice(i) } };
      flags = TOP | TCLOSE;
      let end = i;
      while (end < source.length && (source[end] === '.' || isDigit(source[end]))) end++;
      token = { kind: 'number', text: source.slice(i, end) };
      i = end;
    } else if (isFirstVarChar(c)) {
      if ((flags & TWORD) === 0) return { text: true };
      flags = TOP | TOPEN | TCLOSE;
      let end = i;
      while (end < source.length && isVarChar(source[end])) end++;
      token = { kind: 'word', text: source.slice(i, end) };
      i = end;
    } else if (c === '(' || c === ')') {
      if (c === '(' && (flags & TOPEN) !== 0) flags = TNUMBER | TWORD | TOPEN | TCLOSE;
      else if (c === ')' && (flags & TCLOSE) !== 0) flags = TOP | TCLOSE;
      else return { failure: { failure: 'unexpected-character', character: c } };
      token = c === '(' ? { kind: 'open' } : { kind: 'close' };
      i++;
    } else if ((flags & TOP) === 0) {
      if (c !== '-' && c !== '!' && c !== '^') return { failure: { failure: 'operator-where-operand', character: c } };
      flags = TNUMBER | TWORD | TOPEN;
      token = { kind: 'operator', text: c, unary: true };
      i++;
    } else {
      let end = i;
      let found = false;
      while (end < source.length && !isVarChar(source[end]) && !isSpace(source[end]) && source[end] !== '(' && source[end] !== ')') {
        if (BINARY_PRECEDENCE[source.slice(i, end + 1)] !== undefined) found = true;
        else if (found) break;
        end++;
      }
      if (!found) return { failure: { failure: 'unknown-operator', operator: source.slice(i, end) } };
      flags = TNUMBER | TWORD | TOPEN;
      token = { kind: 'operator', text: source.slice(i, end), unary: false };
      i = end;
    }
    if (token.kind === 'word') {
      const stop = takePending(token);
      if (stop) return stop;
      pending = token.text;
      continue;
    }
    const stop = takePending(token);
    if (stop) return stop;
    tokens.push(token);
  }
  return takePending(undefined) ?? { tokens };
}

/** The text esmini keeps when an expression holds a word it does not know (expr_create's string mode). */
export function glueText(source: string): string {
  let result = '';
  for (let i = 0; i < source.length; i++) {
    if (isSpace(source[i])) {
      let j = i;
      let plus = false;
      while (j < source.length && (isSpace(source[j]) || source[j] === '+')) {
        plus = plus || source[j] === '+';
        j++;
      }
      if (plus) {
        i = j;
        if (i >= source.length) break;
      }
    }
    result += source[i];
  }
  return result;
}

/** expr_parse_number: digits with at most one dot, NaN otherwise. */
function parseNumber(text: string): number {
  const dot = text.indexOf('.');
  if (dot >= 0 && text.indexOf('.', dot + 1) >= 0) return NaN;
  return Number(dot === text.length - 1 ? text.slice(0, -1) : text);
}

const toInt = (x: number) => (Number.isNaN(x) ? 0 : !Number.isFinite(x) ? (x > 0 ? 2147483647 : -2147483647) : Math.trunc(x) | 0);

/** C's remainder(): x - n*y with n = x/y rounded half to even. */
export function ieeeRemainder(x: number, y: number): number {
  if (!Number.isFinite(x) || Number.isNaN(y) || y === 0) return NaN;
  if (!Number.isFinite(y)) return x;
  const quotient = x / y;
  const n = roundHalfToEven(quotient);
  const result = x - n * y;
  return result === 0 ? (x < 0 ? -0 : 0) : result;
}

/** rint() in the default rounding mode: half to even. */
export function roundHalfToEven(x: number): number {
  if (!Number.isFinite(x)) return x;
  const floor = Math.floor(x);
  const diff = x - floor;
  if (diff < 0.5) return floor;
  if (diff > 0.5) return floor + 1;
  return floor % 2 === 0 ? floor : floor + 1;
}

function applyEsminiFunction(name: string, args: number[], rules: ValueRule[]): number {
  const [a, b] = args;
  switch (name) {
    case 'round':
      if (roundHalfToEven(a) !== (a < 0 ? -Math.round(-a) : Math.round(a))) addRule(rules, 'round');
      return roundHalfToEven(a);
    case 'sign':
      if (a === 0) addRule(rules, 'sign');
      return a < 0 ? -1 : 1;
    case 'max':
      return b > a ? b : a;
    case 'min':
      return b < a ? b : a;
  }
  // Names esmini does not know are refused before evaluation (ESMINI_FUNCTIONS).
  if (!Object.hasOwn(SHARED_MATH_FUNCTIONS, name)) throw new Error(`'${name}' is not a function esmini knows`);
  return SHARED_MATH_FUNCTIONS[name as SharedMathFunction](a, b);
}

class ParseFailure extends Error {
  constructor(readonly failure: EsminiEvaluationFailure) {
    super(failure.failure);
  }
}

/** Evaluates the tokens with expr's precedence (a lower number binds tighter; unary operators tightest). */
function evaluateTokens(tokens: Token[], rules: ValueRule[]): number {
  let index = 0;
  const fail = (failure: EsminiEvaluationFailure): never => {
    throw new ParseFailure(failure);
  };
  const operand = (): number => {
    const token = tokens[index++];
    if (!token) return fail({ failure: 'operand-missing' });
    if (token.kind === 'number') {
      const value = parseNumber(token.text);
      if (Number.isNaN(value)) fail({ failure: 'not-a-number', text: token.text });
      return value;
    }
    if (token.kind === 'operator' && token.unary) {
      const value = operand();
      if (token.text === '-') return -value;
      addRule(rules, 'comparisons');
      return token.text === '!' ? (value ? 0 : 1) : ~toInt(value);
    }
    if (token.kind === 'open') {
      const value = expression(12);
      if (tokens[index++]?.kind !== 'close') fail({ failure: 'parenthesis-not-closed' });
      return value;
    }
    if (token.kind === 'word') {
      if (CONSTANTS[token.text] !== undefined) return CONSTANTS[token.text];
      index++; // the '(' the scan found after a function name
      const args: number[] = [];
      if (tokens[index]?.kind !== 'close') {
        args.push(expression(11));
        while (tokens[index]?.kind === 'operator' && (tokens[index] as { text: string }).text === ',') {
          index++;
          args.push(expression(11));
        }
      }
      if (tokens[index++]?.kind !== 'close') fail({ failure: 'arguments-not-closed', name: token.text });
      if (args.length < ESMINI_FUNCTIONS[token.text])
        fail({ failure: 'too-few-arguments', name: token.text, count: ESMINI_FUNCTIONS[token.text] });
      return applyEsminiFunction(token.text, args, rules);
    }
    return fail({ failure: 'operand-expected' });
  };
  const expression = (limit: number): number => {
    let left = operand();
    for (;;) {
      const token = tokens[index];
      if (!token || token.kind !== 'operator' || token.unary) return left;
      const precedence = BINARY_PRECEDENCE[token.text];
      if (precedence > limit) return left;
      index++;
      const right = expression(RIGHT_ASSOCIATIVE.has(token.text) ? precedence : precedence - 1);
      left = binary(token.text, left, right, rules);
    }
  };
  const value = expression(12);
  if (index < tokens.length) fail({ failure: 'trailing-text' });
  return value;
}

function binary(operator: string, a: number, b: number, rules: ValueRule[]): number {
  switch (operator) {
    case '**':
      return Math.pow(a, b);
    case '*':
      return a * b;
    case '/':
      if (b === 0) addRule(rules, 'divisionByZero');
      return a / b;
    case '%':
      if (b === 0) addRule(rules, 'divisionByZero');
      else if (ieeeRemainder(a, b) !== a % b) addRule(rules, 'remainder');
      return ieeeRemainder(a, b);
    case '+':
      return a + b;
    case '-':
      return a - b;
    case ',':
      return b;
    case '=':
      throw new ParseFailure({ failure: 'assignment' });
  }
  addRule(rules, 'comparisons');
  switch (operator) {
    case '<<':
      return toInt(a) << toInt(b);
    case '>>':
      return toInt(a) >> toInt(b);
    case '<':
      return a < b ? 1 : 0;
    case '<=':
      return a <= b ? 1 : 0;
    case '>':
      return a > b ? 1 : 0;
    case '>=':
      return a >= b ? 1 : 0;
    case '==':
      return a === b ? 1 : 0;
    case '!=':
      return a !== b ? 1 : 0;
    case '&':
      return toInt(a) & toInt(b);
    case '|':
      return toInt(a) | toInt(b);
    case '^':
      return toInt(a) ^ toInt(b);
    case '&&':
      return a !== 0 && b !== 0 ? b : 0;
    default:
      return a !== 0 && !Number.isNaN(a) ? a : b !== 0 ? b : 0;
  }
}

/** std::to_string of a double: printf's "%f", six decimals. */
export function sixDecimals(value: number): string {
  if (Number.isNaN(value)) return 'nan';
  if (!Number.isFinite(value)) return value > 0 ? 'inf' : '-inf';
  const sign = value < 0 || Object.is(value, -0) ? '-' : '';
  const magnitude = Math.abs(value);
  if (magnitude < 1e21) return sign + magnitude.toFixed(6);
  return `${sign}${BigInt(magnitude).toString()}.000000`;
}

/** The value of a `${...}` body as esmini computes it (Parameters::ReadAttribute). */
export function esminiExpression(body: string, lookup: EsminiParameterText): EsminiText {
  const rules: ValueRule[] = [];
  const closing = body.indexOf('}');
  const substituted = substitute(closing >= 0 ? body.slice(0, closing) : body, lookup, rules);
  if ('stop' in substituted) return { ok: false, stop: substituted.stop, rules };
  let text = substituted.text;
  for (const [search, replacement] of [
    ['not ', '!'],
    ['not(', '!('],
    ['and ', '&& '],
    ['or ', '|| '],
    ['true ', '1 '],
    ['false ', '0 '],
  ]) {
    const replaced = replaceAll(text, search, replacement);
    if (replaced !== text) addRule(rules, 'keywords');
    text = replaced;
  }
  const scanned = scan(text);
  if ('text' in scanned) {
    addRule(rules, 'textGluing');
    return { ok: true, text: glueText(text), rules };
  }
  const failed = (failure: EsminiEvaluationFailure): EsminiText => ({
    ok: false,
    stop: { stop: 'evaluation', failure, text },
    rules: [...rules, 'failure'],
  });
  if ('failure' in scanned) return failed(scanned.failure);
  if (scanned.tokens.length === 0) return { ok: true, text: sixDecimals(0), rules };
  try {
    const value = evaluateTokens(scanned.tokens, rules);
    if (Number.isNaN(value)) return failed({ failure: 'result-not-a-number' });
    return { ok: true, text: sixDecimals(value), rules: [...rules, 'resultText'] };
  } catch (error) {
    if (error instanceof ParseFailure) return failed(error.failure);
    throw error;
  }
}

/** A parameter text esmini's tokenizer reads as one number (an optional unary minus, digits, one dot). */
const PLAIN_NUMBER = /^-?[0-9]+(?:\.[0-9]*)?$/;
/** What esminiFromTree leaves to the text: an exponent, a number starting with its dot (esmini fails on it), the words esmini rewrites. */
const NEEDS_TEXT = /[0-9.][eE][+-]?[0-9]|(?:^|[^0-9])\.[0-9]|not|and|or|true|false/;

/** The number a plain numeric text reads as (see PLAIN_NUMBER); undefined for any other text. */
export function plainNumber(text: string): number | undefined {
  return PLAIN_NUMBER.test(text) ? (text.startsWith('-') ? -parseNumber(text.slice(1)) : parseNumber(text)) : undefined;
}

class NotPlain extends Error {}
const NOT_PLAIN = new NotPlain();

function treeValue(node: ExpressionNode, lookup: EsminiParameterText, rules: ValueRule[]): number {
  switch (node.kind) {
    case 'number':
      return node.value;
    case 'parameter': {
      const text = lookup(node.name);
      const value = text?.ok ? (text.number ?? plainNumber(text.text)) : undefined;
      if (value === undefined || !text?.ok) throw NOT_PLAIN;
      for (const rule of text.rules) if (!rules.includes(rule)) rules.push(rule);
      return value;
    }
    case 'unary':
      if (node.operator !== '-') throw NOT_PLAIN;
      return -treeValue(node.operand, lookup, rules);
    case 'binary':
      if (node.operator === 'and' || node.operator === 'or') throw NOT_PLAIN;
      return binary(node.operator, treeValue(node.left, lookup, rules), treeValue(node.right, lookup, rules), rules);
    case 'call':
      return applyEsminiFunction(
        node.name,
        node.args.map((arg) => treeValue(arg, lookup, rules)),
        rules,
      );
    default:
      throw NOT_PLAIN;
  }
}

/**
 * esmini's value of an expression computed on its parsed tree instead of its text, when that gives
 * the same: only numbers without an exponent, `$parameters` whose text is a plain number, unary
 * minus, + - * / % and functions (what substituting the texts and tokenizing would read the same
 * way). Undefined when the expression needs the text (words, booleans, exponents, other texts) or
 * esmini fails on it; `esminiExpression` then reads it as esmini does.
 */
export function esminiFromTree(tree: ExpressionNode, body: string, lookup: EsminiParameterText): EsminiText | undefined {
  if (NEEDS_TEXT.test(body)) return undefined;
  const rules: ValueRule[] = [];
  let value: number;
  try {
    value = treeValue(tree, lookup, rules);
  } catch (error) {
    if (error === NOT_PLAIN) return undefined;
    throw error;
  }
  if (Number.isNaN(value)) return undefined;
  rules.push('resultText');
  const text = sixDecimals(value);
  return { ok: true, text, rules, number: Number.isFinite(value) ? Number(text) : undefined };
}

/** atof(): the longest prefix that reads as a number (glibc strtod), 0 when there is none. */
export function atof(text: string): number {
  // Number() reads a whole numeric text as strtod does (the texts esmini writes are such); only a prefix needs the scan.
  const whole = Number(text);
  if (!Number.isNaN(whole) && text.trim() !== '' && !/^\s*[+-]?0[xXbBoO]/.test(text)) return whole;
  const match = /^[ \t\n\v\f\r]*([+-]?)(inf(?:inity)?|nan|(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)/i.exec(text);
  if (!match) return 0;
  const sign = match[1] === '-' ? -1 : 1;
  const body = match[2].toLowerCase();
  if (body.startsWith('inf')) return sign * Infinity;
  if (body === 'nan') return NaN;
  return sign * Number(body);
}

/** atoi(): (int) strtol, so a value beyond the int range wraps (and beyond the long range clamps first). */
export function atoi(text: string): number {
  const match = /^[ \t\n\v\f\r]*([+-]?[0-9]+)/.exec(text);
  if (!match) return 0;
  let value = BigInt(match[1]);
  const longMax = (1n << 63n) - 1n;
  if (value > longMax) value = longMax;
  if (value < -longMax - 1n) value = -longMax - 1n;
  return Number(BigInt.asIntN(32, value));
}

/** The value esmini reads from a text for a declared type (Parameters::parseParameterDeclarations). */
export function esminiTyped(text: string, type: ParameterType | undefined): { value: ParameterValue; rule?: ValueRule } {
  switch (type) {
    case 'int':
      return { value: atoi(text), rule: 'intConversion' };
    case 'double':
      return { value: atof(text), rule: 'doubleConversion' };
    case 'boolean':
      return { value: text === 'true', rule: 'booleanConversion' };
    default:
      return { value: text };
  }
}

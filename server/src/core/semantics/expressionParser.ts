import { EsminiComputes, ExpressionFact, ExpressionSyntaxFact, FoundToken } from '../diagnostics/expressionFacts';

/**
 * ASAM OpenSCENARIO 1.x `${...}` expressions: parsing, with the offset of every part, and how an
 * attribute value is written (a literal, a `$name` or an expression). Evaluation is in
 * ./expressionEvaluation.ts.
 *
 * Grammar (ASAM OpenSCENARIO 1.1-1.3, "Expressions"; the XSD pattern of `expression` allows only
 * blanks, letters, digits, `_ + - * / % $ ( ) . ,`, so there are no comparison operators), lowest
 * precedence first:
 *
 *     or-expr   := and-expr ('or' and-expr)*
 *     and-expr  := not-expr ('and' not-expr)*
 *     not-expr  := 'not' not-expr | sum
 *     sum       := product (('+' | '-') product)*
 *     product   := unary (('*' | '/' | '%') unary)*
 *     unary     := '-' unary | primary
 *     primary   := number | 'true' | 'false' | '$'name | function '(' args ')' | '(' or-expr ')'
 *
 * Functions: round floor ceil sqrt pow (1.1) and abs sign min max sin cos tan asin acos atan (1.3).
 * esmini (simple_expr.c, release 3.6.0) also knows the constants `pi` and `e`; they are evaluated
 * but reported as not standard.
 */

/** Text to write instead, at document offsets, to reach the standard's form. */
export interface ExpressionFix {
  start: number;
  end: number;
  text: string;
}

/**
 * An error or warning at offsets of the document (or of the string given to the parser when its base is 0): a fact
 * its code's module words (core/diagnostics/expressionWords.ts). `lenient`: a form the standard does not allow with
 * one clear meaning that esmini accepts (a warning, SPEC 12); `simulator`: esmini computes another value than the
 * standard (a warning); `overflow`: a double beyond its range, an error by the standard's rules.
 */
export type ExpressionError = ExpressionFact & {
  start: number;
  end: number;
  fix?: ExpressionFix;
  /** What esmini computes where the standard fails (on the first error of a value esmini computes). */
  esminiComputes?: EsminiComputes;
};

export type ExpressionNode =
  | { kind: 'number'; value: number; start: number; end: number }
  | { kind: 'boolean'; value: boolean; start: number; end: number }
  | { kind: 'constant'; name: 'pi' | 'e'; start: number; end: number }
  | { kind: 'parameter'; name: string; start: number; end: number }
  /** A word without `$` that is no function or constant: a parameter written bare, or text esmini glues. */
  | { kind: 'name'; name: string; start: number; end: number }
  | { kind: 'unary'; operator: '-' | 'not'; operand: ExpressionNode; start: number; end: number }
  | { kind: 'binary'; operator: BinaryOperator; left: ExpressionNode; right: ExpressionNode; start: number; end: number }
  | { kind: 'call'; name: FunctionName; args: ExpressionNode[]; start: number; end: number };

export type BinaryOperator = '+' | '-' | '*' | '/' | '%' | 'and' | 'or';

/** Each function with its number of arguments and the standard's revision that introduced it. */
export const FUNCTIONS = {
  round: { arity: 1, since: '1.1' },
  floor: { arity: 1, since: '1.1' },
  ceil: { arity: 1, since: '1.1' },
  sqrt: { arity: 1, since: '1.1' },
  pow: { arity: 2, since: '1.1' },
  abs: { arity: 1, since: '1.3' },
  sign: { arity: 1, since: '1.3' },
  min: { arity: 2, since: '1.3' },
  max: { arity: 2, since: '1.3' },
  sin: { arity: 1, since: '1.3' },
  cos: { arity: 1, since: '1.3' },
  tan: { arity: 1, since: '1.3' },
  asin: { arity: 1, since: '1.3' },
  acos: { arity: 1, since: '1.3' },
  atan: { arity: 1, since: '1.3' },
} as const;

export type FunctionName = keyof typeof FUNCTIONS;

/** The function names the standard knows, as an unknown name's fact lists them. */
export const FUNCTION_NAMES: readonly string[] = Object.keys(FUNCTIONS);

/** Every word an expression may hold besides parameter names: operators, literals, functions, constants (pi, e: nonstandard-expression). */
const KNOWN_WORDS: ReadonlySet<string> = new Set(['and', 'or', 'not', 'true', 'false', 'pi', 'e', ...FUNCTION_NAMES]);

/** A `${...}` expression as parsed: its tree (absent after a syntax error) and its problems. */
export interface ParsedExpression {
  /** Offsets of the whole `${...}` and of its body. */
  start: number;
  end: number;
  bodyStart: number;
  bodyEnd: number;
  tree: ExpressionNode | undefined;
  errors: ExpressionError[];
  /** Every `$name` inside, in order. */
  parameters: { name: string; start: number; end: number }[];
  /** Every bare word inside (a parameter written without `$`, or text esmini glues), in order. */
  names: { name: string; start: number; end: number }[];
}

type Token =
  | { kind: 'number'; value: number; start: number; end: number }
  | { kind: 'parameter'; name: string; start: number; end: number }
  | { kind: 'word'; word: string; start: number; end: number }
  | { kind: 'symbol'; symbol: string; start: number; end: number }
  | { kind: 'end'; start: number; end: number };

const NUMBER = /(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?/y;
const NAME = /[A-Za-z_][A-Za-z0-9_]*/y;

function tokenize(body: string, base: number, errors: ExpressionError[]): Token[] {
  const tokens: Token[] = [];
  let i = 0;
  while (i < body.length) {
    const char = body[i];
    if (char === ' ' || char === '\t' || char === '\n' || char === '\r') {
      i++;
      continue;
    }
    NUMBER.lastIndex = i;
    const number = NUMBER.exec(body);
    if (number) {
      tokens.push({ kind: 'number', value: Number(number[0]), start: base + i, end: base + i + number[0].length });
      i += number[0].length;
      continue;
    }
    if (char === '$') {
      NAME.lastIndex = i + 1;
      const name = NAME.exec(body);
      if (!name) {
        errors.push({ kind: 'syntax', fact: 'dollar-without-name', start: base + i, end: base + i + 1 });
        i++;
        continue;
      }
      tokens.push({ kind: 'parameter', name: name[0], start: base + i, end: base + i + 1 + name[0].length });
      i += 1 + name[0].length;
      continue;
    }
    NAME.lastIndex = i;
    const word = NAME.exec(body);
    if (word) {
      tokens.push({ kind: 'word', word: word[0], start: base + i, end: base + i + word[0].length });
      i += word[0].length;
      continue;
    }
    if ('+-*/%(),'.includes(char)) {
      tokens.push({ kind: 'symbol', symbol: char, start: base + i, end: base + i + 1 });
      i++;
      continue;
    }
    errors.push({ kind: 'syntax', fact: 'character', character: char, start: base + i, end: base + i + 1 });
    i++;
  }
  tokens.push({ kind: 'end', start: base + body.length, end: base + body.length });
  return tokens;
}

class SyntaxFailure extends Error {
  constructor(readonly error: ExpressionError) {
    super(error.kind);
  }
}

/** Parses the body of a `${...}` (the text between the braces), which starts at `base` in the document. */
export function parseExpressionBody(body: string, base = 0): { tree: ExpressionNode | undefined; errors: ExpressionError[] } {
  const errors: ExpressionError[] = [];
  const tokens = tokenize(body, base, errors);
  if (errors.length > 0) return { tree: undefined, errors };
  let index = 0;
  const peek = () => tokens[index];
  const fail = (token: Token, fact: ExpressionSyntaxFact): never => {
    throw new SyntaxFailure({ ...fact, start: token.start, end: Math.max(token.end, token.start + 1) });
  };
  const isWord = (token: Token, word: string) => token.kind === 'word' && token.word === word;
  // Where an operator or a closing symbol was expected, a word the standard's expressions lack is an unknown operator.
  const unexpected = (token: Token, fact: ExpressionSyntaxFact): never =>
    token.kind === 'word' && !KNOWN_WORDS.has(token.word)
      ? fail(token, { kind: 'syntax', fact: 'unknown-operator', word: token.word })
      : fail(token, fact);
  const isSymbol = (token: Token, symbol: string) => token.kind === 'symbol' && token.symbol === symbol;
  const describe = (token: Token): FoundToken =>
    token.kind === 'end'
      ? { kind: 'end' }
      : token.kind === 'symbol'
        ? { kind: 'symbol', symbol: token.symbol }
        : token.kind === 'word'
          ? { kind: 'word', word: token.word }
          : { kind: 'value' };

  const binaryLevel = (operators: BinaryOperator[], next: () => ExpressionNode) => (): ExpressionNode => {
    let left = next();
    for (;;) {
      const token = peek();
      const operator = operators.find((candidate) => isSymbol(token, candidate) || isWord(token, candidate));
      if (!operator) return left;
      index++;
      const right = next();
      left = { kind: 'binary', operator, left, right, start: left.start, end: right.end };
    }
  };
  const primary = (): ExpressionNode => {
    const token = peek();
    if (token.kind === 'number') {
      index++;
      return { kind: 'number', value: token.value, start: token.start, end: token.end };
    }
    if (token.kind === 'parameter') {
      index++;
      return { kind: 'parameter', name: token.name, start: token.start, end: token.end };
    }
    if (isSymbol(token, '(')) {
      index++;
      const inner = orExpression();
      const close = peek();
      if (!isSymbol(close, ')'))
        unexpected(close, { kind: 'syntax', fact: 'unclosed-parenthesis', column: token.start - base + 1, found: describe(close) });
      index++;
      return { ...inner, start: token.start, end: close.end };
    }
    if (token.kind === 'word') {
      index++;
      if (token.word === 'true' || token.word === 'false')
        return { kind: 'boolean', value: token.word === 'true', start: token.start, end: token.end };
      if (token.word in FUNCTIONS) {
        const name = token.word as FunctionName;
        const open = peek();
        if (!isSymbol(open, '(')) fail(open, { kind: 'syntax', fact: 'call-without-parenthesis', name });
        index++;
        const args: ExpressionNode[] = [];
        if (!isSymbol(peek(), ')')) {
          args.push(orExpression());
          while (isSymbol(peek(), ',')) {
            index++;
            args.push(orExpression());
          }
        }
        const close = peek();
        if (!isSymbol(close, ')')) unexpected(close, { kind: 'syntax', fact: 'arguments-not-closed', name, found: describe(close) });
        index++;
        const arity = FUNCTIONS[name].arity;
        if (args.length !== arity) {
          fail(
            { kind: 'word', word: name, start: token.start, end: close.end },
            { kind: 'syntax', fact: 'arity', name, arity, given: args.length },
          );
        }
        return { kind: 'call', name, args, start: token.start, end: close.end };
      }
      if (token.word === 'pi' || token.word === 'e') return { kind: 'constant', name: token.word, start: token.start, end: token.end };
      if (isSymbol(peek(), '(')) fail(token, { kind: 'syntax', fact: 'unknown-function', name: token.word, functions: FUNCTION_NAMES });
      return { kind: 'name', name: token.word, start: token.start, end: token.end };
    }
    return fail(token, { kind: 'syntax', fact: 'operand-expected', found: describe(token) });
  };
  const unary = (): ExpressionNode => {
    const token = peek();
    if (isSymbol(token, '-')) {
      index++;
      const operand = unary();
      return { kind: 'unary', operator: '-', operand, start: token.start, end: operand.end };
    }
    return primary();
  };
  const product = binaryLevel(['*', '/', '%'], unary);
  const sum = binaryLevel(['+', '-'], product);
  const notExpression = (): ExpressionNode => {
    const token = peek();
    if (isWord(token, 'not')) {
      index++;
      const operand = notExpression();
      return { kind: 'unary', operator: 'not', operand, start: token.start, end: operand.end };
    }
    return sum();
  };
  const andExpression = binaryLevel(['and'], notExpression);
  const orExpression = binaryLevel(['or'], andExpression);
  try {
    const tree = orExpression();
    const rest = peek();
    if (rest.kind !== 'end') unexpected(rest, { kind: 'syntax', fact: 'operator-expected', found: describe(rest) });
    return { tree, errors };
  } catch (error) {
    if (error instanceof SyntaxFailure) return { tree: undefined, errors: [error.error] };
    throw error;
  }
}

/** Every bare word of a tree (a parameter written without `$`, or text), in order. */
export function namesOf(tree: ExpressionNode | undefined): { name: string; start: number; end: number }[] {
  const found: { name: string; start: number; end: number }[] = [];
  const visit = (node: ExpressionNode) => {
    if (node.kind === 'name') found.push({ name: node.name, start: node.start, end: node.end });
    else if (node.kind === 'unary') visit(node.operand);
    else if (node.kind === 'binary') {
      visit(node.left);
      visit(node.right);
    } else if (node.kind === 'call') node.args.forEach(visit);
  };
  if (tree) visit(tree);
  return found;
}

/** Every `$name` of a tree, in order. */
export function parametersOf(tree: ExpressionNode | undefined): { name: string; start: number; end: number }[] {
  const found: { name: string; start: number; end: number }[] = [];
  const visit = (node: ExpressionNode) => {
    switch (node.kind) {
      case 'parameter':
        found.push({ name: node.name, start: node.start, end: node.end });
        break;
      case 'unary':
        visit(node.operand);
        break;
      case 'binary':
        visit(node.left);
        visit(node.right);
        break;
      case 'call':
        node.args.forEach(visit);
        break;
      default:
        break;
    }
  };
  if (tree) visit(tree);
  return found;
}

/** Every `$name` token of a body that did not parse: rename, references and the unused check still reach each one. */
function parameterTokens(body: string, base: number): { name: string; start: number; end: number }[] {
  return tokenize(body, base, []).flatMap((token) =>
    token.kind === 'parameter' ? [{ name: token.name, start: token.start, end: token.end }] : [],
  );
}

/** A `$name` written as a whole attribute value (XSD `parameter`: `[$][A-Za-z_][A-Za-z0-9_]*`). */
export const PARAMETER_VALUE = /^\$([A-Za-z_][A-Za-z0-9_]*)$/;

/** How an attribute value is written: a literal, a `$name`, or a `${...}` expression. */
export type ValueForm =
  | { kind: 'literal' }
  | { kind: 'parameter'; name: string; start: number; end: number }
  | { kind: 'expression'; expression: ParsedExpression };

/**
 * Classifies a raw attribute value whose first character is at `base` in the document. A value that
 * starts with `${` is an expression (an unclosed one is a syntax error); `$name` is a reference.
 */
export function valueForm(value: string, base = 0): ValueForm {
  if (value.charCodeAt(0) !== 36) return { kind: 'literal' };
  const trimmed = value.trimEnd();
  const parameter = PARAMETER_VALUE.exec(trimmed);
  if (parameter) return { kind: 'parameter', name: parameter[1], start: base, end: base + trimmed.length };
  if (trimmed.startsWith('${')) {
    const closed = trimmed.endsWith('}');
    const bodyEnd = closed ? trimmed.length - 1 : trimmed.length;
    const parsed = parseExpressionBody(trimmed.slice(2, bodyEnd), base + 2);
    if (!closed)
      parsed.errors.unshift({
        kind: 'syntax',
        fact: 'unclosed-expression',
        start: base + trimmed.length - 1,
        end: base + trimmed.length,
      });
    const expression: ParsedExpression = {
      start: base,
      end: base + trimmed.length,
      bodyStart: base + 2,
      bodyEnd: base + bodyEnd,
      tree: closed ? parsed.tree : undefined,
      errors: parsed.errors,
      parameters:
        parsed.tree && parsed.errors.length === 0 ? parametersOf(parsed.tree) : parameterTokens(trimmed.slice(2, bodyEnd), base + 2),
      names: namesOf(parsed.tree),
    };
    return { kind: 'expression', expression };
  }
  return { kind: 'literal' };
}

/**
 * ASAM OpenSCENARIO 1.x parameter values and `${...}` expressions: parsing (with the offset of every
 * part), evaluation and conversion to a declared `parameterType`.
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

export type ParameterType = 'double' | 'int' | 'unsignedInt' | 'unsignedShort' | 'boolean' | 'string' | 'dateTime';

/** A value a parameter or an expression takes. */
export type ParameterValue = number | boolean | string;

/** What the standard's `parameterType` names (1.0 wrote `integer`); undefined for anything else. */
export function normalizeParameterType(written: string | undefined): ParameterType | undefined {
  switch (written?.trim()) {
    case 'double':
      return 'double';
    case 'int':
    case 'integer':
      return 'int';
    case 'unsignedInt':
      return 'unsignedInt';
    case 'unsignedShort':
      return 'unsignedShort';
    case 'boolean':
      return 'boolean';
    case 'string':
      return 'string';
    case 'dateTime':
      return 'dateTime';
    default:
      return undefined;
  }
}

/**
 * `lenient`: a form the standard does not allow with one clear meaning that esmini accepts (a warning,
 * SPEC 12); `simulator`: esmini computes another value than the standard (a warning); `overflow`: a
 * double beyond its range, an error by the standard's rules.
 */
export type ExpressionErrorKind =
  'syntax' | 'unknown-parameter' | 'type-mismatch' | 'division-by-zero' | 'nonstandard' | 'lenient' | 'overflow' | 'simulator';

/** Text to write instead, at document offsets, to reach the standard's form. */
export interface ExpressionFix {
  start: number;
  end: number;
  text: string;
}

/** An error at offsets of the document (or of the string given to the parser when its base is 0). */
export interface ExpressionError {
  kind: ExpressionErrorKind;
  message: string;
  start: number;
  end: number;
  fix?: ExpressionFix;
  /** Set on an error caused by text where a value was expected (a bare unknown word, a string parameter): esmini glues such an expression as text. */
  text?: boolean;
}

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
        errors.push({ kind: 'syntax', message: `'$' must be followed by a parameter name`, start: base + i, end: base + i + 1 });
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
    errors.push({ kind: 'syntax', message: `'${char}' is not allowed in an expression`, start: base + i, end: base + i + 1 });
    i++;
  }
  tokens.push({ kind: 'end', start: base + body.length, end: base + body.length });
  return tokens;
}

class SyntaxFailure extends Error {
  constructor(readonly error: ExpressionError) {
    super(error.message);
  }
}

/** Parses the body of a `${...}` (the text between the braces), which starts at `base` in the document. */
export function parseExpressionBody(body: string, base = 0): { tree: ExpressionNode | undefined; errors: ExpressionError[] } {
  const errors: ExpressionError[] = [];
  const tokens = tokenize(body, base, errors);
  if (errors.length > 0) return { tree: undefined, errors };
  let index = 0;
  const peek = () => tokens[index];
  const fail = (token: Token, message: string): never => {
    throw new SyntaxFailure({ kind: 'syntax', message, start: token.start, end: Math.max(token.end, token.start + 1) });
  };
  const isWord = (token: Token, word: string) => token.kind === 'word' && token.word === word;
  const isSymbol = (token: Token, symbol: string) => token.kind === 'symbol' && token.symbol === symbol;
  const describe = (token: Token) =>
    token.kind === 'end'
      ? 'the end of the expression'
      : token.kind === 'symbol'
        ? `'${token.symbol}'`
        : token.kind === 'word'
          ? `'${token.word}'`
          : 'a value';

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
      if (!isSymbol(close, ')')) fail(close, `expected ')' to close the '(' at column ${token.start - base + 1}, found ${describe(close)}`);
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
        if (!isSymbol(open, '(')) fail(open, `expected '(' after the function ${name}`);
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
        if (!isSymbol(close, ')')) fail(close, `expected ',' or ')' in the arguments of ${name}, found ${describe(close)}`);
        index++;
        const arity = FUNCTIONS[name].arity;
        if (args.length !== arity) {
          fail(
            { kind: 'word', word: name, start: token.start, end: close.end },
            `${name} takes ${arity} argument${arity === 1 ? '' : 's'}, not ${args.length}`,
          );
        }
        return { kind: 'call', name, args, start: token.start, end: close.end };
      }
      if (token.word === 'pi' || token.word === 'e') return { kind: 'constant', name: token.word, start: token.start, end: token.end };
      return { kind: 'name', name: token.word, start: token.start, end: token.end };
    }
    return fail(token, `expected a number, a $parameter, a function or '(', found ${describe(token)}`);
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
    if (rest.kind !== 'end') fail(rest, `unexpected ${describe(rest)}: an operator or the end of the expression was expected`);
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
        message: `an expression must end with '}'`,
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

/** A value with the type the standard gives it inside expressions. */
export interface TypedValue {
  value: ParameterValue;
  type: ParameterType;
}

/** A parameter's value, with where its `parameterType` value is written (a string parameter read as a number is fixed there). */
export type LookupResult = TypedValue & { retype?: { start: number; end: number } };

/** Looks up `$name` (its offsets for messages); undefined when no declaration is in scope. */
export type ParameterLookup = (name: string, start: number, end: number) => LookupResult | { error: ExpressionError } | undefined;

export type Evaluation = { ok: true; value: ParameterValue; type: ParameterType } | { ok: false; errors: ExpressionError[] };

class EvaluationFailure extends Error {
  constructor(readonly error: ExpressionError) {
    super(error.message);
  }
}

const DOUBLE_TEXT = /^[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$/;

/** The number or boolean a string parameter's text reads as, as esmini and the ASAM OpenSCENARIO API read it. */
export function readStringAsValue(text: string): TypedValue | undefined {
  const trimmed = text.trim();
  if (DOUBLE_TEXT.test(trimmed)) return { value: Number(trimmed), type: 'double' };
  if (trimmed === 'true' || trimmed === 'false') return { value: trimmed === 'true', type: 'boolean' };
  return undefined;
}

const isNumeric = (type: ParameterType) => type === 'double' || type === 'int' || type === 'unsignedInt' || type === 'unsignedShort';

/** Half away from zero, as the standard's round() and C's round() do (esmini uses rint, half to even). */
export function roundHalfAwayFromZero(value: number): number {
  return value < 0 ? -Math.round(-value) : Math.round(value);
}

/**
 * Evaluates a parsed expression. Numbers are doubles throughout (the result is converted to the
 * target's type afterwards, see convertValue); `and`, `or` and `not` take booleans.
 * Non-standard constants are reported through `warnings` and still evaluated.
 */
/** Why a constant is not standard here: `pi` came with OpenSCENARIO 1.4, after every version the project reads (1.0-1.3). */
const CONSTANT_MESSAGES: Record<'pi' | 'e', string> = {
  pi: "'pi' is a constant from OpenSCENARIO 1.4 on, not of 1.3 and the versions before it (esmini knows it); a simulator of an earlier version rejects it",
  e: "'e' is an esmini constant, not part of the OpenSCENARIO standard; other simulators reject it",
};

export function evaluateTree(tree: ExpressionNode, lookup: ParameterLookup, warnings: ExpressionError[] = []): Evaluation {
  const mismatch = (node: ExpressionNode, message: string): never => {
    throw new EvaluationFailure({ kind: 'type-mismatch', message, start: node.start, end: node.end });
  };
  const numberOf = (node: ExpressionNode, what: string): number => {
    const result = visit(node);
    if (typeof result.value !== 'number')
      mismatch(node, `${what} needs a number, but this is the ${result.type} ${JSON.stringify(result.value)}`);
    return result.value as number;
  };
  const booleanOf = (node: ExpressionNode, operator: string): boolean => {
    const result = visit(node);
    if (typeof result.value !== 'boolean')
      mismatch(node, `'${operator}' needs a boolean, but this is the ${result.type} ${JSON.stringify(result.value)}`);
    return result.value as boolean;
  };
  const number = (value: number): TypedValue => ({ value, type: 'double' });
  const finite = (node: ExpressionNode, value: number, left: number, right = 0): TypedValue => {
    if (!Number.isFinite(value) && !Number.isNaN(value) && Number.isFinite(left) && Number.isFinite(right)) {
      throw new EvaluationFailure({
        kind: 'overflow',
        message: `the result is beyond the range of a double (at most 1.7976931348623157E308)`,
        start: node.start,
        end: node.end,
      });
    }
    return number(value);
  };
  const parameterValue = (node: ExpressionNode & { name: string }, found: LookupResult): TypedValue => {
    if (found.type === 'dateTime') mismatch(node, `the dateTime parameter '${node.name}' cannot be used in an expression`);
    if (found.type !== 'string') return found;
    const read = readStringAsValue(String(found.value));
    if (!read)
      throw new EvaluationFailure({
        kind: 'type-mismatch',
        message: `the string parameter '${node.name}' (${JSON.stringify(found.value)}) cannot be used in an expression`,
        start: node.start,
        end: node.end,
        text: true,
      });
    warnings.push({
      kind: 'lenient',
      message: `'${node.name}' is a string parameter: the standard allows no string in an expression; esmini and the ASAM OpenSCENARIO API read its text ${JSON.stringify(found.value)} as the ${read.type} ${String(read.value)}`,
      start: node.start,
      end: node.end,
      fix: found.retype ? { ...found.retype, text: read.type } : undefined,
    });
    return read;
  };
  const visit = (node: ExpressionNode): TypedValue => {
    switch (node.kind) {
      case 'number':
        if (!Number.isFinite(node.value)) {
          throw new EvaluationFailure({
            kind: 'overflow',
            message: `this number is beyond the range of a double (at most 1.7976931348623157E308)`,
            start: node.start,
            end: node.end,
          });
        }
        return number(node.value);
      case 'boolean':
        return { value: node.value, type: 'boolean' };
      case 'constant':
        warnings.push({ kind: 'nonstandard', message: CONSTANT_MESSAGES[node.name], start: node.start, end: node.end });
        return number(node.name === 'pi' ? Math.PI : Math.E);
      case 'name': {
        const found = lookup(node.name, node.start, node.end);
        if (!found) {
          throw new EvaluationFailure({
            kind: 'syntax',
            message: `unknown name '${node.name}': a parameter is written $${node.name}; the functions are ${Object.keys(FUNCTIONS).join(', ')}`,
            start: node.start,
            end: node.end,
            text: true,
          });
        }
        if ('error' in found) throw new EvaluationFailure(found.error);
        warnings.push({
          kind: 'lenient',
          message: `'${node.name}' is the parameter $${node.name} written without '$': the standard names parameters in expressions only as $${node.name}; esmini reads the bare word as text`,
          start: node.start,
          end: node.end,
          fix: { start: node.start, end: node.end, text: `$${node.name}` },
        });
        return parameterValue(node, found);
      }
      case 'parameter': {
        const found = lookup(node.name, node.start, node.end);
        if (!found)
          throw new EvaluationFailure({
            kind: 'unknown-parameter',
            message: `parameter '${node.name}' is not declared in this scope`,
            start: node.start,
            end: node.end,
          });
        if ('error' in found) throw new EvaluationFailure(found.error);
        return parameterValue(node, found);
      }
      case 'unary':
        if (node.operator === '-') return number(-numberOf(node.operand, `unary '-'`));
        return { value: !booleanOf(node.operand, 'not'), type: 'boolean' };
      case 'binary': {
        if (node.operator === 'and' || node.operator === 'or') {
          const left = booleanOf(node.left, node.operator);
          const right = booleanOf(node.right, node.operator);
          return { value: node.operator === 'and' ? left && right : left || right, type: 'boolean' };
        }
        const left = numberOf(node.left, `'${node.operator}'`);
        const right = numberOf(node.right, `'${node.operator}'`);
        switch (node.operator) {
          case '+':
            return finite(node, left + right, left, right);
          case '-':
            return finite(node, left - right, left, right);
          case '*':
            return finite(node, left * right, left, right);
          case '/':
          case '%':
            if (right === 0)
              throw new EvaluationFailure({
                kind: 'division-by-zero',
                message: `division by zero: the right side of '${node.operator}' is 0`,
                start: node.right.start,
                end: node.right.end,
              });
            return finite(node, node.operator === '/' ? left / right : left % right, left, right);
        }
        break;
      }
      case 'call': {
        const args = node.args.map((arg) => numberOf(arg, `${node.name}()`));
        const value = applyFunction(node.name, args);
        if (!Number.isNaN(value)) return finite(node, value, args.every(Number.isFinite) ? 0 : Infinity);
        if (!Number.isFinite(value)) {
          throw new EvaluationFailure({
            kind: 'type-mismatch',
            message: `${node.name}(${args.join(', ')}) has no real value`,
            start: node.start,
            end: node.end,
          });
        }
        return number(value);
      }
    }
    throw new Error('unreachable');
  };
  try {
    const result = visit(tree);
    return { ok: true, value: result.value, type: result.type };
  } catch (error) {
    if (error instanceof EvaluationFailure) return { ok: false, errors: [error.error] };
    throw error;
  }
}

function applyFunction(name: FunctionName, args: number[]): number {
  const [a, b] = args;
  switch (name) {
    case 'round':
      return roundHalfAwayFromZero(a);
    case 'floor':
      return Math.floor(a);
    case 'ceil':
      return Math.ceil(a);
    case 'sqrt':
      return Math.sqrt(a);
    case 'pow':
      return Math.pow(a, b);
    case 'abs':
      return Math.abs(a);
    case 'sign':
      return a > 0 ? 1 : a < 0 ? -1 : 0;
    case 'min':
      return Math.min(a, b);
    case 'max':
      return Math.max(a, b);
    case 'sin':
      return Math.sin(a);
    case 'cos':
      return Math.cos(a);
    case 'tan':
      return Math.tan(a);
    case 'asin':
      return Math.asin(a);
    case 'acos':
      return Math.acos(a);
    case 'atan':
      return Math.atan(a);
  }
}

const INTEGER = /^[+-]?[0-9]+$/;
const DOUBLE = /^[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$|^[+-]?INF$|^NaN$/;
const DATE_TIME = /^-?[0-9]{4,}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}(?:\.[0-9]+)?(?:Z|[+-][0-9]{2}:[0-9]{2})?$/;

const INTEGRAL_WITH_FRACTION = /^([+-]?[0-9]+)\.0*$/;

/**
 * Reads a literal written for a parameter of `type` (XSD lexical forms); a message when it does not fit.
 * `lenient` names a form the standard refuses that has one clear meaning (`-5.0` for an int).
 */
export function parseLiteral(
  text: string,
  type: ParameterType,
): { value: ParameterValue; lenient?: { message: string; standard: string } } | { message: string } {
  const trimmed = text.trim();
  switch (type) {
    case 'double':
      if (!DOUBLE.test(trimmed)) return { message: `'${text}' is not a double` };
      return { value: trimmed.endsWith('INF') ? (trimmed.startsWith('-') ? -Infinity : Infinity) : Number(trimmed) };
    case 'int':
    case 'unsignedInt':
    case 'unsignedShort': {
      const integral = INTEGRAL_WITH_FRACTION.exec(trimmed);
      if (integral) {
        const value = Number(integral[1]);
        const standard = String(value);
        const range = checkRange(value, type);
        if (range) return range;
        return {
          value,
          lenient: {
            standard,
            message: `'${trimmed}' is not ${type === 'int' ? 'an int' : `an ${type}`} by the standard (no fraction is allowed, not even .0); esmini reads it as ${standard}`,
          },
        };
      }
      if (!INTEGER.test(trimmed)) return { message: `'${text}' is not ${type === 'int' ? 'an int' : `an ${type}`}` };
      return checkRange(Number(trimmed), type) ?? { value: Number(trimmed) };
    }
    case 'boolean':
      if (trimmed === 'true' || trimmed === '1') return { value: true };
      if (trimmed === 'false' || trimmed === '0') return { value: false };
      return { message: `'${text}' is not a boolean (true or false)` };
    case 'dateTime':
      return DATE_TIME.test(trimmed) ? { value: trimmed } : { message: `'${text}' is not a dateTime (YYYY-MM-DDThh:mm:ss)` };
    case 'string':
      return { value: text };
  }
}

function checkRange(value: number, type: ParameterType): { message: string } | undefined {
  if (type === 'int' && (value < -2147483648 || value > 2147483647)) return { message: `${value} is outside the range of an int` };
  if (type === 'unsignedInt' && (value < 0 || value > 4294967295))
    return { message: `${value} is outside the range of an unsignedInt (0 to 4294967295)` };
  if (type === 'unsignedShort' && (value < 0 || value > 65535))
    return { message: `${value} is outside the range of an unsignedShort (0 to 65535)` };
  return undefined;
}

/**
 * Converts an evaluated value to a declared type. A double given to an integer type is rounded half
 * away from zero (the standard converts expression results to the attribute's type; the rounding rule
 * is this project's choice, stated here). A string target takes the value's text.
 */
export function convertValue(value: TypedValue, target: ParameterType): { value: ParameterValue } | { message: string } {
  if (target === 'string') return { value: String(value.value) };
  if (target === value.type) return { value: value.value };
  if (typeof value.value === 'number' && isNumeric(target)) {
    const converted = target === 'double' ? value.value : roundHalfAwayFromZero(value.value);
    return checkRange(converted, target) ?? { value: converted };
  }
  if (typeof value.value === 'string') return parseLiteral(value.value, target);
  return { message: `a ${value.type} value cannot be a ${target}` };
}

/** The standard's error for an expression value given to an integer type that is not integral (convertValue would round it). */
export function integralConversionError(value: TypedValue, target: ParameterType): string | undefined {
  if (typeof value.value !== 'number' || (target !== 'int' && target !== 'unsignedInt' && target !== 'unsignedShort')) return undefined;
  if (Number.isInteger(value.value)) return undefined;
  return `${formatValue(value.value)} is not integral: the standard converts a double to ${target === 'int' ? 'an int' : `an ${target}`} only when it has no fraction`;
}

/** A value as the simulator would write it back into the attribute (for hovers and inlay hints). */
export function formatValue(value: ParameterValue): string {
  if (typeof value === 'number') return Number.isInteger(value) ? String(value) : String(Number(value.toPrecision(12)));
  return String(value);
}

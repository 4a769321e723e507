/*
 * The expressions of conditional breakpoints, Watch and hover while a scenario is paused: numbers, `$Parameter`,
 * `entity.field` (x, y, z, h, speed, acceleration, s, t, lane, road, laneOffset), `time`, `gap(a, b)` and
 * `ttc(a, b)`, arithmetic, comparisons and `&&`, `||`, `!`. `${...}` around the whole is accepted, as OpenSCENARIO
 * writes its expressions.
 */

export type WatchValue = number | string | boolean;

/** What an expression can read of the paused run. */
export interface WatchContext {
  time: number;
  /** An entity's fields by name, undefined when there is no such entity. */
  entity(name: string): Record<string, number> | undefined;
  /** A parameter's or variable's live value, undefined when there is none. */
  parameter(name: string): WatchValue | undefined;
  /** `gap` or `ttc` from one entity to another, undefined when esmini gives none. */
  pair(measure: 'gap' | 'ttc', from: string, to: string): number | undefined;
}

export class WatchError extends Error {}

/** A run's number as the user reads it: settled to 6 digits first, so a sum of 0.0001 s steps (0.44499999…) reads 0.445 in every view. */
export function settled(value: number): number {
  return Number(value.toFixed(6));
}

/** A run's number in fixed digits ('—' when there is none), rounded from its settled value, as an evaluation of it shows it. */
export function shownFixed(value: number | undefined, digits = 2): string {
  return value === undefined || !Number.isFinite(value) ? '—' : settled(value).toFixed(digits);
}

/** An evaluation's result as Watch, hover and the Debug Console show it. */
export function shownValue(value: WatchValue): string {
  return typeof value === 'number' && !Number.isInteger(value) ? String(settled(value)) : String(value);
}

type Token =
  { kind: 'number'; value: number } | { kind: 'string'; value: string } | { kind: 'name'; value: string } | { kind: 'op'; value: string };

const OPERATORS = ['&&', '||', '<=', '>=', '==', '!=', '<', '>', '+', '-', '*', '/', '%', '!', '(', ')', ',', '.'];

function tokenize(text: string): Token[] {
  const tokens: Token[] = [];
  let index = 0;
  while (index < text.length) {
    const rest = text.slice(index);
    const space = /^\s+/.exec(rest);
    if (space) {
      index += space[0].length;
      continue;
    }
    const number = /^(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?/.exec(rest);
    if (number) {
      tokens.push({ kind: 'number', value: Number(number[0]) });
      index += number[0].length;
      continue;
    }
    const name = /^\$?[A-Za-z_]\w*/.exec(rest);
    if (name) {
      tokens.push({ kind: 'name', value: name[0] });
      index += name[0].length;
      continue;
    }
    const quoted = /^(['"])(.*?)\1/.exec(rest);
    if (quoted) {
      tokens.push({ kind: 'string', value: quoted[2] });
      index += quoted[0].length;
      continue;
    }
    const operator = OPERATORS.find((candidate) => rest.startsWith(candidate));
    if (!operator) throw new WatchError(`unexpected '${rest[0]}' at ${index + 1}`);
    tokens.push({ kind: 'op', value: operator });
    index += operator.length;
  }
  return tokens;
}

/** Evaluates `text` against the paused run; throws WatchError saying what is wrong. */
export function evaluateWatch(text: string, context: WatchContext): WatchValue {
  let source = text.trim();
  const wrapped = /^\$\{([\s\S]*)\}$/.exec(source);
  if (wrapped) source = wrapped[1];
  const tokens = tokenize(source);
  let position = 0;
  const peek = () => tokens[position];
  const isOp = (value: string) => peek()?.kind === 'op' && peek()?.value === value;
  const expect = (value: string) => {
    if (!isOp(value)) throw new WatchError(`expected '${value}'`);
    position++;
  };
  const number = (value: WatchValue, what: string): number => {
    if (typeof value === 'number') return value;
    if (typeof value === 'boolean') return value ? 1 : 0;
    const parsed = Number(value);
    if (value.trim() === '' || !Number.isFinite(parsed)) throw new WatchError(`${what} is '${value}', not a number`);
    return parsed;
  };
  const truth = (value: WatchValue) => (typeof value === 'string' ? value === 'true' : Boolean(value));

  const binary = (
    next: () => WatchValue,
    operators: string[],
    apply: (operator: string, left: WatchValue, right: WatchValue) => WatchValue,
  ) => {
    let left = next();
    while (peek()?.kind === 'op' && operators.includes(peek().value as string)) {
      const operator = tokens[position++].value as string;
      left = apply(operator, left, next());
    }
    return left;
  };
  const or = (): WatchValue => binary(and, ['||'], (_, left, right) => truth(left) || truth(right));
  const and = (): WatchValue => binary(comparison, ['&&'], (_, left, right) => truth(left) && truth(right));
  const comparison = (): WatchValue =>
    binary(sum, ['<', '>', '<=', '>=', '==', '!='], (operator, left, right) => {
      if (operator === '==' || operator === '!=') {
        const equal =
          typeof left === 'number' || typeof right === 'number'
            ? number(left, 'the left side') === number(right, 'the right side')
            : String(left) === String(right);
        return operator === '==' ? equal : !equal;
      }
      const a = number(left, 'the left side');
      const b = number(right, 'the right side');
      return operator === '<' ? a < b : operator === '>' ? a > b : operator === '<=' ? a <= b : a >= b;
    });
  const sum = (): WatchValue =>
    binary(product, ['+', '-'], (operator, left, right) =>
      operator === '+'
        ? number(left, 'the left side') + number(right, 'the right side')
        : number(left, 'the left side') - number(right, 'the right side'),
    );
  const product = (): WatchValue =>
    binary(unary, ['*', '/', '%'], (operator, left, right) => {
      const a = number(left, 'the left side');
      const b = number(right, 'the right side');
      return operator === '*' ? a * b : operator === '/' ? a / b : a % b;
    });
  const unary = (): WatchValue => {
    if (isOp('-')) {
      position++;
      return -number(unary(), 'the operand of -');
    }
    if (isOp('!')) {
      position++;
      return !truth(unary());
    }
    return primary();
  };
  const primary = (): WatchValue => {
    const token = tokens[position++];
    if (!token) throw new WatchError('the expression ends too early');
    if (token.kind === 'number' || token.kind === 'string') return token.value;
    if (token.kind === 'op') {
      if (token.value !== '(') throw new WatchError(`unexpected '${token.value}'`);
      const value = or();
      expect(')');
      return value;
    }
    const name = token.value;
    if (name.startsWith('$')) {
      const value = context.parameter(name.slice(1));
      if (value === undefined) throw new WatchError(`no parameter or variable ${name}`);
      return value;
    }
    if (name === 'true' || name === 'false') return name === 'true';
    if ((name === 'gap' || name === 'ttc') && isOp('(')) {
      position++;
      const from = entityName();
      expect(',');
      const to = entityName();
      expect(')');
      const value = context.pair(name, from, to);
      if (value === undefined) throw new WatchError(`esmini gives no ${name} from ${from} to ${to}`);
      return value;
    }
    if (isOp('.')) {
      position++;
      const field = tokens[position++];
      if (field?.kind !== 'name') throw new WatchError(`expected a field after '${name}.'`);
      const entity = context.entity(name);
      if (!entity) throw new WatchError(`no entity ${name}`);
      const value = entity[field.value];
      if (value === undefined) throw new WatchError(`${name} has no field ${field.value} (${Object.keys(entity).join(', ')})`);
      return value;
    }
    if (name === 'time' || name === 't') return context.time;
    const value = context.parameter(name);
    if (value !== undefined) return value;
    throw new WatchError(`unknown name ${name}: write $Parameter, entity.field, time, gap(a, b) or ttc(a, b)`);
  };
  const entityName = (): string => {
    const token = tokens[position++];
    if (token?.kind !== 'name' && token?.kind !== 'string') throw new WatchError('expected an entity name');
    return String(token.value);
  };
  const value = or();
  if (position < tokens.length) throw new WatchError(`unexpected '${String(tokens[position].value)}'`);
  return value;
}

/** A hit count condition as VS Code passes it (`5`, `>= 5`, `% 2`, `== 3`): whether the n-th hit stops. */
export function hitConditionMet(condition: string | undefined, hits: number): boolean {
  if (!condition || !condition.trim()) return true;
  const match = /^\s*(>=|<=|==|>|<|%)?\s*(\d+)\s*$/.exec(condition);
  if (!match) throw new WatchError(`hit count '${condition}' is not a number, optionally after >=, >, ==, <, <= or %`);
  const count = Number(match[2]);
  switch (match[1]) {
    case '>':
      return hits > count;
    case '<':
      return hits < count;
    case '<=':
      return hits <= count;
    case '%':
      return count > 0 && hits % count === 0;
    case '==':
      return hits === count;
    default:
      return match[1] === '>=' ? hits >= count : hits === count;
  }
}

/** A function breakpoint's simulated time: `t=5`, `t >= 5.0`, `time=5`, `@5`, or a bare number. */
export function timeBreakpoint(name: string): number | undefined {
  const match = /^\s*(?:(?:t|time)\s*(?:=|>=|==)\s*|@\s*)?(\d+(?:\.\d*)?|\.\d+)\s*s?\s*$/.exec(name);
  return match ? Number(match[1]) : undefined;
}

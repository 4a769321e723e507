/** Evaluation of a parsed `${...}` expression: doubles, booleans and the standard's functions (./expressionParser.ts parses). */

import { ExpressionError, ExpressionNode, FUNCTIONS, FunctionName } from './expressionParser';
import { ParameterType, ParameterValue, readStringAsValue, roundHalfAwayFromZero, SHARED_MATH_FUNCTIONS, TypedValue } from './values';

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

/** Why a constant is not standard here: `pi` came with OpenSCENARIO 1.4, after every version the project reads (1.0-1.3). */
const CONSTANT_MESSAGES: Record<'pi' | 'e', string> = {
  pi: "'pi' is a constant from OpenSCENARIO 1.4 on, not of 1.3 and the versions before it (esmini knows it); a simulator of an earlier version rejects it",
  e: "'e' is an esmini constant, not part of the OpenSCENARIO standard; other simulators reject it",
};

/**
 * Evaluates a parsed expression. Numbers are doubles throughout (the result is converted to the
 * target's type afterwards, see convertValue); `and`, `or` and `not` take booleans.
 * Non-standard constants are reported through `warnings` and still evaluated.
 */
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
    case 'sign':
      return a > 0 ? 1 : a < 0 ? -1 : 0;
    case 'min':
      return Math.min(a, b);
    case 'max':
      return Math.max(a, b);
    default:
      return SHARED_MATH_FUNCTIONS[name](a, b);
  }
}

/** Evaluation of a parsed `${...}` expression: doubles, booleans and the standard's functions (./expressionParser.ts parses). */

import { NumberOperand } from '../diagnostics/expressionFacts';
import { ExpressionError, ExpressionNode, FUNCTION_NAMES, FunctionName } from './expressionParser';
import { ParameterType, ParameterValue, readStringAsValue, roundHalfAwayFromZero, SHARED_MATH_FUNCTIONS, TypedValue } from './values';

/** A parameter's value, with where its `parameterType` value is written (a string parameter read as a number is fixed there). */
export type LookupResult = TypedValue & { retype?: { start: number; end: number } };

/** Looks up `$name` (its offsets for messages); undefined when no declaration is in scope. */
export type ParameterLookup = (name: string, start: number, end: number) => LookupResult | { error: ExpressionError } | undefined;

const NEGATION: NumberOperand = { role: 'negation' };

export type Evaluation = { ok: true; value: ParameterValue; type: ParameterType } | { ok: false; errors: ExpressionError[] };

class EvaluationFailure extends Error {
  constructor(readonly error: ExpressionError) {
    super(error.kind);
  }
}

/**
 * Evaluates a parsed expression. Numbers are doubles throughout (the result is converted to the
 * target's type afterwards, see convertValue); `and`, `or` and `not` take booleans.
 * Non-standard constants are reported through `warnings` and still evaluated.
 */
export function evaluateTree(tree: ExpressionNode, lookup: ParameterLookup, warnings: ExpressionError[] = []): Evaluation {
  const numberOf = (node: ExpressionNode, operand: NumberOperand): number => {
    const result = visit(node);
    if (typeof result.value !== 'number')
      throw new EvaluationFailure({
        kind: 'type-mismatch',
        fact: 'needs-number',
        operand,
        type: result.type,
        value: result.value,
        start: node.start,
        end: node.end,
      });
    return result.value;
  };
  const booleanOf = (node: ExpressionNode, operator: string): boolean => {
    const result = visit(node);
    if (typeof result.value !== 'boolean')
      throw new EvaluationFailure({
        kind: 'type-mismatch',
        fact: 'needs-boolean',
        operator,
        type: result.type,
        value: result.value,
        start: node.start,
        end: node.end,
      });
    return result.value;
  };
  const number = (value: number): TypedValue => ({ value, type: 'double' });
  const finite = (node: ExpressionNode, value: number, left: number, right = 0): TypedValue => {
    if (!Number.isFinite(value) && !Number.isNaN(value) && Number.isFinite(left) && Number.isFinite(right)) {
      throw new EvaluationFailure({
        kind: 'overflow',
        fact: 'result',
        start: node.start,
        end: node.end,
      });
    }
    return number(value);
  };
  const parameterValue = (node: ExpressionNode & { name: string }, found: LookupResult): TypedValue => {
    if (found.type === 'dateTime')
      throw new EvaluationFailure({
        kind: 'type-mismatch',
        fact: 'date-time-parameter',
        name: node.name,
        start: node.start,
        end: node.end,
      });
    if (found.type !== 'string') return found;
    const read = readStringAsValue(String(found.value));
    if (!read)
      throw new EvaluationFailure({
        kind: 'type-mismatch',
        fact: 'string-parameter',
        name: node.name,
        value: found.value,
        start: node.start,
        end: node.end,
      });
    warnings.push({
      kind: 'lenient',
      fact: 'string-parameter',
      name: node.name,
      value: found.value,
      type: read.type,
      read: String(read.value),
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
            fact: 'number',
            start: node.start,
            end: node.end,
          });
        }
        return number(node.value);
      case 'boolean':
        return { value: node.value, type: 'boolean' };
      case 'constant':
        warnings.push({ kind: 'nonstandard', constant: node.name, start: node.start, end: node.end });
        return number(node.name === 'pi' ? Math.PI : Math.E);
      case 'name': {
        const found = lookup(node.name, node.start, node.end);
        if (!found) {
          throw new EvaluationFailure({
            kind: 'syntax',
            fact: 'unknown-name',
            name: node.name,
            functions: FUNCTION_NAMES,
            start: node.start,
            end: node.end,
          });
        }
        if ('error' in found) throw new EvaluationFailure(found.error);
        warnings.push({
          kind: 'lenient',
          fact: 'bare-parameter',
          name: node.name,
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
            fact: 'undeclared',
            name: node.name,
            start: node.start,
            end: node.end,
          });
        if ('error' in found) throw new EvaluationFailure(found.error);
        return parameterValue(node, found);
      }
      case 'unary':
        if (node.operator === '-') return number(-numberOf(node.operand, NEGATION));
        return { value: !booleanOf(node.operand, 'not'), type: 'boolean' };
      case 'binary': {
        if (node.operator === 'and' || node.operator === 'or') {
          const left = booleanOf(node.left, node.operator);
          const right = booleanOf(node.right, node.operator);
          return { value: node.operator === 'and' ? left && right : left || right, type: 'boolean' };
        }
        const operand: NumberOperand = { role: 'operator', operator: node.operator };
        const left = numberOf(node.left, operand);
        const right = numberOf(node.right, operand);
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
                operator: node.operator,
                start: node.right.start,
                end: node.right.end,
              });
            return finite(node, node.operator === '/' ? left / right : left % right, left, right);
        }
        break;
      }
      case 'call': {
        const operand: NumberOperand = { role: 'function', name: node.name };
        const args = node.args.map((arg) => numberOf(arg, operand));
        const value = applyFunction(node.name, args);
        if (!Number.isNaN(value)) return finite(node, value, args.every(Number.isFinite) ? 0 : Infinity);
        if (!Number.isFinite(value)) {
          throw new EvaluationFailure({
            kind: 'type-mismatch',
            fact: 'no-real-value',
            name: node.name,
            args,
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

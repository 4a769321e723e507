import * as assert from 'node:assert/strict';
import { expressionMessage } from '../../server/src/core/diagnostics/expressionWords';
import { evaluateTree, ParameterLookup } from '../../server/src/core/semantics/expressionEvaluation';
import { ExpressionError, parseExpressionBody, valueForm } from '../../server/src/core/semantics/expressionParser';
import { convertValue, parseLiteral, TypedValue } from '../../server/src/core/semantics/values';

const PARAMETERS: Record<string, TypedValue> = {
  a: { value: 6, type: 'double' },
  b: { value: 4, type: 'double' },
  n: { value: 3, type: 'int' },
  yes: { value: true, type: 'boolean' },
  no: { value: false, type: 'boolean' },
  label: { value: 'ego', type: 'string' },
};

const lookup: ParameterLookup = (name) => PARAMETERS[name];

function evaluate(body: string): TypedValue['value'] {
  const parsed = parseExpressionBody(body);
  assert.deepEqual(parsed.errors, [], `parse errors for ${body}`);
  const result = evaluateTree(parsed.tree!, lookup);
  assert.ok(result.ok, `evaluation of ${body} failed: ${JSON.stringify(!result.ok && result.errors)}`);
  return result.value;
}

function errorOf(body: string): ExpressionError {
  const parsed = parseExpressionBody(body);
  if (parsed.errors.length > 0) return parsed.errors[0];
  const result = evaluateTree(parsed.tree!, lookup);
  assert.ok(!result.ok, `${body} evaluated to ${result.ok && result.value}`);
  return result.errors[0];
}

describe('expressions', () => {
  it('evaluates numbers, parameters and the arithmetic operators', () => {
    assert.equal(evaluate('1'), 1);
    assert.equal(evaluate('2.5e2'), 250);
    assert.equal(evaluate('.5'), 0.5);
    assert.equal(evaluate('$a + $b'), 10);
    assert.equal(evaluate('$a - $b'), 2);
    assert.equal(evaluate('$a * $b'), 24);
    assert.equal(evaluate('$a / $b'), 1.5);
    assert.equal(evaluate('7 % 3'), 1);
    assert.equal(evaluate('-7 % 3'), -1);
    assert.equal(evaluate('250/3.6'), 250 / 3.6);
  });

  it('follows the precedence of the standard: unary minus, then * / %, then + -, then not, and, or', () => {
    assert.equal(evaluate('2 + 3 * 4'), 14);
    assert.equal(evaluate('(2 + 3) * 4'), 20);
    assert.equal(evaluate('10 - 4 - 3'), 3, 'left associative');
    assert.equal(evaluate('24 / 4 / 2'), 3, 'left associative');
    assert.equal(evaluate('2 * 3 % 4'), 2, '(2*3)%4');
    assert.equal(evaluate('-2 * -3'), 6);
    assert.equal(evaluate('--2'), 2);
    assert.equal(evaluate('-$a + 1'), -5);
    assert.equal(evaluate('2 * $a / $b'), 3);
    assert.equal(evaluate('not $no and $yes'), true, '(not false) and true');
    assert.equal(evaluate('$yes or $no and $no'), true, 'true or (false and false)');
    assert.equal(evaluate('not ($yes or $no)'), false);
    assert.equal(evaluate('not not $yes'), true);
    assert.equal(evaluate('true and false'), false);
  });

  it('evaluates every function', () => {
    assert.equal(evaluate('round(2.5)'), 3);
    assert.equal(evaluate('round(-2.5)'), -3, 'half away from zero');
    assert.equal(evaluate('round(2.4)'), 2);
    assert.equal(evaluate('floor(-1.5)'), -2);
    assert.equal(evaluate('ceil(1.2)'), 2);
    assert.equal(evaluate('sqrt(16)'), 4);
    assert.equal(evaluate('pow(2, 10)'), 1024);
    assert.equal(evaluate('abs(-3.5)'), 3.5);
    assert.equal(evaluate('sign(-0.1)'), -1);
    assert.equal(evaluate('sign(0)'), 0);
    assert.equal(evaluate('sign(7)'), 1);
    assert.equal(evaluate('min($a, $b)'), 4);
    assert.equal(evaluate('max($a, $b)'), 6);
    assert.equal(evaluate('sin(0)'), 0);
    assert.equal(evaluate('cos(0)'), 1);
    assert.equal(evaluate('tan(0)'), 0);
    assert.equal(evaluate('asin(1)'), Math.PI / 2);
    assert.equal(evaluate('acos(1)'), 0);
    assert.equal(evaluate('atan(1)'), Math.PI / 4);
    assert.equal(evaluate('max(1, min(5, pow($n, 2)))'), 5);
    assert.equal(evaluate('sqrt(pow(3,2) + pow(4,2))'), 5);
  });

  it('reports syntax errors with their column', () => {
    assert.deepEqual(pick(errorOf('1 +')), { kind: 'syntax', start: 3 });
    assert.deepEqual(pick(errorOf('(1 + 2')), { kind: 'syntax', start: 6 });
    assert.deepEqual(pick(errorOf('1 2')), { kind: 'syntax', start: 2 });
    assert.deepEqual(pick(errorOf('pow(1)')), { kind: 'syntax', start: 0 });
    assert.deepEqual(pick(errorOf('$')), { kind: 'syntax', start: 0 });
    assert.deepEqual(pick(errorOf('1 < 2')), { kind: 'syntax', start: 2 });
    assert.deepEqual(pick(errorOf('speed + 1')), { kind: 'syntax', start: 0 });
    assert.match(expressionMessage(errorOf('speed + 1')), /\$speed/);
  });

  it('reports unknown parameters, type mismatches and division by zero at their operand', () => {
    assert.deepEqual(pick(errorOf('1 + $missing')), { kind: 'unknown-parameter', start: 4 });
    assert.deepEqual(pick(errorOf('$a / ($b - 4)')), { kind: 'division-by-zero', start: 5 });
    assert.deepEqual(pick(errorOf('5 % 0')), { kind: 'division-by-zero', start: 4 });
    assert.deepEqual(pick(errorOf('$yes + 1')), { kind: 'type-mismatch', start: 0 });
    assert.deepEqual(pick(errorOf('not 1')), { kind: 'type-mismatch', start: 4 });
    assert.deepEqual(pick(errorOf('2 * $label')), { kind: 'type-mismatch', start: 4 });
    assert.deepEqual(pick(errorOf('sqrt(-1)')), { kind: 'type-mismatch', start: 0 });
  });

  it('evaluates the esmini constant pi with a warning', () => {
    const parsed = parseExpressionBody('pi / 2');
    const warnings: ExpressionError[] = [];
    const result = evaluateTree(parsed.tree!, lookup, warnings);
    assert.ok(result.ok && result.value === Math.PI / 2);
    assert.equal(warnings[0].kind, 'nonstandard');
  });

  it('classifies attribute values and places expressions at document offsets', () => {
    assert.deepEqual(valueForm('20'), { kind: 'literal' });
    assert.deepEqual(valueForm('$TargetSpeed', 100), { kind: 'parameter', name: 'TargetSpeed', start: 100, end: 112 });
    const form = valueForm('${$a / 3.6}', 50);
    assert.equal(form.kind, 'expression');
    if (form.kind !== 'expression') return;
    assert.deepEqual(form.expression.parameters, [{ name: 'a', start: 52, end: 54 }]);
    assert.equal(form.expression.bodyStart, 52);
    const unclosed = valueForm('${1 + 2', 0);
    assert.ok(unclosed.kind === 'expression' && unclosed.expression.errors[0].kind === 'syntax');
  });

  it('reads literals of every parameterType and converts values to a declared type', () => {
    assert.deepEqual(parseLiteral('20', 'double'), { value: 20 });
    assert.deepEqual(parseLiteral('-1.5e1', 'double'), { value: -15 });
    assert.ok('mismatch' in parseLiteral('time', 'double'));
    assert.deepEqual(parseLiteral('7', 'int'), { value: 7 });
    assert.ok('mismatch' in parseLiteral('7.5', 'int'));
    assert.ok('mismatch' in parseLiteral('-1', 'unsignedInt'));
    assert.ok('mismatch' in parseLiteral('70000', 'unsignedShort'));
    assert.deepEqual(parseLiteral('65535', 'unsignedShort'), { value: 65535 });
    assert.deepEqual(parseLiteral('true', 'boolean'), { value: true });
    assert.deepEqual(parseLiteral('0', 'boolean'), { value: false });
    assert.ok('mismatch' in parseLiteral('yes', 'boolean'));
    assert.deepEqual(parseLiteral('2026-01-01T10:00:00', 'dateTime'), { value: '2026-01-01T10:00:00' });
    assert.ok('mismatch' in parseLiteral('tomorrow', 'dateTime'));
    assert.deepEqual(parseLiteral(' any text ', 'string'), { value: ' any text ' });
    assert.deepEqual(convertValue({ value: 2.5, type: 'double' }, 'int'), { value: 3 });
    assert.deepEqual(convertValue({ value: -2.5, type: 'double' }, 'int'), { value: -3 });
    assert.ok('mismatch' in convertValue({ value: -1, type: 'double' }, 'unsignedInt'));
    assert.deepEqual(convertValue({ value: 1.5, type: 'double' }, 'string'), { value: '1.5' });
    assert.ok('mismatch' in convertValue({ value: true, type: 'boolean' }, 'double'));
  });
});

function pick(error: ExpressionError): { kind: string; start: number } {
  return { kind: error.kind, start: error.start };
}

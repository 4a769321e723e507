import * as assert from 'node:assert/strict';
import { EXPRESSION_SYNTAX } from '../../../server/src/core/diagnostics/expressionSyntax';
import { ruleIdOf, ruleOf } from '../../../server/src/core/rules';
import { QC } from '../../../server/src/core/diagnostics/qcRules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: expression-syntax', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(EXPRESSION_SYNTAX.code, 'expression-syntax');
    assert.equal(EXPRESSION_SYNTAX.severity, 'error');
    assert.equal(ruleIdOf('expression-syntax'), EXPRESSION_SYNTAX.rule.qcRule ?? 'modular2simple:expression-syntax');
  });

  it('is what the document checks report', async () => {
    const problems = (await semanticProblemsOf(roadScenario({ groups: [group(speed('${1 +}'))] }))).filter(
      (problem) => problem.code === 'expression-syntax',
    );
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'error',
        code: 'expression-syntax',
        message: "expected a number, a $parameter, a function or '(', found the end of the expression",
      },
    ]);
  });

  // ASAM's checker's test files (qc-openscenarioxml tests/data/allowed_operators) write `${2_3}`, `${powerer(2, 3)}`, `^` and a stray `}`.
  it("an operator, function or character the standard lacks names ASAM's allowed_operators rule; other syntax errors do not", async () => {
    const reported = async (value: string) =>
      (await semanticProblemsOf(roadScenario({ groups: [group(speed(value))] })))
        .filter((problem) => problem.code === 'expression-syntax')
        .map((problem) => ({ message: problem.message, rule: ruleOf(problem).id }));
    const functions = 'round, floor, ceil, sqrt, pow, abs, sign, min, max, sin, cos, tan, asin, acos, atan';
    assert.deepEqual(await reported('${powerer(2, 3)}'), [
      { message: `unknown function 'powerer': the functions are ${functions}`, rule: QC.allowedOperators },
    ]);
    assert.deepEqual(await reported('${2_3}'), [
      { message: "unknown operator '_3': the operators are +, -, *, /, %, and, or, not", rule: QC.allowedOperators },
    ]);
    assert.deepEqual(await reported('${(1 xor 2)}'), [
      { message: "unknown operator 'xor': the operators are +, -, *, /, %, and, or, not", rule: QC.allowedOperators },
    ]);
    assert.deepEqual(await reported('${2 ^ 3}'), [{ message: "'^' is not allowed in an expression", rule: QC.allowedOperators }]);
    assert.deepEqual(await reported('${1 +}'), [
      {
        message: "expected a number, a $parameter, a function or '(', found the end of the expression",
        rule: 'modular2simple:expression-syntax',
      },
    ]);
    assert.deepEqual(await reported('${2 round(1)}'), [
      { message: "unexpected 'round': an operator or the end of the expression was expected", rule: 'modular2simple:expression-syntax' },
    ]);
  });
});

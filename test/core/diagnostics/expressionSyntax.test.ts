import * as assert from 'node:assert/strict';
import { EXPRESSION_SYNTAX } from '../../../server/src/core/diagnostics/expressionSyntax';
import { ruleIdOf } from '../../../server/src/core/rules';
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
});

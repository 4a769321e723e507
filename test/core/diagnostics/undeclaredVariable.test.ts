import * as assert from 'node:assert/strict';
import { UNDECLARED_VARIABLE } from '../../../server/src/core/diagnostics/undeclaredVariable';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed, trigger } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: undeclared-variable', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNDECLARED_VARIABLE.code, 'undeclared-variable');
    assert.equal(UNDECLARED_VARIABLE.severity, 'error');
    assert.equal(ruleIdOf('undeclared-variable'), UNDECLARED_VARIABLE.rule.qcRule ?? 'modular2simple:undeclared-variable');
    assert.equal(UNDECLARED_VARIABLE.isData!({ variable: 'V', entry: 'car' }), true);
    assert.equal(UNDECLARED_VARIABLE.isData!({ variable: 'V', entry: 3 }), false);
  });

  it('is what the document checks report', async () => {
    const problems = (
      await semanticProblemsOf(
        roadScenario({
          groups: [
            group(speed('1')).replace('<StartTrigger/>', trigger('<VariableCondition variableRef="Nope" rule="equalTo" value="1"/>')),
          ],
        }),
      )
    ).filter((problem) => problem.code === 'undeclared-variable');
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'error',
        code: 'undeclared-variable',
        message: "variable 'Nope' is not declared in the VariableDeclarations of this file",
      },
    ]);
    assert.deepEqual(problems[0].data, { variable: 'Nope' });
  });
});

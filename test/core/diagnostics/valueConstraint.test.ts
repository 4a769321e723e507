import * as assert from 'node:assert/strict';
import { VALUE_CONSTRAINT } from '../../../server/src/core/diagnostics/valueConstraint';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: value-constraint', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(VALUE_CONSTRAINT.code, 'value-constraint');
    assert.equal(VALUE_CONSTRAINT.severity, 'error');
    assert.equal(ruleIdOf('value-constraint'), VALUE_CONSTRAINT.rule.qcRule ?? 'modular2simple:value-constraint');
  });

  it('is what the document checks report', async () => {
    const problems = (
      await semanticProblemsOf(
        roadScenario({
          parameters:
            '<ParameterDeclaration name="P" parameterType="double" value="5"><ConstraintGroup><ValueConstraint rule="lessThan" value="3"/></ConstraintGroup></ParameterDeclaration>',
          groups: [group(speed('$P'))],
        }),
      )
    ).filter((problem) => problem.code === 'value-constraint');
    assert.deepEqual(problems.map(wordingOf), [
      { severity: 'error', code: 'value-constraint', message: "the value 5 of parameter 'P' breaks its ConstraintGroup: it is not < 3" },
    ]);
  });
});

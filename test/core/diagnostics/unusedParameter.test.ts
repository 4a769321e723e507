import * as assert from 'node:assert/strict';
import { UNUSED_PARAMETER } from '../../../server/src/core/diagnostics/unusedParameter';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: unused-parameter', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(UNUSED_PARAMETER.code, 'unused-parameter');
    assert.equal(UNUSED_PARAMETER.severity, 'hint');
    assert.equal(ruleIdOf('unused-parameter'), UNUSED_PARAMETER.rule.qcRule ?? 'modular2simple:unused-parameter');
    assert.equal(UNUSED_PARAMETER.unnecessary, true);
  });

  it('is what the document checks report', async () => {
    const problems = (
      await semanticProblemsOf(
        roadScenario({ parameters: '<ParameterDeclaration name="Unused" parameterType="double" value="1"/>', groups: [group(speed('1'))] }),
      )
    ).filter((problem) => problem.code === 'unused-parameter');
    assert.deepEqual(problems.map(wordingOf), [
      { severity: 'hint', code: 'unused-parameter', message: "parameter 'Unused' is never used" },
    ]);
  });
});

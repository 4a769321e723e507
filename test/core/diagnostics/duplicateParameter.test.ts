import * as assert from 'node:assert/strict';
import { DUPLICATE_PARAMETER } from '../../../server/src/core/diagnostics/duplicateParameter';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: duplicate-parameter', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(DUPLICATE_PARAMETER.code, 'duplicate-parameter');
    assert.equal(DUPLICATE_PARAMETER.severity, 'warning');
    assert.equal(ruleIdOf('duplicate-parameter'), DUPLICATE_PARAMETER.rule.qcRule ?? 'modular2simple:duplicate-parameter');
  });

  it('is what the document checks report', async () => {
    const problems = (
      await semanticProblemsOf(
        roadScenario({
          parameters:
            '<ParameterDeclaration name="P" parameterType="double" value="1"/><ParameterDeclaration name="P" parameterType="double" value="2"/>',
          groups: [group(speed('$P'))],
        }),
      )
    ).filter((problem) => problem.code === 'duplicate-parameter');
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'warning',
        code: 'duplicate-parameter',
        message: "parameter 'P' is declared twice in <OpenSCENARIO>; references use the first declaration",
      },
    ]);
  });
});

import * as assert from 'node:assert/strict';
import { UNDECLARED_PARAMETER } from '../../../server/src/core/diagnostics/undeclaredParameter';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: undeclared-parameter', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNDECLARED_PARAMETER.code, 'undeclared-parameter');
    assert.equal(UNDECLARED_PARAMETER.severity, 'error');
    assert.equal(ruleIdOf('undeclared-parameter'), UNDECLARED_PARAMETER.rule.qcRule ?? 'modular2simple:undeclared-parameter');
    assert.equal(UNDECLARED_PARAMETER.isData!({ parameter: 'P' }), true);
    assert.equal(UNDECLARED_PARAMETER.isData!({ parameter: 1 }), false);
  });

  it('is what the document checks report', async () => {
    const problems = (await semanticProblemsOf(roadScenario({ groups: [group(speed('$Nope'))] }))).filter(
      (problem) => problem.code === 'undeclared-parameter',
    );
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'error',
        code: 'undeclared-parameter',
        message: "parameter 'Nope' is not declared in this scope",
        hint: 'declare <ParameterDeclaration name="Nope" parameterType="..." value="..."/> in the ParameterDeclarations of the file or of an enclosing element',
      },
    ]);
    assert.deepEqual(problems[0].data, { parameter: 'Nope' });
  });
});

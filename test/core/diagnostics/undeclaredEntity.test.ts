import * as assert from 'node:assert/strict';
import { UNDECLARED_ENTITY } from '../../../server/src/core/diagnostics/undeclaredEntity';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: undeclared-entity', () => {
  it('is registered with its severity and rule, and checks the data a client sends back', () => {
    assert.equal(UNDECLARED_ENTITY.code, 'undeclared-entity');
    assert.equal(UNDECLARED_ENTITY.severity, 'error');
    assert.equal(ruleIdOf('undeclared-entity'), UNDECLARED_ENTITY.rule.qcRule ?? 'modular2simple:undeclared-entity');
    assert.equal(UNDECLARED_ENTITY.isData!({ entity: 'E' }), true);
    assert.equal(UNDECLARED_ENTITY.isData!({ entity: 2 }), false);
  });

  it('is what the document checks report', async () => {
    const problems = (await semanticProblemsOf(roadScenario({ groups: [group(speed('1'), 'Nobody')] }))).filter(
      (problem) => problem.code === 'undeclared-entity',
    );
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'error',
        code: 'undeclared-entity',
        message: "entity 'Nobody' is not declared in <Entities>",
        hint: "declare a ScenarioObject named 'Nobody'",
      },
    ]);
    assert.deepEqual(problems[0].data, { entity: 'Nobody' });
  });
});

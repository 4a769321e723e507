import * as assert from 'node:assert/strict';
import { DIVISION_BY_ZERO } from '../../../server/src/core/diagnostics/divisionByZero';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf } from './support';

describe('diagnostics: division-by-zero', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(DIVISION_BY_ZERO.code, 'division-by-zero');
    assert.equal(DIVISION_BY_ZERO.severity, 'error');
    assert.equal(ruleIdOf('division-by-zero'), DIVISION_BY_ZERO.rule.qcRule ?? 'modular2simple:division-by-zero');
  });

  it('is what the document checks report, saying what esmini computes', async () => {
    const problems = (await semanticProblemsOf(roadScenario({ groups: [group(speed('${1 / 0}'))] }))).filter(
      (problem) => problem.code === 'division-by-zero',
    );
    assert.equal(problems.length, 1);
    assert.match(problems[0].message, /^division by zero: the right side of '\/' is 0 \(esmini computes inf/);
    assert.equal(problems[0].severity, DIVISION_BY_ZERO.severity);
  });
});

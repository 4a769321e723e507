import * as assert from 'node:assert/strict';
import { DUPLICATE_PARAMETER } from '../../../server/src/core/diagnostics/duplicateParameter';
import { esminiRule } from '../../../server/src/core/diagnostics/simulatorValue';
import { Simulator } from '../../../server/src/core/profiles/simulators';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';

/** The duplicate-parameter problems of a scenario declaring P as 1, then as 2, checked for `simulator`. */
async function twiceDeclared(simulator?: Simulator) {
  const text = roadScenario({
    parameters:
      '<ParameterDeclaration name="P" parameterType="double" value="1"/><ParameterDeclaration name="P" parameterType="double" value="2"/>',
    groups: [group(speed('$P'))],
  });
  return (await semanticProblemsOf(text, {}, simulator)).filter((problem) => problem.code === 'duplicate-parameter');
}

describe('diagnostics: duplicate-parameter', () => {
  it('is registered with its severity and rule', () => {
    assert.equal(DUPLICATE_PARAMETER.code, 'duplicate-parameter');
    assert.equal(DUPLICATE_PARAMETER.severity, 'warning');
    assert.equal(ruleIdOf('duplicate-parameter'), DUPLICATE_PARAMETER.rule.qcRule ?? 'modular2simple:duplicate-parameter');
  });

  it('is what the document checks report', async () => {
    assert.deepEqual((await twiceDeclared()).map(wordingOf), [
      {
        severity: 'warning',
        code: 'duplicate-parameter',
        message: "parameter 'P' is declared twice in <OpenSCENARIO>; references use the first declaration",
      },
    ]);
  });

  // esmini's follow_reference.xosc declares lane_change_duration twice; esmini logs "Parameter ... redefined" and takes the last.
  it('with simulator esmini, names both values: esmini uses the last declaration (it said only "the first" before)', async () => {
    const problems = await twiceDeclared('esmini');
    assert.deepEqual(problems.map(wordingOf), [
      {
        severity: 'warning',
        code: 'duplicate-parameter',
        message: `parameter 'P' is declared twice in <OpenSCENARIO>; references use the first declaration (value '1'); ${esminiRule('redeclaration')}, here value '2'`,
      },
    ]);
    assert.match(problems[0].message, /esmini uses the last of two declarations .*Parameters\.cpp:566-582/);
  });
});

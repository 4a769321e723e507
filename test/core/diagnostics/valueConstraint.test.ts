import * as assert from 'node:assert/strict';
import { VALUE_CONSTRAINT } from '../../../server/src/core/diagnostics/valueConstraint';
import { ruleIdOf } from '../../../server/src/core/rules';
import { roadScenario } from '../../support/fixtures';
import { group, speed } from './semanticSupport';
import { semanticProblemsOf, wordingOf } from './support';
import { analyzeDocument, CatalogLoader, semanticProblems } from '../../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../../server/src/core/sources';
import { parseXml } from '../../../server/src/core/xml';

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

  // The shape of the ASAM OpenSCENARIO API's test ALKS_Scenario_4.2_1_FullyBlockingTarget_ParameterValidation(Error).xosc.
  it("checks the standard's value under simulator esmini too, which keeps an unsignedInt as text and reads no ConstraintGroup", async () => {
    const text = (rule: string) =>
      roadScenario({
        parameters: `<ParameterDeclaration name="N" parameterType="unsignedInt" value="60000"><ConstraintGroup><ValueConstraint rule="${rule}" value="60000"/></ConstraintGroup></ParameterDeclaration>`,
        groups: [group(speed('10'))],
      });
    const messages = async (rule: string) => {
      const semantics = await analyzeDocument(
        diskRef('/nowhere/scenario.xosc'),
        parseXml(text(rule)),
        new CatalogLoader(new ScenarioStore()),
        false,
        'esmini',
      );
      return semanticProblems(semantics)
        .filter((problem) => problem.code === 'value-constraint')
        .map((problem) => problem.message);
    };
    assert.deepEqual(await messages('equalTo'), []);
    assert.deepEqual(await messages('notEqualTo'), ["the value 60000 of parameter 'N' breaks its ConstraintGroup: it is not ≠ 60000"]);
  });
});

import * as assert from 'node:assert/strict';
import { UNUSED_PARAMETER } from '../../../server/src/core/diagnostics/unusedParameter';
import { ruleIdOf } from '../../../server/src/core/rules';
import { catalogFile, roadScenario } from '../../support/fixtures';
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

  it("is not said of a parameter that a referenced catalog entry uses undeclared: esmini takes it from the scenario (esmini's synchronize.xosc, AccRate)", async () => {
    // esmini 3.6 on esmini's own synchronize.xosc without its AccRate declaration: "Failed to resolve parameter $AccRate", nothing runs.
    const maneuver = `<Maneuver name="Accelerate"><Event name="E" priority="override"><Action name="A">${speed('$AccRate')}</Action><StartTrigger/></Event></Maneuver>`;
    const reference = `<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><CatalogReference catalogName="Maneuvers" entryName="Accelerate"/></ManeuverGroup>`;
    const text = roadScenario({
      parameters:
        '<ParameterDeclaration name="AccRate" parameterType="double" value="3"/><ParameterDeclaration name="Unused" parameterType="double" value="1"/>',
      groups: [reference],
    }).replace(
      '<CatalogLocations/>',
      '<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>',
    );
    for (const simulator of [undefined, 'esmini'] as const) {
      const problems = await semanticProblemsOf(text, { 'catalogs/Maneuvers.xosc': catalogFile('Maneuvers', maneuver) }, simulator);
      assert.deepEqual(
        problems.filter((problem) => problem.code === 'unused-parameter').map(wordingOf),
        [{ severity: 'hint', code: 'unused-parameter', message: "parameter 'Unused' is never used" }],
        String(simulator),
      );
      assert.deepEqual(
        problems.filter((problem) => problem.code === 'undeclared-parameter'),
        [],
        'the scenario declares what the entry uses',
      );
    }
  });
});

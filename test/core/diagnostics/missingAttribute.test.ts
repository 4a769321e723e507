import * as assert from 'node:assert/strict';
import {
  incompleteParameterReferenceWording,
  MISSING_ATTRIBUTE,
  missingGroupNameWording,
  missingScenarioFileNameWording,
} from '../../../server/src/core/diagnostics/missingAttribute';
import { mainOf } from '../../support/fixtures';
import { analysisProblemsOf, wordingOf } from './support';

describe('diagnostics: missing-attribute', () => {
  it('names the reference element and the attribute it lacks', () => {
    assert.deepEqual(missingScenarioFileNameWording(), {
      severity: 'error',
      code: 'missing-attribute',
      message: 'ScenarioReference has no scenarioFileName attribute',
      hint: 'add scenarioFileName="NAME.xosc" or "NAME.mosc"',
    });
    assert.deepEqual(missingGroupNameWording(), {
      severity: 'error',
      code: 'missing-attribute',
      message: 'ManeuverGroupReference has no maneuverGroupName attribute',
    });
    assert.deepEqual(incompleteParameterReferenceWording(), {
      severity: 'error',
      code: 'missing-attribute',
      message: 'ParameterReference needs both key and value attributes',
      hint: 'write <ParameterReference key="Element.attribute" value="..."/>',
    });
    assert.equal(MISSING_ATTRIBUTE.severity, 'error');
  });

  it('is what an analysis reports on a ScenarioReference without scenarioFileName', async () => {
    const main = mainOf('simple.xosc').replace(' scenarioFileName="simple.xosc"', '');
    assert.notEqual(main, mainOf('simple.xosc'));
    const problems = await analysisProblemsOf({ 'main.xosc': main });
    assert.deepEqual(problems.filter((problem) => problem.code === 'missing-attribute').map(wordingOf), [missingScenarioFileNameWording()]);
  });
});

import * as assert from 'node:assert/strict';
import { NEGATIVE_TRANSITION_TIME, negativeTransitionTimeWording } from '../../../server/src/core/diagnostics/negativeTransitionTime';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: negative-transition-time', () => {
  it('gives the time found', () => {
    assert.deepEqual(negativeTransitionTimeWording(-0.5), {
      severity: 'error',
      code: 'negative-transition-time',
      message: 'the transition time of a LightStateAction must not be negative; it is -0.5 s',
    });
    assert.equal(NEGATIVE_TRANSITION_TIME.severity, 'error');
  });

  it('is what the document checks report on a negative transitionTime', async () => {
    const light = `<PrivateAction><AppearanceAction><LightStateAction transitionTime="-0.5"><LightType><VehicleLight vehicleLightType="headLights"/></LightType><LightState mode="on"/></LightStateAction></AppearanceAction></PrivateAction>`;
    const problems = await semanticProblemsOf(groupScenario(light), { 'road.xodr': ROAD });
    assert.deepEqual(problems.filter((problem) => problem.code === 'negative-transition-time').map(wordingOf), [
      negativeTransitionTimeWording(-0.5),
    ]);
  });
});

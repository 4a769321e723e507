import * as assert from 'node:assert/strict';
import { NO_ACTOR, NO_ACTOR_ACTION_NOTE, noActorWording } from '../../../server/src/core/diagnostics/noActor';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: no-actor', () => {
  it('names the group and both readings, and says what to add', () => {
    assert.deepEqual(noActorWording('G'), {
      severity: 'warning',
      code: 'no-actor',
      message:
        "ManeuverGroup 'G' holds private actions but names no actor for them to act on (ASAM's Quality Checker reports it as an error; esmini runs it, the actions acting on no entity)",
      hint: 'add <EntityRef entityRef="..."/> to its <Actors>',
    });
    assert.equal(NO_ACTOR.severity, 'warning');
  });

  it('is what the document checks report on a group with a private action and no actor, pointing at the action', async () => {
    const action = '<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>';
    const problems = (await semanticProblemsOf(groupScenario(action, { actors: '' }), { 'road.xodr': ROAD })).filter(
      (problem) => problem.code === 'no-actor',
    );
    assert.deepEqual(problems.map(wordingOf), [noActorWording('G')]);
    assert.deepEqual(
      problems[0].related?.map((related) => related.message),
      [NO_ACTOR_ACTION_NOTE],
    );
  });
});

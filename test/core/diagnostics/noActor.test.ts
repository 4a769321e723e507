import * as assert from 'node:assert/strict';
import { NO_ACTOR, NO_ACTOR_ACTION_NOTE, noActorWording } from '../../../server/src/core/diagnostics/noActor';
import { groupScenario, ROAD } from './networkSupport';
import { semanticProblemsOf, wordingOf } from './support';

describe('diagnostics: no-actor', () => {
  it('names the group, says esmini refuses the scenario and what to add', () => {
    assert.deepEqual(noActorWording('G'), {
      severity: 'error',
      code: 'no-actor',
      message: `ManeuverGroup 'G' holds private actions but names no actor for them to act on (esmini refuses the scenario: "missing actor(s)")`,
      hint: 'add <EntityRef entityRef="..."/> to its <Actors>',
    });
    assert.equal(
      noActorWording('G', true).message,
      `ManeuverGroup 'G' holds private actions but takes its actors from the triggering entities, and its Act's StartTrigger has no entity condition to give any (esmini refuses the scenario: "missing actor(s)")`,
    );
    assert.equal(NO_ACTOR.severity, 'error');
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

  // ASAM's checker's negative file (qc-openscenarioxml tests/data/valid_actor_reference_in_private_actions) has this shape.
  it('selectTriggeringEntities="true" names actors only when the Act\'s StartTrigger has an entity condition', async () => {
    const action = '<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>';
    const selecting = groupScenario(action, { actors: '' }).replace('selectTriggeringEntities="false"', 'selectTriggeringEntities="true"');
    const noActors = async (text: string) =>
      (await semanticProblemsOf(text, { 'road.xodr': ROAD })).filter((problem) => problem.code === 'no-actor').map(wordingOf);
    assert.deepEqual(await noActors(selecting), [noActorWording('G', true)]);
    const entityCondition =
      '<StartTrigger><ConditionGroup><Condition name="Near" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities><EntityCondition><StandStillCondition duration="1"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger>\n      </Act>';
    const withTrigger = selecting.replace(/<StartTrigger\/>\n {6}<\/Act>/, entityCondition);
    assert.notEqual(withTrigger, selecting);
    assert.deepEqual(await noActors(withTrigger), []);
  });
});

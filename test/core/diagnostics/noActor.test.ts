import * as assert from 'node:assert/strict';
import { NO_ACTOR, NO_ACTOR_ACTION_NOTE, noActorWording } from '../../../server/src/core/diagnostics/noActor';
import { groupScenario, ROAD } from './networkSupport';
import { SIMULATOR } from '../../../server/src/core/diagnostics/simulator';
import { applyEdits } from '../../support/textEdits';
import { fixContext, semanticProblemsOf, wordingOf } from './support';

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

  it("for esmini, selectTriggeringEntities alone is an error (it reads only EntityRefs), fixed by the EntityRef of the Act's one triggering entity", async () => {
    const action = '<PrivateAction><ActivateControllerAction longitudinal="false"/></PrivateAction>';
    const entityCondition = (entities: string) =>
      `<StartTrigger><ConditionGroup><Condition name="Near" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any">${entities}</TriggeringEntities><EntityCondition><StandStillCondition duration="1"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger>\n      </Act>`;
    const selecting = groupScenario(action, { actors: '' })
      .replace('selectTriggeringEntities="false">', 'selectTriggeringEntities="true">')
      .replace(/<StartTrigger\/>\n {6}<\/Act>/, entityCondition('<EntityRef entityRef="Ego"/>'));
    assert.match(selecting, /<TriggeringEntities/);
    const problems = await semanticProblemsOf(selecting, { 'road.xodr': ROAD }, 'esmini');
    assert.deepEqual(
      problems.filter((problem) => problem.code === 'no-actor'),
      [],
    );
    const refusals = problems.filter((problem) => problem.code === 'simulator');
    assert.deepEqual(refusals.map(wordingOf), [
      {
        severity: 'error',
        code: 'simulator',
        message:
          'esmini takes a ManeuverGroup\'s actors only from the EntityRefs of its Actors, never from selectTriggeringEntities, and refuses to load a private action with none ("PrivateAction ... missing actor(s). SelectTriggeringEntities feature not supported yet"): ' +
          "ManeuverGroup 'G' holds private actions and takes its actors only from the triggering entities of its Act (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:5424-5444, 5304-5310)",
        hint: 'add <EntityRef entityRef="Ego"/> to its <Actors>, the Act\'s triggering entity',
      },
    ]);
    const [refusal] = refusals;
    const lines = selecting.split('\n');
    assert.equal(lines[refusal.range.start.line].slice(refusal.range.start.character, refusal.range.end.character), 'true');
    assert.deepEqual(refusal.data, { actor: 'Ego' });
    assert.deepEqual(
      refusal.related?.map((related) => related.message),
      [NO_ACTOR_ACTION_NOTE],
    );
    // The fix: one EntityRef in the Actors, after which esmini's check is silent.
    const fixes = (await SIMULATOR.fixes?.(fixContext(refusal.data, undefined, selecting, refusal.range))) ?? [];
    assert.deepEqual(
      fixes.map((fix) => fix.title),
      ['Add <EntityRef entityRef="Ego"/> to the Actors'],
    );
    const fixed = applyEdits(selecting, fixes[0].edits);
    assert.match(fixed, /<Actors selectTriggeringEntities="true"><EntityRef entityRef="Ego"\/><\/Actors>/);
    assert.deepEqual(
      (await semanticProblemsOf(fixed, { 'road.xodr': ROAD }, 'esmini')).filter((problem) =>
        ['simulator', 'no-actor'].includes(problem.code),
      ),
      [],
    );
    // A self-closing Actors opens; two triggering entities give no fix (which of them the standard takes is known only as it runs).
    const selfClosing = selecting.replace(
      /<Actors selectTriggeringEntities="true"><\/Actors>/,
      '<Actors selectTriggeringEntities="true"/>',
    );
    const [closed] = (await semanticProblemsOf(selfClosing, { 'road.xodr': ROAD }, 'esmini')).filter(
      (problem) => problem.code === 'simulator',
    );
    const [opened] = (await SIMULATOR.fixes?.(fixContext(closed.data, undefined, selfClosing, closed.range))) ?? [];
    assert.match(
      applyEdits(selfClosing, opened.edits),
      /<Actors selectTriggeringEntities="true">\n {12}<EntityRef entityRef="Ego"\/>\n {10}<\/Actors>/,
    );
    const two = selecting.replace(
      '<EntityRef entityRef="Ego"/></TriggeringEntities>',
      '<EntityRef entityRef="Ego"/><EntityRef entityRef="Other"/></TriggeringEntities>',
    );
    const [unfixed] = (await semanticProblemsOf(two, { 'road.xodr': ROAD }, 'esmini')).filter((problem) => problem.code === 'simulator');
    assert.equal(unfixed.data, undefined);
    assert.equal(unfixed.hint, 'add <EntityRef entityRef="..."/> to its <Actors>');
    // The standard alone takes the triggering entities: nothing to say.
    assert.deepEqual(
      (await semanticProblemsOf(selecting, { 'road.xodr': ROAD })).filter((problem) => ['simulator', 'no-actor'].includes(problem.code)),
      [],
    );
  });
});

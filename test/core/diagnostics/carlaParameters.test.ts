import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { CARLA_FACTS } from '../../../server/src/core/profiles/carla';
import { Problem } from '../../../server/src/core/problems';
import { semanticProblemsOf } from './support';
import { afterASecond, parameterCondition, parameterStoryScenario, settingEvent, storyAct } from '../../support/carlaStories';

/*
 * A ParameterCondition on a parameter only a story's ParameterAction sets: ScenarioRunner holds it as its declared
 * text until that action runs, and a lessThan/greaterThan condition ticked before then raises TypeError
 * (core/semantics/checks/carlaParameters.ts; test/carla/profile.test.ts ticks the same patterns in ScenarioRunner).
 */

const setsGap = (name = 'Sets'): string => settingEvent(name, afterASecond(`${name}Starts`), 'gap');

/** The CARLA findings on ParameterConditions of `text`, checked as `check --simulator carla` does. */
async function parameterFindings(text: string): Promise<Problem[]> {
  const facts = Object.entries(CARLA_FACTS).filter(([name]) => name.startsWith('parameter') && name !== 'parameterNotResolved');
  return (await semanticProblemsOf(text, {}, 'carla')).filter(
    (problem) => problem.code === 'simulator' && facts.some(([, fact]) => problem.message.includes(fact.does)),
  );
}

/** Each finding as [line (1-based), severity, the fact it states]. */
async function verdicts(text: string): Promise<[number, string, string][]> {
  const facts = Object.entries(CARLA_FACTS);
  return (await parameterFindings(text)).map((problem) => [
    problem.range.start.line + 1,
    problem.severity,
    facts.find(([, fact]) => problem.message.includes(fact.does))?.[0] ?? problem.message,
  ]);
}

const lineOf = (text: string, needle: string): number => text.split('\n').findIndex((line) => line.includes(needle)) + 1;

describe('diagnostics: simulator (carla), a parameter only a story sets (issue 26)', () => {
  it('is an error where no story action can run before the condition is first ticked', async () => {
    // esmini's lane_change.xosc: the condition starts an event ahead of the one that sets the parameter, in one Act.
    const earlierEvent = parameterStoryScenario([
      storyAct('A', [settingEvent('Checks', parameterCondition('GapAbove', 'greaterThan', '10')), setsGap()]),
    ]);
    // The action waits for the condition: in the Event it starts, or in the Act it starts.
    const sameEvent = parameterStoryScenario([
      storyAct('A', [settingEvent('Sets', parameterCondition('GapBelow', 'lessThan', '2'), 'gap')]),
    ]);
    const startsItsAct = parameterStoryScenario([storyAct('A', [setsGap()], parameterCondition('GapBelow', 'lessThan', '2'))]);
    // An Act's StartTrigger is ticked from the stories' first tick, ahead of every later Act.
    const startsAnEarlierAct = parameterStoryScenario([
      storyAct('A', [settingEvent('Other', afterASecond('X'))], parameterCondition('GapBelow', 'lessThan', '2')),
      storyAct('B', [setsGap()]),
    ]);
    for (const [text, name] of [
      [earlierEvent, 'GapAbove'],
      [sameEvent, 'GapBelow'],
      [startsItsAct, 'GapBelow'],
      [startsAnEarlierAct, 'GapBelow'],
    ])
      assert.deepEqual(await verdicts(text), [[lineOf(text, `name="${name}"`), 'error', 'parameterSetAfterCondition']], text);
    const [problem] = await parameterFindings(earlierEvent);
    assert.match(problem.message, /'gap' is declared as '3' and compared greaterThan 10, and set only at line \d+/);
    assert.match(problem.message, /open_scenario\.py:369-385, 425-454, 482-503\)$/);
    assert.deepEqual(problem.data, { exportMaps: true });
    assert.deepEqual(
      problem.related?.map((place) => [place.range.start.line + 1, place.message]),
      [[lineOf(earlierEvent, 'name="SetsAction"'), "this ParameterAction sets 'gap' in a story"]],
    );
  });

  it('is a warning naming the order where an action may run first: ahead of it in one Act, in another Act, before an Act StopTrigger', async () => {
    const aheadInAct = parameterStoryScenario([
      storyAct('A', [setsGap(), settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2'))]),
    ]);
    const otherActAfter = parameterStoryScenario([
      storyAct('A', [settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2'))]),
      storyAct('B', [setsGap()]),
    ]);
    const otherActBefore = parameterStoryScenario([
      storyAct('B', [setsGap()]),
      storyAct('A', [settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2'))]),
    ]);
    const stopTrigger = parameterStoryScenario([
      storyAct(
        'A',
        [setsGap()],
        undefined,
        `<StopTrigger><ConditionGroup>${parameterCondition('GapBelow', 'lessThan', '2')}</ConditionGroup></StopTrigger>`,
      ),
    ]);
    const setter = (text: string): number => lineOf(text, 'name="SetsAction"');
    const expected: [string, string][] = [
      [aheadInAct, `line ${setter(aheadInAct)} comes before it in that order;`],
      [otherActAfter, `line ${setter(otherActAfter)} comes after it in that order, in another Act;`],
      [otherActBefore, `line ${setter(otherActBefore)} comes before it in that order, in another Act;`],
      [stopTrigger, `line ${setter(stopTrigger)} comes before it in that order;`],
    ];
    for (const [text, order] of expected) {
      assert.deepEqual(await verdicts(text), [[lineOf(text, 'name="GapBelow"'), 'warning', 'parameterSetInStoryOrder']], text);
      assert.ok((await parameterFindings(text))[0].message.includes(order), order);
    }
  });

  it('is a warning where a ParameterAction in a catalog Maneuver sets it, whose place in the tick order the scenario does not show', async () => {
    const catalog = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-11-29T00:00:00" description="maneuvers" author="modular2simple tests"/>
  <Catalog name="Maneuvers">
    <Maneuver name="SetsGap">${setsGap()}
    </Maneuver>
  </Catalog>
</OpenSCENARIO>
`;
    const text = parameterStoryScenario([storyAct('A', [settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2'))])])
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>',
      )
      .replace(
        '<Actors selectTriggeringEntities="false"/>',
        '<Actors selectTriggeringEntities="false"/><CatalogReference catalogName="Maneuvers" entryName="SetsGap"/>',
      );
    const problems = (await semanticProblemsOf(text, { 'catalogs/ManeuverCatalog.xosc': catalog }, 'carla')).filter((problem) =>
      problem.message.includes(CARLA_FACTS.parameterSetInStoryOrder.does),
    );
    assert.deepEqual(
      problems.map((problem) => problem.range.start.line + 1),
      [lineOf(text, 'name="GapBelow"')],
    );
    const line = lineOf(catalog, 'name="SetsAction"');
    assert.ok(problems[0].message.includes(`line ${line} of ManeuverCatalog.xosc is in a catalog entry;`), problems[0].message);
    assert.deepEqual(
      problems[0].related?.map((place) => [path.basename(place.source.disk), place.range.start.line + 1]),
      [['ManeuverCatalog.xosc', line]],
    );
  });

  it('is nothing for equalTo a number (it holds once the action ran) or a parameter the Init sets; a value that is no number is an error whatever sets it', async () => {
    const equal = parameterStoryScenario([storyAct('A', [settingEvent('Checks', parameterCondition('GapIs', 'equalTo', '1')), setsGap()])]);
    assert.deepEqual(await verdicts(equal), []);
    // On the declared value the standard holds at once, ScenarioRunner only once the story set it.
    const asDeclared = parameterStoryScenario([
      storyAct('A', [settingEvent('Checks', parameterCondition('GapIs', 'equalTo', '$gap')), setsGap()]),
    ]);
    assert.deepEqual(await verdicts(asDeclared), [[lineOf(asDeclared, 'name="GapIs"'), 'warning', 'parameterNotEqualAsDeclared']]);
    const initSets = parameterStoryScenario(
      [storyAct('A', [settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2')), setsGap()])],
      '<GlobalAction><ParameterAction parameterRef="gap"><SetAction value="3"/></ParameterAction></GlobalAction>',
    );
    assert.deepEqual(await verdicts(initSets), []);
    const text = parameterStoryScenario([
      storyAct('A', [setsGap(), settingEvent('Checks', parameterCondition('DoneTrue', 'equalTo', 'true', 'done'))]),
    ]);
    assert.deepEqual(await verdicts(text), [[lineOf(text, 'name="DoneTrue"'), 'error', 'parameterValueNotNumber']]);
  });

  it('still names a parameter nothing sets as compared as text; equalTo only where the declared value is the one compared with', async () => {
    const text = parameterStoryScenario([
      storyAct('A', [
        settingEvent('Checks', parameterCondition('GapBelow', 'lessThan', '2')),
        settingEvent('Equal', parameterCondition('GapIs', 'equalTo', '3')),
        settingEvent('Other', parameterCondition('GapIsNot', 'equalTo', '4')),
      ]),
    ]);
    assert.deepEqual(await verdicts(text), [
      [lineOf(text, 'name="GapBelow"'), 'error', 'parameterComparedAsText'],
      [lineOf(text, 'name="GapIs"'), 'warning', 'parameterNeverEqual'],
    ]);
  });
});

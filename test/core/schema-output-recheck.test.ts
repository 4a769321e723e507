import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { Problem } from '../../server/src/core/problems';
import { outputSchemaProblems } from '../../server/src/core/flatten';
import { SchemaCheckMemory } from '../../server/src/core/schema/problems';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { temporaryWorkspace } from '../support/workspace';

const simple = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="s" author="t"/>
  <Entities><ScenarioObject name="ego"/></Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S"><Act name="A">
      <ManeuverGroup name="G" maximumExecutionCount="1">
        <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
        <Maneuver name="M"><Event name="E" priority="overwrite"><Action name="Speed">
          <PrivateAction><LongitudinalAction><SpeedAction>
            <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
            <SpeedActionTarget><AbsoluteTargetSpeed parameterAttributes="value" value="3"/></SpeedActionTarget>
          </SpeedAction></LongitudinalAction></PrivateAction>
        </Action>
        <StartTrigger/></Event></Maneuver>
      </ManeuverGroup>
    </Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;

const main = (speeds: string[], dynamics: string) => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="m" author="t"/>
  <Entities><ScenarioObject name="ego"/></Entities>
  <Storyboard>
    <Init><Actions><Private entityRef="ego"><PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="${dynamics}" value="0" dynamicsDimension="time"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="1"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Private></Actions></Init>
    <Story name="Main"><Act name="Act">
${speeds
  .map(
    (speed, index) => `      <ManeuverGroup name="Car${index}" maximumExecutionCount="1">
        <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
        <ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="G">
          <ParameterReference key="AbsoluteTargetSpeed.value" value="${speed}"/>
        </ManeuverGroupReference></ScenarioReference>
      </ManeuverGroup>`,
  )
  .join('\n')}
    </Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;

/** One memory of schema checks for every flattener here, as the checks of one process shared before. */
const schemaChecks = new SchemaCheckMemory();

/** The output's schema problems, with paths relative to the workspace and in a stable order. */
async function outputProblems(store: ScenarioStore, root: string): Promise<string[]> {
  const result = await new Flattener(store, 'asam', { version: 'auto' }, schemaChecks).flatten(diskRef(path.join(root, 'main.xosc')), {
    force: true,
  });
  const describe = (problem: Problem) =>
    `${path.relative(root, problem.source.disk)}:${problem.range.start.line}:${problem.range.start.character}-${problem.range.end.line}:${problem.range.end.character} ${problem.severity} ${problem.code} ${problem.message} ${problem.hint ?? ''} ${JSON.stringify(problem.data ?? {})}`;
  return outputSchemaProblems(result.source, schemaChecks, { version: 'auto' }).map(describe).sort();
}

describe('strict schema check of an output after an edit inside one value', function () {
  this.timeout(60_000);

  it('equals the full check of the same output, edit after edit (and when the text did not change)', async () => {
    const edited = temporaryWorkspace({ 'main.xosc': main(['3', '4', '5'], 'step'), 'simple.xosc': simple });
    const store = new ScenarioStore({ scenarioPath: [], root: edited });
    const ref = diskRef(path.join(edited, 'main.xosc'));
    // Typing in override values (valid, invalid, empty) and in a value of the main file's own.
    const steps: [string[], string][] = [
      [['3', '4', '5'], 'step'],
      [['3', 'x', '5'], 'step'],
      [['3', 'xy', '5'], 'step'],
      [['3', 'xy', ''], 'step'],
      // Unchanged text (a new flattener reads it again).
      [['3', 'xy', ''], 'step'],
      [['31', 'xy', ''], 'step'],
      [['31', 'xy', ''], 'stepp'],
      [['31', '4', ''], 'stepp'],
      [['31', '4', '5'], 'step'],
    ];
    let findings = 0;
    for (const [speeds, dynamics] of steps) {
      const text = main(speeds, dynamics);
      store.setOverlay(ref, text);
      const incremental = await outputProblems(store, edited);
      // A new workspace each time: nothing remembered, the whole output is checked.
      const fresh = temporaryWorkspace({ 'main.xosc': text, 'simple.xosc': simple });
      assert.deepEqual(
        incremental,
        await outputProblems(new ScenarioStore({ scenarioPath: [], root: fresh }), fresh),
        `${speeds.join(',')} ${dynamics}`,
      );
      findings += incremental.length;
    }
    // The outputs do break the schema (no CatalogLocations, invalid values): the comparison is not of empty lists.
    assert.ok(findings > steps.length, `${findings} findings`);
  });
});

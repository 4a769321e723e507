import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { carryShortcut } from '../../server/src/core/flatten/carry';
import { Flattener } from '../../server/src/core/flatten';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { caseStudyDir, libraryDir, repoRoot, requireCorpus } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

/** Flattens with and without planCarry's shortcut: text, problems and plan must be the same. */
async function flattenBothWays(root: string, main: string) {
  const run = async (enabled: boolean) => {
    carryShortcut.enabled = enabled;
    try {
      const result = await new Flattener(new ScenarioStore({ scenarioPath: [], root })).flatten(diskRef(main));
      const carried = result.source.carried;
      return {
        text: result.text,
        problems: result.problems.map(
          (problem) =>
            `${problem.source.disk}:${problem.range.start.line}:${problem.range.start.character}:${problem.code}:${problem.message}`,
        ),
        declarations: carried?.declarations.map((entry) => `${entry.name}=${entry.text}`),
        locations: carried?.locations.map((entry) => `${entry.kind}:${entry.directory}`),
      };
    } finally {
      carryShortcut.enabled = true;
    }
  };
  const shortcut = await run(true);
  assert.deepEqual(shortcut, await run(false), main);
  return shortcut;
}

const simple = (body: string, head = '') => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="s" author="t"/>${head}
  <Entities><ScenarioObject name="ego"/></Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="S"><Act name="A">
${body}
    </Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;

const group = (name: string, speed: string) => `      <ManeuverGroup name="${name}" maximumExecutionCount="1">
        <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
        <Maneuver name="M"><Event name="E" priority="overwrite"><Action name="Speed">
          <PrivateAction><LongitudinalAction><SpeedAction>
            <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
            <SpeedActionTarget><AbsoluteTargetSpeed parameterAttributes="value" value="${speed}"/></SpeedActionTarget>
          </SpeedAction></LongitudinalAction></PrivateAction>
        </Action>
        <StartTrigger/></Event></Maneuver>
      </ManeuverGroup>`;

const main = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" description="m" author="t"/>
  <Entities><ScenarioObject name="ego"/></Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="Main"><Act name="Act">
      <ManeuverGroup name="First" maximumExecutionCount="1">
        <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
        <ScenarioReference scenarioFileName="plain.xosc"><ManeuverGroupReference maneuverGroupName="G"/></ScenarioReference>
      </ManeuverGroup>
      <ManeuverGroup name="Second" maximumExecutionCount="1">
        <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
        <ScenarioReference scenarioFileName="carrying.xosc"><ManeuverGroupReference maneuverGroupName="G"/></ScenarioReference>
      </ManeuverGroup>
    </Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;

describe('planCarry shortcut (nothing reaches outside the copies: no model of the output)', function () {
  this.timeout(120_000);

  it('gives the same output, problems and plan as reading every copy, with and without carried declarations', async () => {
    const root = temporaryWorkspace({
      'main.xosc': main,
      'plain.xosc': simple(group('G', '3')),
      // Uses a root declaration of its source: it is carried.
      'carrying.xosc': simple(
        group('G', '$Speed'),
        '\n  <ParameterDeclarations><ParameterDeclaration name="Speed" parameterType="double" value="7"/></ParameterDeclarations>',
      ),
      'only-plain.xosc': main.replace('carrying.xosc', 'plain.xosc'),
    });
    const both = await flattenBothWays(root, path.join(root, 'main.xosc'));
    assert.deepEqual(both.declarations, ['Speed=<ParameterDeclaration name="Speed" parameterType="double" value="7"/>']);
    assert.deepEqual((await flattenBothWays(root, path.join(root, 'only-plain.xosc'))).declarations, []);
  });

  it('gives the same results on the project fixture and on every main of the corpus', async function () {
    await flattenBothWays(
      path.join(repoRoot, 'test', 'fixtures', 'semantics'),
      path.join(repoRoot, 'test', 'fixtures', 'semantics', 'main.xosc'),
    );
    requireCorpus(this);
    await flattenBothWays(caseStudyDir, path.join(caseStudyDir, 'main.xosc'));
    for (const entry of fs.readdirSync(libraryDir, { withFileTypes: true })) {
      const folder = path.join(libraryDir, entry.name);
      if (entry.isDirectory() && fs.existsSync(path.join(folder, 'main.xosc')))
        await flattenBothWays(folder, path.join(folder, 'main.xosc'));
    }
  });
});

import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { SIMULATOR } from '../../../server/src/core/diagnostics/simulator';
import { esminiBinary, esminiRoads, requireEsmini, runEsmini, tracksOf } from '../../support/esmini';
import { element, fileHeader, runCli, scenarioDocument, vehicleObject } from '../../support/fixtures';
import { temporaryFolder } from '../../support/temporaryDirectory';
import { applyEdits } from '../../support/textEdits';
import { fixContext, semanticProblemsOf } from './support';

const condition = (name: string, edge: string, delay: number, rule: string, value: number) =>
  `<Condition name="${name}" delay="${delay}" conditionEdge="${edge}"><ByValueCondition><SimulationTimeCondition rule="${rule}" value="${value}"/></ByValueCondition></Condition>`;

/**
 * The paper's library's pattern on esmini's straight_500m.xodr (1.0): Car stands in lane -1; an Act started by `act`, one
 * Event in it that sets Car's speed to 10 m/s when `event` holds; the scenario ends at 4 s.
 */
function scenario(act: string, event: string): string {
  const init = `      <Actions>
        <Private entityRef="Car">
          <PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="50" offset="0"/></Position></TeleportAction></PrivateAction>
        </Private>
      </Actions>
`;
  const story = `      <Act name="Behavior">
        <ManeuverGroup maximumExecutionCount="1" name="Group">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Car"/></Actors>
          <Maneuver name="Drive">
            <Event name="SetSpeed" priority="overwrite">
              <Action name="SetSpeed"><PrivateAction><LongitudinalAction><SpeedAction>
                <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
                <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget>
              </SpeedAction></LongitudinalAction></PrivateAction></Action>
              <StartTrigger><ConditionGroup>
                ${event}
              </ConditionGroup></StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger><ConditionGroup>
          ${act}
        </ConditionGroup></StartTrigger>
      </Act>
`;
  const stop = `    <StopTrigger><ConditionGroup>${condition('End', 'none', 0, 'greaterThan', 4)}</ConditionGroup></StopTrigger>\n`;
  return scenarioDocument({
    header: fileHeader({ revMinor: '0' }),
    parameters: '',
    catalogLocations: '',
    roadNetwork: `    <LogicFile filepath="${path.join(esminiRoads, 'straight_500m.xodr')}"/>\n`,
    entities: vehicleObject('Car'),
    storyboard: element('Init', init, 4) + element('Story', story, 4, ' name="MyStory"') + stop,
  });
}

/** The paper's: the Act on a rising edge of SimulationTime = 0 (and a delay), its Event on SimulationTime = 0. */
const PAPER = scenario(condition('ActStarts', 'rising', 1, 'equalTo', 0), condition('EventStarts', 'rising', 0, 'equalTo', 0));

async function esminiFindings(text: string) {
  return (await semanticProblemsOf(text, {}, 'esmini')).filter(
    (problem) => problem.code === 'simulator' && /SimulationTime/.test(problem.message),
  );
}

/** Every fix of every finding applied, one finding at a time (each fix edits the text the next finding is found in). */
async function fixedAll(text: string): Promise<string> {
  for (let round = 0; round < 5; round++) {
    const [problem] = await esminiFindings(text);
    if (!problem) return text;
    const [fix] = (await SIMULATOR.fixes?.(fixContext(problem.data, undefined, text, problem.range))) ?? [];
    assert.ok(fix, problem.message);
    text = applyEdits(text, fix.edits);
  }
  assert.fail('the fixes do not converge');
}

describe('diagnostics: simulator (esmini), a SimulationTimeCondition esmini never fires (the paper library)', () => {
  it("warns at the Act's rising edge and at the Event's equalTo 0, each with the fix that makes esmini start it", async () => {
    const lines = PAPER.split('\n');
    const findings = await esminiFindings(PAPER);
    assert.deepEqual(
      findings.map((problem) => [
        lines[problem.range.start.line].trim().slice(0, 40),
        problem.severity,
        problem.message.split(': ').slice(-2).join(': '),
      ]),
      [
        [
          '<Condition name="EventStarts" delay="0" ',
          'warning',
          "SimulationTime equalTo 0: this Event's Act does not start at time 0, so the Event never starts (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/StoryboardElement.cpp:127-160, 174-204, EnvironmentSimulator/Modules/ScenarioEngine/OSCTypeDefs/OSCCondition.cpp:56-88)",
        ],
        [
          '<Condition name="ActStarts" delay="1" co',
          'warning',
          "SimulationTime equalTo 0 with edge rising already holds when this Act's StartTrigger is first evaluated, at time 0: the Act never starts (EnvironmentSimulator/Modules/ScenarioEngine/OSCTypeDefs/OSCCondition.cpp:205-238, 282-291, EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/StoryboardElement.cpp:127-160, 174-204, EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioEngine.cpp:140-161, EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:5334-5350)",
        ],
      ],
    );
    const titles = await Promise.all(
      findings.map(async (problem) =>
        (await SIMULATOR.fixes?.(fixContext(problem.data, undefined, PAPER, problem.range)))?.map((fix) => fix.title),
      ),
    );
    assert.deepEqual(titles, [
      ['Write rule="greaterThan", conditionEdge="none": esmini starts it when first evaluated'],
      ['Write conditionEdge="none": esmini starts it when first evaluated'],
    ]);
    const fixed = await fixedAll(PAPER);
    assert.match(
      fixed,
      /name="ActStarts" delay="1" conditionEdge="none"><ByValueCondition><SimulationTimeCondition rule="equalTo" value="0"/,
    );
    assert.match(
      fixed,
      /name="EventStarts" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition rule="greaterThan" value="0"/,
    );
    // Not for the standard alone, nor for CARLA, whose ScenarioRunner ignores edges.
    assert.deepEqual(
      (await semanticProblemsOf(PAPER, {})).filter((problem) => /SimulationTime/.test(problem.message)),
      [],
    );
  });

  it('says nothing where esmini fires it: an edge of none, a time it reaches later, an Event of an Act that starts at time 0', async () => {
    for (const text of [
      scenario(condition('ActStarts', 'none', 1, 'equalTo', 0), condition('EventStarts', 'none', 0, 'greaterThan', 0)),
      scenario(condition('ActStarts', 'rising', 0, 'greaterThan', 1), condition('EventStarts', 'rising', 0, 'greaterThan', 2)),
      scenario(condition('ActStarts', 'none', 0, 'greaterOrEqual', 0), condition('EventStarts', 'none', 0, 'equalTo', 0)),
      scenario(condition('ActStarts', 'falling', 0, 'equalTo', 0), condition('EventStarts', 'none', 0, 'greaterThan', 0)),
    ])
      assert.deepEqual(
        (await esminiFindings(text)).map((problem) => problem.message),
        [],
      );
  });

  it('run names them when the file is run in esmini, whatever the simulator setting, with what to write; the fixed scenario runs without a word (issue 27)', async function () {
    requireEsmini(this);
    const folder = temporaryFolder('m2s-simulation-time-run-');
    fs.writeFileSync(path.join(folder, 'paper.xosc'), PAPER);
    fs.writeFileSync(path.join(folder, 'fixed.xosc'), await fixedAll(PAPER));
    const run = (name: string) => runCli(['run', name, '--esmini', esminiBinary], { cwd: folder });
    const paper = run('paper.xosc');
    assert.equal(paper.status, 0, paper.stderr);
    const lines = PAPER.split('\n');
    const edge = lines.findIndex((line) => line.includes('name="ActStarts"')) + 1;
    const zero = lines.findIndex((line) => line.includes('name="EventStarts"')) + 1;
    // Before: only esmini's own 'could be missed', and 'the check with the simulator set to esmini names such conditions'.
    // The Act that never starts is named first: its Event's finding follows from it, wherever the two stand.
    assert.ok(edge > zero, "the fixture writes the Act's StartTrigger after its Event");
    const edgeAt = paper.stderr.search(
      new RegExp(`^paper\\.xosc:${edge}:\\d+: warning: esmini checks a condition's edge only from its second evaluation`, 'm'),
    );
    const zeroAt = paper.stderr.search(
      new RegExp(`^paper\\.xosc:${zero}:\\d+: warning: esmini evaluates an Event's StartTrigger from the step its Act starts`, 'm'),
    );
    assert.ok(edgeAt >= 0 && zeroAt > edgeAt, paper.stderr);
    assert.match(
      paper.stderr,
      /^ {2}hint: write conditionEdge="none" on this Condition: esmini then fires it when it is first evaluated$/m,
    );
    assert.match(paper.stderr, /^ {2}hint: write rule="greaterThan" here, and conditionEdge="none" on its Condition/m);
    assert.match(
      paper.stderr,
      new RegExp(
        `no entity moved: each stood where the Init placed it for the whole run \\(esmini runs it otherwise than written: the run names 2 esmini findings, the first at paper\\.xosc:${edge}\\)`,
      ),
    );
    const fixed = run('fixed.xosc');
    assert.equal(fixed.status, 0, fixed.stderr);
    assert.doesNotMatch(fixed.stderr, /: warning: esmini |no entity moved/);
  });

  it('is what esmini does: the paper pattern never moves the car, the fixed scenario drives it from 1 s at 10 m/s', async function () {
    requireEsmini(this);
    const folder = temporaryFolder('m2s-simulation-time-start-');
    try {
      const xAt = async (name: string, text: string, time: number): Promise<number> => {
        const file = path.join(folder, name);
        fs.writeFileSync(file, text);
        const track = tracksOf(await runEsmini(file, 4)).get('Car') ?? [];
        const step = track.find((each) => Math.abs(each.time - time) < 1e-6);
        assert.ok(step, `${name}: no step at ${time} s`);
        return step.x;
      };
      assert.equal((await xAt('paper.xosc', PAPER, 3)) - (await xAt('paper.xosc', PAPER, 0)), 0);
      const fixed = await fixedAll(PAPER);
      // The Act starts at 1 s (its delay), the Event at its first evaluation then: 2 s at 10 m/s by 3 s.
      const driven = (await xAt('fixed.xosc', fixed, 3)) - (await xAt('fixed.xosc', fixed, 0));
      assert.ok(Math.abs(driven - 20) < 0.6, `driven ${driven} m`);
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});

import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { fileHeader, openScenarioFile, runCli } from '../support/fixtures';
import { listFiles, temporaryWorkspace } from '../support/workspace';

const SCENARIO = openScenarioFile(
  `  <Entities><ScenarioObject name="Box"><MiscObject name="box" mass="1" miscObjectCategory="obstacle"><BoundingBox><Center x="0" y="0" z="0.5"/><Dimensions width="1" length="1" height="1"/></BoundingBox><Properties/></MiscObject></ScenarioObject></Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="s"><Act name="a"><ManeuverGroup name="g" maximumExecutionCount="1">
      <Actors selectTriggeringEntities="false"><EntityRef entityRef="Box"/></Actors>
      <Maneuver name="m"><Event name="e" priority="overwrite"><Action name="x">
        <PrivateAction><VisibilityAction graphics="false" traffic="true" sensors="true"/></PrivateAction>
      </Action>
      <StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
        <TimeOfDayCondition dateTime="2026-01-01T08:00:00" rule="greaterThan"/>
      </ByValueCondition></Condition></ConditionGroup></StartTrigger>
      </Event></Maneuver>
    </ManeuverGroup></Act></Story>
  </Storyboard>
`,
  fileHeader({ description: 'simulator' }),
);

describe('cli: --simulator', () => {
  it('check reports what the chosen simulator refuses as errors at the source line (exit 1), what it runs otherwise as warnings', () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO });
    const file = path.join(root, 'scenario.xosc');
    const carla = runCli(['check', '--simulator', 'carla', file]);
    assert.equal(carla.status, 1, carla.stderr);
    assert.match(
      carla.stderr,
      /scenario\.xosc:3:\d+: error: CARLA ScenarioRunner accepts only OpenSCENARIO 1\.0; this file states 1\.2 \(srunner\/scenarioconfigs\/openscenario_configuration\.py:105\)/,
    );
    assert.match(carla.stderr, /scenario\.xosc:10:\d+: error: CARLA ScenarioRunner does not support VisibilityAction in a Story/);
    assert.match(carla.stderr, /scenario\.xosc:2:1: error: CARLA ScenarioRunner takes the CARLA town from RoadNetwork\/LogicFile/);
    const esmini = runCli(['check', '--simulator', 'esmini', file]);
    assert.match(esmini.stderr, /scenario\.xosc:13:\d+: warning: esmini does not support TimeOfDayCondition/);
    assert.doesNotMatch(esmini.stderr, /VisibilityAction/);
    const asam = runCli(['check', file]);
    assert.match(asam.stderr, /0 warnings/);
    const json = JSON.parse(runCli(['check', '--simulator', 'carla', '--format', 'json', file]).stdout) as { problems: { code: string }[] };
    assert.ok(json.problems.length >= 2 && json.problems.every((problem) => problem.code === 'simulator'));
  });

  it('flatten refuses what the simulator refuses, writes it with --force, and writes past warnings', () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO });
    const refused = runCli(['flatten', '--simulator', 'carla', 'scenario.xosc', '-o', 'out.xosc'], { cwd: root });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(refused.stderr, /error: CARLA ScenarioRunner accepts only OpenSCENARIO 1\.0/);
    assert.deepEqual(listFiles(root), ['scenario.xosc']);
    const forced = runCli(['flatten', '--simulator', 'carla', '--force', 'scenario.xosc', '-o', 'out.xosc'], { cwd: root });
    assert.equal(forced.status, 0, forced.stderr);
    assert.deepEqual(listFiles(root), ['out.xosc', 'scenario.xosc']);
    const esmini = runCli(['flatten', '--simulator', 'esmini', 'scenario.xosc', '-o', 'esmini.xosc'], { cwd: root });
    assert.equal(esmini.status, 0, esmini.stderr);
    assert.match(esmini.stderr, /warning: esmini does not support TimeOfDayCondition/);
  });

  it('--carla picks the ScenarioRunner release: a route action is the 0.9.16 crash, and builds under 0.9.15', () => {
    const route = SCENARIO.replace('revMinor="2"', 'revMinor="0"').replace(
      '<VisibilityAction graphics="false" traffic="true" sensors="true"/>',
      '<RoutingAction><AcquirePositionAction><Position><WorldPosition x="1" y="2"/></Position></AcquirePositionAction></RoutingAction>',
    );
    const root = temporaryWorkspace({ 'scenario.xosc': route });
    const latest = runCli(['check', '--simulator', 'carla', 'scenario.xosc'], { cwd: root });
    assert.match(latest.stderr, /error: CARLA ScenarioRunner does not support AcquirePositionAction: .*ab5996d7/);
    const older = runCli(['check', '--simulator', 'carla', '--carla', '0.9.15', 'scenario.xosc'], { cwd: root });
    assert.doesNotMatch(older.stderr, /AcquirePositionAction/);
    const bad = runCli(['check', '--simulator', 'carla', '--carla', '0.9.14', 'scenario.xosc'], { cwd: root });
    assert.equal(bad.status, 2);
    assert.match(bad.stderr, /--carla takes 0\.9\.15, 0\.9\.16, not '0\.9\.14'/);
  });

  it('rejects an unknown simulator with exit code 2', () => {
    const run = runCli(['check', '--simulator', 'prescan', 'x.xosc']);
    assert.equal(run.status, 2);
    assert.match(run.stderr, /--simulator takes asam, carla, esmini/);
  });
});

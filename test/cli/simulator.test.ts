import * as assert from 'node:assert/strict';
import * as path from 'node:path';
import { runCli } from '../support/fixtures';
import { listFiles, temporaryWorkspace } from '../support/workspace';

const SCENARIO = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="simulator" author="test"/>
  <Entities/>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="s"><Act name="a"><ManeuverGroup name="g" maximumExecutionCount="1">
      <Actors selectTriggeringEntities="true"/>
      <Maneuver name="m"><Event name="e" priority="overwrite"><Action name="x">
        <PrivateAction><VisibilityAction graphics="false" traffic="true" sensors="true"/></PrivateAction>
      </Action>
      <StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
        <TimeOfDayCondition dateTime="2026-01-01T08:00:00" rule="greaterThan"/>
      </ByValueCondition></Condition></ConditionGroup></StartTrigger>
      </Event></Maneuver>
    </ManeuverGroup></Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;

describe('cli: --simulator', () => {
  it('check warns about what the chosen simulator does not run, at the source line, and still exits 0', () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO });
    const file = path.join(root, 'scenario.xosc');
    const carla = runCli(['check', '--simulator', 'carla', file]);
    assert.equal(carla.status, 0, carla.stderr);
    assert.match(carla.stderr, /scenario\.xosc:3:\d+: warning: CARLA ScenarioRunner accepts only OpenSCENARIO 1\.0; this file states 1\.2/);
    assert.match(carla.stderr, /scenario\.xosc:10:\d+: warning: CARLA ScenarioRunner does not support VisibilityAction/);
    const esmini = runCli(['check', '--simulator', 'esmini', file]);
    assert.match(esmini.stderr, /scenario\.xosc:13:\d+: warning: esmini does not support TimeOfDayCondition/);
    assert.doesNotMatch(esmini.stderr, /VisibilityAction/);
    const asam = runCli(['check', file]);
    assert.match(asam.stderr, /0 warnings/);
    const json = JSON.parse(runCli(['check', '--simulator', 'carla', '--format', 'json', file]).stdout) as { problems: { code: string }[] };
    assert.ok(json.problems.length >= 2 && json.problems.every((problem) => problem.code === 'simulator'));
  });

  it('flatten prints the warnings and still writes its output', () => {
    const root = temporaryWorkspace({ 'scenario.xosc': SCENARIO });
    const run = runCli(['flatten', '--simulator', 'carla', 'scenario.xosc', '-o', 'out.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /warning: CARLA ScenarioRunner/);
    assert.deepEqual(listFiles(root), ['out.xosc', 'scenario.xosc']);
  });

  it('rejects an unknown simulator with exit code 2', () => {
    const run = runCli(['check', '--simulator', 'prescan', 'x.xosc']);
    assert.equal(run.status, 2);
    assert.match(run.stderr, /--simulator takes asam, carla, esmini/);
  });
});

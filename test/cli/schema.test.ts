import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { runCli } from '../support/fixtures';
import { temporaryWorkspace } from '../support/workspace';

const SCENARIO = (minor: string, group: string, root = '') => `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="${minor}" date="2024-01-01T00:00:00" description="d" author="a"/>
${root}  <CatalogLocations/>
  <RoadNetwork/>
  <Entities><ScenarioObject name="ego"><CatalogReference catalogName="C" entryName="car"/></ScenarioObject></Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <Story name="s"><Act name="a">
${group}      <StartTrigger/></Act></Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;

// The group names its actor (flattening sets that EntityRef to the main's; a group without one has none, which esmini refuses).
const SIMPLE = SCENARIO(
  '0',
  `        <ManeuverGroup maximumExecutionCount="1" name="G"><Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors><Maneuver name="M"><Event name="E" priority="overwrite"><Action name="A"><PrivateAction><TeleportAction><Position><WorldPosition parameterAttributes="x" x="1" y="2"/></Position></TeleportAction></PrivateAction></Action><StartTrigger/></Event></Maneuver></ManeuverGroup>\n`,
);

const GROUP = '        <ManeuverGroup maximumExecutionCount="1" name="g"><Actors selectTriggeringEntities="false"/></ManeuverGroup>\n';

const main = (value: string) =>
  SCENARIO(
    '0',
    `        <ManeuverGroup maximumExecutionCount="1" name="Outer"><Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>\n          <ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="G"><ParameterReference key="x" value="${value}"/></ManeuverGroupReference></ScenarioReference>\n        </ManeuverGroup>\n`,
  );

describe('cli: OpenSCENARIO schema validation', () => {
  it('check reports schema problems of plain files against their own version, as the editor does', () => {
    const root = temporaryWorkspace({
      'old.xosc': SCENARIO('0', GROUP, '  <VariableDeclarations/>\n'),
      'new.xosc': SCENARIO('2', GROUP, '  <VariableDeclarations/>\n'),
    });
    const run = runCli(['check', root], { cwd: root, schema: true });
    assert.equal(run.status, 1, run.stderr);
    const lines = (run.stdout + run.stderr).split('\n').filter((line) => /: (error|warning):/.test(line));
    assert.deepEqual(lines, ['old.xosc:4:4: error: <OpenSCENARIO> has no child <VariableDeclarations> in OpenSCENARIO 1.0']);
    const pinned = runCli(['check', root, '--schema-version', '1.2'], { cwd: root, schema: true });
    assert.equal(pinned.status, 0, pinned.stdout + pinned.stderr);
    const off = runCli(['check', root, '--schema-version=off'], { cwd: root, schema: true });
    assert.equal(off.status, 0);
    const bad = runCli(['check', root, '--schema-version=2.0'], { cwd: root, schema: true });
    assert.equal(bad.status, 2);
    assert.match(bad.stderr, /--schema-version takes auto, off, 1\.0, 1\.1, 1\.2, 1\.3/);
  });

  it('flatten refuses an output that is not valid OpenSCENARIO, naming the source position, unless --force', () => {
    const root = temporaryWorkspace({ 'main.xosc': main('far'), 'simple.xosc': SIMPLE });
    const out = path.join(root, 'out.xosc');
    const refused = runCli(['flatten', 'main.xosc', '-o', out], { cwd: root, schema: true });
    assert.equal(refused.status, 1);
    assert.match(refused.stdout + refused.stderr, /main\.xosc:11:\d+: error: 'far' is not a valid value of WorldPosition\.x \(Double\)/);
    assert.ok(!fs.existsSync(out));
    const forced = runCli(['flatten', 'main.xosc', '-o', out, '--force'], { cwd: root, schema: true });
    assert.equal(forced.status, 0, forced.stderr);
    assert.match(fs.readFileSync(out, 'utf8'), /<WorldPosition x="far" y="2"\/>/);
    const fine = temporaryWorkspace({ 'main.xosc': main('-3'), 'simple.xosc': SIMPLE });
    const written = runCli(['flatten', 'main.xosc', '-o', path.join(fine, 'out.xosc')], { cwd: fine, schema: true });
    assert.equal(written.status, 0, written.stdout + written.stderr);
  });
});

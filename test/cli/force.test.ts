import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, esminiCatalogs, esminiRoads, requireEsmini } from '../support/esmini';
import { runCli, scenario, simpleGroup } from '../support/fixtures';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { listFiles, temporaryWorkspace } from '../support/workspace';
import { temporaryFolder } from '../support/temporaryDirectory';

const esminiScenarios = path.join(openscenarioDir, 'esmini');
/** The temporary folders made, removed after the suite. */
const made: string[] = [];

/** A group of the composition: the outer group's name and actor, and the group it imports from an esmini scenario. */
interface Imported {
  name: string;
  actor: string;
  file: string;
  group: string;
}

const GROUPS: Imported[] = [
  { name: 'CutIn', actor: 'OverTaker', file: 'cut-in.xosc', group: 'CutInAndBrakeSequence' },
  { name: 'Lights', actor: 'Ego', file: 'traffic_lights.xosc', group: 'StopLightsManueverGroup' },
  { name: 'Environment', actor: 'OverTaker', file: 'cut-in_environment.xosc', group: 'CutInAndBrakeSequence' },
  { name: 'Alks', actor: 'OverTaker', file: 'alks_r157_cut_in_quick_brake.xosc', group: 'CutInAndBrakeSequence' },
];

function outerGroup({ name, actor, file, group }: Imported): string {
  return `            <ManeuverGroup maximumExecutionCount="1" name="${name}">
               <Actors selectTriggeringEntities="false">
                  <EntityRef entityRef="${actor}"/>
               </Actors>
               <ScenarioReference scenarioFileName="${file}">
                  <ManeuverGroupReference maneuverGroupName="${group}"/>
               </ScenarioReference>
            </ManeuverGroup>
`;
}

/**
 * esmini's own layout (xosc/ with its Catalogs beside xodr/) holding a copy of the esmini scenarios and a
 * main.xosc made from cut-in.xosc whose story imports `groups`. The main declares a double parameter
 * whose value is no number, an error by any policy, so that only a forced flatten or run goes through;
 * the ALKS copy declares a parameter in the 0.9 style (`name="$TargetBrakeDistance"`) and uses it.
 */
function composition(groups: Imported[]): string {
  const root = temporaryFolder('m2s-force-');
  made.push(root);
  const scenarios = path.join(root, 'xosc');
  fs.cpSync(esminiCatalogs, path.join(scenarios, 'Catalogs'), { recursive: true });
  for (const { file } of GROUPS) fs.copyFileSync(path.join(esminiScenarios, file), path.join(scenarios, file));
  const alks = path.join(scenarios, 'alks_r157_cut_in_quick_brake.xosc');
  const alksText = fs.readFileSync(alks, 'utf8');
  const brakeTime = alksText.match(/<ParameterDeclaration name="TargetBrakeTime"[^>]*\/>/)?.[0];
  assert.ok(brakeTime && alksText.includes('$TargetBrakeTime'), 'the ALKS scenario declares and uses TargetBrakeTime');
  fs.writeFileSync(
    alks,
    alksText
      .replace(brakeTime, `${brakeTime}\n        <ParameterDeclaration name="$TargetBrakeDistance" parameterType="double" value="12"/>`)
      .replace('$TargetBrakeTime', '${$TargetBrakeTime + $TargetBrakeDistance - 12}'),
  );
  const cutIn = fs.readFileSync(path.join(esminiScenarios, 'cut-in.xosc'), 'utf8');
  const story = `<Story name="CutInAndBrakeStory">
         <Act name="CutInAndBrakeAct">
${groups.map(outerGroup).join('')}            <StartTrigger>
               <ConditionGroup>
                  <Condition name="Start" delay="0" conditionEdge="rising">
                     <ByValueCondition>
                        <SimulationTimeCondition value="0" rule="greaterThan"/>
                     </ByValueCondition>
                  </Condition>
               </ConditionGroup>
            </StartTrigger>
         </Act>
      </Story>
      <StopTrigger/>
   `;
  const main = cutIn
    .slice(0, cutIn.indexOf('<Story name='))
    .replace(
      '<ParameterDeclarations>',
      '<ParameterDeclarations>\n      <ParameterDeclaration name="Pace" parameterType="double" value="fast"/>',
    )
    .concat(story, cutIn.slice(cutIn.indexOf('</Storyboard>')));
  fs.writeFileSync(path.join(scenarios, 'main.xosc'), main);
  return scenarios;
}

describe('cli: --force writes and runs whatever can be produced, listing what was wrong', function () {
  this.timeout(120_000);

  before(function () {
    if (!fs.existsSync(esminiScenarios) || !fs.existsSync(esminiCatalogs)) {
      console.log(`    (skipped: ${esminiScenarios} or ${esminiCatalogs} is absent)`);
      this.skip();
    }
  });

  after(() => {
    for (const root of made.splice(0)) fs.rmSync(root, { recursive: true, force: true });
  });

  it("flatten --force writes a composition of groups of esmini's cut-in, traffic_lights, cut-in_environment and alks_r157 scenarios", () => {
    const folder = composition(GROUPS);
    const before = listFiles(folder);
    const refused = runCli(['flatten', 'main.xosc', '-o', 'out.xosc'], { cwd: folder, schema: true });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(refused.stderr, /main\.xosc:\d+:\d+: error: 'fast' is not a double/);
    assert.match(refused.stderr, /errors?; nothing was written \(--force writes it anyway/);
    assert.deepEqual(listFiles(folder), before);

    const forced = runCli(['flatten', 'main.xosc', '-o', 'out.xosc', '--force'], { cwd: folder, schema: true });
    assert.equal(forced.status, 0, forced.stderr);
    assert.match(forced.stderr, /main\.xosc:\d+:\d+: error: 'fast' is not a double/, 'the errors are listed');
    assert.match(forced.stderr, /\d+ errors?; written anyway \(--force\)/);
    assert.match(forced.stderr, /wrote out\.xosc/);
    const output = fs.readFileSync(path.join(folder, 'out.xosc'), 'utf8');
    // Every imported group is in the output under its outer group's name, with what it uses carried along.
    for (const { name, group } of GROUPS) assert.match(output, new RegExp(`<ManeuverGroup [^>]*name="${name}\\.${group}"`), name);
    assert.doesNotMatch(output, /ScenarioReference|parameterAttributes/);
    assert.match(output, /\$\{\$TargetBrakeTime \+ \$TargetBrakeDistance - 12\}/);
    assert.match(output, /name="RedLightDistance"/);
  });

  it('flatten --force still writes nothing when the output cannot be produced (a group that does not exist)', () => {
    const folder = composition([{ ...GROUPS[0], group: 'NoSuchGroup' }]);
    const run = runCli(['flatten', 'main.xosc', '-o', 'out.xosc', '--force'], { cwd: folder });
    assert.equal(run.status, 1);
    assert.match(run.stderr, /has no ManeuverGroup named 'NoSuchGroup'/);
    assert.match(run.stderr, /nothing was written$/m);
    assert.ok(!fs.existsSync(path.join(folder, 'out.xosc')));
  });

  it('flatten --force onto its own input, or into a folder that does not exist, says only that it wrote nothing (it said "written anyway" first)', () => {
    // Errors --force writes past: the fixture's group is no schema-valid OpenSCENARIO 1.0.
    const text = scenario(simpleGroup('Go'));
    const folder = temporaryWorkspace({ 'a.xosc': text });
    for (const [output, status, said] of [
      ['a.xosc', 1, /refusing to write a\.xosc: it is an input/],
      ['missing/out.xosc', 3, /cannot write the output \(the folder .*missing does not exist\); nothing was changed/],
    ] as const) {
      const run = runCli(['flatten', 'a.xosc', '--force', '-o', output], { cwd: folder, schema: true });
      assert.equal(run.status, status, run.stderr);
      assert.match(run.stderr, /a\.xosc:\d+:\d+: error: /);
      assert.match(run.stderr, said);
      assert.doesNotMatch(run.stderr, /written anyway/);
      assert.deepEqual(listFiles(folder), ['a.xosc']);
      assert.equal(fs.readFileSync(path.join(folder, 'a.xosc'), 'utf8'), text);
    }
    const written = runCli(['flatten', 'a.xosc', '--force', '-o', 'out.xosc'], { cwd: folder, schema: true });
    assert.equal(written.status, 0, written.stderr);
    assert.match(written.stderr, /wrote out\.xosc \(\d+ lines\)\n\d+ errors?; written anyway \(--force\)/);
  });

  it('run refuses a composition with errors, saying --force runs it; run --force runs it in esmini', function () {
    requireEsmini(this);
    const folder = composition(GROUPS.slice(0, 1));
    const args = ['run', 'main.xosc', '--duration', '3', '--road-path', esminiRoads, '--esmini', esminiBinary];
    const refused = runCli(args, { cwd: folder });
    assert.equal(refused.status, 1, refused.stderr);
    assert.match(refused.stderr, /main\.xosc:\d+:\d+: error: 'fast' is not a double/);
    assert.match(refused.stderr, /main\.xosc: the scenario has \d+ errors?; nothing was run \(--force runs it anyway\)/);
    const csv = path.join(folder, 'run.csv');
    const forced = runCli([...args, '--force', '--csv', csv], { cwd: folder });
    assert.equal(forced.status, 0, forced.stderr);
    assert.match(forced.stderr, /main\.xosc:\d+:\d+: error: 'fast' is not a double/, 'the errors are listed');
    assert.match(
      forced.stderr,
      /main\.xosc: esmini: \d+ errors?, \d+ warnings?; 3\.00 s simulated: stopped at the 3 s limit set by --duration, before the scenario ended by itself.*\(run anyway despite \d+ errors? in the scenario\)/,
    );
    const rows = fs.readFileSync(csv, 'utf8').trim().split('\n').slice(7);
    assert.equal(Number(rows[rows.length - 1].split(',')[1]), 3);
  });
});

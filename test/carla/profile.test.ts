import { strict as assert } from 'node:assert';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { harnessVerdicts, HarnessVerdict, requireCarlaHarness, scenarioRunnerVehicle } from '../support/carla';
import { afterASecond, atOnce, parameterCondition, parameterStoryScenario, settingEvent, storyAct } from '../support/carlaStories';
import { esminiCatalogs, esminiRoads } from '../support/esmini';
import { runCli } from '../support/fixtures';
import { openscenarioDir } from '../support/openscenarioCorpus';
import { libraryDir, requireCorpus } from '../support/paths';

/*
 * check --simulator carla against ScenarioRunner's own loader (../shared/carla/check.py): every file the
 * harness refuses gets a CARLA error, and no file it builds gets an error at all.
 */

interface CheckedProblem {
  file: string;
  severity: string;
  code: string;
  message: string;
}

/** `check --simulator carla --format json` over the files, in one run; the problems by file. */
function checkForCarla(files: string[], release: '0.9.15' | '0.9.16'): Map<string, CheckedProblem[]> {
  const run = runCli(['check', '--simulator', 'carla', '--carla', release, '--format', 'json', ...files]);
  assert.ok(run.status === 0 || run.status === 1, `check exited ${run.status}: ${run.stderr.slice(-2000)}`);
  const problems = (JSON.parse(run.stdout) as { problems: CheckedProblem[] }).problems;
  const byFile = new Map<string, CheckedProblem[]>();
  for (const problem of problems) byFile.set(path.resolve(problem.file), [...(byFile.get(path.resolve(problem.file)) ?? []), problem]);
  return byFile;
}

/** The disagreements of the profile with the harness: a refused file without a CARLA error, a built file with any error. */
function disagreements(verdicts: Map<string, HarnessVerdict>, checked: Map<string, CheckedProblem[]>): string[] {
  const found: string[] = [];
  for (const [file, verdict] of verdicts) {
    const errors = (checked.get(file) ?? []).filter((problem) => problem.severity === 'error');
    if (verdict.status === 'OK' && errors.length > 0)
      found.push(`${file}: ScenarioRunner builds it, yet ${errors.map((problem) => problem.message).join(' | ')}`);
    if (verdict.status === 'FAIL' && !errors.some((problem) => problem.code === 'simulator'))
      found.push(`${file}: ScenarioRunner refuses it (${verdict.stage}: ${verdict.reason}), yet no CARLA error`);
  }
  return found;
}

function scenarioFiles(folder: string): string[] {
  return fs
    .readdirSync(folder)
    .filter((name) => name.endsWith('.xosc') && !/Catalog\.xosc$/.test(name))
    .map((name) => path.join(folder, name));
}

describe('check --simulator carla agrees with ScenarioRunner', function () {
  this.timeout(600_000);
  let workspace: string;
  let esminiFiles: string[];
  const runnerFiles = () => scenarioFiles(path.join(openscenarioDir, 'scenario_runner'));
  const libraryResults = () =>
    fs
      .readdirSync(libraryDir)
      .filter((name) => name.startsWith('modular_'))
      .map((name) => path.join(libraryDir, name, 'result.xosc'));

  before(function () {
    requireCorpus(this);
    requireCarlaHarness(this);
    // esmini's samples as esmini lays them out (xosc/ with its Catalogs beside xodr/), so their roads and catalogs resolve.
    workspace = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-carla-profile-'));
    const xosc = path.join(workspace, 'xosc');
    fs.mkdirSync(xosc);
    fs.cpSync(esminiCatalogs, path.join(xosc, 'Catalogs'), { recursive: true });
    fs.symlinkSync(esminiRoads, path.join(workspace, 'xodr'));
    esminiFiles = scenarioFiles(path.join(openscenarioDir, 'esmini')).map((file) => {
      const copy = path.join(xosc, path.basename(file));
      fs.copyFileSync(file, copy);
      return copy;
    });
  });

  after(() => {
    if (workspace) fs.rmSync(workspace, { recursive: true, force: true });
  });

  it('0.9.16: esmini samples, ScenarioRunner examples, the paper library: refused ones get an error, built ones none', async () => {
    const files = [...esminiFiles, ...runnerFiles(), ...libraryResults()];
    const verdicts = new Map([...(await harnessVerdicts(files))].filter(([, verdict]) => verdict.status !== 'SKIP'));
    assert.ok(verdicts.size >= 100, `the harness judged ${verdicts.size} files`);
    const built = [...verdicts.values()].filter((verdict) => verdict.status === 'OK').length;
    assert.ok(built >= 10 && built < verdicts.size, `${built} of ${verdicts.size} built: both kinds are checked`);
    assert.deepEqual(disagreements(verdicts, checkForCarla([...verdicts.keys()], '0.9.16')), []);
  });

  it('0.9.15 (the harness with --fix-sr-bugs): the route actions build, and the profile reports no error on them', async () => {
    const files = [...runnerFiles(), ...libraryResults()];
    const verdicts = new Map([...(await harnessVerdicts(files, { fixSrBugs: true }))].filter(([, verdict]) => verdict.status !== 'SKIP'));
    assert.ok([...verdicts.values()].filter((verdict) => verdict.status === 'OK').length >= 40);
    assert.deepEqual(disagreements(verdicts, checkForCarla([...verdicts.keys()], '0.9.15')), []);
  });
});

describe("check --simulator carla agrees with ScenarioRunner's loader and its ticks on small scenarios", function () {
  this.timeout(120_000);
  let folder: string;
  before(function () {
    requireCarlaHarness(this);
    folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-carla-parameters-'));
  });
  after(() => {
    if (folder) fs.rmSync(folder, { recursive: true, force: true });
  });

  const condition = (name: string, parameter: string, rule: string, value: string): string =>
    `<Condition name="${name}" delay="0" conditionEdge="none"><ByValueCondition><ParameterCondition parameterRef="${parameter}" value="${value}" rule="${rule}"/></ByValueCondition></Condition>`;
  /** A 1.0 scenario on Town01 whose one event sets 'set' and starts on the conditions given, each in a group of its own. */
  const scenario = (conditions: string[]): string => `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-11-29T00:00:00" description="parameters compared" author="modular2simple tests"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="braking" parameterType="boolean" value="true"/>
    <ParameterDeclaration name="gap" parameterType="double" value="3"/>
    <ParameterDeclaration name="set" parameterType="double" value="0"/>
  </ParameterDeclarations>
  <CatalogLocations/>
  <RoadNetwork><LogicFile filepath="Town01"/></RoadNetwork>
  <Entities>
${scenarioRunnerVehicle('Ego', 'ego_vehicle')}
  </Entities>
  <Storyboard>
    <Init><Actions>
      <GlobalAction><ParameterAction parameterRef="set"><SetAction value="1"/></ParameterAction></GlobalAction>
      <Private entityRef="Ego"><PrivateAction><TeleportAction><Position><WorldPosition x="100" y="-2" z="0" h="0"/></Position></TeleportAction></PrivateAction></Private>
    </Actions></Init>
    <Story name="Compared">
      <Act name="Compared">
        <ManeuverGroup maximumExecutionCount="1" name="Group">
          <Actors selectTriggeringEntities="false"/>
          <Maneuver name="Compared">
            <Event name="Compared" priority="parallel">
              <Action name="Sets"><GlobalAction><ParameterAction parameterRef="set"><SetAction value="2"/></ParameterAction></GlobalAction></Action>
              <StartTrigger>${conditions.map((each) => `<ConditionGroup>${each}</ConditionGroup>`).join('')}</StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger><ConditionGroup><Condition name="ActStarts" delay="0" conditionEdge="none">
          <ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition>
        </Condition></ConditionGroup></StartTrigger>
      </Act>
    </Story>
    <StopTrigger><ConditionGroup>
      ${condition('criteria_RunningStopTest', '', 'lessThan', '')}
      ${condition('NeverTicked', 'gap', 'greaterThan', '2')}
    </ConditionGroup></StopTrigger>
  </Storyboard>
</OpenSCENARIO>
`;

  it("a negative start speed is an error at its value, as ScenarioRunner's loader refuses it; a positive one is nothing (issue 26)", async () => {
    const speed = (value: string): string =>
      `<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="${value}"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>`;
    const withSpeed = (value: string): string =>
      scenario([condition('GapIs', 'set', 'equalTo', '2')])
        .replace('</TeleportAction></PrivateAction>', `</TeleportAction></PrivateAction>${speed(value)}`)
        .replace(
          '<ParameterDeclarations>',
          '<ParameterDeclarations><ParameterDeclaration name="backwards" parameterType="double" value="-1.5"/>',
        );
    const files = { backwards: path.join(folder, 'backwards.xosc'), forwards: path.join(folder, 'forwards.xosc') };
    fs.writeFileSync(files.backwards, withSpeed('$backwards'));
    fs.writeFileSync(files.forwards, withSpeed('2'));
    const checked = checkForCarla(Object.values(files), '0.9.16');
    const speedErrors = (file: string) =>
      (checked.get(path.resolve(file)) ?? [])
        .filter((problem) => /must be positive/.test(problem.message))
        .map((problem) => [problem.severity, (problem as CheckedProblem & { line: number }).line, problem.message.split(': ').pop()]);
    const line =
      withSpeed('$backwards')
        .split('\n')
        .findIndex((each) => each.includes('value="$backwards"')) + 1;
    assert.deepEqual(speedErrors(files.backwards), [
      [
        'error',
        line,
        'the start speed -1.5 of Ego is negative (srunner/scenarioconfigs/openscenario_configuration.py:396-406 (_get_actor_speed))',
      ],
    ]);
    assert.deepEqual(speedErrors(files.forwards), []);
    const verdicts = await harnessVerdicts(Object.values(files));
    assert.equal(verdicts.get(path.resolve(files.backwards))?.status, 'FAIL');
    assert.match(verdicts.get(path.resolve(files.backwards))?.reason ?? '', /must be positive/);
    assert.equal(verdicts.get(path.resolve(files.forwards))?.status, 'OK');
  });

  it('an error where a tick raises, a warning where it never holds, nothing on a parameter the Init sets, a criterion or the Storyboard StopTrigger (issue 26)', async () => {
    const compared: [string, string, string, string][] = [
      ['BrakingIsTrue', 'braking', 'equalTo', 'true'],
      ['GapAbove', 'gap', 'greaterThan', '2'],
      ['GapIs', 'gap', 'equalTo', '3'],
      ['SetBelow', 'set', 'lessThan', '5'],
    ];
    const file = path.join(folder, 'compared.xosc');
    const text = scenario(compared.map(([name, parameter, rule, value]) => condition(name, parameter, rule, value)));
    fs.writeFileSync(file, text);
    const run = runCli(['check', '--simulator', 'carla', '--format', 'json', file]);
    const problems = (JSON.parse(run.stdout) as { problems: (CheckedProblem & { line: number })[] }).problems;
    const findings = problems
      .filter((problem) => /compares a parameter that no ParameterAction sets/.test(problem.message))
      .map((problem) => [problem.line, problem.severity]);
    const lineOf = (name: string): number => text.split('\n').findIndex((line) => line.includes(`name="${name}"`)) + 1;
    assert.deepEqual(findings, [
      [lineOf('BrakingIsTrue'), 'error'],
      [lineOf('GapAbove'), 'error'],
      [lineOf('GapIs'), 'warning'],
    ]);
    assert.deepEqual(
      problems.filter((problem) => problem.severity === 'error' && !/compares a parameter/.test(problem.message)),
      [],
    );
    // ScenarioRunner builds it; its own CheckParameters, ticked, raise exactly where check says error.
    const verdict = (await harnessVerdicts([file], { tree: true })).get(path.resolve(file));
    assert.equal(verdict?.status, 'OK', JSON.stringify(verdict));
    const ticks = new Map((verdict?.parameter_ticks ?? []).map(([name, first, then]) => [name, [first, then]]));
    assert.match(ticks.get('BrakingIsTrue')?.[0] ?? '', /^raises ValueError/);
    assert.match(ticks.get('GapAbove')?.[0] ?? '', /^raises TypeError/);
    assert.deepEqual(ticks.get('GapIs'), ['RUNNING', 'RUNNING']);
    assert.deepEqual(ticks.get('SetBelow'), ['SUCCESS', 'SUCCESS']);
  });
});

describe("check --simulator carla on a parameter only a story sets agrees with ScenarioRunner's ticks (issue 26)", function () {
  this.timeout(120_000);
  let folder: string;
  before(function () {
    requireCarlaHarness(this);
    folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-carla-story-parameters-'));
  });
  after(() => {
    if (folder) fs.rmSync(folder, { recursive: true, force: true });
  });

  it('an error where the stories, ticked, always raise at the condition; a warning where that depends on when the action runs', async () => {
    const gapBelow = parameterCondition('GapBelow', 'lessThan', '2');
    const checks = settingEvent('Checks', gapBelow);
    const setsLater = settingEvent('Sets', afterASecond('SetsStarts'), 'gap');
    const setsAtOnce = settingEvent('Sets', atOnce('SetsStarts'), 'gap');
    const files: Record<string, { acts: string[]; check: string; raises: boolean }> = {
      // esmini's lane_change.xosc: the condition starts an event ahead of the one that sets the parameter.
      earlierEvent: { acts: [storyAct('A', [checks, setsAtOnce])], check: 'error', raises: true },
      sameEvent: { acts: [storyAct('A', [settingEvent('Sets', gapBelow, 'gap')])], check: 'error', raises: true },
      startsItsAct: { acts: [storyAct('A', [setsAtOnce], gapBelow)], check: 'error', raises: true },
      startsEarlierAct: {
        acts: [storyAct('A', [settingEvent('Other', atOnce('X'))], gapBelow), storyAct('B', [setsAtOnce])],
        check: 'error',
        raises: true,
      },
      // Ahead of the condition: it depends on when the action's event starts.
      aheadAtOnce: { acts: [storyAct('A', [setsAtOnce, checks])], check: 'warning', raises: false },
      // A ParameterModifyAction makes it a number too (ChangeParameter adds to float(text)).
      modifyAheadAtOnce: {
        acts: [
          storyAct('A', [
            setsAtOnce.replace('<SetAction value="1"/>', '<ModifyAction><Rule><AddValue value="-2"/></Rule></ModifyAction>'),
            checks,
          ]),
        ],
        check: 'warning',
        raises: false,
      },
      aheadLater: { acts: [storyAct('A', [setsLater, checks])], check: 'warning', raises: true },
      otherActBefore: { acts: [storyAct('B', [setsAtOnce]), storyAct('A', [checks])], check: 'warning', raises: false },
      otherActAfter: { acts: [storyAct('A', [checks]), storyAct('B', [setsAtOnce])], check: 'warning', raises: true },
      stopTrigger: {
        acts: [storyAct('A', [setsAtOnce], undefined, `<StopTrigger><ConditionGroup>${gapBelow}</ConditionGroup></StopTrigger>`)],
        check: 'warning',
        raises: false,
      },
      equalTo: {
        acts: [storyAct('A', [settingEvent('Checks', parameterCondition('GapIs', 'equalTo', '1')), setsAtOnce])],
        check: 'none',
        raises: false,
      },
      // The standard holds on the declared 3 at once; ScenarioRunner's tick compares the text '3' with 3.0 (below).
      equalToDeclared: {
        acts: [storyAct('A', [settingEvent('Checks', parameterCondition('GapIs', 'equalTo', '3')), setsLater])],
        check: 'warning',
        raises: false,
      },
    };
    const written = Object.entries(files).map(([name, { acts }]) => {
      const file = path.join(folder, `${name}.xosc`);
      fs.writeFileSync(file, parameterStoryScenario(acts));
      return file;
    });
    const checked = checkForCarla(written, '0.9.16');
    const verdicts = await harnessVerdicts(written, { tree: true, storyTicks: true });
    const seen = Object.keys(files).map((name) => {
      const file = path.resolve(folder, `${name}.xosc`);
      const problems = checked.get(file) ?? [];
      const parameters = problems.filter((problem) => /ParameterAction|compares a parameter/.test(problem.message));
      const verdict = verdicts.get(file);
      assert.equal(verdict?.status, 'OK', JSON.stringify(verdict));
      assert.deepEqual(
        problems.filter((problem) => problem.severity === 'error' && !parameters.includes(problem)),
        [],
      );
      return [name, parameters.map((problem) => problem.severity).join(',') || 'none', /raises TypeError/.test(verdict?.story_ticks ?? '')];
    });
    assert.deepEqual(
      seen,
      Object.entries(files).map(([name, { check, raises }]) => [name, check, raises]),
    );
    const declaredTicks = verdicts.get(path.resolve(folder, 'equalToDeclared.xosc'))?.parameter_ticks;
    assert.deepEqual(declaredTicks, [['GapIs', 'RUNNING', 'RUNNING']]);
  });
});

describe("check --simulator carla on a LanePosition's offset, and on the export's (issue 26)", function () {
  this.timeout(120_000);
  let folder: string;
  before(() => (folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-carla-lane-offsets-'))));
  after(() => {
    if (folder) fs.rmSync(folder, { recursive: true, force: true });
  });
  const teleport = (actor: string, position: string): string =>
    `<Private entityRef="${actor}"><PrivateAction><TeleportAction><Position>${position}</Position></TeleportAction></PrivateAction></Private>`;
  const placements: [string, string][] = [
    ['Along', '<LanePosition roadId="1" laneId="-1" s="50" offset="1"/>'],
    ['Against', '<LanePosition roadId="1" laneId="1" s="80" offset="1"/>'],
    ['Reversed', '<LanePosition roadId="1" laneId="-1" s="110" offset="1"><Orientation type="relative" h="3.14159"/></LanePosition>'],
    ['Across', '<LanePosition roadId="1" laneId="-1" s="140" offset="2"><Orientation type="relative" h="1.5708"/></LanePosition>'],
  ];
  const text = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="0" date="2026-11-29T00:00:00" description="lane offsets" author="modular2simple tests"/>
  <ParameterDeclarations/>
  <CatalogLocations/>
  <RoadNetwork><LogicFile filepath="straight_500m.xodr"/></RoadNetwork>
  <Entities>
${placements.map(([actor], index) => scenarioRunnerVehicle(actor, index === 0 ? 'ego_vehicle' : 'simulation')).join('\n')}
  </Entities>
  <Storyboard>
    <Init><Actions>
${placements.map(([actor, position]) => `      ${teleport(actor, position)}`).join('\n')}
    </Actions></Init>
    <Story name="Still"><Act name="Still">
      <ManeuverGroup maximumExecutionCount="1" name="Group"><Actors selectTriggeringEntities="false"/></ManeuverGroup>
      <StartTrigger><ConditionGroup><Condition name="ActStarts" delay="0" conditionEdge="none">
        <ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition>
      </Condition></ConditionGroup></StartTrigger>
    </Act></Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>
`;
  const offsetFindings = (file: string): [number, string, string][] =>
    (checkForCarla([file], '0.9.16').get(path.resolve(file)) ?? [])
      .filter((problem) => /moves a LanePosition by its offset/.test(problem.message))
      .map((problem) => [
        (problem as CheckedProblem & { line: number }).line,
        problem.severity,
        problem.message.split(': ').pop()?.split(' (')[0] ?? '',
      ]);

  it("warns where ScenarioRunner puts the offset elsewhere than OpenSCENARIO; on the export's, ScenarioRunner puts it where the original means (issue 26)", async () => {
    const file = path.join(folder, 'offsets.xosc');
    fs.writeFileSync(file, text);
    fs.copyFileSync(path.join(esminiRoads, 'straight_500m.xodr'), path.join(folder, 'straight_500m.xodr'));
    const lineOf = (actor: string): number => text.split('\n').findIndex((line) => line.includes(`<Private entityRef="${actor}">`)) + 1;
    // A left lane heads against the road and a lane turned round faces back: ScenarioRunner's right is OpenSCENARIO's left there.
    assert.deepEqual(offsetFindings(file), [
      [lineOf('Along'), 'warning', "this one lands 1 m to the right of lane -1's centre, where OpenSCENARIO puts it 1 m to the left"],
      [
        lineOf('Across'),
        'warning',
        "this one lands on lane -1's centre and 2 m on along the road, where OpenSCENARIO puts it 2 m to the left",
      ],
    ]);
    const exported = path.join(folder, 'exported.xosc');
    const run = runCli(['export', '--target', 'carla', file, '-o', exported, '-q']);
    assert.equal(run.status, 0, run.stderr);
    // The export writes the offset where ScenarioRunner puts it on the side the original means: read by the standard, the
    // written file says the other side, and the profile's reading of it lands where the original's 1 m to the left is.
    const exportedText = fs.readFileSync(exported, 'utf8');
    assert.deepEqual(offsetFindings(exported), [
      [
        exportedText.split('\n').findIndex((line) => /laneId="-1"[^>]*offset="-1"/.test(line)) + 1,
        'warning',
        "this one lands 1 m to the left of lane -1's centre, where OpenSCENARIO puts it 1 m to the right",
      ],
    ]);
  });
});

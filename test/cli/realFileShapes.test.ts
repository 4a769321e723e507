import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinary, esminiRoads, requireEsmini } from '../support/esmini';
import { runBounded } from '../support/processes';
import JSZip from 'jszip';
import {
  distributionFile,
  fileHeader,
  openScenarioFile,
  outerGroup,
  roadScenario,
  runCli,
  scenario,
  simpleGroup,
} from '../support/fixtures';
import { STRAIGHT_ROAD } from '../support/roads';
import { temporaryWorkspace } from '../support/workspace';

/**
 * Issue 27's false alarms, each on a file of the shape real files have (a scenario-generation library's
 * output, the standard's examples), written here: `check` as a user runs it, its JSON read.
 */

interface Reported {
  code: string;
  severity: string;
  message: string;
  line: number;
}

function check(folder: string, file: string, ...options: string[]): Reported[] {
  const run = runCli(['check', path.join(folder, file), '--format', 'json', ...options], { cwd: folder, schema: true });
  assert.ok(run.status === 0 || run.status === 1, run.stderr);
  const report = JSON.parse(run.stdout) as { problems: Reported[] };
  return report.problems.map(({ code, severity, message, line }) => ({ code, severity, message, line }));
}

const VEHICLE = `<Vehicle name="car" vehicleCategory="car"><BoundingBox><Center x="1.4" y="0" z="0.9"/><Dimensions width="2" length="4.5" height="1.5"/></BoundingBox><Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="9"/><Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3" positionZ="0.3"/><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.8" positionX="0" positionZ="0.3"/></Axles><Properties/></Vehicle>`;

/** A schema-valid 1.2 scenario with `locations` as its CatalogLocations and `entity` as Ego's. */
function scenarioWith(parts: { locations?: string; entity?: string; parameters?: string; header?: string }): string {
  const body = `  <ParameterDeclarations>${parts.parameters ?? ''}</ParameterDeclarations>
  <CatalogLocations>${parts.locations ?? ''}</CatalogLocations>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="Ego">${parts.entity ?? VEHICLE}</ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions/></Init>
    <StopTrigger/>
  </Storyboard>
`;
  return openScenarioFile(body, parts.header ?? fileHeader({ description: 'shape', author: 't' }));
}

const VEHICLE_CATALOG = openScenarioFile(
  `  <Catalog name="VehicleCatalog">${VEHICLE}</Catalog>\n`,
  fileHeader({ description: 'vehicles', author: 't' }),
);

/** A ParameterValueDistribution of scenario.xosc with `body` as its Deterministic's distributions. */
const distributionOf = (body: string): string =>
  distributionFile('scenario.xosc', `    <Deterministic>${body}\n    </Deterministic>\n`, fileHeader({ description: 'd', author: 't' }));

describe('real file shapes: no false alarms (issue 27)', function () {
  this.timeout(60_000);
  let folder: string;
  afterEach(() => fs.rmSync(folder, { recursive: true, force: true }));

  describe('catalog-directory', () => {
    // What a generator writes: every kind with an empty path (the file's own folder), and Route and
    // Trajectory catalogs in folders that do not exist, none of which a reference uses.
    const generated = ['VehicleCatalog', 'PedestrianCatalog', 'MiscObjectCatalog', 'ControllerCatalog', 'EnvironmentCatalog']
      .map((kind) => `<${kind}><Directory path=""/></${kind}>`)
      .concat(
        '<RouteCatalog><Directory path="../Catalogs/Routes"/></RouteCatalog>',
        '<TrajectoryCatalog><Directory path="missing/trajectories"/></TrajectoryCatalog>',
      )
      .join('');
    const reference = '<CatalogReference catalogName="VehicleCatalog" entryName="car"/>';

    it('empty paths and directories no reference needs are not reported; an empty path finds the catalogs beside the file', () => {
      folder = temporaryWorkspace({
        'main.xosc': scenarioWith({ locations: generated, entity: reference }),
        'VehicleCatalog.xosc': VEHICLE_CATALOG,
      });
      assert.deepEqual(check(folder, 'main.xosc'), []);
    });

    it('a missing directory of the kind an unresolved reference needs is an error without a scenario path, and the one problem', () => {
      folder = temporaryWorkspace({
        'main.xosc': scenarioWith({
          locations: generated.replace(
            '<VehicleCatalog><Directory path=""/></VehicleCatalog>',
            '<VehicleCatalog><Directory path="missing/vehicles"/></VehicleCatalog>',
          ),
          entity: reference,
        }),
      });
      const problems = check(folder, 'main.xosc');
      // An error as with a scenario path (SPEC 12: its references resolve nowhere; esmini refuses the file without --path too).
      assert.deepEqual(
        problems.filter((problem) => problem.code === 'catalog-directory').map(({ severity, message }) => ({ severity, message })),
        [
          {
            severity: 'error',
            message:
              "the VehicleCatalog directory 'missing/vehicles' does not exist beside this file nor in SCENARIO_PATH, so the catalog references that need it resolve nowhere",
          },
        ],
      );
      assert.ok(!problems.some((problem) => problem.code === 'unknown-catalog'), 'the missing directory is the one problem');
    });

    // With a scenario path, esmini also searches each of its folders for the directory (and the folder itself):
    // a directory missing beside the file is still that, not an unknown catalog at every reference.
    const missingVehicles = scenarioWith({
      locations: '<VehicleCatalog><Directory path="Catalogs/Vehicles"/></VehicleCatalog>',
      entity: reference,
    }).replace('</Entities>', `  <ScenarioObject name="Other">${reference}</ScenarioObject>\n  </Entities>`);

    it('with --scenario-path whose folders hold no such catalog: the missing directory at its line, with what to do, still an error', () => {
      folder = temporaryWorkspace({ 'main.xosc': missingVehicles, 'shared/README.md': 'no catalogs here' });
      const problems = check(folder, 'main.xosc', '--scenario-path', 'shared');
      assert.deepEqual(problems, [
        {
          code: 'catalog-directory',
          severity: 'error',
          line: missingVehicles.split('\n').findIndex((line) => line.includes('Catalogs/Vehicles')) + 1,
          message: `the VehicleCatalog directory 'Catalogs/Vehicles' does not exist beside this file, and the SCENARIO_PATH folders searched for it (${path.join(folder, 'shared')}) hold no catalog its references name`,
        },
      ]);
      const text = runCli(['check', 'main.xosc', '--scenario-path', 'shared'], { cwd: folder, schema: true });
      assert.match(text.stderr, /hint: correct the path, or add the folder that holds the catalogs to SCENARIO_PATH \(--scenario-path/);
      // The same through SCENARIO_PATH, as the editor's setting gives it.
      const viaEnvironment = runCli(['check', 'main.xosc', '--format', 'json'], {
        cwd: folder,
        schema: true,
        env: { SCENARIO_PATH: path.join(folder, 'shared') },
      });
      assert.deepEqual(
        (JSON.parse(viaEnvironment.stdout) as { problems: Reported[] }).problems.map((problem) => problem.code),
        ['catalog-directory'],
      );
    });

    it('with --scenario-path whose folder holds the catalog: found there, nothing reported', () => {
      folder = temporaryWorkspace({ 'main.xosc': missingVehicles, 'shared/Vehicles/VehicleCatalog.xosc': VEHICLE_CATALOG });
      assert.deepEqual(check(folder, 'main.xosc', '--scenario-path', 'shared'), []);
    });

    // esmini 3.6 looks a catalog up as NAME.xosc in each --path folder itself, never in D/Vehicles: a run hands it the
    // directory the check found, so what check accepts esmini loads, and what check refuses run does not start.
    it('run: the catalog the check found through --scenario-path or --road-path is the one esmini loads; without either, nothing is run', function () {
      requireEsmini(this);
      const runnable = missingVehicles
        .replace('<RoadNetwork/>', `<RoadNetwork><LogicFile filepath="${path.join(esminiRoads, 'straight_500m.xodr')}"/></RoadNetwork>`)
        .replace(
          '<Init><Actions/></Init>',
          `<Init><Actions>${['Ego', 'Other']
            .map(
              (name, index) =>
                `<Private entityRef="${name}"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="${20 + 30 * index}" offset="0"/></Position></TeleportAction></PrivateAction></Private>`,
            )
            .join('')}</Actions></Init>`,
        );
      folder = temporaryWorkspace({ 'main.xosc': runnable, 'shared/Vehicles/VehicleCatalog.xosc': VEHICLE_CATALOG });
      const run = (...options: string[]) =>
        runCli(['run', 'main.xosc', '--duration', '1', '--esmini', esminiBinary, ...options], { cwd: folder, schema: true });
      for (const option of ['--scenario-path', '--road-path']) {
        const ran = run(option, 'shared');
        assert.equal(ran.status, 0, `${option}: ${ran.stderr}`);
        assert.match(ran.stderr, /main\.xosc: esmini: 0 errors, /, `${option}: ${ran.stderr}`);
      }
      const refused = run();
      assert.equal(refused.status, 1, refused.stderr);
      assert.match(refused.stderr, /main\.xosc:\d+:\d+: error: the VehicleCatalog directory 'Catalogs\/Vehicles' does not exist/);
      assert.match(refused.stderr, /main\.xosc: the scenario has 1 error; nothing was run/);
    });
  });

  describe("a distribution's parameterName written with '$'", () => {
    // scenariogeneration writes parameterName="$egospeed" for the root parameter egospeed; esmini reads it so.
    const distribution = distributionOf(`
      <DeterministicSingleParameterDistribution parameterName="$egospeed">
        <DistributionSet><Element value="10"/><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`);
    const files = () => ({
      'scenario.xosc': scenarioWith({ parameters: '<ParameterDeclaration name="egospeed" parameterType="double" value="5"/>' }),
      'distribution.xosc': distribution,
    });

    it("check reports no undeclared parameter (vary's warning only) and flatten writes the file", () => {
      folder = temporaryWorkspace(files());
      assert.deepEqual(
        check(folder, 'distribution.xosc').map(({ code, severity, line }) => ({ code, severity, line })),
        [{ code: 'distribution', severity: 'warning', line: 7 }],
      );
      const flattened = runCli(['flatten', 'distribution.xosc', '-o', 'out.xosc'], { cwd: folder });
      assert.equal(flattened.status, 0, flattened.stderr);
      assert.ok(fs.existsSync(path.join(folder, 'out.xosc')));
    });

    it("vary varies the root parameter egospeed, warning that the standard's name has no '$'", () => {
      folder = temporaryWorkspace(files());
      const count = runCli(['vary', 'distribution.xosc', '--count'], { cwd: folder });
      assert.equal(count.status, 0, count.stderr);
      assert.equal(count.stdout.trim(), '2');
      assert.match(count.stderr, /warning: the standard names a parameter without '\$' \('egospeed'\)/);
      const second = runCli(['vary', 'distribution.xosc', '--index', '1'], { cwd: folder });
      assert.match(second.stdout, /<ParameterDeclaration name="egospeed" parameterType="double" value="20"\/>/);
    });
  });

  it('check validates a distribution file as vary does: a parameterName the ScenarioFile no longer declares is an error at its line', () => {
    folder = temporaryWorkspace({
      'scenario.xosc': scenarioWith({ parameters: '<ParameterDeclaration name="EgoSpeed" parameterType="double" value="5"/>' }),
      'distribution.xosc': distributionOf(`
      <DeterministicSingleParameterDistribution parameterName="EgoSpeed">
        <DistributionSet><Element value="10"/><Element value="20"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="Ego_InitSpeed">
        <DistributionSet><Element value="10"/></DistributionSet>
      </DeterministicSingleParameterDistribution>`),
    });
    assert.deepEqual(check(folder, 'distribution.xosc'), [
      {
        code: 'unknown-distribution-parameter',
        severity: 'error',
        line: 10,
        message: "parameter 'Ego_InitSpeed' is not declared in the root ParameterDeclarations of scenario.xosc; did you mean 'EgoSpeed'?",
      },
    ]);
    const text = runCli(['check', 'distribution.xosc'], { cwd: folder, schema: true });
    assert.equal(text.status, 1);
    assert.match(text.stderr, /^distribution\.xosc:10:\d+: error: parameter 'Ego_InitSpeed' is not declared/m);
    const vary = runCli(['vary', 'distribution.xosc', '--count'], { cwd: folder });
    assert.equal(vary.status, 1, 'vary refuses it alike');
  });

  it("a double parameter holding 'time': an error by the standard, a warning under simulator esmini, which runs it with atof's 0", () => {
    folder = temporaryWorkspace({
      'main.xosc': scenarioWith({ parameters: '<ParameterDeclaration name="t" parameterType="double" value="time"/>' }),
    });
    const notUnused = (problems: Reported[]) => problems.filter((problem) => problem.code !== 'unused-parameter');
    const standard = notUnused(check(folder, 'main.xosc'));
    assert.deepEqual(
      standard.map(({ code, severity }) => ({ code, severity })),
      [{ code: 'type-mismatch', severity: 'error' }],
    );
    const esmini = notUnused(check(folder, 'main.xosc', '--simulator', 'esmini'));
    assert.deepEqual(
      esmini.map(({ code, severity, line }) => ({ code, severity, line })),
      [{ code: 'simulator-value', severity: 'warning', line: 4 }],
    );
    assert.match(
      esmini[0].message,
      /^'time' is not a double, but 't' is declared double, so the standard refuses it; esmini runs it: esmini puts a parameter's text as written where \$name is used .*; esmini reads a double with atof\(\).*: 'time' where the text is used, 0 where a double is$/,
    );
  });

  it("a 0.9 FileHeader read as 1.0: priority 'override' is a 1.2 value, not a misspelling of 'overwrite' (deprecated since 1.2)", () => {
    folder = temporaryWorkspace({
      'main.xosc': scenarioWith({
        header: '<FileHeader revMajor="0" revMinor="9" date="2026-01-01T00:00:00" description="old" author="t"/>',
      }).replace(
        '<StopTrigger/>',
        '<Story name="S"><Act name="A"><ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"/><Maneuver name="M"><Event name="E" priority="override"><Action name="a"><GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="s" state="on"/></TrafficSignalAction></InfrastructureAction></GlobalAction></Action><StartTrigger/></Event></Maneuver></ManeuverGroup><StartTrigger/></Act></Story><StopTrigger/>',
      ),
    });
    const run = runCli(['check', 'main.xosc', '--format', 'json'], { cwd: folder, schema: true });
    const report = JSON.parse(run.stdout) as { problems: { code: string; message: string; hint?: string }[] };
    const priority = report.problems.find((problem) => problem.message.startsWith("'override' is not a valid value of Event.priority"));
    assert.ok(priority, run.stdout);
    assert.equal(priority.hint, "'override' is a value of OpenSCENARIO 1.2, 1.3; the FileHeader states 0.9 (revMinor)");
    assert.doesNotMatch(run.stdout, /did you mean 'overwrite'/);
  });

  it('simulator-value on unsignedShort and unsignedInt parameters says what differs: esmini does not support the type', () => {
    folder = temporaryWorkspace({
      'main.xosc': scenarioWith({
        parameters:
          '<ParameterDeclaration name="count" parameterType="unsignedShort" value="65535"/><ParameterDeclaration name="n" parameterType="unsignedInt" value="3"/>',
      }),
    });
    const problems = check(folder, 'main.xosc').filter((problem) => problem.code === 'simulator-value');
    assert.deepEqual(
      problems.map((problem) => problem.message),
      ['count', 'n'].map(
        (name, index) =>
          `'${name}': esmini does not support parameters of type ${['unsignedShort', 'unsignedInt'][index]}: it logs "Type ${['unsignedShort', 'unsignedInt'][index]} is not supported yet" and keeps the value as text ('${['65535', '3'][index]}'), which an attribute then reads as written (esmini 3.6 Parameters.cpp parseParameterDeclarations)`,
      ),
    );
    assert.ok(problems.every((problem) => problem.severity === 'warning'));
  });
});

describe('real file shapes: what a missing scenarioFileName says to do (issue 27)', function () {
  this.timeout(60_000);
  let folder: string;
  afterEach(() => fs.rmSync(folder, { recursive: true, force: true }));

  // The paper's result.mosc: a package holding only main.xosc, whose simple scenarios lie beside the library (SPEC 3:
  // a package never searches its parent folders). It used to say "did you mean 'main.xosc'?", the file itself.
  it("a package's main naming a file outside it: the SCENARIO_PATH hint, never the main itself; a misspelt name still gets its suggestion", async () => {
    const main = scenario(outerGroup('Car', 'car', [{ file: 'simple_1.xosc', groups: [{ name: 'Go' }] }]));
    const zip = new JSZip();
    zip.file('main.xosc', main);
    folder = temporaryWorkspace({
      'simple_1.xosc': scenario(simpleGroup('Go')),
      'misspelt/main.xosc': main.replace('simple_1.xosc', 'simple_l.xosc'),
    });
    fs.writeFileSync(path.join(folder, 'result.mosc'), await zip.generateAsync({ type: 'nodebuffer' }));
    const line = main.split('\n').findIndex((text) => text.includes('simple_1.xosc')) + 1;
    const packaged = check(folder, 'result.mosc').filter((problem) => problem.code === 'missing-file');
    assert.deepEqual(
      packaged.map(({ line }) => line),
      [line],
    );
    const text = runCli(['check', 'result.mosc'], { cwd: folder });
    assert.equal(text.status, 1, text.stderr);
    assert.match(text.stderr, /result\.mosc\/main\.xosc:\d+:\d+: error: cannot find 'simple_1\.xosc'/);
    assert.match(
      text.stderr,
      /hint: set SCENARIO_PATH \(--scenario-path, the modular2simple\.scenarioPath setting\) to the folder that holds it/,
    );
    assert.doesNotMatch(text.stderr, /did you mean 'main\.xosc'/);
    assert.equal(runCli(['check', 'result.mosc', '--scenario-path', '.'], { cwd: folder }).status, 0);
    const misspelt = runCli(['check', 'misspelt/main.xosc'], { cwd: folder });
    assert.match(misspelt.stderr, /cannot find 'simple_l\.xosc'.*\n\s+hint: did you mean 'simple_1\.xosc'\?/);
  });
});

describe('real file shapes: a road file esmini would not find (issue 27)', function () {
  this.timeout(120_000);

  /** A scenario on ../xodr/straight.xodr that ends after a second of simulated time. */
  const SCENARIO = roadScenario({ logicFile: '../xodr/straight.xodr', groups: [] }).replace(
    /<StopTrigger\/>(\s*<\/Storyboard>)/,
    '<StopTrigger><ConditionGroup><Condition name="end" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>$1',
  );
  /** esmini's own layout: the scenario in xosc/, its road named ../xodr/NAME, which here lies in roads/ instead. */
  const layout = (road: string) => temporaryWorkspace({ 'xosc/s.xosc': SCENARIO, 'roads/straight.xodr': road });

  it('check says so at the LogicFile: a warning, an error with --simulator esmini, nothing once --road-path names its folder', () => {
    const folder = layout(STRAIGHT_ROAD);
    const line = SCENARIO.split('\n').findIndex((text) => text.includes('<LogicFile')) + 1;
    const plain = check(folder, 'xosc/s.xosc').filter((problem) => problem.code === 'road-file');
    assert.deepEqual(
      plain.map(({ severity, line }) => [severity, line]),
      [['warning', line]],
    );
    assert.match(plain[0].message, /^road file '\.\.\/xodr\/straight\.xodr' is not found beside this file \(.*xosc\): esmini stops/);
    const esmini = runCli(['check', 'xosc/s.xosc', '--simulator', 'esmini'], { cwd: folder });
    assert.equal(esmini.status, 1, esmini.stderr);
    assert.match(esmini.stderr, /s\.xosc:\d+:\d+: error: road file '\.\.\/xodr\/straight\.xodr' is not found/);
    assert.deepEqual(
      check(folder, 'xosc/s.xosc', '--road-path', 'roads', '--simulator', 'esmini').filter((problem) => problem.code === 'road-file'),
      [],
    );
  });

  it('agrees with esmini: without the folder esmini fails to locate the road, with it as --path esmini loads it', async function () {
    requireEsmini(this);
    const folder = layout(fs.readFileSync(path.join(esminiRoads, 'straight_500m.xodr'), 'utf8'));
    const esmini = (...extra: string[]) =>
      runBounded(
        esminiBinary,
        ['--headless', '--osc', 'xosc/s.xosc', '--fixed_timestep', '0.05', '--disable_log', ...extra],
        { cwd: folder },
        60_000,
      );
    assert.match((await esmini()).output, /Failed to locate OpenDRIVE file \.\.\/xodr\/straight\.xodr/);
    assert.equal(check(folder, 'xosc/s.xosc').filter((problem) => problem.code === 'road-file').length, 1);
    const found = await esmini('--path', path.join(folder, 'roads'));
    assert.doesNotMatch(found.output, /Failed to locate OpenDRIVE file/);
    assert.match(found.output, /Loaded OpenDRIVE: .*straight\.xodr/);
  });
});

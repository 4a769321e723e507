import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
// The module object itself, whose functions the product's modules call through: a test can stand in for one of them.
import nodeFs = require('node:fs');
import * as os from 'node:os';
import * as path from 'node:path';
import { Flattener } from '../../server/src/core/flatten';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseEsminiLog } from '../../server/src/esmini/log';
import { locateEsmini, projectEsminiFolder } from '../../server/src/esmini/locate';
import { mapEsminiMessages, UNPLACED_NOTE, withoutRunFolder } from '../../server/src/esmini/messages';
import { lastCsvTime, makeRunFolder, removeRunFolderAt, runEsminiProcess, sharedRunsFolder } from '../../server/src/esmini/process';
import { EsminiRunOptions, EsminiRunResult, removeRunFolder, runScenario } from '../../server/src/esmini/run';
import { runLimit, RUNAWAY_SECONDS, TIME_LIMIT_CONDITION, withTimeLimit } from '../../server/src/esmini/timeLimit';
import { parseXml } from '../../server/src/core/xml';
import { catalogFile, drivingScenario, roadScenario } from '../support/fixtures';
import { SIMULATOR } from '../../server/src/core/diagnostics/simulator';
import { applyEdits } from '../support/textEdits';
import { fixContext } from '../core/diagnostics/support';
import { esminiBinary, tracksOf, readEsminiCsv, requireEsmini, esminiCatalogs, esminiRoads } from '../support/esmini';
import { libraryDir, repoRoot, requireCorpus } from '../support/paths';
import { listFiles } from '../support/workspace';
import { temporaryFolder } from '../support/temporaryDirectory';

const examples = path.join(repoRoot, 'examples');

/** A copy of the bundled examples in a fresh folder, with `edit` applied to one file's text. */
function examplesCopy(edit?: { file: string; from: string; to: string }): string {
  const root = temporaryFolder('m2s-esmini-');
  fs.cpSync(examples, root, { recursive: true });
  if (edit) {
    const file = path.join(root, edit.file);
    const text = fs.readFileSync(file, 'utf8');
    assert.ok(text.includes(edit.from), `${edit.file} holds ${edit.from}`);
    fs.writeFileSync(file, text.replace(edit.from, edit.to));
  }
  return root;
}

function lineOf(file: string, line: number): string {
  return fs.readFileSync(file, 'utf8').split(/\r?\n/)[line];
}

const results: EsminiRunResult[] = [];
async function run(store: ScenarioStore, main: string, options: EsminiRunOptions = {}): Promise<EsminiRunResult> {
  const result = await runScenario(new Flattener(store), diskRef(main), { esminiPath: esminiBinary, roadPath: [esminiRoads], ...options });
  results.push(result);
  return result;
}

/** A scenario on straight_500m.xodr, Ego driving 1.4 m/s, whose StopTrigger ends it when the simulation time reaches `seconds`. */
function stoppingAt(seconds: string): string {
  const init =
    '<Private entityRef="Ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="10" offset="0"/></Position></TeleportAction></PrivateAction></Private>';
  const stop = `<StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="rising"><ByValueCondition><SimulationTimeCondition value="${seconds}" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>`;
  return roadScenario({ logicFile: 'straight_500m.xodr', init, groups: [] }).replace('<StopTrigger/>', stop);
}

const errorsOf = (result: EsminiRunResult) => result.problems.filter((problem) => problem.severity === 'error');

describe('esmini: time limit and log (no simulator needed)', () => {
  it('adds the time limit to the StopTrigger as an OR, keeping every element before it in place', () => {
    const text = fs.readFileSync(path.join(examples, 'lane_change.xosc'), 'utf8');
    const limited = withTimeLimit(text, 12.5) as string;
    const stop = parseXml(limited)
      .root?.children.find((child) => child.name === 'Storyboard')
      ?.children.find((child) => child.name === 'StopTrigger');
    assert.ok(stop);
    assert.match(
      limited.slice(stop.start, stop.end),
      new RegExp(`name="${TIME_LIMIT_CONDITION}".*<SimulationTimeCondition value="12.5" rule="greaterThan"/>`),
    );
    assert.equal(limited.slice(0, stop.start), text.slice(0, stop.start));
    const withOwnStop = text.replace(
      '<StopTrigger/>',
      '<StopTrigger><ConditionGroup><Condition name="own"/></ConditionGroup></StopTrigger>',
    );
    assert.match(
      withTimeLimit(withOwnStop, 3) as string,
      /<Condition name="own"\/><\/ConditionGroup><ConditionGroup><Condition name="modular2simple_time_limit"/,
    );
    assert.match(
      withTimeLimit(text.replace('<StopTrigger/>', ''), 3) as string,
      /<StopTrigger><ConditionGroup>.*<\/StopTrigger>\s*<\/Storyboard>/s,
    );
    assert.equal(withTimeLimit('<OpenSCENARIO/>', 3), undefined);
  });

  it('moves the runaway guard past a StopTrigger that ends the scenario by time at or after it (ALKS free driving at 5 km/h, issue 27)', () => {
    assert.deepEqual(runLimit(stoppingAt('100'), undefined), { seconds: RUNAWAY_SECONDS, kind: 'runaway', setBy: undefined });
    // The scenario ends at the step of 3600 s (esmini's 5000 / (5 / 3.6)), the guard a second later.
    assert.deepEqual(runLimit(stoppingAt('${5000.0 / (5 / 3.6)}'), undefined), { seconds: 3601, kind: 'runaway', setBy: undefined });
    assert.equal(runLimit(stoppingAt('1e9'), undefined).seconds, 24 * RUNAWAY_SECONDS);
    assert.equal(runLimit(stoppingAt('5000'), 20).seconds, 20);
  });

  it("says a path into a worker's job folder from the scenario's folder it stands for, the folders above it included (a queued batch, issue 27)", () => {
    // A job lays the scenario's folder out as LAYOUT/d0 when its files reach one folder up (../catalogs).
    const said = withoutRunFolder(
      'Failed to load /w/job-1/d0/roads/x.xodr; see /w/job-1/catalogs/c.xosc, /w/job-1',
      '/w/job-1',
      '/home/u/proj/scenarios',
      new Map(),
      () => false,
      '/w/job-1/d0',
    );
    assert.equal(said, 'Failed to load /home/u/proj/scenarios/roads/x.xodr; see /home/u/proj/catalogs/c.xosc, /home/u/proj');
  });

  it('reads the last complete CSV row, ignoring a row being written', () => {
    const folder = temporaryFolder('m2s-csv-');
    const csv = path.join(folder, 'a.csv');
    fs.writeFileSync(csv, 'esmini GIT REV: x\nIndex [-], TimeStamp [s], #1 Entity_Name [-]\n0, 0.000000, ego\n1, 0.050000, ego\n2, 0.1');
    assert.equal(lastCsvTime(csv), 0.05);
    assert.equal(lastCsvTime(path.join(folder, 'missing.csv')), undefined);
  });

  it('keeps [error] and [warn] lines, drops the harmless ones, joins a fatal error with its exception, and says a level once', () => {
    const messages = parseEsminiLog(
      [
        '[] [info] Loaded x.xosc',
        '[] [warn] 3D model car_white.osgb not located, using specified file path',
        '[] [warn] Unsupported geo reference attr: +no_defs',
        '[] [error] Property: color format invalid, shall be #RRGGBB, skipping',
        '[2.600] [warn] Stopping object walker Walk on conflicting Longitudinal domain(s)',
        '[] [error] Exception: [] [error] Failed to locate OpenDRIVE file Town04',
        // ALKS's ALKSController: the level once, not 'warning: Warning: ...'.
        '[] [warn] Warning: Controller ALKSController operating domains: Longitudinal. Skipping activation on domain Lateral',
        '[] [error] Error: Failed to find road 0',
        '[] [warn] Error: a warning that says error keeps its word',
      ].join('\n'),
    );
    assert.deepEqual(
      messages.map((message) => [message.level, message.time, message.text]),
      [
        ['error', undefined, 'Property: color format invalid, shall be #RRGGBB, skipping'],
        ['warn', 2.6, 'Stopping object walker Walk on conflicting Longitudinal domain(s)'],
        ['error', undefined, 'Failed to locate OpenDRIVE file Town04'],
        ['warn', undefined, 'Controller ALKSController operating domains: Longitudinal. Skipping activation on domain Lateral'],
        ['error', undefined, 'Failed to find road 0'],
        ['warn', undefined, 'Error: a warning that says error keeps its word'],
      ],
    );
  });

  it('maps messages that name nothing, a name or a value to the source line they come from', async () => {
    const store = new ScenarioStore({ root: examples });
    const main = diskRef(path.join(examples, 'main.xosc'));
    const flat = await new Flattener(store).flatten(main);
    const log = [
      '[] [error] Exception: Dynamics shape sinusoidal unexpected. Supported: linear',
      '[2.600] [warn] Stopping object walker Walk on conflicting Longitudinal domain(s)',
      '[] [error] Failed to locate OpenDRIVE file Town05',
      '[] [warn] Something esmini says about nothing here',
    ].join('\n');
    const problems = mapEsminiMessages(parseEsminiLog(log), flat.source, main);
    const at = (index: number) => [
      path.basename(problems[index].source.disk),
      lineOf(problems[index].source.disk, problems[index].range.start.line).trim(),
    ];
    assert.deepEqual(at(0), [
      'lane_change.xosc',
      '<LaneChangeActionDynamics parameterAttributes="value, dynamicsShape" dynamicsShape="sinusoidal" value="2" dynamicsDimension="time"/>',
    ]);
    assert.deepEqual(at(1), ['crossing.xosc', '<Action name="Walk">']);
    assert.deepEqual(at(2), ['main.xosc', '<LogicFile filepath="Town05"/>']);
    assert.deepEqual([problems[3].located, problems[3].range.start.line, path.basename(problems[3].source.disk)], [false, 0, 'main.xosc']);
  });

  it('puts "No orientation type specified" on each Orientation without a type, in order (Euro NCAP, ALKS: at 1:1 before)', async () => {
    const root = temporaryFolder('m2s-esmini-orientation-');
    const position = (orientation: string) =>
      `<Private entityRef="Ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="10" offset="0">${orientation}</LanePosition></Position></TeleportAction></PrivateAction></Private>`;
    const init = [
      position('<Orientation h="0.1" type="relative"/>'),
      position('<Orientation h="0.2"/>'),
      position('<Orientation h="0.3" type="sideways"/>'),
    ];
    const text = roadScenario({ logicFile: 'straight_500m.xodr', init: init.join('\n'), groups: [] });
    fs.writeFileSync(path.join(root, 's.xosc'), text);
    const main = diskRef(path.join(root, 's.xosc'));
    const flat = await new Flattener(new ScenarioStore({ root })).flatten(main);
    const log = [
      '[] [warn] No orientation type specified - using relative (default for OSC version >= 1.3)',
      '[] [warn] Invalid orientation type specified - using relative (default for OSC version >= 1.3)',
    ].join('\n');
    const problems = mapEsminiMessages(parseEsminiLog(log), flat.source, main);
    const lines = text.split('\n');
    assert.deepEqual(
      problems.map((problem) => {
        const line = lines[problem.range.start.line];
        return [problem.located, line.slice(problem.range.start.character, problem.range.end.character), /h="([^"]+)"/.exec(line)?.[1]];
      }),
      [
        [true, 'Orientation', '0.2'],
        [true, 'sideways', '0.3'],
      ],
    );
  });

  it("puts esmini's messages about a misplaced ActivateControllerAction, a deprecated attribute, dynamic constraints, a missing displacement and a road-less RoadNetwork on their elements (esmini's samples: at 1:1 before)", async () => {
    const root = temporaryFolder('m2s-esmini-placed-');
    const private_ = (action: string) => `<Private entityRef="Ego"><PrivateAction>${action}</PrivateAction></Private>`;
    const distance = (extra: string, acceleration: string) =>
      `<LongitudinalAction><LongitudinalDistanceAction entityRef="Ego" freespace="false" continuous="true" distance="5"${extra}><DynamicConstraints maxAcceleration="${acceleration}" maxDeceleration="3" maxSpeed="10"/></LongitudinalDistanceAction></LongitudinalAction>`;
    const init = [
      private_('<ControllerAction><ActivateControllerAction longitudinal="true" lateral="true"/></ControllerAction>'),
      private_('<ActivateControllerAction longitudinal="true" lateral="false"/>'),
      private_(distance(' displacement="any"', '3')),
      private_(distance('', '$Max')),
    ];
    const group =
      '<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><Maneuver name="M"><Event name="E" priority="override"><Action name="A"><PrivateAction><ActivateControllerAction longitudinal="false" lateral="true"/></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="rising"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities><EntityCondition><TimeHeadwayCondition entityRef="Ego" value="1.5" freespace="false" alongRoute="false" rule="lessThan"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>';
    // No LogicFile, as esmini's trailer_connect.xosc and parking_lot.xosc (esmini runs them without roads).
    const text = roadScenario({
      logicFile: 'straight_500m.xodr',
      parameters: '<ParameterDeclaration name="Max" parameterType="double" value="15"/>',
      init: init.join('\n'),
      groups: [group],
    }).replace('<LogicFile filepath="straight_500m.xodr"/>', '');
    fs.writeFileSync(path.join(root, 's.xosc'), text);
    const main = diskRef(path.join(root, 's.xosc'));
    const flat = await new Flattener(new ScenarioStore({ root })).flatten(main);
    const log = [
      '[] [warn] In OSC 1.1 ActivateControllerAction should be placed under ControllerAction. Accepting anyway.',
      '[] [warn] In OSC 1.1 ActivateControllerAction should be placed under ControllerAction. Accepting anyway.',
      '[] [warn] In OSC 1.0 ActivateControllerAction should be placed under PrivateAction. Accepting anyway.',
      '[] [warn] alongRoute attribute is depricated from v1.1. Reading it anyway.',
      '[] [warn] parseDynamicConstraints: maxAcceleration value 15.00 exceeds object performance value: 5.00, truncating',
      '[] [warn] displacement attribute missing, setting default trailingReferencedEntity',
      '[] [warn] No OpenDRIVE file specified, continue without',
    ].join('\n');
    const problems = mapEsminiMessages(parseEsminiLog(log), flat.source, main);
    const lines = text.split('\n');
    const placed = problems.map((problem) => {
      const line = lines[problem.range.start.line];
      const at = problem.range.start.character;
      return [
        problem.located,
        line.slice(at, problem.range.end.character),
        line.slice(line.lastIndexOf('<', at), line.indexOf('>', at) + 1),
      ];
    });
    fs.rmSync(root, { recursive: true, force: true });
    assert.deepEqual(placed, [
      [true, 'ActivateControllerAction', '<ActivateControllerAction longitudinal="true" lateral="false"/>'],
      [true, 'ActivateControllerAction', '<ActivateControllerAction longitudinal="false" lateral="true"/>'],
      [true, 'ActivateControllerAction', '<ActivateControllerAction longitudinal="true" lateral="true"/>'],
      [true, 'false', '<TimeHeadwayCondition entityRef="Ego" value="1.5" freespace="false" alongRoute="false" rule="lessThan"/>'],
      [true, '$Max', '<DynamicConstraints maxAcceleration="$Max" maxDeceleration="3" maxSpeed="10"/>'],
      [true, 'LongitudinalDistanceAction', '<LongitudinalDistanceAction entityRef="Ego" freespace="false" continuous="true" distance="5">'],
      [true, 'RoadNetwork', '<RoadNetwork>'],
    ]);
  });

  it("puts esmini's messages about catalog entries in the catalog file, on the entry's line, and says so where esmini names no place (at 1:1 before)", async () => {
    const root = temporaryFolder('m2s-esmini-catalog-messages-');
    const vehicle = (name: string, declarations: string) =>
      `<Vehicle name="${name}" vehicleCategory="car"><ParameterDeclarations>${declarations}</ParameterDeclarations><BoundingBox><Center x="0" y="0" z="0"/><Dimensions width="2" length="4" height="1.5"/></BoundingBox><Performance maxSpeed="50" maxAcceleration="5" maxDeceleration="5"/><Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.8" positionX="3" positionZ="0.3"/><RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.8" positionX="0" positionZ="0.3"/></Axles><Properties/></Vehicle>`;
    const offset = '<ParameterDeclaration name="Offset" parameterType="double" value="0"/>';
    fs.mkdirSync(path.join(root, 'catalogs'));
    // `outline` declares Offset twice (esmini's car_white_with_outline); a TrafficSwarmAction would read it unreferenced.
    fs.writeFileSync(
      path.join(root, 'catalogs', 'VehicleCatalog.xosc'),
      catalogFile('VehicleCatalog', [vehicle('plain', offset), vehicle('outline', offset + '\n' + offset)].join('\n')),
    );
    fs.writeFileSync(
      path.join(root, 'catalogs', 'EnvironmentCatalog.xosc'),
      catalogFile(
        'EnvironmentCatalog',
        '<Environment name="thin"><TimeOfDay animation="false" dateTime="2026-01-01T12:00:00"/><Weather atmosphericPressure="10000" temperature="280"/><RoadCondition frictionScaleFactor="1"/></Environment>',
      ),
    );
    fs.writeFileSync(
      path.join(root, 'catalogs', 'ManeuverCatalog.xosc'),
      catalogFile(
        'ManeuverCatalog',
        '<Maneuver name="Wait"><Event name="Go" priority="override"><Action name="Speed"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="$Rate" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="After" delay="0" conditionEdge="none"><ByValueCondition><StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="Go" state="endTransition"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver>',
      ),
    );
    const locations =
      '<CatalogLocations><VehicleCatalog><Directory path="catalogs"/></VehicleCatalog><EnvironmentCatalog><Directory path="catalogs"/></EnvironmentCatalog><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>';
    const group = (name: string) =>
      `<ManeuverGroup name="${name}" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><CatalogReference catalogName="ManeuverCatalog" entryName="Wait"/></ManeuverGroup>`;
    const text = roadScenario({
      logicFile: 'straight_500m.xodr',
      init: '<GlobalAction><EnvironmentAction><CatalogReference catalogName="EnvironmentCatalog" entryName="thin"/></EnvironmentAction></GlobalAction>',
      groups: [group('G1'), group('G2')],
    })
      .replace('<CatalogLocations/>', locations)
      .replace(/<Vehicle name="car"[^]*?<\/Vehicle>/, '<CatalogReference catalogName="VehicleCatalog" entryName="plain"/>');
    fs.writeFileSync(path.join(root, 's.xosc'), text);
    const main = diskRef(path.join(root, 's.xosc'));
    const flat = await new Flattener(new ScenarioStore({ root })).flatten(main, { force: true });
    const log = [
      '[] [warn] Parameter Offset redefined. Previous value 0 will be shadowed by 0',
      '[] [warn] Atmospheric pressure clamped between 80000.0 and 120000.0 Pa',
      '[] [warn] Warning: Non unique element name: Go, picking first occurrence',
      '[] [error] Failed to resolve parameter $Rate',
      '[2.000] [warn] Deactivating ctrl  conflicting on domain Longitudinal (< osc v1.3)',
    ].join('\n');
    const problems = mapEsminiMessages(parseEsminiLog(log), flat.source, main);
    const placed = problems.map((problem) => {
      const line = fs.readFileSync(problem.source.disk, 'utf8').split('\n')[problem.range.start.line];
      return [
        path.relative(root, problem.source.disk),
        problem.located,
        line.slice(problem.range.start.character, problem.range.end.character),
        problem.located
          ? line.slice(line.lastIndexOf('<', problem.range.start.character), line.indexOf('>', problem.range.start.character) + 1)
          : '',
        problem.note,
      ];
    });
    fs.rmSync(root, { recursive: true, force: true });
    assert.deepEqual(placed, [
      ['catalogs/VehicleCatalog.xosc', true, 'Offset', offset, undefined],
      ['catalogs/EnvironmentCatalog.xosc', true, '10000', '<Weather atmosphericPressure="10000" temperature="280"/>', undefined],
      [
        'catalogs/ManeuverCatalog.xosc',
        true,
        'Go',
        '<StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="Go" state="endTransition"/>',
        undefined,
      ],
      [
        'catalogs/ManeuverCatalog.xosc',
        true,
        '$Rate',
        '<SpeedActionDynamics dynamicsShape="step" value="$Rate" dynamicsDimension="time"/>',
        undefined,
      ],
      ['s.xosc', false, '', '', UNPLACED_NOTE],
    ]);
  });

  it('maps a value that an override set to the ParameterReference that set it, through a package too', async () => {
    const root = examplesCopy({
      file: 'main.xosc',
      from: '<ParameterReference key="LaneChangeActionDynamics.value" value="1.5"/>',
      to: '<ParameterReference key="LaneChangeActionDynamics.value" value="1.5"/>\n              <ParameterReference key="LaneChangeActionDynamics.dynamicsShape" value="jerky"/>',
    });
    const main = diskRef(path.join(root, 'main.xosc'));
    const flat = await new Flattener(new ScenarioStore({ root })).flatten(main);
    assert.ok(flat.text, JSON.stringify(flat.problems));
    const [problem] = mapEsminiMessages(
      parseEsminiLog('[] [error] Exception: Dynamics shape jerky unexpected. Supported: linear'),
      flat.source,
      main,
    );
    assert.equal(problem.source.disk, main.disk);
    assert.match(lineOf(main.disk, problem.range.start.line), /key="LaneChangeActionDynamics.dynamicsShape" value="jerky"/);
    // A name, through two levels of packages: the event in the simple scenario inside braking.mosc.
    const [inPackage] = mapEsminiMessages(parseEsminiLog('[1.000] [warn] Event Brake already running, trigger ignored'), flat.source, main);
    assert.deepEqual([path.basename(inPackage.source.disk), ...inPackage.source.entries], ['braking.mosc', 'hard_brake.xosc']);
  });

  it('maps a message about a road or lane to the position naming them: the override that set the lane, a ${...} lane, else the road', async () => {
    const teleport =
      '<Event name="Jump" priority="overwrite"><Action name="Jump"><PrivateAction><TeleportAction><Position><LanePosition parameterAttributes="laneId" roadId="550" laneId="-1" s="10" offset="0"/></Position></TeleportAction></PrivateAction></Action></Event>';
    const root = examplesCopy({
      file: 'lane_change.xosc',
      from: '<Event name="ChangeLane" priority="overwrite">',
      to: `${teleport}\n            <Event name="ChangeLane" priority="overwrite">`,
    });
    const mainFile = path.join(root, 'main.xosc');
    const mainText = fs.readFileSync(mainFile, 'utf8');
    assert.ok(
      mainText.includes('<WorldPosition x="-50" y="0.8" z="0" h="3.14159"/>') &&
        mainText.includes('<ParameterReference key="RelativeDistanceCondition.value" value="12"/>'),
    );
    fs.writeFileSync(
      mainFile,
      mainText
        .replace('<WorldPosition x="-50" y="0.8" z="0" h="3.14159"/>', '<LanePosition roadId="550" laneId="${-2 + 1}" s="5"/>')
        .replace(
          '<ParameterReference key="RelativeDistanceCondition.value" value="12"/>',
          '<ParameterReference key="RelativeDistanceCondition.value" value="12"/>\n              <ParameterReference key="LanePosition.laneId" value="-2"/>',
        ),
    );
    const main = diskRef(mainFile);
    const flat = await new Flattener(new ScenarioStore({ root })).flatten(main);
    assert.ok(flat.text, JSON.stringify(flat.problems));
    const log = [
      '[] [error] Lane id -2 does not exist on road 550 on laneSection 0',
      '[] [error] Lane id -1 does not exist on road 550 on laneSection 0',
      '[] [error] Position::Set Error: track 550 not available',
      '[] [error] Lane id -3 does not exist on road 550 on laneSection 0',
      '[] [error] Invalid s value 10.00000 for road 550 of length 7.00000, truncating to 7.00',
      '[] [error] Invalid s value 8.00000 for road 550 of length 7.00000, truncating to 7.00',
    ].join('\n');
    const problems = mapEsminiMessages(parseEsminiLog(log), flat.source, main);
    const at = (index: number) => {
      const { source, range, located } = problems[index];
      const line = lineOf(source.disk, range.start.line);
      return [located, path.basename(source.disk), line.trim(), line.slice(range.start.character, range.end.character)];
    };
    // Lane -2 on road 550 is the imported LanePosition whose laneId the main file's override set.
    assert.deepEqual(at(0), [true, 'main.xosc', '<ParameterReference key="LanePosition.laneId" value="-2"/>', '-2']);
    // Lane -1 is the main file's own LanePosition, whose laneId is an expression.
    assert.deepEqual(at(1), [true, 'main.xosc', '<LanePosition roadId="550" laneId="${-2 + 1}" s="5"/>', '${-2 + 1}']);
    // Road only, or a lane no position names: the first position on that road.
    assert.deepEqual(at(2), [true, 'main.xosc', '<LanePosition roadId="550" laneId="${-2 + 1}" s="5"/>', '550']);
    assert.deepEqual(at(3), [true, 'main.xosc', '<LanePosition roadId="550" laneId="${-2 + 1}" s="5"/>', '550']);
    // An s past the road's end (issue 27: esmini's ltap-od-relative-speed.xosc, at 1:1): the position on that road with that s, else the first on it.
    assert.deepEqual(at(4).slice(0, 2), [true, 'lane_change.xosc']);
    assert.match(String(at(4)[2]), /<LanePosition parameterAttributes="laneId" roadId="550" laneId="-1" s="10" offset="0"\/>/);
    assert.equal(at(4)[3], '10');
    assert.deepEqual(at(5), [true, 'main.xosc', '<LanePosition roadId="550" laneId="${-2 + 1}" s="5"/>', '5']);
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('stops a run that makes no progress as hung (no fixed wall-clock limit: a long run that progresses goes on)', async () => {
    const folder = temporaryFolder('m2s-stall-');
    // A stand-in that hangs before its first step, as esmini stuck loading would.
    const program = path.join(folder, 'stuck');
    fs.writeFileSync(program, '#!/bin/sh\nexec sleep 60\n', { mode: 0o755 });
    const started = Date.now();
    const result = await runEsminiProcess({
      program,
      scenarioFile: path.join(folder, 'scenario.xosc'),
      workDir: folder,
      csvFile: path.join(folder, 'run.csv'),
      searchPath: [],
      timeStep: 0.05,
      seed: 1,
      duration: 30,
      stallMs: 1500,
      maxCsvBytes: 1e6,
      maxOutputChars: 1e4,
    });
    fs.rmSync(folder, { recursive: true, force: true });
    assert.equal(result.end, 'killed', result.reason);
    assert.equal(result.stoppedBy, 'stall');
    assert.match(result.reason ?? '', /made no progress for 1\.5 s of wall-clock time \(before its first step\)/);
    assert.ok(Date.now() - started < 55_000, 'stopped long before the stand-in would have ended');
  });

  it('tells how to get esmini when it is missing, and runs nothing', async () => {
    const location = locateEsmini(undefined, process.cwd(), '', []);
    assert.equal(location.found, false);
    assert.match((location as { message: string }).message, /modular2simple\.esmini\.path.*build\.sh \.cache\/esmini/s);
    const configured = locateEsmini('no/such/esmini', os.tmpdir());
    assert.match((configured as { message: string }).message, /esmini is not at .*no\/such\/esmini/);
    const result = await runScenario(new Flattener(new ScenarioStore({ root: examples })), diskRef(path.join(examples, 'main.xosc')), {
      esminiPath: path.join(os.tmpdir(), 'no-such-esmini'),
    });
    assert.equal(result.outcome, 'no-esmini');
    assert.equal(result.runFolder, undefined);
  });
});

describe('esmini: where it is found', () => {
  it('after the setting and PATH, in .cache/esmini/bin of the project the program runs from (where npm start builds it)', () => {
    const project = temporaryFolder('m2s-locate-');
    try {
      fs.writeFileSync(path.join(project, 'package.json'), '{}');
      const built = path.join(project, '.cache', 'esmini', 'bin');
      const onPath = path.join(project, 'on-path');
      for (const folder of [built, onPath, path.join(project, 'dist')]) fs.mkdirSync(folder, { recursive: true });
      for (const folder of [built, onPath]) fs.writeFileSync(path.join(folder, 'esmini'), '#!/bin/sh\n', { mode: 0o755 });
      assert.equal(projectEsminiFolder(path.join(project, 'dist')), built);
      assert.equal(
        projectEsminiFolder(path.join(__dirname, '..', '..', 'server', 'src', 'esmini')),
        path.resolve(__dirname, '..', '..', '.cache', 'esmini', 'bin'),
      );
      assert.deepEqual(locateEsmini(undefined, project, '', [built]), { found: true, program: path.join(built, 'esmini') });
      assert.deepEqual(locateEsmini(undefined, project, onPath, [built]), { found: true, program: path.join(onPath, 'esmini') });
      // A configured path that holds no esmini is reported, not replaced by the one built.
      assert.equal(locateEsmini('elsewhere', project, '', [built]).found, false);
    } finally {
      fs.rmSync(project, { recursive: true, force: true });
    }
  });
});

describe('esmini: runs (the simulator built by the test setup)', function () {
  this.timeout(180_000);
  after(() => results.forEach(removeRunFolder));

  it('runs the bundled examples with no error, and their vehicles move', async function () {
    requireEsmini(this);
    const root = examplesCopy();
    const before = listFiles(root);
    const result = await run(new ScenarioStore({ root }), path.join(root, 'main.xosc'), { duration: 20 });
    assert.equal(result.outcome, 'ok', `${result.message}\n${result.log.slice(-3000)}`);
    assert.deepEqual(errorsOf(result), []);
    assert.equal(result.simulatedTime, 20);
    assert.ok(result.csvFile && result.scenarioFile);
    assert.ok(!result.scenarioFile.startsWith(root), 'the flattened file is written in a private folder, not beside the sources');
    assert.deepEqual(listFiles(root), before, 'nothing written beside the sources');
    const tracks = tracksOf(readEsminiCsv(result.csvFile));
    assert.deepEqual([...tracks.keys()].sort(), ['adversary', 'ego', 'lead', 'walker']);
    for (const name of ['ego', 'adversary', 'lead', 'walker']) {
      const track = tracks.get(name) ?? [];
      const first = track[0];
      const moved = Math.max(...track.map((point) => Math.hypot(point.x - first.x, point.y - first.y)));
      assert.ok(moved > 5, `${name} moved ${moved.toFixed(1)} m`);
    }
    assert.ok(Math.max(...(tracks.get('ego') ?? []).map((point) => point.time)) <= 20 + 0.05 + 1e-9, 'stopped at the limit');
    // The lead brakes at 10 s, as main.xosc overrides.
    const lead = tracks.get('lead') ?? [];
    const speedBetween = (from: number, to: number) => {
      const [a, b] = [lead.find((point) => point.time >= from), lead.find((point) => point.time >= to)];
      return a && b ? Math.hypot(b.x - a.x, b.y - a.y) / (b.time - a.time) : NaN;
    };
    assert.ok(speedBetween(5, 9) > 9 && speedBetween(17, 19) < 0.1, `lead: ${speedBetween(5, 9)} m/s, then ${speedBetween(17, 19)} m/s`);
  });

  it('runs every bundled example on its own (simple scenarios and packages too) with no error, and something moves', async function () {
    requireEsmini(this);
    const store = new ScenarioStore({ root: examples });
    for (const [file, main] of [
      ['lane_change.xosc', diskRef(path.join(examples, 'lane_change.xosc'))],
      ['crossing.xosc', diskRef(path.join(examples, 'crossing.xosc'))],
      ['pedestrian/main.xosc', diskRef(path.join(examples, 'pedestrian', 'main.xosc'))],
      ['braking.mosc', childRef(diskRef(path.join(examples, 'braking.mosc')), 'main.xosc')],
    ] as const) {
      const result = await runScenario(new Flattener(store), main, { esminiPath: esminiBinary, roadPath: [esminiRoads], duration: 10 });
      results.push(result);
      assert.equal(result.outcome, 'ok', `${file}: ${result.message}`);
      assert.deepEqual(errorsOf(result), [], file);
      const moved = [...tracksOf(readEsminiCsv(result.csvFile as string)).values()].map((track) =>
        Math.hypot(track[track.length - 1].x - track[0].x, track[track.length - 1].y - track[0].y),
      );
      assert.ok(Math.max(...moved) > 5, `${file}: moved ${moved.map((distance) => distance.toFixed(1)).join(', ')} m`);
    }
  });

  it('follows the CSV and interrupts a scenario past the limit when nothing else stops it (SIGINT, a clean quit)', async function () {
    requireEsmini(this);
    const flat = await new Flattener(new ScenarioStore({ root: examples })).flatten(diskRef(path.join(examples, 'main.xosc')));
    const folder = makeRunFolder(temporaryFolder('m2s-sigint-'));
    const scenarioFile = path.join(folder, 'scenario.xosc');
    fs.writeFileSync(scenarioFile, flat.text as string);
    const csvFile = path.join(folder, 'run.csv');
    const result = await runEsminiProcess({
      program: esminiBinary,
      scenarioFile,
      workDir: folder,
      csvFile,
      searchPath: [examples, esminiRoads],
      timeStep: 0.05,
      seed: 1,
      duration: 2,
      stallMs: 60_000,
      maxCsvBytes: 200e6,
      maxOutputChars: 1e6,
    });
    const last = lastCsvTime(csvFile) as number;
    fs.rmSync(folder, { recursive: true, force: true });
    assert.equal(result.end, 'interrupted', result.reason);
    assert.equal(result.exitCode, 0, 'SIGINT is a clean quit for esmini');
    assert.match(result.reason ?? '', /passed the 2 s limit/);
    assert.ok(last > 2 && last < 3600, `stopped at ${last} s, past the limit and long before esmini's own hour`);
  });

  it('repeats exactly with the same step and seed', async function () {
    requireEsmini(this);
    const store = new ScenarioStore({ root: examples });
    const [a, b] = [
      await run(store, path.join(examples, 'main.xosc'), { duration: 5 }),
      await run(store, path.join(examples, 'main.xosc'), { duration: 5 }),
    ];
    const rows = (result: EsminiRunResult) =>
      fs
        .readFileSync(result.csvFile as string, 'utf8')
        .split('\n')
        .slice(6)
        .join('\n');
    assert.equal(rows(a), rows(b));
  });

  it("shows esmini's message on the line of the simple scenario that has the mistake", async function () {
    requireEsmini(this);
    const root = examplesCopy({
      file: 'lane_change.xosc',
      from: 'dynamicsShape="linear" value="3"',
      to: 'dynamicsShape="wobbly" value="3"',
    });
    const result = await run(new ScenarioStore({ root }), path.join(root, 'main.xosc'), { duration: 5 });
    // esmini stops at the unknown shape before it simulates anything (exit 255): the run did not happen.
    assert.equal(result.outcome, 'failed');
    assert.match(result.message, /^esmini did not run the scenario \(exit code \d+\): Dynamics shape wobbly unexpected/);
    const [error] = errorsOf(result);
    assert.ok(error, result.log);
    assert.equal(error.source.disk, path.join(root, 'lane_change.xosc'));
    assert.match(lineOf(error.source.disk, error.range.start.line), /<SpeedActionDynamics dynamicsShape="wobbly"/);
    assert.match(error.message, /wobbly/);
  });

  it('refuses selectTriggeringEntities alone, as check --simulator esmini says, and runs it with the EntityRef its fix adds', async function () {
    requireEsmini(this);
    const group = `<ManeuverGroup name="Follow" maximumExecutionCount="1"><Actors selectTriggeringEntities="true"/><Maneuver name="M"><Event name="E" priority="override"><Action name="Go"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>`;
    const trigger =
      '<StartTrigger><ConditionGroup><Condition name="Still" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities><EntityCondition><StandStillCondition duration="0.1"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger>\n      </Act>';
    const text = drivingScenario('straight_500m.xodr', group).replace(/<StartTrigger\/>\n {6}<\/Act>/, trigger);
    assert.match(text, /name="Still"/);
    const root = temporaryFolder('m2s-esmini-actors-');
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(main, text);
    const store = new ScenarioStore({ root });
    const refused = await run(store, main, { duration: 3 });
    assert.equal(refused.outcome, 'failed', refused.log);
    assert.match(refused.message, /PrivateAction Go missing actor\(s\)\. SelectTriggeringEntities feature not supported yet/);
    const [error] = (await new Flattener(store, 'esmini').analyze(diskRef(main))).problems.filter(
      (problem) => problem.code === 'simulator',
    );
    assert.equal(error?.severity, 'error');
    assert.match(error.message, /refuses to load a private action with none/);
    const [fix] = (await SIMULATOR.fixes?.(fixContext(error.data, undefined, text, error.range))) ?? [];
    fs.writeFileSync(main, applyEdits(text, fix.edits));
    const ran = await run(new ScenarioStore({ root }), main, { duration: 3 });
    assert.equal(ran.outcome, 'ok', `${ran.message}\n${ran.log.slice(-2000)}`);
    const ego = tracksOf(readEsminiCsv(ran.csvFile as string)).get('Ego') ?? [];
    assert.ok(ego[ego.length - 1].x - ego[0].x > 5, 'Ego, the added actor, drives');
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('places the error of a run that fails in a catalog entry on that entry, in its catalog file (at 1:1 before)', async function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-esmini-catalog-failure-');
    fs.mkdirSync(path.join(root, 'catalogs'));
    const maneuver =
      '<Maneuver name="Drive"><Event name="Go" priority="override"><Action name="Speed"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="linear" value="$Rate" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver>';
    fs.writeFileSync(path.join(root, 'catalogs', 'ManeuverCatalog.xosc'), catalogFile('ManeuverCatalog', maneuver));
    const group =
      '<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><CatalogReference catalogName="ManeuverCatalog" entryName="Drive"/></ManeuverGroup>';
    const text = drivingScenario('straight_500m.xodr', group).replace(
      '<CatalogLocations/>',
      '<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>',
    );
    fs.writeFileSync(path.join(root, 'main.xosc'), text);
    // Forced: $Rate is declared nowhere, which the check reports too.
    const result = await run(new ScenarioStore({ root }), path.join(root, 'main.xosc'), { duration: 2, force: true });
    assert.equal(result.outcome, 'failed', result.log);
    const error = errorsOf(result).find((problem) => /Failed to resolve parameter/.test(problem.message));
    assert.ok(error?.located, JSON.stringify(result.problems));
    assert.equal(error.source.disk, path.join(root, 'catalogs', 'ManeuverCatalog.xosc'));
    const line = lineOf(error.source.disk, error.range.start.line);
    assert.equal(line.slice(error.range.start.character, error.range.end.character), '$Rate');
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('takes the last of two declarations of one name, as check --simulator esmini says', async function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-esmini-redeclared-');
    const main = path.join(root, 'main.xosc');
    const text = drivingScenario('straight_500m.xodr', 'Drive').replace(
      '<ParameterDeclarations></ParameterDeclarations>',
      '<ParameterDeclarations><ParameterDeclaration name="Speed" parameterType="double" value="5"/><ParameterDeclaration name="Speed" parameterType="double" value="15"/></ParameterDeclarations>',
    );
    assert.match(text, /name="Speed"/);
    fs.writeFileSync(
      main,
      text.replace('<AbsoluteTargetSpeed parameterAttributes="value" value="10"/>', '<AbsoluteTargetSpeed value="$Speed"/>'),
    );
    const [warning] = (await new Flattener(new ScenarioStore({ root }), 'esmini').analyze(diskRef(main))).problems.filter(
      (problem) => problem.code === 'duplicate-parameter',
    );
    assert.match(warning.message, /the first declaration \(value '5'\); esmini uses the last .*, here value '15'/);
    const result = await run(new ScenarioStore({ root }), main, { duration: 3 });
    assert.equal(result.outcome, 'ok', result.log.slice(-2000));
    const ego = tracksOf(readEsminiCsv(result.csvFile as string)).get('Ego') ?? [];
    const [a, b] = [ego.find((point) => point.time >= 1), ego.find((point) => point.time >= 2)];
    assert.ok(a && b);
    assert.ok(Math.abs((b.x - a.x) / (b.time - a.time) - 15) < 0.1, `Ego drives ${((b.x - a.x) / (b.time - a.time)).toFixed(2)} m/s`);
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('refuses what check --simulator esmini calls its refusals (RelativeAngleCondition, displacement="any", a swarm without velocity, a GeoPosition, a steady state to a stop, an entity after an ExternalObjectReference), and runs each written as esmini reads it', async function () {
    requireEsmini(this);
    const event = (action: string, condition: string) =>
      `<ManeuverGroup name="W" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><Maneuver name="M2"><Event name="E2" priority="override"><Action name="A2">${action}</Action><StartTrigger><ConditionGroup><Condition name="C2" delay="0" conditionEdge="none">${condition}</Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>`;
    const speed =
      '<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="5"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>';
    const atOne = '<ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/></ByValueCondition>';
    const angle = (name: string) =>
      `<ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities><EntityCondition><${name} entityRef="Ego" angleType="heading" angle="0" angleTolerance="0.1"/></EntityCondition></ByEntityCondition>`;
    const lateral = (displacement: string) =>
      `<PrivateAction><LateralAction><LateralDistanceAction entityRef="Ego" distance="1" freespace="false" continuous="false"${displacement}/></LateralAction></PrivateAction>`;
    const swarm = (velocity: string) =>
      `<GlobalAction><TrafficAction><TrafficSwarmAction innerRadius="10" semiMajorAxis="100" semiMinorAxis="50" numberOfVehicles="2" offset="0"${velocity}><CentralObject entityRef="Ego"/><TrafficDefinition name="t"><VehicleCategoryDistribution><VehicleCategoryDistributionEntry category="car" weight="1"/></VehicleCategoryDistribution><ControllerDistribution><ControllerDistributionEntry weight="1"><Controller name="c"><Properties/></Controller></ControllerDistributionEntry></ControllerDistribution></TrafficDefinition></TrafficSwarmAction></TrafficAction></GlobalAction>`;
    const teleport = (position: string) =>
      `<PrivateAction><TeleportAction><Position>${position}</Position></TeleportAction></PrivateAction>`;
    const synchronize = (speed: string) =>
      `<PrivateAction><SynchronizeAction masterEntityRef="Ego"><TargetPositionMaster><LanePosition roadId="1" laneId="-1" s="200" offset="0"/></TargetPositionMaster><TargetPosition><LanePosition roadId="1" laneId="-1" s="100" offset="0"/></TargetPosition><FinalSpeed><AbsoluteSpeed value="${speed}"><TargetTimeSteadyState time="1"/></AbsoluteSpeed></FinalSpeed></SynchronizeAction></PrivateAction>`;
    const EXTERNAL = '<ScenarioObject name="Far"><ExternalObjectReference name="elsewhere"/></ScenarioObject>';
    const cases: { refused: string; runs: string; says: RegExp; entities?: (text: string) => string }[] = [
      {
        refused: event(speed, angle('RelativeAngleCondition')),
        runs: event(speed, angle('AngleCondition')),
        says: /Entity condition RelativeAngleCondition not supported/,
      },
      {
        refused: event(lateral(' displacement="any"'), atOne),
        runs: event(lateral(''), atOne),
        says: /Unsupported displacement type: any/,
      },
      { refused: event(swarm(''), atOne), runs: event(swarm(' velocity="10"'), atOne), says: /stod/ },
      {
        refused: event(teleport('<GeoPosition latitudeDeg="0.0001" longitudeDeg="0.0001"/>'), atOne),
        runs: event(teleport('<WorldPosition x="20" y="-1.5"/>'), atOne),
        says: /Failed parse position in node Position/,
      },
      {
        refused: event(synchronize('0'), atOne),
        runs: event(synchronize('5'), atOne),
        says: /steady state with 0 or negative final speed/,
      },
      {
        refused: event(speed, atOne),
        runs: event(speed, atOne),
        says: /Failed to find object/,
        entities: (text: string) => text.replace('<Entities>', `<Entities>${EXTERNAL}`),
      },
    ];
    const root = temporaryFolder('m2s-esmini-refusals-');
    const main = path.join(root, 'main.xosc');
    const write = (group: string, entities: (text: string) => string = (text) => text) =>
      fs.writeFileSync(
        main,
        entities(
          drivingScenario('straight_500m.xodr', 'Drive')
            .replace('revMinor="2"', 'revMinor="3"')
            .replace('</ManeuverGroup>', `</ManeuverGroup>\n        ${group}`),
        ),
      );
    for (const { refused, runs, says, entities } of cases) {
      write(refused, entities);
      const errors = (await new Flattener(new ScenarioStore({ root }), 'esmini').analyze(diskRef(main))).problems.filter(
        (problem) => problem.code === 'simulator' && problem.severity === 'error',
      );
      assert.equal(errors.length, 1, `${says}: ${JSON.stringify(errors.map((problem) => problem.message))}`);
      const failed = await run(new ScenarioStore({ root }), main, { duration: 2 });
      assert.equal(failed.outcome, 'failed', `${says}: ${failed.message}`);
      assert.match(failed.log, says);
      // The ExternalObjectReference after every other ScenarioObject: esmini reads them all.
      write(runs, entities && ((text) => text.replace('</Entities>', `${EXTERNAL}</Entities>`)));
      // No error: the ExternalObjectReference itself stays a warning (esmini runs without it).
      assert.deepEqual(
        (await new Flattener(new ScenarioStore({ root }), 'esmini').analyze(diskRef(main))).problems.filter(
          (problem) => problem.code === 'simulator' && (entities === undefined || problem.severity === 'error'),
        ),
        [],
      );
      const ran = await run(new ScenarioStore({ root }), main, { duration: 2 });
      // esmini logs the ExternalObjectReference as an [error] and runs on.
      assert.equal(ran.outcome, entities ? 'errors' : 'ok', `${says}: ${ran.message}\n${ran.log.slice(-1500)}`);
      assert.equal(ran.simulatedTime, 2, `${says}: ${ran.message}`);
    }
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('measures an AngleCondition in lane coordinates along the lane (no fallback to road coordinates), which check --simulator esmini no longer warns of', async function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-esmini-lane-angle-');
    const main = path.join(root, 'main.xosc');
    // Ego in lane 1, heading along that lane's driving direction: 0 from the lane's heading, pi from the road's.
    const started = async (system: string) => {
      const group = `<ManeuverGroup name="W" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors><Maneuver name="M2"><Event name="Along" priority="override"><Action name="A2"><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="3"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="C2" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities><EntityCondition><AngleCondition angleType="heading" angle="0" angleTolerance="0.1" coordinateSystem="${system}"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>`;
      fs.writeFileSync(
        main,
        drivingScenario('straight_500m.xodr', group).replace('revMinor="2"', 'revMinor="3"').replace('laneId="-1"', 'laneId="1"'),
      );
      const findings = (await new Flattener(new ScenarioStore({ root }), 'esmini').analyze(diskRef(main))).problems.filter(
        (problem) => problem.code === 'simulator',
      );
      assert.deepEqual(findings, []);
      const result = await run(new ScenarioStore({ root }), main, { duration: 2 });
      assert.equal(result.outcome, 'ok', result.message);
      return /Along standbyState -> startTransition -> runningState/.test(result.log);
    };
    assert.equal(await started('lane'), true, "lane: the heading is the lane's");
    assert.equal(await started('road'), false, "road: the heading is pi from the road's");
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('runs the unsaved text: an editor overlay with a mistake is what esmini gets', async function () {
    requireEsmini(this);
    const root = examplesCopy();
    const store = new ScenarioStore({ root });
    const simple = diskRef(path.join(root, 'lane_change.xosc'));
    store.setOverlay(simple, fs.readFileSync(simple.disk, 'utf8').replace('dynamicsShape="sinusoidal"', 'dynamicsShape="bumpy"'));
    const result = await run(store, path.join(root, 'main.xosc'), { duration: 5 });
    const [error] = errorsOf(result);
    assert.ok(error, result.log);
    assert.equal(error.source.disk, simple.disk);
    assert.match(lineOf(simple.disk, error.range.start.line), /<LaneChangeActionDynamics /);
  });

  /** The examples' lane_change.xosc in `root` on roads/straight.xodr, its adversary a car_red of catalogs/vehicles, placed by lane positions. */
  function plainLaneChange(root: string): string {
    fs.mkdirSync(path.join(root, 'roads'));
    fs.copyFileSync(path.join(esminiRoads, 'straight_500m.xodr'), path.join(root, 'roads', 'straight.xodr'));
    fs.cpSync(path.join(esminiCatalogs, 'Vehicles'), path.join(root, 'catalogs', 'vehicles'), { recursive: true });
    return fs
      .readFileSync(path.join(root, 'lane_change.xosc'), 'utf8')
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations><VehicleCatalog><Directory path="catalogs/vehicles"/></VehicleCatalog></CatalogLocations>',
      )
      .replace('<LogicFile filepath="Town05"/>', '<LogicFile filepath="roads/straight.xodr"/>')
      .replace(
        /<Vehicle name="vehicle\.audi\.tt"[\s\S]*?<\/Vehicle>/,
        '<CatalogReference catalogName="VehicleCatalog" entryName="car_red"/>',
      )
      .replace(
        /<Init>[\s\S]*?<\/Init>/,
        '<Init><Actions><Private entityRef="ego"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="50" offset="0"/></Position></TeleportAction></PrivateAction></Private><Private entityRef="adversary"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="20" offset="0"/></Position></TeleportAction></PrivateAction></Private></Actions></Init>',
      );
  }

  it('finds roads and catalogs as the scenario names them, relative to its own folder', async function () {
    requireEsmini(this);
    const root = examplesCopy();
    const text = plainLaneChange(root);
    fs.writeFileSync(path.join(root, 'plain.xosc'), text);
    const result = await run(new ScenarioStore({ root }), path.join(root, 'plain.xosc'), { duration: 3, roadPath: [] });
    assert.equal(
      result.outcome,
      'ok',
      `${result.message}\n${JSON.stringify(result.problems)}\n${result.log
        .split('\n')
        .filter((line) => /error|warn/.test(line))
        .join('\n')}`,
    );
    assert.match(result.log, /Loaded OpenDRIVE: .*roads\/straight\.xodr/);
    assert.deepEqual(errorsOf(result), []);
    // A road the file does not have: the message lands on the position that names it.
    fs.writeFileSync(path.join(root, 'plain.xosc'), text.replace('roadId="1" laneId="-1" s="20"', 'roadId="7" laneId="-1" s="20"'));
    const wrong = await run(new ScenarioStore({ root }), path.join(root, 'plain.xosc'), { duration: 3, roadPath: [] });
    const [error] = errorsOf(wrong);
    assert.ok(error?.located, wrong.log);
    assert.match(lineOf(error.source.disk, error.range.start.line), /roadId="7"/);
  });

  it("places esmini's messages about a controller on the controller that the scenario gives, inline or from a catalog, and names no private folder (issue 27: esmini's cut-in_sumo.xosc, at 1:1, naming the run's folder)", async function () {
    requireEsmini(this);
    const root = examplesCopy();
    const sumo =
      '<Controller name="sumo"><ParameterDeclarations><ParameterDeclaration name="CfgFile" parameterType="string" value="../sumo_inputs/e6mini.sumocfg"/></ParameterDeclarations>' +
      '<Properties><Property name="esminiController" value="SumoController"/><File filepath="$CfgFile"/></Properties></Controller>';
    fs.mkdirSync(path.join(root, 'catalogs', 'controllers'), { recursive: true });
    // The same path written as it stands in another entry: esmini looks it up from the scenario's folder too, not the catalog's.
    const literal =
      '<Controller name="sumo_literal"><Properties><Property name="esminiController" value="SumoController"/><File filepath="../sumo_inputs/e6mini.sumocfg"/></Properties></Controller>';
    fs.writeFileSync(
      path.join(root, 'catalogs', 'controllers', 'ControllerCatalog.xosc'),
      catalogFile('ControllerCatalog', sumo + literal),
    );
    const base = plainLaneChange(root).replace(
      '<CatalogLocations><VehicleCatalog>',
      '<CatalogLocations><ControllerCatalog><Directory path="catalogs/controllers"/></ControllerCatalog><VehicleCatalog>',
    );
    for (const [name, controller, attribute] of [
      ['inline.xosc', sumo, 'name="sumo"'],
      ['catalog.xosc', '<CatalogReference catalogName="ControllerCatalog" entryName="sumo"/>', 'entryName="sumo"'],
      ['literal.xosc', '<CatalogReference catalogName="ControllerCatalog" entryName="sumo_literal"/>', 'entryName="sumo_literal"'],
    ]) {
      const text = base.replace(
        '<CatalogReference catalogName="VehicleCatalog" entryName="car_red"/>',
        `<CatalogReference catalogName="VehicleCatalog" entryName="car_red"/><ObjectController>${controller}</ObjectController>`,
      );
      assert.notEqual(text, base);
      fs.writeFileSync(path.join(root, name), text);
      const result = await run(new ScenarioStore({ root }), path.join(root, name), { duration: 1, roadPath: [] });
      const errors = errorsOf(result);
      assert.deepEqual(
        errors.map((error) => error.message),
        [
          `Failed to localize controller file ../sumo_inputs/e6mini.sumocfg, also tried ${path.join(path.dirname(root), 'sumo_inputs', 'e6mini.sumocfg')}`,
          'Unsupported controller type: SumoController. Falling back to default controller',
        ],
        name,
      );
      for (const error of errors) {
        assert.ok(error.located, `${name}: ${error.message}`);
        assert.equal(error.source.disk, path.join(root, name));
        const line = lineOf(error.source.disk, error.range.start.line);
        assert.equal(line.slice(error.range.start.character - attribute.indexOf('"') - 1).startsWith(attribute), true, `${name}: ${line}`);
      }
    }
    // Beside the scenario, the file is there: the run's copy, in a private folder, reaches it as the scenario does (SPEC 11.6),
    // inline or from a catalog, the catalog's parameter assigned by the reference or not, or its path written in the entry
    // (issue 27: esmini missed it).
    fs.writeFileSync(
      path.join(root, 'assigned.xosc'),
      fs
        .readFileSync(path.join(root, 'catalog.xosc'), 'utf8')
        .replace(
          '<CatalogReference catalogName="ControllerCatalog" entryName="sumo"/>',
          '<CatalogReference catalogName="ControllerCatalog" entryName="sumo"><ParameterAssignments><ParameterAssignment parameterRef="CfgFile" value="../sumo_inputs/e6mini.sumocfg"/></ParameterAssignments></CatalogReference>',
        ),
    );
    fs.mkdirSync(path.join(path.dirname(root), 'sumo_inputs'), { recursive: true });
    const config = path.join(path.dirname(root), 'sumo_inputs', 'e6mini.sumocfg');
    fs.writeFileSync(config, '<configuration/>');
    try {
      for (const name of ['inline.xosc', 'catalog.xosc', 'assigned.xosc', 'literal.xosc']) {
        const before = fs.readFileSync(path.join(root, name), 'utf8');
        const result = await run(new ScenarioStore({ root }), path.join(root, name), { duration: 1, roadPath: [] });
        assert.deepEqual(
          errorsOf(result).map((error) => error.message),
          ['Unsupported controller type: SumoController. Falling back to default controller'],
          `${name}: ${result.log}`,
        );
        assert.equal(fs.readFileSync(path.join(root, name), 'utf8'), before, `${name} is left as it was`);
      }
    } finally {
      fs.rmSync(path.dirname(config), { recursive: true, force: true });
    }
  });

  it('a scenario whose StopTrigger ends it at 3600 s ends by itself, not as a runaway (ALKS free driving at 5 km/h, issue 27)', async function () {
    requireEsmini(this);
    const root = temporaryFolder('m2s-esmini-hour-');
    fs.writeFileSync(path.join(root, 'hour.xosc'), stoppingAt('${5000.0 / (5 / 3.6)}'));
    const result = await run(new ScenarioStore({ root }), path.join(root, 'hour.xosc'));
    assert.equal(result.outcome, 'ok', result.message);
    assert.ok(!result.reachedLimit, result.message);
    assert.match(result.message, /; 3600\.00 s simulated \(the run took/);
  });

  it('stops a scenario whose own StopTrigger never fires at the time limit', async function () {
    requireEsmini(this);
    const result = await run(new ScenarioStore({ root: examples }), path.join(examples, 'main.xosc'), { duration: 2.5 });
    assert.equal(result.end, 'exited');
    assert.equal(result.exitCode, 0);
    const last = lastCsvTime(result.csvFile as string) as number;
    assert.ok(last > 2.5 && last <= 2.5 + 0.05 + 1e-9, `last row at ${last} s`);
  });
});

describe('esmini: the 31 library examples (SPEC 8) run with no error', function () {
  this.timeout(600_000);
  after(() => results.forEach(removeRunFolder));

  it('each flattens and runs; the never-rising simulationTime = 0 warning shows on its source line', async function () {
    requireCorpus(this);
    requireEsmini(this);
    const mains = fs
      .readdirSync(libraryDir)
      .filter((name) => fs.existsSync(path.join(libraryDir, name, 'main.xosc')))
      .map((name) => path.join(libraryDir, name, 'main.xosc'));
    assert.equal(mains.length, 31);
    const store = new ScenarioStore({ scenarioPath: [libraryDir], root: libraryDir });
    for (const main of mains) {
      const result = await run(store, main, { duration: 1 });
      assert.equal(result.outcome, 'ok', `${main}: ${result.message}\n${result.log.slice(-2000)}`);
      assert.deepEqual(errorsOf(result), [], main);
      const rising = result.problems.filter((problem) => /simulationTime = 0 condition used with edge "rising"/.test(problem.message));
      assert.ok(rising.length > 0, `${main}: the warning is shown`);
      for (const problem of rising) {
        assert.ok(problem.located, main);
        assert.match(path.basename(problem.source.disk), /^simple_\d\.xosc$/, 'on the simple scenario it comes from');
        const line = lineOf(problem.source.disk, problem.range.start.line);
        assert.match(line, /<Condition .*conditionEdge="rising"/);
        assert.match(lineOf(problem.source.disk, problem.range.start.line + 2), /<SimulationTimeCondition value="0"/);
      }
      removeRunFolder(result);
    }
  });
});

describe('esmini: the shared parent of run folders in the temporary directory', () => {
  const before = process.env.TMPDIR;
  afterEach(() => {
    process.env.TMPDIR = before;
  });

  it('goes with the last run folder removed from it, stays while another run holds a folder there, and comes back for the next run', () => {
    process.env.TMPDIR = temporaryFolder('m2s-shared-runs-');
    const parent = sharedRunsFolder();
    const first = makeRunFolder(parent);
    const second = makeRunFolder(parent);
    fs.writeFileSync(path.join(first, 'scenario.xosc'), '');
    removeRunFolderAt(first);
    assert.deepEqual(fs.readdirSync(parent), [path.basename(second)]);
    removeRunFolderAt(second);
    assert.equal(fs.existsSync(parent), false);
    const third = makeRunFolder(parent);
    assert.equal(path.dirname(third), parent);
    removeRunFolderAt(third);
    assert.deepEqual(fs.readdirSync(process.env.TMPDIR), []);
  });

  it('is made again when another run removes it between making it and making the run folder in it', () => {
    process.env.TMPDIR = temporaryFolder('m2s-shared-runs-race-');
    const parent = sharedRunsFolder();
    const mkdtemp = nodeFs.mkdtempSync;
    let removedOnce = false;
    // The other run's removal lands between makeRunFolder's mkdirSync and mkdtempSync.
    nodeFs.mkdtempSync = ((prefix: string) => {
      if (!removedOnce) {
        removedOnce = true;
        fs.rmdirSync(parent);
      }
      return mkdtemp(prefix);
    }) as typeof nodeFs.mkdtempSync;
    let folder: string;
    try {
      folder = makeRunFolder(parent);
    } finally {
      nodeFs.mkdtempSync = mkdtemp;
    }
    assert.ok(removedOnce);
    assert.equal(path.dirname(folder), parent);
    removeRunFolderAt(folder);
    assert.deepEqual(fs.readdirSync(process.env.TMPDIR), []);
  });

  it('is never removed when a run folder lies in a folder of the caller (batch --keep-runs)', () => {
    const own = temporaryFolder('m2s-own-runs-');
    removeRunFolderAt(makeRunFolder(own));
    assert.deepEqual(fs.readdirSync(own), []);
  });
});

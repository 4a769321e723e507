import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { simulatorWording } from '../../server/src/core/diagnostics/simulator';
import { Flattener } from '../../server/src/core/flatten';
import { CARLA_FACTS, CARLA_PROFILE } from '../../server/src/core/profiles/carla';
import { simulatorFindings } from '../../server/src/core/profiles/checks';
import { ESMINI_FACTS, ESMINI_PROFILE } from '../../server/src/core/profiles/esmini';
import { Simulator } from '../../server/src/core/profiles/simulators';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { outerGroup, overwritingManeuverCatalog, scenario, simpleGroup } from '../support/fixtures';
import { sharedDir } from '../support/paths';
import { semanticProblemsOf } from './diagnostics/support';
import { temporaryWorkspace } from '../support/workspace';

function scenarioText(minor: string, init: string, story: string): string {
  return `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="${minor}" date="2026-01-01T00:00:00" description="profiles" author="test"/>
  <ParameterDeclarations/>
  <CatalogLocations/>
  <RoadNetwork/>
  <Entities>
    <ScenarioObject name="ego"/>
  </Entities>
  <Storyboard>
    <Init>
      <Actions>
${init}
      </Actions>
    </Init>
    <Story name="story">
      <Act name="act">
        <ManeuverGroup name="group" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
          <Maneuver name="maneuver">
            <Event name="event" priority="overwrite">
              <Action name="action">
${story}
              </Action>
            </Event>
          </Maneuver>
        </ManeuverGroup>
      </Act>
    </Story>
  </Storyboard>
</OpenSCENARIO>
`;
}

const VISIBILITY = '<PrivateAction><VisibilityAction graphics="false" traffic="true" sensors="true"/></PrivateAction>';
const LANE_CHANGE = `<PrivateAction><LateralAction><LaneChangeAction>
  <LaneChangeActionDynamics dynamicsShape="linear" value="20" dynamicsDimension="distance"/>
  <LaneChangeTarget><RelativeTargetLane entityRef="ego" value="1"/></LaneChangeTarget>
</LaneChangeAction></LateralAction></PrivateAction>`;
const TIME_OF_DAY =
  '<GlobalAction/><StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><TimeOfDayCondition dateTime="2026-01-01T08:00:00" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>';

/** A workspace whose main.xosc (1.0, a lane change of its own) imports the group Go of `simple` as simple.xosc, and a CARLA flattener for it. */
function importingGo(simple: string): { root: string; flattener: Flattener } {
  const main = scenarioText('0', '', LANE_CHANGE).replace(
    /<ManeuverGroup name="group"[\s\S]*<\/ManeuverGroup>/,
    '<ManeuverGroup name="outer" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors><ScenarioReference scenarioFileName="simple.xosc"><ManeuverGroupReference maneuverGroupName="Go"/></ScenarioReference></ManeuverGroup>',
  );
  const root = temporaryWorkspace({ 'simple.xosc': simple, 'main.xosc': main });
  return { root, flattener: new Flattener(new ScenarioStore({ scenarioPath: [], root }), 'carla') };
}

function messages(simulator: Simulator, text: string, fileName = 'scenario.xosc'): string[] {
  return simulatorFindings(simulator, parseXml(text), fileName).map((finding) => simulatorWording(finding).message);
}

describe('simulator profiles', () => {
  it('carla flags a 1.1 header and an unsupported action; asam flags neither', () => {
    const text = scenarioText('1', '', VISIBILITY);
    const carla = messages('carla', text);
    assert.ok(
      carla.some((message) =>
        /^CARLA ScenarioRunner accepts only OpenSCENARIO 1\.0; this file states 1\.1 \(srunner\/scenarioconfigs\/openscenario_configuration\.py:105\)$/.test(
          message,
        ),
      ),
      carla.join('\n'),
    );
    assert.ok(
      carla.some((message) =>
        /^CARLA ScenarioRunner does not support VisibilityAction in a Story.*\(srunner\/tools\/openscenario_parser\.py:1454\)$/.test(
          message,
        ),
      ),
      carla.join('\n'),
    );
    assert.deepEqual(messages('asam', text), []);
    assert.deepEqual(messages('carla', scenarioText('0', '', LANE_CHANGE)), []);
  });

  it("carla names where the Init's global actions are read (parameters and entities only), not the private actions' loop", () => {
    const signal =
      '<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalStateAction name="1" state="on;off"/></TrafficSignalAction></InfrastructureAction></GlobalAction>';
    const inInit = messages('carla', scenarioText('0', signal, ''));
    assert.equal(inInit.length, 1);
    assert.match(
      inInit[0],
      /^CARLA ScenarioRunner ignores TrafficSignalStateAction in the Init: .*\(srunner\/scenarios\/open_scenario\.py:201-215, 598-620\)$/,
    );
  });

  it('carla reports the finding at the source position (the revMinor value, the action tag), as an error with its one-edit fix', () => {
    const text = scenarioText('1', '', VISIBILITY);
    const document = parseXml(text);
    const findings = simulatorFindings('carla', document, 'scenario.xosc');
    const version = findings.find((finding) => finding.attribute?.name === 'revMinor');
    assert.ok(version?.attribute);
    assert.equal(text.slice(version.attribute.valueStart, version.attribute.valueEnd), '1');
    assert.equal(version.severity, 'error');
    assert.equal(version.suggestion, '0');
    const visibility = findings.find((finding) => finding.element.name === 'VisibilityAction');
    assert.equal(visibility?.severity, 'error');
  });

  it('carla: a route action is an error under 0.9.16 (the ChangeActorWaypoints crash) and nothing under 0.9.15', () => {
    const acquire =
      '<PrivateAction><RoutingAction><AcquirePositionAction><Position><WorldPosition x="1" y="2"/></Position></AcquirePositionAction></RoutingAction></PrivateAction>';
    const text = scenarioText('0', '', acquire);
    const latest = simulatorFindings('carla', parseXml(text), 'scenario.xosc', '0.9.16');
    assert.deepEqual(
      latest.map((finding) => [finding.severity, finding.element.name]),
      [['error', 'AcquirePositionAction']],
    );
    assert.match(simulatorWording(latest[0]).message, /atomic_behaviors\.py:773/);
    assert.deepEqual(simulatorFindings('carla', parseXml(text), 'scenario.xosc', '0.9.15'), []);
    // In a story the export may write it as a trajectory from where the actor is expected when it starts (export/routeTrajectories.ts): offered.
    assert.equal(latest[0].exportMaps, true);
    // In the Init it may write it as a FollowTrajectoryAction along the route's lanes (export/routeTrajectories.ts): offered.
    const init = `<Private entityRef="ego">${acquire}</Private>`;
    const inInit = simulatorFindings('carla', parseXml(scenarioText('0', init, '')), 'scenario.xosc', '0.9.16');
    assert.deepEqual(
      inInit.map((finding) => [finding.severity, finding.element.name, finding.exportMaps]),
      [['error', 'AcquirePositionAction', true]],
    );
  });

  it('carla knows where an action may stand: a lane change runs in a Story, not in the Init', () => {
    const init = `<Private entityRef="ego">${LANE_CHANGE}</Private>`;
    const inInit = messages('carla', scenarioText('0', init, ''));
    assert.equal(inInit.length, 1);
    assert.match(
      inInit[0],
      /^CARLA ScenarioRunner ignores LaneChangeAction in the Init: the Init runs Speed, .*\(srunner\/scenarios\/open_scenario\.py:263-348\)$/,
    );
    assert.deepEqual(messages('carla', scenarioText('0', '', LANE_CHANGE)), []);
  });

  it('carla flags values it does not run, but not $parameters it resolves', () => {
    const story = `<PrivateAction><LateralAction><LaneChangeAction>
      <LaneChangeActionDynamics dynamicsShape="$shape" value="2" dynamicsDimension="distance"/>
      <LaneChangeTarget><RelativeTargetLane entityRef="ego" value="1"/></LaneChangeTarget>
    </LaneChangeAction></LateralAction></PrivateAction>`;
    assert.deepEqual(messages('carla', scenarioText('0', '', story)), []);
    // By time, ScenarioRunner plans the lane change over an infinite distance (openscenario_parser.py:1386-1399).
    assert.deepEqual(messages('carla', scenarioText('0', '', story.replace('"distance"', '"time"'))), [
      'CARLA ScenarioRunner does not support dynamicsDimension="time" on LaneChangeActionDynamics: a lane change by time or rate is planned over an infinite distance (distance_lane_change=inf): the value is read as a duration that nothing uses (srunner/tools/openscenario_parser.py:1386-1399)',
    ]);
    const sinusoidal = simulatorFindings(
      'carla',
      parseXml(scenarioText('0', '', LANE_CHANGE.replace('"linear"', '"sinusoidal"'))),
      'a.xosc',
    );
    assert.equal(sinusoidal.length, 1);
    assert.match(simulatorWording(sinusoidal[0]).message, /dynamicsShape="sinusoidal" on LaneChangeActionDynamics/);
    assert.equal(sinusoidal[0].severity, 'warning');
    // The export writes a time as the distance the actor drives in it (carlaRules.ts laneChangeTimes): the finding offers it; no export follows a shape.
    for (const dimension of ['"time"', '"rate"']) {
      const found = simulatorFindings('carla', parseXml(scenarioText('0', '', story.replace('"distance"', dimension))), 'a.xosc');
      assert.deepEqual(
        found.map((finding) => finding.exportMaps),
        [true],
        dimension,
      );
    }
    assert.equal(sinusoidal[0].exportMaps, undefined);
  });

  it('carla reads catalogs only from files named <Type>Catalog.xosc; the version of a catalog is not checked', () => {
    const catalog =
      '<OpenSCENARIO><FileHeader revMajor="0" revMinor="9" date="x" description="c" author=""/><Catalog name="cars"><Vehicle name="car"/></Catalog></OpenSCENARIO>';
    assert.deepEqual(messages('carla', catalog, 'VehicleCatalog.xosc'), []);
    const misnamed = messages('carla', catalog, 'Cars.xosc');
    assert.deepEqual(misnamed, [
      'CARLA ScenarioRunner reads a catalog of Vehicle entries only from a file named VehicleCatalog.xosc in the catalog directory; this file is Cars.xosc (srunner/scenarioconfigs/openscenario_configuration.py:108-144)',
    ]);
    assert.deepEqual(messages('esmini', catalog, 'Cars.xosc'), []);
  });

  it('esmini flags one of its unsupported elements; asam and carla-only facts do not apply', () => {
    const text = scenarioText('2', '', TIME_OF_DAY);
    const esmini = messages('esmini', text);
    assert.deepEqual(esmini, ['esmini does not support TimeOfDayCondition: the condition is ignored (osc_coverage.txt)']);
    assert.deepEqual(messages('asam', text), []);
    const modify =
      '<GlobalAction><ParameterAction parameterRef="p"><ModifyAction><Rule><AddValue value="1"/></Rule></ModifyAction></ParameterAction></GlobalAction>';
    assert.equal(messages('esmini', scenarioText('1', '', modify)).length, 1);
    // The same element under a VariableAction is supported.
    assert.deepEqual(
      messages(
        'esmini',
        scenarioText(
          '2',
          '',
          modify.replace(/ParameterAction parameterRef/, 'VariableAction variableRef').replace('</ParameterAction>', '</VariableAction>'),
        ),
      ),
      [],
    );
  });

  // Each of the four quits esmini 3.6 at load (exit 255), as test/server/esmini.test.ts runs it; the standard allows each.
  it('esmini refuses a RelativeAngleCondition, a LateralDistanceAction with displacement="any" written, a TrafficSwarmAction without velocity, a GeoPosition: errors there', () => {
    const findings = (story: string, minor = '3') =>
      simulatorFindings('esmini', parseXml(scenarioText(minor, '', story)), 'scenario.xosc').map((finding) => [
        finding.severity,
        finding.element.name,
        finding.attribute?.name,
        simulatorWording(finding).message,
      ]);
    const angle =
      '<PrivateAction><VisibilityAction graphics="false" traffic="true" sensors="true"/></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="ego"/></TriggeringEntities><EntityCondition><RelativeAngleCondition entityRef="ego" angleType="heading" angle="0" angleTolerance="0.1"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger><Action name="x">' +
      VISIBILITY;
    assert.deepEqual(findings(angle), [
      [
        'error',
        'RelativeAngleCondition',
        undefined,
        'esmini does not support RelativeAngleCondition: it reads the entity conditions up to AngleCondition and refuses the scenario on this one ("Entity condition RelativeAngleCondition not supported") (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:4615-5051)',
      ],
    ]);
    const lateral = (displacement: string) =>
      `<PrivateAction><LateralAction><LateralDistanceAction entityRef="ego" distance="1" freespace="false" continuous="false"${displacement}/></LateralAction></PrivateAction>`;
    assert.deepEqual(findings(lateral(' displacement="any"')), [
      [
        'error',
        'LateralDistanceAction',
        'displacement',
        `esmini does not support displacement="any" on LateralDistanceAction: it reads only leftToReferencedEntity and rightToReferencedEntity and refuses the scenario on any other value written ("Unsupported displacement type: any"); without the attribute it takes 'any' (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:3130-3148)`,
      ],
    ]);
    assert.deepEqual(findings(lateral('')), []);
    assert.deepEqual(findings(lateral(' displacement="leftToReferencedEntity"')), []);
    const swarm = (velocity: string) =>
      `<GlobalAction><TrafficAction><TrafficSwarmAction innerRadius="10" semiMajorAxis="100" semiMinorAxis="50" numberOfVehicles="2" offset="0"${velocity}><CentralObject entityRef="ego"/></TrafficSwarmAction></TrafficAction></GlobalAction>`;
    assert.deepEqual(findings(swarm('')), [
      [
        'error',
        'TrafficSwarmAction',
        undefined,
        'esmini does not support TrafficSwarmAction without velocity: it reads velocity with std::stod, which stops it when the attribute is absent ("Exception: stod"); the standard makes it optional (deprecated from 1.2 on) (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:2466-2467)',
      ],
    ]);
    assert.deepEqual(findings(swarm(' velocity="30"')), []);
    const teleport = (position: string) =>
      `<PrivateAction><TeleportAction><Position>${position}</Position></TeleportAction></PrivateAction>`;
    assert.deepEqual(findings(teleport('<GeoPosition latitudeDeg="0.001" longitudeDeg="0.001"/>')), [
      [
        'error',
        'GeoPosition',
        undefined,
        'esmini does not support GeoPosition: its position reader has no GeoPosition and refuses the scenario ("Failed parse position in node Position") (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:1854-2259)',
      ],
    ]);
    assert.deepEqual(findings(teleport('<WorldPosition x="1" y="2"/>')), []);
    assert.deepEqual(messages('asam', scenarioText('3', '', swarm('') + lateral(' displacement="any"'))), []);
  });

  // The pattern of esmini's own Catalogs/ (corpus): entries that no scenario of the folder references, flagged in the catalog before.
  it('an element a simulator does not run in a catalog entry is flagged on the CatalogReference that uses the entry, not in the catalog, nor for an entry no scenario uses', async () => {
    const route = (name: string, position: string) =>
      `<Route name="${name}" closed="false"><Waypoint routeStrategy="shortest"><Position>${position}</Position></Waypoint><Waypoint routeStrategy="shortest"><Position><WorldPosition x="1" y="2"/></Position></Waypoint></Route>`;
    const geo = '<GeoPosition latitudeDeg="0.001" longitudeDeg="0.001"/>';
    const catalog = `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2026-01-01T00:00:00" description="routes" author="test"/>
  <Catalog name="routes">
    ${route('used', geo)}
    ${route('unused', geo)}
    ${route('plain', '<WorldPosition x="0" y="0"/>')}
  </Catalog>
</OpenSCENARIO>
`;
    const assign = (entry: string) =>
      `<Private entityRef="ego"><PrivateAction><RoutingAction><AssignRouteAction><CatalogReference catalogName="routes" entryName="${entry}"/></AssignRouteAction></RoutingAction></PrivateAction></Private>`;
    const main = (entries: string[]) =>
      scenarioText('3', entries.map(assign).join(''), VISIBILITY).replace(
        '<CatalogLocations/>',
        '<CatalogLocations><RouteCatalog><Directory path="Routes"/></RouteCatalog></CatalogLocations>',
      );
    const files = { 'Routes/routes.xosc': catalog };
    const simulatorProblems = async (text: string) =>
      (await semanticProblemsOf(text, files, 'esmini'))
        .filter((problem) => problem.code === 'simulator')
        .map((problem) => [problem.severity, problem.range.start.line, problem.message]);
    // The catalog alone: no entry is used by it, so nothing is flagged there.
    assert.deepEqual(await simulatorProblems(catalog), []);
    const used = main(['used', 'plain']);
    const referenceLine = used.split('\n').findIndex((line) => line.includes('entryName="used"'));
    assert.deepEqual(await simulatorProblems(used), [
      [
        'error',
        referenceLine,
        `in catalog entry 'used' (routes.xosc:5:84): esmini does not support GeoPosition: its position reader has no GeoPosition and refuses the scenario ("Failed parse position in node Position") (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:1854-2259)`,
      ],
    ]);
    assert.deepEqual(await simulatorProblems(main(['plain'])), []);
    assert.deepEqual(
      (await semanticProblemsOf(used, files, 'asam')).filter((problem) => problem.code === 'simulator'),
      [],
    );
  });

  it("carla: the Storyboard's StopTrigger is warned of unless every Act's StopTrigger holds its group, attributes in any order", async () => {
    const group = (first: string, second: string) =>
      `<ConditionGroup><Condition ${first} ${second} conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="9" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup>`;
    const withStops = (actStop: string) =>
      scenarioText('0', '', LANE_CHANGE)
        .replace('</Act>', `${actStop}</Act>`)
        .replace('</Storyboard>', `<StopTrigger>${group('name="End"', 'delay="0"')}</StopTrigger></Storyboard>`);
    const ignored = async (text: string) =>
      (await semanticProblemsOf(text, {}, 'carla')).filter((problem) => problem.message.includes("ignores the Storyboard's StopTrigger"))
        .length;
    assert.equal(await ignored(withStops('')), 1);
    assert.equal(await ignored(withStops(`<StopTrigger>${group('delay="0"', 'name="End"')}</StopTrigger>`)), 0);
    assert.equal(await ignored(withStops(`<StopTrigger>${group('delay="1"', 'name="End"')}</StopTrigger>`)), 1);
  });

  it("carla: a maneuver catalog entry's Event priority is flagged on the reference of a scenario that uses it, not in the catalog", async () => {
    const catalog = overwritingManeuverCatalog({ used: ['e1', 'e2'], unused: ['e3', 'e4'] });
    const main = scenarioText('0', '', LANE_CHANGE)
      .replace(
        '<CatalogLocations/>',
        '<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>',
      )
      .replace(/<Maneuver name="maneuver">[^]*<\/Maneuver>/, '<CatalogReference catalogName="ManeuverCatalog" entryName="used"/>');
    const files = { 'catalogs/ManeuverCatalog.xosc': catalog };
    const priority = async (text: string) =>
      (await semanticProblemsOf(text, files, 'carla'))
        .filter((problem) => problem.message.includes('ignores Event priority'))
        .map((problem) => [problem.range.start.line, problem.message.replace(/: the events[^]*/, '')]);
    assert.deepEqual(await priority(catalog), []);
    const line = main.split('\n').findIndex((text) => text.includes('entryName="used"'));
    assert.deepEqual(await priority(main), [
      [line, "in catalog entry 'used' (ManeuverCatalog.xosc:5:54): CARLA ScenarioRunner ignores Event priority"],
      [line, "in catalog entry 'used' (ManeuverCatalog.xosc:5:460): CARLA ScenarioRunner ignores Event priority"],
    ]);
  });

  // esmini 3.6 measures an AngleCondition in lane coordinates against the lane's driving direction (test/server/esmini.test.ts runs it).
  it('esmini warns of coordinateSystem="lane" where it falls back to road coordinates, not on an AngleCondition nor a Euclidean distance', () => {
    const condition = (inner: string) =>
      `${VISIBILITY}</Action><StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="ego"/></TriggeringEntities><EntityCondition>${inner}</EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger><Action name="x">${VISIBILITY}`;
    const distance = (type: string) =>
      condition(
        `<RelativeDistanceCondition entityRef="ego" relativeDistanceType="${type}" value="5" freespace="false" rule="lessThan" coordinateSystem="lane"/>`,
      );
    assert.deepEqual(messages('esmini', scenarioText('3', '', distance('longitudinal'))), [
      'esmini does not support coordinateSystem="lane" on RelativeDistanceCondition: it falls back to road coordinates for lateral and longitudinal distances ("Lane coordinateSystem not supported yet") (osc_coverage.txt, EnvironmentSimulator/Modules/RoadManager/RoadManager.cpp:11837-11843, 11932-11938)',
    ]);
    assert.deepEqual(messages('esmini', scenarioText('3', '', distance('euclidianDistance'))), []);
    const angle = condition('<AngleCondition angleType="heading" angle="0" angleTolerance="0.1" coordinateSystem="lane"/>');
    assert.deepEqual(messages('esmini', scenarioText('3', '', angle)), []);
  });

  it("esmini: a catalog maneuver's steady state to a stop is an error on the reference that sets its final speed to 0, not in the catalog", async () => {
    const maneuver = (name: string) =>
      `<Maneuver name="${name}"><ParameterDeclarations><ParameterDeclaration name="Final" parameterType="double" value="0"/></ParameterDeclarations>` +
      `<Event name="e${name}" priority="override"><Action name="a${name}"><PrivateAction><SynchronizeAction masterEntityRef="ego"><TargetPositionMaster><WorldPosition x="10" y="0"/></TargetPositionMaster><TargetPosition><WorldPosition x="5" y="0"/></TargetPosition><FinalSpeed><AbsoluteSpeed value="$Final"><TargetTimeSteadyState time="1"/></AbsoluteSpeed></FinalSpeed></SynchronizeAction></PrivateAction></Action>` +
      '<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="rising"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver>';
    const catalog = `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="maneuvers" author="test"/>
  <Catalog name="ManeuverCatalog">
    ${maneuver('sync')}
    ${maneuver('unused')}
  </Catalog>
</OpenSCENARIO>
`;
    const main = (assignment: string) =>
      scenarioText('2', '', VISIBILITY)
        .replace(
          '<CatalogLocations/>',
          '<CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>',
        )
        .replace(
          /<Maneuver name="maneuver">[^]*<\/Maneuver>/,
          `<CatalogReference catalogName="ManeuverCatalog" entryName="sync">${assignment}</CatalogReference>`,
        );
    const files = { 'catalogs/ManeuverCatalog.xosc': catalog };
    const refusals = async (text: string) =>
      (await semanticProblemsOf(text, files, 'esmini'))
        .filter((problem) => problem.code === 'simulator')
        .map((problem) => [problem.range.start.line, problem.message]);
    assert.deepEqual(await refusals(catalog), []);
    const stopped = main('');
    const line = stopped.split('\n').findIndex((text) => text.includes('entryName="sync"'));
    assert.deepEqual(await refusals(stopped), [
      [
        line,
        'in catalog entry \'sync\' (ManeuverCatalog.xosc:5:429): esmini refuses a SynchronizeAction whose FinalSpeed is an AbsoluteSpeed of 0 or less with a steady state ("SynchronizeAction steady state with 0 or negative final speed is not supported"): a final speed of 0 with <TargetTimeSteadyState> (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:3269-3282)',
      ],
    ]);
    assert.deepEqual(
      await refusals(main('<ParameterAssignments><ParameterAssignment parameterRef="Final" value="5"/></ParameterAssignments>')),
      [],
    );
  });

  it('esmini refuses a SynchronizeAction steady state to a final AbsoluteSpeed of 0 or less, also set by a parameter: an error on the value', async () => {
    const synchronize = (speed: string, steady = '<TargetTimeSteadyState time="1"/>') =>
      `<PrivateAction><SynchronizeAction masterEntityRef="ego"><TargetPositionMaster><WorldPosition x="10" y="0"/></TargetPositionMaster><TargetPosition><WorldPosition x="5" y="0"/></TargetPosition><FinalSpeed><AbsoluteSpeed value="${speed}">${steady}</AbsoluteSpeed></FinalSpeed></SynchronizeAction></PrivateAction>`;
    const refusals = async (story: string, simulator: Simulator = 'esmini') =>
      (
        await semanticProblemsOf(
          scenarioText('2', '', story).replace(
            '<ParameterDeclarations/>',
            '<ParameterDeclarations><ParameterDeclaration name="Stop" parameterType="double" value="0"/></ParameterDeclarations>',
          ),
          {},
          simulator,
        )
      )
        .filter((problem) => problem.code === 'simulator')
        .map((problem) => [problem.severity, problem.range.start.line, problem.message]);
    const line = scenarioText('2', '', synchronize('0'))
      .split('\n')
      .findIndex((text) => text.includes('<AbsoluteSpeed'));
    assert.deepEqual(await refusals(synchronize('0')), [
      [
        'error',
        line,
        'esmini refuses a SynchronizeAction whose FinalSpeed is an AbsoluteSpeed of 0 or less with a steady state ("SynchronizeAction steady state with 0 or negative final speed is not supported"): a final speed of 0 with <TargetTimeSteadyState> (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:3269-3282)',
      ],
    ]);
    assert.equal((await refusals(synchronize('$Stop'))).length, 1);
    assert.deepEqual(await refusals(synchronize('5')), []);
    // esmini's SMALL_NUMBER is 1e-6 (CommonMini.hpp): a final speed below it is a stop to esmini, one above it is not.
    assert.equal((await refusals(synchronize('0.0000005'))).length, 1);
    assert.deepEqual(await refusals(synchronize('0.000002')), []);
    assert.deepEqual(await refusals(synchronize('0', '')), []);
    assert.deepEqual(await refusals(synchronize('0'), 'asam'), []);
  });

  it('esmini reads no ScenarioObject after an ExternalObjectReference: an error on each one the scenario references, none before it', async () => {
    const external = '<ScenarioObject name="far"><ExternalObjectReference name="elsewhere"/></ScenarioObject>';
    const text = (entities: string) => scenarioText('2', '', VISIBILITY).replace('<ScenarioObject name="ego"/>', entities);
    const found = async (entities: string) =>
      (await semanticProblemsOf(text(entities), {}, 'esmini'))
        .filter((problem) => problem.code === 'simulator' && problem.severity === 'error')
        .map((problem) => problem.message);
    assert.deepEqual(await found(`${external}<ScenarioObject name="ego"/><ScenarioObject name="idle"/>`), [
      `esmini stops reading the Entities at an ExternalObjectReference (parseEntities returns there), so a ScenarioObject after it does not exist for esmini, which refuses a reference to it ("Failed to find object"): 'ego' comes after 'far', and the scenario references it (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:1656-1660, 270-281)`,
    ]);
    assert.deepEqual(await found(`<ScenarioObject name="ego"/>${external}`), []);
  });

  // 76 of the ASAM OpenSCENARIO API's 158 test resources state 0.9; esmini 3.6 quits on each (exit 255).
  it('esmini refuses a scenario that states a version before 1.0: an error at its revMajor; a 0.9 catalog, 1.x and asam are silent', () => {
    const old = scenarioText('9', '', VISIBILITY).replace('revMajor="1"', 'revMajor="0"');
    const findings = simulatorFindings('esmini', parseXml(old), 'scenario.xosc');
    assert.deepEqual(
      findings.map((finding) => [finding.severity, finding.attribute?.name, simulatorWording(finding).message]),
      [
        [
          'error',
          'revMajor',
          'esmini runs OpenSCENARIO 1.0 or later; this file states 0.9, which it refuses ("OpenSCENARIO v0.9 not supported. Please migrate scenario to v1.0 or higher and try again.") (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioEngine.cpp:454-459)',
        ],
      ],
    );
    assert.deepEqual(messages('esmini', scenarioText('0', '', VISIBILITY)), []);
    assert.deepEqual(messages('asam', old), []);
    const catalog = `<?xml version="1.0"?>
<OpenSCENARIO><FileHeader revMajor="0" revMinor="9" date="2026-01-01T00:00:00" description="c" author="t"/><Catalog name="C"/></OpenSCENARIO>`;
    assert.deepEqual(messages('esmini', catalog), []);
  });

  it('every fact names the file it was read from, and each profile names its revision', () => {
    for (const profile of [CARLA_PROFILE, ESMINI_PROFILE]) {
      assert.match(profile.revision, /^[0-9a-f]{40}$/);
      for (const fact of [...profile.elements, ...profile.attributes])
        assert.ok(fact.source.length > 0, `${profile.name}: ${JSON.stringify(fact)}`);
    }
    for (const fact of [...Object.values(CARLA_FACTS), ...Object.values(ESMINI_FACTS)])
      assert.ok(/\S/.test(fact.source), JSON.stringify(fact));
  });

  it('reports findings of an imported group in the file the group was written in, and none without a simulator', async () => {
    const simple = scenarioText('0', '', VISIBILITY).replace('name="group"', 'name="Go"');
    const { root, flattener } = importingGo(simple);
    // Forced: the scenario has no road, which ScenarioRunner refuses (an error that blocks a flatten otherwise).
    const result = await flattener.flatten(diskRef(path.join(root, 'main.xosc')), { force: true });
    assert.ok(result.text, JSON.stringify(result.problems.map((problem) => problem.message)));
    const problems = result.problems.filter((problem) => problem.code === 'simulator');
    assert.equal(
      problems.filter((problem) => /VisibilityAction/.test(problem.message)).length,
      1,
      'reported once, though the source and the output are both checked',
    );
    const visibility = problems.find((problem) => /VisibilityAction/.test(problem.message));
    assert.ok(visibility, problems.map((problem) => problem.message).join('\n'));
    assert.equal(path.basename(visibility.source.disk), 'simple.xosc');
    const line = simple.split('\n').findIndex((text) => text.includes('<VisibilityAction'));
    assert.equal(visibility.range.start.line, line);
    assert.equal(visibility.severity, 'error');
    const standard = await new Flattener(new ScenarioStore({ scenarioPath: [], root })).flatten(diskRef(path.join(root, 'main.xosc')));
    assert.deepEqual(
      standard.problems.filter((problem) => problem.code === 'simulator'),
      [],
    );
  });

  it("a simulator's findings in an imported file outside the imported group are not the importer's (a library module's revMinor 1 under a 1.0 main)", async () => {
    // The source states 1.1 and marks no ego (ScenarioRunner refuses and warns, for that file run alone); its group Other,
    // not imported, holds a VisibilityAction; only the imported group's VisibilityAction reaches the main.
    const simple = scenarioText('1', '', VISIBILITY)
      .replace('name="group"', 'name="Go"')
      .replace(
        '</Act>',
        `  <ManeuverGroup name="Other" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
          <Maneuver name="m2"><Event name="e2" priority="overwrite"><Action name="a2">${VISIBILITY}</Action></Event></Maneuver>
        </ManeuverGroup>
      </Act>`,
      );
    const { root, flattener } = importingGo(simple);
    const alone = await flattener.flatten(diskRef(path.join(root, 'simple.xosc')), { force: true });
    assert.ok(
      alone.problems.some((problem) => /accepts only OpenSCENARIO 1\.0; this file states 1\.1/.test(problem.message)),
      'the source run alone is refused for its version',
    );
    const result = await flattener.flatten(diskRef(path.join(root, 'main.xosc')), { force: true });
    const messages = result.problems.map(
      (problem) => `${path.basename(problem.source.disk)}:${problem.range.start.line + 1}: ${problem.message}`,
    );
    const sourceErrors = result.problems.filter((problem) => problem.code === 'source-errors');
    // The one error that comes along: the imported group's VisibilityAction (not the version, the road or the other group's).
    assert.deepEqual(
      sourceErrors.map((problem) => problem.message.replace(/:.*/s, '')),
      ["'simple.xosc' has 1 error"],
      messages.join('\n'),
    );
    const inSource = result.problems.filter(
      (problem) => problem.code === 'simulator' && path.basename(problem.source.disk) === 'simple.xosc',
    );
    const imported = simple.split('\n').findIndex((text) => text.includes('<VisibilityAction'));
    assert.deepEqual(
      inSource.map((problem) => problem.range.start.line),
      [imported],
      messages.join('\n'),
    );
    assert.equal(inSource[0].severity, 'error');
  });

  it('checks the flattened output too: a value set through a ParameterReference is reported where it is written', async () => {
    const body = `              <Action name="Change">
                <LaneChangeActionDynamics parameterAttributes="dynamicsShape" dynamicsShape="linear" value="2" dynamicsDimension="time"/>
              </Action>
`;
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go', body)),
      'main.xosc': scenario(
        outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['dynamicsShape', 'sinusoidal']] }] }]),
      ),
    });
    const result = await new Flattener(new ScenarioStore({ scenarioPath: [], root }), 'carla').flatten(
      diskRef(path.join(root, 'main.xosc')),
      {
        force: true,
      },
    );
    assert.ok(result.text, JSON.stringify(result.problems.map((problem) => problem.message)));
    const shape = result.problems.filter((problem) => problem.code === 'simulator' && /dynamicsShape/.test(problem.message));
    assert.equal(shape.length, 1, JSON.stringify(result.problems.map((problem) => problem.message)));
    assert.match(shape[0].message, /dynamicsShape="sinusoidal" on LaneChangeActionDynamics/);
    assert.equal(path.basename(shape[0].source.disk), 'simple.xosc');
  });
});

describe('simulator profiles on the corpus files each simulator runs', function () {
  const corpus = path.join(sharedDir, 'corpus', 'openscenario');
  before(function () {
    if (!fs.existsSync(corpus)) {
      console.log(`    (skipped: ${corpus} is absent)`);
      this.skip();
    }
  });

  const walk = (folder: string): string[] =>
    fs.readdirSync(folder, { withFileTypes: true }).flatMap((entry) => {
      const full = path.join(folder, entry.name);
      if (entry.isDirectory()) return walk(full);
      return /\.xosc$/i.test(entry.name) ? [full] : [];
    });

  for (const [simulator, folder] of [
    ['carla', 'scenario_runner'],
    ['esmini', 'esmini'],
  ] as const) {
    it(`${simulator} warns about nothing that its own example scenarios (${folder}) use`, () => {
      const files = walk(path.join(corpus, folder));
      assert.ok(files.length >= 20, `found only ${files.length} files`);
      const found: string[] = [];
      for (const file of files) {
        // 0.9.15: the release before the route-action regression, which two of CARLA's examples hit in 0.9.16.
        for (const finding of simulatorFindings(simulator, parseXml(fs.readFileSync(file, 'utf8')), path.basename(file), '0.9.15')) {
          found.push(`${path.relative(corpus, file)}: ${simulatorWording(finding).message}`);
        }
      }
      // No exceptions are needed: SceneGraphFile, which CARLA ignores but which changes nothing the scenario
      // does, is not a fact of the profile, and the 0.9 headers of CARLA's own catalogs are not checked
      // because CARLA checks the version of the scenario only (openscenario_configuration.py).
      assert.deepEqual(found, []);
    });
  }

  it('carla 0.9.16 finds the route-action crash in two of its own examples, and nothing else', () => {
    const found = walk(path.join(corpus, 'scenario_runner')).flatMap((file) =>
      simulatorFindings('carla', parseXml(fs.readFileSync(file, 'utf8')), path.basename(file)).map(
        (finding) => `${path.basename(file)}: ${finding.severity} ${finding.element.name}`,
      ),
    );
    assert.deepEqual(found, [
      'IntersectionCollisionAvoidance.xosc: error AcquirePositionAction',
      'SyncArrivalIntersection.xosc: error AcquirePositionAction',
    ]);
  });

  it('carla reports no error in the modular library written for CARLA 0.9.15, flattened as CARLA gets it, and the route-action crash under 0.9.16', async function () {
    const library = path.join(sharedDir, 'corpus', 'modular2simple', 'library');
    const mains = fs
      .readdirSync(library)
      .filter((name) => name.startsWith('modular_'))
      .map((name) => path.join(library, name, 'main.xosc'));
    assert.ok(mains.length >= 30);
    const store = new ScenarioStore({ scenarioPath: [library], root: library });
    const older = new Flattener(store, 'carla', undefined, undefined, '0.9.15');
    const latest = new Flattener(store, 'carla');
    for (const main of mains) {
      const result = await older.flatten(diskRef(main));
      assert.ok(result.text, main);
      assert.deepEqual(
        result.problems.filter((problem) => problem.severity === 'error').map((problem) => problem.message),
        [],
        main,
      );
      const crashes = (await latest.flatten(diskRef(main))).problems.filter((problem) => problem.severity === 'error');
      assert.ok(crashes.length > 0, main);
      assert.ok(
        crashes.every((problem) => /does not support (AcquirePositionAction|AssignRouteAction): .*ab5996d7/.test(problem.message)),
        crashes.map((problem) => problem.message).join('\n'),
      );
    }
  });

  it('carla finds what CARLA does not run in esmini scenarios (the checks are not vacuous)', () => {
    const files = walk(path.join(corpus, 'esmini'));
    const messages = files.flatMap((file) =>
      simulatorFindings('carla', parseXml(fs.readFileSync(file, 'utf8')), path.basename(file)).map(
        (finding) => simulatorWording(finding).message,
      ),
    );
    assert.ok(messages.some((message) => /accepts only OpenSCENARIO 1\.0; this file states 1\.[123]/.test(message)));
    assert.ok(messages.some((message) => /does not support RoutePosition/.test(message)));
  });
});

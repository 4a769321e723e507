import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { SceneParams, SceneRequest } from '../../common/src/sceneProtocol';
import { outerGroup } from '../support/fixtures';
import { sceneScenario, STRAIGHT_ROAD, teleport } from '../support/roads';
import { fileUri, TestClient } from './harness';
import { positionAfter } from '../support/cursor';
import { temporaryWorkspace } from '../support/workspace';

const SIMPLE = sceneScenario(
  'straight.xodr',
  '',
  `<Story name="S"><Act name="A"><ManeuverGroup name="Simple" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="ego"/></Actors>
  <Maneuver name="M"><Event name="Brake" priority="overwrite"><Action name="a"/><StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="3" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver>
  </ManeuverGroup></Act></Story>`,
);
const MAIN = sceneScenario(
  'straight.xodr',
  teleport('ego', '<LanePosition roadId="1" laneId="-1" s="$EgoS"/>') +
    teleport('other', '<RelativeLanePosition entityRef="ego" dLane="0" ds="15"/>'),
  `<Story name="S"><Act name="A">\n${outerGroup('Outer', 'ego', [{ file: 'simple.xosc', groups: [{ name: 'Simple' }] }])}</Act></Story>`,
  '<ParameterDeclaration name="EgoS" parameterType="double" value="40"/>',
);

const ROUTES = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO><FileHeader revMajor="1" revMinor="1" date="2026-01-01T00:00:00" description="routes" author="test"/>
  <Catalog name="StraightRoutes"><Route name="Along" closed="false">
    <ParameterDeclarations><ParameterDeclaration name="From" parameterType="double" value="10"/></ParameterDeclarations>
    <Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1" s="$From"/></Position></Waypoint>
    <Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1" s="190"/></Position></Waypoint>
  </Route></Catalog>
</OpenSCENARIO>
`;
const ON_ROUTE = teleport(
  'third',
  '<RoutePosition><RouteRef><CatalogReference catalogName="StraightRoutes" entryName="Along"><ParameterAssignments><ParameterAssignment parameterRef="From" value="20"/></ParameterAssignments></CatalogReference></RouteRef><InRoutePosition><FromLaneCoordinates pathS="30" laneId="-1"/></InRoutePosition></RoutePosition>',
);
const VEHICLES = `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO><FileHeader revMajor="1" revMinor="1" date="2026-01-01T00:00:00" description="vehicles" author="test"/>
  <Catalog name="VehicleCatalog"><Vehicle name="car_red" vehicleCategory="car"/></Catalog>
</OpenSCENARIO>
`;
// With catalog locations given, the fixture's car_red must be found too (else the scenario does not flatten).
const withRoutes = (scenario: string) =>
  scenario.replace(
    '<RoadNetwork>',
    '<CatalogLocations><VehicleCatalog><Directory path="Vehicles"/></VehicleCatalog><RouteCatalog><Directory path="Routes"/></RouteCatalog></CatalogLocations><RoadNetwork>',
  );
/** A scenario read as written, and one flattened (it imports simple.xosc), each placing an entity on a catalog route. */
const PLAIN_ROUTE = withRoutes(sceneScenario('straight.xodr', ON_ROUTE));
const MODULAR_ROUTE = withRoutes(MAIN.replace('</Actions></Init>', `${ON_ROUTE}</Actions></Init>`));

describe('language server: modular2simple/scene (JSON-RPC)', function () {
  let root: string;
  let client: TestClient;

  before(async function () {
    const zip = new JSZip();
    zip.file('main.xosc', MAIN);
    zip.file('simple.xosc', SIMPLE);
    root = temporaryWorkspace(
      {
        'roads/straight.xodr': STRAIGHT_ROAD,
        'main.xosc': MAIN,
        'simple.xosc': SIMPLE,
        'Routes/StraightRoutes.xosc': ROUTES,
        'Vehicles/VehicleCatalog.xosc': VEHICLES,
        'plainRoute.xosc': PLAIN_ROUTE,
        'modularRoute.xosc': MODULAR_ROUTE,
        'packed/pkg.mosc': await zip.generateAsync({ type: 'uint8array' }),
        'packed/straight.xodr': STRAIGHT_ROAD,
      },
      'm2s-server-',
    );
    client = await TestClient.start({ root });
    await client.indexed();
  });

  after(async function () {
    await client?.stop();
    if (root) fs.rmSync(root, { recursive: true, force: true });
  });

  const scene = (params: SceneParams) => client.connection.sendRequest(SceneRequest, params);

  it('answers roads as lane-border polylines, entities at their start and events at their source', async () => {
    const mainUri = fileUri(path.join(root, 'main.xosc'));
    const result = await scene({ uri: mainUri, roadPath: ['roads'] });
    assert.deepEqual(result.problems, []);
    assert.equal(result.roadFile?.resolved, path.join(root, 'roads', 'straight.xodr'));
    assert.equal(result.roadFile?.roadCount, 1);
    assert.equal(result.sections.length, 1);
    assert.deepEqual(
      result.sections[0].lanes.map((lane) => lane.id),
      [1, 0, -1, -2],
    );
    const [ego, other] = result.entities;
    assert.deepEqual([ego.name, ego.x, ego.y], ['ego', 40, -1.75]);
    assert.deepEqual([other.x, other.y], [55, -1.75]);
    // The entity opens at its TeleportAction's position; the event, imported by flattening, in the simple scenario.
    assert.deepEqual(ego.source, { uri: mainUri, ...positionAfter(MAIN, '<Private entityRef="ego"><PrivateAction><TeleportAction>') });
    assert.equal(result.events.length, 1);
    assert.deepEqual([result.events[0].name, result.events[0].group, result.events[0].plannedTime], ['Brake', 'Outer.Simple', 3]);
    assert.deepEqual(result.events[0].source, { uri: fileUri(path.join(root, 'simple.xosc')), ...positionAfter(SIMPLE, '<Event name="') });
  });

  it('reads a road file again when it changed on disk', async () => {
    const road = path.join(root, 'roads', 'straight.xodr');
    const mainUri = fileUri(path.join(root, 'main.xosc'));
    fs.writeFileSync(
      road,
      STRAIGHT_ROAD.replace('<width sOffset="0" a="2" b="0" c="0" d="0"/>', '<width sOffset="0" a="3" b="0" c="0" d="0"/>'),
    );
    try {
      const widened = await scene({ uri: mainUri, roadPath: ['roads'] });
      assert.equal(widened.sections[0].borders[3][1], -6.5);
    } finally {
      fs.writeFileSync(road, STRAIGHT_ROAD);
    }
    assert.equal((await scene({ uri: mainUri, roadPath: ['roads'] })).sections[0].borders[3][1], -5.5);
  });

  it('uses unsaved edits and says where it looked for a missing road file', async () => {
    const mainUri = fileUri(path.join(root, 'main.xosc'));
    await client.open(mainUri, MAIN.replace('value="40"', 'value="70"'));
    try {
      const moved = await scene({ uri: mainUri, roadPath: ['roads'] });
      assert.equal(moved.entities[0].x, 70);
      const missing = await scene({ uri: mainUri });
      assert.equal(missing.sections.length, 0);
      assert.match(
        missing.problems.join('\n'),
        /road file "straight.xodr" not found; looked for .*m2s-server.*straight\.xodr.*modular2simple\.esmini\.roadPath/s,
      );
      assert.match(missing.problems.join('\n'), /ego: the road network is not loaded/);
    } finally {
      await client.close(mainUri);
    }
  });

  it('works for a scenario inside a .mosc: the road file is found beside the package', async () => {
    const uri = `mosc:${path.join(root, 'packed', 'pkg.mosc')}/main.xosc`;
    const result = await scene({ uri });
    assert.deepEqual(result.problems, []);
    assert.equal(result.roadFile?.resolved, path.join(root, 'packed', 'straight.xodr'));
    assert.equal(result.entities[0].x, 40);
    assert.equal(result.events[0].source?.uri, `mosc:${path.join(root, 'packed', 'pkg.mosc')}/simple.xosc`);
  });

  it('places an entity on a Route from a catalog, in a scenario as written and in a flattened one', async () => {
    for (const file of ['plainRoute.xosc', 'modularRoute.xosc']) {
      const result = await scene({ uri: fileUri(path.join(root, file)), roadPath: ['roads'] });
      const third = result.entities.find((entity) => entity.name === 'third');
      assert.deepEqual(result.problems, [], file);
      // 30 m along the route from s 20 (the reference's assignment) on lane -1.
      assert.deepEqual([third?.x, third?.y, third?.problem], [50, -1.75, undefined], file);
    }
  });

  it('answers an error for what is not a scenario', async () => {
    await assert.rejects(scene({ uri: 'https://example.com/x.xosc' }), /not a scenario URI/);
  });
});

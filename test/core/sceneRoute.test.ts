import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { scenarioScene } from '../../server/src/core/scene';
import { analyzeDocument, CatalogLoader } from '../../server/src/core/semantics';
import { diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { esminiXodrDir } from '../support/esminiBinaries';
import { requireEsmini, runEsmini } from '../support/esmini';
import { sceneScenario, STRAIGHT_ROAD, teleport } from '../support/roads';
import { temporaryFolder } from '../support/temporaryDirectory';

const close = (actual: number | undefined, expected: number, what: string) =>
  assert.ok(actual !== undefined && Math.abs(actual - expected) < 1e-6, `${what}: ${actual} is not ${expected}`);

const waypoint = (position: string) => `<Waypoint routeStrategy="shortest"><Position>${position}</Position></Waypoint>`;

function routePosition(route: string, inRoute: string): string {
  return `<RoutePosition><RouteRef>${route}</RouteRef><InRoutePosition>${inRoute}</InRoutePosition></RoutePosition>`;
}

const VEHICLE = `<Vehicle name="car" vehicleCategory="car"><Performance maxSpeed="69" maxAcceleration="10" maxDeceleration="10"/>
  <BoundingBox><Center x="1.4" y="0" z="0.8"/><Dimensions width="2" length="5" height="1.5"/></BoundingBox>
  <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.7" positionX="2.9" positionZ="0.4"/><RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.7" positionX="0" positionZ="0.4"/></Axles><Properties/></Vehicle>`;

describe('core: scene, entities placed by RoutePosition', function () {
  this.timeout(60_000);
  const network = parseOpenDrive(STRAIGHT_ROAD);

  it('reads FromLaneCoordinates and FromRoadCoordinates along an inline route, in the direction of its first lane', () => {
    const right = `<Route name="R" closed="false">${waypoint('<LanePosition roadId="1" laneId="-1" s="$From"/>')}${waypoint('<LanePosition roadId="1" laneId="-1" s="180"/>')}</Route>`;
    const left = `<Route name="L" closed="false">${waypoint('<LanePosition roadId="1" laneId="1" s="150"/>')}${waypoint('<LanePosition roadId="1" laneId="1" s="20"/>')}</Route>`;
    const text = sceneScenario(
      'straight.xodr',
      teleport('ego', routePosition(right, '<FromLaneCoordinates pathS="$PathS" laneId="-1" laneOffset="0.5"/>')) +
        teleport('other', routePosition(right, '<FromRoadCoordinates pathS="5" t="2"/>')) +
        teleport('third', routePosition(left, '<FromLaneCoordinates pathS="30" laneId="1"/>')),
      '',
      '<ParameterDeclaration name="From" parameterType="double" value="10"/><ParameterDeclaration name="PathS" parameterType="double" value="${$From + 15}"/>',
    );
    const [ego, other, third] = scenarioScene(parseXml(text), network).entities;
    assert.deepEqual([ego.problem, other.problem, third.problem], [undefined, undefined, undefined]);
    // 25 m along from s 10; lane -1 center at -1.75, offset 0.5 to the left.
    close(ego.x, 35, 'lane x');
    close(ego.y, -1.25, 'lane y');
    close(ego.hdg, 0, 'lane heading');
    assert.match(ego.described, /RoutePosition R, pathS 25, lane -1 \(road 1, s 35\)/);
    close(other.x, 15, 'road x');
    close(other.y, 2, 'road y');
    // A route that starts in a left lane runs against the reference line.
    close(third.x, 120, 'left x');
    close(third.y, 1.75, 'left y');
    close(third.hdg, Math.PI, 'left heading');
  });

  it('says why a route position cannot be placed: past the first road, from the current entity, an unresolved catalog route', () => {
    const twoRoads = `<Route name="R" closed="false">${waypoint('<LanePosition roadId="1" laneId="-1" s="190"/>')}${waypoint('<LanePosition roadId="2" laneId="-1" s="5"/>')}</Route>`;
    const twoRoadNetwork = parseOpenDrive(
      STRAIGHT_ROAD.replace(
        '</OpenDRIVE>',
        STRAIGHT_ROAD.slice(STRAIGHT_ROAD.indexOf('<road '), STRAIGHT_ROAD.indexOf('</road>') + 7).replace('id="1"', 'id="2"') +
          '</OpenDRIVE>',
      ),
    );
    const text = sceneScenario(
      'straight.xodr',
      teleport('ego', routePosition(twoRoads, '<FromLaneCoordinates pathS="15" laneId="-1"/>')) +
        teleport('other', routePosition(twoRoads, '<FromCurrentEntity entityRef="ego"/>')) +
        teleport(
          'third',
          routePosition('<CatalogReference catalogName="Routes" entryName="Nowhere"/>', '<FromLaneCoordinates pathS="0" laneId="-1"/>'),
        ),
    );
    const [ego, other, third] = scenarioScene(parseXml(text), twoRoadNetwork).entities;
    assert.match(ego.problem ?? '', /pathS 15 lies past road 1, 10 m along the route; the roads between its waypoints need routing/);
    assert.match(other.problem ?? '', /FromCurrentEntity is not evaluated/);
    assert.match(third.problem ?? '', /route Routes\/Nowhere is not found in the catalogs/);
    // Within the first road the same route places it.
    const near = scenarioScene(
      parseXml(sceneScenario('straight.xodr', teleport('ego', routePosition(twoRoads, '<FromLaneCoordinates pathS="8" laneId="-1"/>')))),
      twoRoadNetwork,
    );
    close(near.entities[0].x, 198, 'x near the road end');
  });

  it('on a real esmini run: routes from a catalog (with a parameter assigned) start where esmini starts them, within 1 cm', async function () {
    requireEsmini(this);
    const folder = temporaryFolder('m2s-route-');
    try {
      fs.mkdirSync(path.join(folder, 'Routes'));
      fs.writeFileSync(
        path.join(folder, 'Routes', 'FabriksgatanRoutes.xosc'),
        `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO><FileHeader revMajor="1" revMinor="1" date="2026-11-22T00:00:00" description="routes" author="modular2simple tests"/>
  <Catalog name="FabriksgatanRoutes">
    <Route name="LeftTurn" closed="false">
      <ParameterDeclarations><ParameterDeclaration name="StartS" parameterType="double" value="20"/></ParameterDeclarations>
      ${waypoint('<LanePosition roadId="2" laneId="-1" offset="0" s="$StartS"/>')}${waypoint('<LanePosition roadId="1" laneId="-1" offset="0" s="5"/>')}
    </Route>
  </Catalog>
</OpenSCENARIO>
`,
      );
      const inline = `<Route name="Straight" closed="false">${waypoint('<LanePosition roadId="0" laneId="1" offset="0" s="63"/>')}${waypoint('<LanePosition roadId="2" laneId="1" offset="0" s="5"/>')}</Route>`;
      const scenario = path.join(folder, 'route.xosc');
      fs.writeFileSync(
        scenario,
        `<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-11-22T00:00:00" description="RoutePosition start positions" author="modular2simple tests"/>
  <ParameterDeclarations><ParameterDeclaration name="PathS" parameterType="double" value="150"/></ParameterDeclarations>
  <CatalogLocations><RouteCatalog><Directory path="Routes"/></RouteCatalog></CatalogLocations>
  <RoadNetwork><LogicFile filepath="fabriksgatan.xodr"/></RoadNetwork>
  <Entities>
    <ScenarioObject name="Ego">${VEHICLE}</ScenarioObject>
    <ScenarioObject name="Npc">${VEHICLE}</ScenarioObject>
    <ScenarioObject name="Side">${VEHICLE}</ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions>
      ${teleport('Ego', routePosition(inline, '<FromLaneCoordinates pathS="12" laneId="1" laneOffset="0.3"/>'))}
      ${teleport('Npc', routePosition('<CatalogReference catalogName="FabriksgatanRoutes" entryName="LeftTurn"><ParameterAssignments><ParameterAssignment parameterRef="StartS" value="100"/></ParameterAssignments></CatalogReference>', '<FromLaneCoordinates pathS="$PathS" laneId="-1"/>'))}
      ${teleport('Side', routePosition('<CatalogReference catalogName="FabriksgatanRoutes" entryName="LeftTurn"/>', '<FromRoadCoordinates pathS="40" t="-3"/>'))}
    </Actions></Init>
    <StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0.1" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
  </Storyboard>
</OpenSCENARIO>
`,
      );
      const [first] = await runEsmini(scenario, 0);
      const document = parseXml(fs.readFileSync(scenario, 'utf8'));
      const semantics = await analyzeDocument(
        diskRef(scenario),
        document,
        new CatalogLoader(new ScenarioStore({ scenarioPath: [], root: folder })),
        false,
      );
      const roads = parseOpenDrive(fs.readFileSync(path.join(esminiXodrDir, 'fabriksgatan.xodr'), 'utf8'));
      const scene = scenarioScene(document, roads, semantics);
      assert.match(scene.entities[1].described, /road 2, s 250/);
      for (const entity of scene.entities) {
        assert.equal(entity.problem, undefined, entity.name);
        const [x, y] = first.positions[entity.name];
        const distance = Math.hypot((entity.x ?? NaN) - x, (entity.y ?? NaN) - y);
        assert.ok(distance < 0.01, `${entity.name}: (${entity.x}, ${entity.y}) vs esmini (${x}, ${y})`);
      }
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});

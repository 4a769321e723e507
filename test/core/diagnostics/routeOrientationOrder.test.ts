import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { SIMULATOR } from '../../../server/src/core/diagnostics/simulator';
import { esminiRoads, requireEsmini, runEsmini, tracksOf } from '../../support/esmini';
import { catalogFile, element, fileHeader, scenarioDocument, vehicleObject } from '../../support/fixtures';
import { temporaryFolder } from '../../support/temporaryDirectory';
import { applyEdits } from '../../support/textEdits';
import { fixContext, semanticProblemsOf } from './support';

/** A 1.3 scenario on esmini's straight_500m.xodr: Car placed by a RoutePosition (lane -1, 100 m along), turned by `orientation` written after its InRoutePosition, at 10 m/s. */
function routePositionScenario(orientation: string): string {
  const waypoint = (s: number) =>
    `<Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1" s="${s}" offset="0"/></Position></Waypoint>`;
  const init = `      <Actions>
        <Private entityRef="Car">
          <PrivateAction><TeleportAction><Position>
            <RoutePosition>
              <RouteRef><Route name="Along" closed="false">${waypoint(10)}${waypoint(400)}</Route></RouteRef>
              <InRoutePosition><FromLaneCoordinates pathS="100" laneId="-1"/></InRoutePosition>
              ${orientation}
            </RoutePosition>
          </Position></TeleportAction></PrivateAction>
          <PrivateAction><LongitudinalAction><SpeedAction>
            <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
            <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget>
          </SpeedAction></LongitudinalAction></PrivateAction>
        </Private>
      </Actions>
`;
  const stop = `    <StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="none">
      <ByValueCondition><SimulationTimeCondition value="2" rule="greaterThan"/></ByValueCondition>
    </Condition></ConditionGroup></StopTrigger>
`;
  return scenarioDocument({
    header: fileHeader({ revMinor: '3' }),
    parameters: '',
    catalogLocations: '',
    roadNetwork: `    <LogicFile filepath="${path.join(esminiRoads, 'straight_500m.xodr')}"/>\n`,
    entities: vehicleObject('Car'),
    storyboard: element('Init', init, 4) + stop,
  });
}

const TURNED = '<Orientation h="3.14159" type="relative"/>';

describe("diagnostics: simulator (esmini), a RoutePosition's Orientation after its InRoutePosition", () => {
  it('is a warning at the Orientation naming the source lines, fixed by moving it before the InRoutePosition (Euro NCAP CBFA has one)', async () => {
    const text = routePositionScenario(TURNED);
    const problems = (await semanticProblemsOf(text, {}, 'esmini')).filter((problem) => problem.code === 'simulator');
    assert.deepEqual(
      problems.map(({ severity, message }) => ({ severity, message })),
      [
        {
          severity: 'warning',
          message:
            "esmini applies a RoutePosition's Orientation only to an InRoutePosition it reads after it (it reads the children in the order written; the standard lets them stand in any order), so an Orientation written after the InRoutePosition is dropped (the entity then faces along the route; in a lane of positive id, against it): this <Orientation> comes after <InRoutePosition> (EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/ScenarioReader.cpp:2102-2212)",
        },
      ],
    );
    const [problem] = problems;
    assert.equal(text.split('\n')[problem.range.start.line].trim(), TURNED);
    const fixes = (await SIMULATOR.fixes?.(fixContext(problem.data, undefined, text, problem.range))) ?? [];
    assert.deepEqual(
      fixes.map((fix) => fix.title),
      ['Move <Orientation> before <InRoutePosition>'],
    );
    const fixed = applyEdits(text, fixes[0].edits);
    assert.match(
      fixed,
      /<\/RouteRef>\n {14}<Orientation h="3\.14159" type="relative"\/>\n {14}<InRoutePosition><FromLaneCoordinates pathS="100" laneId="-1"\/><\/InRoutePosition>\n {12}<\/RoutePosition>/,
    );
    assert.deepEqual(
      (await semanticProblemsOf(fixed, {}, 'esmini')).filter((problem) => problem.code === 'simulator'),
      [],
    );
    // Before it, or for another simulator, nothing is said.
    assert.deepEqual(
      (await semanticProblemsOf(text, {})).filter((problem) => problem.code === 'simulator'),
      [],
    );
  });

  it('in a catalog entry, it is found on the CatalogReference that uses the entry (without the fix, which would be in the catalog), not in the catalog', async () => {
    const route = `<RoutePosition><RouteRef><Route name="Along" closed="false"><Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1" s="10"/></Position></Waypoint><Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1" s="400"/></Position></Waypoint></Route></RouteRef><InRoutePosition><FromLaneCoordinates pathS="100" laneId="-1"/></InRoutePosition>${TURNED}</RoutePosition>`;
    const maneuver = (name: string) =>
      `<Maneuver name="${name}"><Event name="e${name}" priority="override"><Action name="a${name}"><PrivateAction><TeleportAction><Position>${route}</Position></TeleportAction></PrivateAction></Action>` +
      '<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver>';
    const catalog = catalogFile('ManeuverCatalog', `    ${maneuver('turned')}\n    ${maneuver('unused')}\n`);
    const group = `      <Act name="A">
        <ManeuverGroup name="G" maximumExecutionCount="1">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Car"/></Actors>
          <CatalogReference catalogName="ManeuverCatalog" entryName="turned"/>
        </ManeuverGroup>
        <StartTrigger/>
      </Act>
`;
    const main = scenarioDocument({
      header: fileHeader({ revMinor: '3' }),
      parameters: '',
      catalogLocations: '    <ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog>\n',
      roadNetwork: `    <LogicFile filepath="${path.join(esminiRoads, 'straight_500m.xodr')}"/>\n`,
      entities: vehicleObject('Car'),
      storyboard: element('Init', element('Actions', '', 6), 4) + element('Story', group, 4, ' name="S"') + '    <StopTrigger/>\n',
    });
    const files = { 'catalogs/ManeuverCatalog.xosc': catalog };
    const found = async (text: string) =>
      (await semanticProblemsOf(text, files, 'esmini')).filter((problem) => problem.code === 'simulator');
    assert.deepEqual(await found(catalog), []);
    const [onReference, ...more] = await found(main);
    assert.deepEqual(more, []);
    assert.match(main.split('\n')[onReference.range.start.line], /<CatalogReference catalogName="ManeuverCatalog" entryName="turned"\/>/);
    assert.match(
      onReference.message,
      /^in catalog entry 'turned' \(ManeuverCatalog\.xosc:\d+:\d+\): esmini applies a RoutePosition's Orientation only/,
    );
    assert.equal(onReference.data, undefined);
  });

  it('is what esmini does: the car written so drives along the route, the fixed one against it', async function () {
    requireEsmini(this);
    const folder = temporaryFolder('m2s-route-orientation-');
    try {
      const directionOf = async (name: string, text: string): Promise<number> => {
        const file = path.join(folder, name);
        fs.writeFileSync(file, text);
        const track = tracksOf(await runEsmini(file, 2)).get('Car') ?? [];
        assert.ok(track.length > 10, `${name}: ${track.length} steps`);
        return Math.sign(track[track.length - 1].x - track[0].x);
      };
      const text = routePositionScenario(TURNED);
      const [problem] = (await semanticProblemsOf(text, {}, 'esmini')).filter((each) => each.code === 'simulator');
      const [fix] = (await SIMULATOR.fixes?.(fixContext(problem.data, undefined, text, problem.range))) ?? [];
      assert.equal(await directionOf('after.xosc', text), 1);
      assert.equal(await directionOf('before.xosc', applyEdits(text, fix.edits)), -1);
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});

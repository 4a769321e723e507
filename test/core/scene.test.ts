import * as assert from 'node:assert/strict';
import { parseOpenDrive } from '../../server/src/core/opendrive/road';
import { sampleNetwork } from '../../server/src/core/opendrive/sample';
import { scenarioScene } from '../../server/src/core/scene';
import { parseXml } from '../../server/src/core/xml';
import { sceneScenario, STRAIGHT_ROAD, teleport } from '../support/roads';

const close = (actual: number | undefined, expected: number, what: string) =>
  assert.ok(actual !== undefined && Math.abs(actual - expected) < 1e-6, `${what}: ${actual} is not ${expected}`);

const STORY = `<Story name="S"><Act name="A"><ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"/>
  <Maneuver name="M">
    <Event name="Go" priority="override"><Action name="a"/><StartTrigger><ConditionGroup><Condition name="c" delay="0.5" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="$Start" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
    <Event name="Near" priority="override"><Action name="b"/><StartTrigger><ConditionGroup><Condition name="d" delay="0" conditionEdge="rising"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any"/><EntityCondition><RelativeDistanceCondition value="10" rule="lessThan"/></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger></Event>
  </Maneuver></ManeuverGroup></Act></Story>`;

describe('core: scene of a scenario (entities at their start, events)', () => {
  const network = parseOpenDrive(STRAIGHT_ROAD);

  it('evaluates LanePosition with $parameters, RelativeLanePosition and RelativeObjectPosition against the road', () => {
    const text = sceneScenario(
      'straight.xodr',
      teleport('ego', '<LanePosition roadId="1" laneId="$Lane" s="$S" offset="0.25"/>') +
        teleport('other', '<RelativeLanePosition entityRef="ego" dLane="1" ds="20" offset="0"/>') +
        teleport('third', '<RelativeObjectPosition entityRef="ego" dx="-10" dy="2"/>'),
      STORY,
      '<ParameterDeclaration name="S" parameterType="double" value="30"/><ParameterDeclaration name="Lane" parameterType="int" value="-1"/><ParameterDeclaration name="Start" parameterType="double" value="$S"/>',
    );
    const scene = scenarioScene(parseXml(text), network);
    assert.equal(scene.logicFile?.filepath, 'straight.xodr');
    const [ego, other, third] = scene.entities;
    // Lane -1 center is 1.75 m right of the reference line; offset 0.25 to the left.
    close(ego.x, 30, 'ego x');
    close(ego.y, -1.5, 'ego y');
    close(ego.hdg, 0, 'ego heading');
    assert.equal(ego.length, 5);
    assert.equal(ego.centerX, 1.5);
    // One lane to the left of lane -1 is lane 1 (lane 0 is skipped), 20 m ahead.
    close(other.x, 50, 'other x');
    close(other.y, 1.75, 'other y');
    assert.match(other.kind, /car_red \(catalog\)/);
    close(third.x, 20, 'third x');
    close(third.y, 0.5, 'third y');
    assert.deepEqual(
      scene.entities.map((entity) => entity.problem),
      [undefined, undefined, undefined],
    );
    assert.deepEqual(
      scene.events.map((event) => [event.name, event.maneuver, event.group, event.act, event.plannedTime]),
      [
        ['Go', 'M', 'G', 'A', 30.5],
        ['Near', 'M', 'G', 'A', undefined],
      ],
    );
    assert.equal(scene.events[1].trigger, 'RelativeDistance lessThan 10');
  });

  it('WorldPosition, RoadPosition and RelativeWorldPosition; a left lane faces against the reference line', () => {
    const text = sceneScenario(
      'straight.xodr',
      teleport('ego', '<WorldPosition x="5" y="6" h="1"/>') +
        teleport('other', '<RoadPosition roadId="1" s="100" t="-3"/>') +
        teleport('third', '<RelativeWorldPosition entityRef="ego" dx="1" dy="-1"/>'),
    );
    const [ego, other, third] = scenarioScene(parseXml(text), network).entities;
    close(ego.x, 5, 'x');
    close(ego.hdg, 1, 'h');
    close(other.x, 100, 'road x');
    close(other.y, -3, 'road y');
    close(third.x, 6, 'relative x');
    close(third.y, 5, 'relative y');
    const left = scenarioScene(
      parseXml(sceneScenario('straight.xodr', teleport('ego', '<LanePosition roadId="1" laneId="1" s="10"/>'))),
      network,
    ).entities[0];
    close(left.hdg, Math.PI, 'left lane heading');
  });

  it('evaluates ${...} expressions in positions through the semantic model', () => {
    const text = sceneScenario(
      'straight.xodr',
      teleport('ego', '<LanePosition roadId="1" laneId="-1" s="${$Half + 5}"/>'),
      '',
      '<ParameterDeclaration name="S" parameterType="double" value="30"/><ParameterDeclaration name="Half" parameterType="double" value="${$S / 2}"/>',
    );
    assert.equal(scenarioScene(parseXml(text), network).entities[0].x, 20);
  });

  it('says why a position cannot be placed instead of guessing', () => {
    const text = sceneScenario(
      'straight.xodr',
      teleport('ego', '<LanePosition roadId="9" laneId="-1" s="10"/>') +
        teleport('other', '<LanePosition roadId="1" laneId="-1" s="${$Missing + 1}"/>') +
        teleport('third', '<RelativeLanePosition entityRef="ego" dLane="0" ds="1"/>'),
    );
    const problems = scenarioScene(parseXml(text), network).entities.map((entity) => entity.problem);
    assert.match(problems[0] ?? '', /road 9 is not in the road network/);
    assert.match(problems[1] ?? '', /LanePosition s="\$\{\$Missing \+ 1\}": .*Missing/);
    assert.match(problems[2] ?? '', /refers to ego, whose position is not known/);
    const noRoads = scenarioScene(
      parseXml(sceneScenario('x.xodr', teleport('ego', '<LanePosition roadId="1" laneId="-1" s="10"/>'))),
      undefined,
    );
    assert.match(noRoads.entities[0].problem ?? '', /road network is not loaded/);
  });

  it('samples lane borders into compact polylines, straight roads with few points', () => {
    const [section] = sampleNetwork(network);
    assert.deepEqual(
      section.lanes.map((lane) => [lane.id, lane.driving]),
      [
        [1, true],
        [0, false],
        [-1, true],
        [-2, false],
      ],
    );
    // 200 m of straight road with constant widths: a few points per border.
    assert.ok(section.borders[0].length <= 2 * 10, `${section.borders[0].length / 2} points`);
    assert.deepEqual(section.borders[0].slice(0, 2), [0, 3.5]);
    assert.deepEqual(section.borders[3].slice(-2), [200, -5.5]);
  });
});

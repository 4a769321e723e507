/**
 * A LanePosition's `offset` written where ScenarioRunner puts it (CARLA_FACTS.laneOffsetSide): OpenSCENARIO (and esmini,
 * RoadManager `Position::SetLanePos`: t = lane centre + offset) measures it along t, ScenarioRunner to the right of the
 * lane's heading in CARLA turned by the Orientation's h. On a right lane facing its way that is the other side: the
 * offset is written negated. Turned across the lane, ScenarioRunner would move the point along the road: on the `.xodr`
 * road the export read it is written as the WorldPosition esmini gives it.
 */
import type { RoadNetwork } from '../opendrive/road';
import { CARLA_FACTS } from '../profiles/carla';
import { scenarioRunnerOffsetPlace } from '../profiles/scenarioRunner';
import type { LossSink } from './carlaLosses';
import { roadPositionPose } from './trajectoryPoint';
import { attr, child, fourDecimals, makeNode, named, Node, numberAttr, replaceNode, setAttr } from './tree';

const LANE_POSITION_SOURCES = CARLA_FACTS.laneOffsetSide.source;

/** Whether ScenarioRunner would move the LanePosition along the road (turned across its lane, with an offset): written as a WorldPosition, which needs the road. */
export function movedAlongByScenarioRunner(position: Node): boolean {
  const orientation = child(position, 'Orientation');
  const h = orientation ? numberAttr(orientation, 'h', 0) : 0;
  return scenarioRunnerOffsetPlace(numberAttr(position, 'laneId', 0), h, numberAttr(position, 'offset', 0)).place === 'along';
}

export function laneOffsets(tree: Node, sink: LossSink, roads: RoadNetwork | undefined): void {
  for (const position of named(tree, 'LanePosition')) {
    const offset = numberAttr(position, 'offset', 0);
    const laneId = numberAttr(position, 'laneId', NaN);
    const orientation = child(position, 'Orientation');
    const h = orientation ? numberAttr(orientation, 'h', 0) : 0;
    if (offset === 0 || !Number.isFinite(offset) || !Number.isInteger(laneId) || laneId === 0 || !Number.isFinite(h)) continue;
    const { along, across, place } = scenarioRunnerOffsetPlace(laneId, h, offset);
    if (place === 'as-written') continue;
    if (place === 'mirrored') {
      setAttr(position, 'offset', fourDecimals(-offset));
      sink.approximated(
        position,
        'LanePosition/@offset',
        `written as ${fourDecimals(-offset)}: the point stays ${Math.abs(offset)} m to the ${offset > 0 ? 'left' : 'right'} of lane ${laneId}'s centre as the road's reference line runs (esmini reads the written offset on the other side)`,
        `ScenarioRunner puts an offset to the right of the lane's heading, which on lane ${laneId} ${orientation ? `turned by h ${h} ` : ''}runs along the road, where OpenSCENARIO puts it to the left of the reference line (${LANE_POSITION_SOURCES})`,
      );
      continue;
    }
    const scenarioRunnerPlace = `${fourDecimals(along)} m along the road and ${fourDecimals(Math.abs(across))} m to the ${across >= 0 ? 'left' : 'right'} of the lane's centre`;
    const carla = `ScenarioRunner puts an offset to the right of the lane's heading turned by the Orientation's h (${LANE_POSITION_SOURCES}): this one ${scenarioRunnerPlace}`;
    const pose = roadPositionPose(position, roads, 'the position');
    if (typeof pose === 'string') {
      sink.approximated(
        position,
        'LanePosition/@offset',
        `kept as written, so ScenarioRunner places it elsewhere than esmini (${Math.abs(offset)} m to the ${offset > 0 ? 'left' : 'right'} of the lane's centre); the export cannot write it as a WorldPosition: ${pose}`,
        carla,
      );
      continue;
    }
    const angles = (['p', 'r'] as const).flatMap((name): [string, string][] => {
      const value = orientation ? attr(orientation, name) : undefined;
      return value !== undefined ? [[name, value]] : [];
    });
    const world = makeNode(
      'WorldPosition',
      [['x', fourDecimals(pose.x)], ['y', fourDecimals(pose.y)], ['h', fourDecimals(pose.h)], ...angles],
      [],
      position.place,
    );
    replaceNode(position, world);
    sink.approximated(
      world,
      'LanePosition',
      `written as WorldPosition x ${fourDecimals(pose.x)}, y ${fourDecimals(pose.y)}, h ${fourDecimals(pose.h)}, where esmini places it; its height is ScenarioRunner's spawn height, not the road's`,
      carla,
    );
  }
}

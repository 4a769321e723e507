/**
 * Where an actor with a trajectory or route in the Init starts. ScenarioRunner spawns an actor at the last Position
 * written in its Init: `_get_actor_transform` converts every Position below the actor's Private, a trajectory's
 * vertices and a route's waypoints included, and keeps the last (SR_CONFIGURATION:359-371). So an actor that is
 * teleported and then follows a trajectory would start at the trajectory's end. The export makes the last Position
 * the one the actor starts at: its TeleportAction written after the routing actions, or, with no TeleportAction, one
 * added where its Init trajectory starts, as esmini places it. A trajectory's `initialDistanceOffset` (1.2+, not in
 * 1.0) is kept by starting the trajectory there: the vertices before it dropped, a vertex written at that point.
 */
import type { RoadNetwork } from '../opendrive/road';
import { ancestorOrSelf } from './carlaLosses';
import type { LossSink } from './carlaLosses';
import { SR_CONFIGURATION, SR_PARSER } from './carlaFacts';
import { alongPolyline, pointAt, polylinePoints } from './trajectoryPoint';
import {
  appendChild,
  attr,
  child,
  childrenNamed,
  cloneNode,
  fourDecimals,
  makeNode,
  named,
  Node,
  numberAttr,
  removeAttr,
  removeNode,
} from './tree';

const SPAWN = `ScenarioRunner spawns an actor at the last Position written in its Init, a trajectory's vertices included (${SR_CONFIGURATION}:359-371 _get_actor_transform)`;

const ROUTING = new Set(['FollowTrajectoryAction', 'AssignRouteAction', 'AcquirePositionAction']);

/** The entity's Init Privates, in document order. */
function privatesByEntity(init: Node): Map<string, Node[]> {
  const byEntity = new Map<string, Node[]>();
  for (const each of childrenNamed(child(init, 'Actions') ?? init, 'Private')) {
    const entity = attr(each, 'entityRef') ?? '';
    byEntity.set(entity, [...(byEntity.get(entity) ?? []), each]);
  }
  return byEntity;
}

export function initStarts(tree: Node, context: { sink: LossSink; roads?: RoadNetwork }): void {
  const init = named(tree, 'Init')[0];
  if (!init) return;
  for (const [entity, privates] of privatesByEntity(init)) {
    const routing = privates.flatMap((each) => named(each, ROUTING));
    if (routing.length === 0) continue;
    const follow = routing.find((each) => each.name === 'FollowTrajectoryAction');
    if (follow) startAtOffset(follow, entity, context);
    // The unit holding the Position ScenarioRunner spawns the actor at; the actor's start goes right after it.
    const lastPosition = privates.flatMap((each) => named(each, 'Position')).pop();
    const holder = lastPosition && ancestorOrSelf(lastPosition, 'PrivateAction');
    if (!holder || !holder.parent) continue;
    const after = (node: Node): void => {
      const siblings = (holder.parent as Node).children;
      appendChild(holder.parent as Node, node, siblings[siblings.indexOf(holder) + 1]);
    };
    const teleport = privates
      .flatMap((each) => named(each, 'TeleportAction'))
      .map((action) => action.parent as Node)
      .pop();
    if (teleport) {
      // Moved no further than past that Position: esmini runs the Init's actions in order too.
      if (teleport !== holder) {
        removeNode(teleport);
        after(teleport);
      }
      continue;
    }
    const first = follow && childrenNamed(named(follow, 'Polyline')[0] ?? follow, 'Vertex')[0];
    const position = first && child(first, 'Position');
    const placed = position?.children[0];
    if (!position || !placed || !['WorldPosition', 'LanePosition', 'RoadPosition'].includes(placed.name)) continue;
    after(makeNode('PrivateAction', [], [makeNode('TeleportAction', [], [cloneNode(position)])], follow.place));
    context.sink.approximated(
      follow,
      'Init/FollowTrajectoryAction',
      `'${entity}' has no TeleportAction in the Init: it starts where its trajectory starts (as esmini places it), written as a TeleportAction after the trajectory`,
      `${SPAWN}; without it, the trajectory's last vertex`,
    );
  }
}

/** The trajectory of an Init FollowTrajectoryAction started at its initialDistanceOffset: the vertices before it dropped, a first vertex written at that point. */
function startAtOffset(follow: Node, entity: string, context: { sink: LossSink; roads?: RoadNetwork }): void {
  const offset = numberAttr(follow, 'initialDistanceOffset', 0);
  removeAttr(follow, 'initialDistanceOffset');
  if (offset === 0) return;
  const polyline = named(follow, 'Polyline')[0];
  const points = polyline ? polylinePoints(polyline, context.roads) : 'its trajectory is not a Polyline';
  const found =
    typeof points === 'string'
      ? points
      : Number.isFinite(offset) && offset > 0
        ? alongPolyline(points, offset)
        : 'the offset is not a distance';
  const carla = `1.0 has no initialDistanceOffset; ${SR_PARSER} get_trajectory reads the vertices only`;
  if (!polyline || typeof points === 'string' || typeof found === 'string') {
    context.sink.approximated(
      follow,
      'FollowTrajectoryAction/@initialDistanceOffset',
      `is not in 1.0: the trajectory is followed from its start (the export cannot place ${offset} m along it: ${found})`,
      carla,
    );
    return;
  }
  const point = pointAt(points, found);
  const vertices = childrenNamed(polyline, 'Vertex');
  const passed = vertices.slice(0, found.segment);
  const [before, after] = [attr(vertices[found.segment - 1], 'time'), attr(vertices[found.segment], 'time')];
  // The time at that point, between its segment's two vertex times, as the actor would pass it.
  const time =
    before === undefined || after === undefined
      ? after
      : fourDecimals(Number(before) + ((Number(after) - Number(before)) * found.along) / found.length);
  for (const vertex of passed) removeNode(vertex);
  const position = makeNode(
    'Position',
    [],
    [
      makeNode('WorldPosition', [
        ['x', fourDecimals(point.x)],
        ['y', fourDecimals(point.y)],
        ['z', '0'],
        ['h', fourDecimals(point.h)],
      ]),
    ],
  );
  appendChild(polyline, makeNode('Vertex', time === undefined ? [] : [['time', time]], [position]), vertices[found.segment]);
  context.sink.approximated(
    follow,
    'FollowTrajectoryAction/@initialDistanceOffset',
    `is not in 1.0: '${entity}' follows the trajectory from ${offset} m along it, written as a first vertex there (x ${fourDecimals(point.x)}, y ${fourDecimals(point.y)}) in place of the ${passed.length} before it`,
    carla,
  );
}

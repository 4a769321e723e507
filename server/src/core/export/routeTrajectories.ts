/**
 * An Init AssignRouteAction or AcquirePositionAction written as the FollowTrajectoryAction that drives the same lanes, for
 * ScenarioRunner 0.9.16: it builds every route action as ChangeActorWaypoints without times, which raises
 * (SR_ATOMICS ChangeActorWaypoints.__init__, a regression of commit ab5996d7), but builds a FollowTrajectoryAction as
 * ChangeActorWaypoints with times and 'shortest' routing, straight lines between the vertices (SR_PARSER 1509-1513,
 * SR_SCENARIO 336-342), which its vehicle controller drives to reach each vertex at its time (npc_vehicle_control.py:103-113).
 * Only a vehicle's, alone in its Init (CARLA_FACTS.initActorSequence: one routing or lateral atomic per actor, its start speed set
 * after it ends; only the vehicle controller drives by the vertex times). The lanes are those esmini drives the route in (core/opendrive/route.ts routeLanes), the vertices LanePositions
 * (ScenarioRunner converts one with CARLA's own map, get_waypoint_xodr, SR_PARSER convert_position_to_transform) at most
 * ROUTE_STEP apart, timed at the actor's speed, which must be certain over the whole run (scenarioTree constantSpeedOf).
 */
import type { RoadNetwork } from '../opendrive/road';
import { routeLanes, RouteWaypoint } from '../opendrive/route';
import { baseName } from '../sources';
import { CARLA_FACTS } from '../profiles/carla';
import { roadPositionPose } from './trajectoryPoint';
import { actorsOf, constantSpeedOf, scenarioObjectOf } from './scenarioTree';
import { ancestor, attr, child, childrenNamed, fourDecimals, makeNode, named, Node, numberAttr } from './tree';

/** The longest straight segment between two vertices: its sagitta on a 10 m radius (a tight junction turn) is 1.25 cm. */
export const ROUTE_STEP = 1;

/** An element's name after 'a' or 'an'. */
function withArticle(name: string): string {
  return `${/^[AEIOU]/.test(name) ? 'an' : 'a'} ${name}`;
}

/** Where a node was written (`file:line`), or '' when it was not. */
function lineOf(node: Node): string {
  return node.place ? `${baseName(node.place.source)}:${node.place.range.start.line + 1}` : '';
}

/** The route's waypoints as lane positions, or why one is not. */
export function routeWaypoints(route: Node): RouteWaypoint[] | string {
  const waypoints: RouteWaypoint[] = [];
  for (const [index, waypoint] of childrenNamed(route, 'Waypoint').entries()) {
    const lane = child(child(waypoint, 'Position') ?? waypoint, 'LanePosition');
    const kind = child(waypoint, 'Position')?.children[0]?.name ?? 'no position';
    if (!lane) return `waypoint ${index + 1} of the route is a ${kind}, and the export plans routes between LanePositions only`;
    const roadId = attr(lane, 'roadId') ?? '';
    const laneId = Number(attr(lane, 'laneId'));
    const s = Number(attr(lane, 's'));
    if (!Number.isInteger(laneId) || laneId === 0 || !Number.isFinite(s)) return `waypoint ${index + 1}'s laneId or s is not a number`;
    // Named by where it is written, so that a message saying where to add a waypoint points at a line.
    const name = waypoint.place ? `the Waypoint at ${lineOf(waypoint)}` : undefined;
    waypoints.push({ roadId, laneId, s, ...(name ? { name } : {}) });
  }
  return waypoints;
}

/** The Init actions ScenarioRunner builds as an actor's one Init atomic (CARLA_FACTS.initActorSequence). */
const INIT_ATOMICS: ReadonlySet<string> = new Set([
  'FollowTrajectoryAction',
  'AssignRouteAction',
  'AcquirePositionAction',
  'LaneOffsetAction',
  'LateralDistanceAction',
]);

/** Actions of a story that move an actor across or along other ways than its lane: while a trajectory runs, they would end it (ScenarioRunner) or fight it (esmini). */
const MOVING: ReadonlySet<string> = new Set(['LateralAction', 'RoutingAction', 'TeleportAction']);

/** The actor's start: the LanePosition of its last Init TeleportAction (routePositions has written a RoutePosition as one by now). */
function startOf(tree: Node, actor: string): (RouteWaypoint & { offset: number }) | string {
  const init = named(tree, 'Init')[0];
  const teleports = init
    ? named(init, 'TeleportAction').filter((each) => attr(ancestor(each, 'Private') ?? each, 'entityRef') === actor)
    : [];
  const teleport = teleports.at(-1);
  if (!teleport) return `'${actor}' has no TeleportAction in the Init to start the route from`;
  const placed = child(teleport, 'Position')?.children[0];
  if (placed?.name !== 'LanePosition')
    return `'${actor}' starts at a ${placed?.name ?? 'Position'}, and the export plans a route from a LanePosition only`;
  if (child(placed, 'Orientation') && numberAttr(child(placed, 'Orientation') as Node, 'h', 0) !== 0)
    return `'${actor}' starts turned by an Orientation, and esmini plans its route from the way it faces`;
  const laneId = numberAttr(placed, 'laneId', NaN);
  const s = numberAttr(placed, 's', NaN);
  const offset = numberAttr(placed, 'offset', 0);
  if (!Number.isInteger(laneId) || laneId === 0 || !Number.isFinite(s) || !Number.isFinite(offset))
    return `${actor}'s start has no lane, s or offset as numbers`;
  return { roadId: attr(placed, 'roadId') ?? '', laneId, s, offset, name: `${actor}'s start (${lineOf(placed)})` };
}

/** The route action's waypoints: its Route's (AssignRouteAction), or from the start to its Position (AcquirePositionAction). */
function waypointsOf(action: Node, start: RouteWaypoint): RouteWaypoint[] | string {
  if (action.name === 'AssignRouteAction') {
    const route = child(action, 'Route');
    return route ? routeWaypoints(route) : 'its route is not written in the scenario or a catalog it loads';
  }
  const target = child(action, 'Position')?.children[0];
  if (target?.name !== 'LanePosition') return `its target is a ${target?.name ?? 'Position'}, and the export plans to a LanePosition only`;
  const laneId = numberAttr(target, 'laneId', NaN);
  const s = numberAttr(target, 's', NaN);
  if (!Number.isInteger(laneId) || laneId === 0 || !Number.isFinite(s)) return "its target's laneId or s is not a number";
  // esmini plans from where the actor is, heading as it drives (AcquirePositionAction::Start).
  return [start, { roadId: attr(target, 'roadId') ?? '', laneId, s, name: `its target (${lineOf(target)})` }];
}

export interface RouteTrajectory {
  /** The FollowTrajectoryAction that replaces the route action. */
  follow: Node;
  /** What the report says it drives: roads, lanes, vertices, speed. */
  summary: string;
}

/** The route action as a FollowTrajectoryAction along the lanes esmini drives it, or why the export cannot write it so. */
export function routeTrajectory(tree: Node, action: Node, roads: RoadNetwork | undefined): RouteTrajectory | string {
  if (!ancestor(action, 'Init'))
    return 'in a story, where the actor is when the action starts is known only as the scenario runs, so no trajectory can start there';
  if (!roads) return 'the road is a CARLA town (or no .xodr file the export read), whose lanes the export cannot plan';
  const actor = actorsOf(action)[0] ?? '';
  const object = scenarioObjectOf(tree, actor);
  const sequence = CARLA_FACTS.initActorSequence;
  if (!object || !child(object, 'Vehicle'))
    return `'${actor}' is not a vehicle: ScenarioRunner's walker controller does not read vertex times (pedestrian_control.py), and ScenarioRunner ${sequence.does} (${sequence.source}), so it would stand at its start`;
  const init = ancestor(action, 'Init') as Node;
  const other = named(init, INIT_ATOMICS).find((each) => each !== action && attr(ancestor(each, 'Private') ?? each, 'entityRef') === actor);
  if (other)
    return `the Init of '${actor}' has ${withArticle(other.name)} too (${lineOf(other) || 'in the Init'}), and ScenarioRunner ${sequence.does} (${sequence.source})`;
  for (const story of named(tree, 'Story'))
    for (const moving of named(story, MOVING)) {
      const group = ancestor(moving, 'ManeuverGroup');
      const actors = group ? child(group, 'Actors') : undefined;
      if (!actors || attr(actors, 'selectTriggeringEntities') === 'true' || actorsOf(moving).includes(actor)) {
        return `its story moves '${actor}' too (${withArticle(moving.children[0]?.name ?? moving.name)} at ${lineOf(moving) || 'a story line'}), which would end the trajectory in ScenarioRunner and fight it in esmini`;
      }
    }
  const speed = constantSpeedOf(tree, actor, action);
  if (speed === undefined)
    return `the speed of '${actor}' is not certain over the route (none set at once in the Init, a controller of its own, or an action of its story changes it), and ScenarioRunner would drive to the vertices by times computed at one speed`;
  if (!(speed > 0)) return `'${actor}' keeps the speed ${speed}, and a trajectory at that speed has no times`;
  const start = startOf(tree, actor);
  if (typeof start === 'string') return start;
  const waypoints = waypointsOf(action, start);
  if (typeof waypoints === 'string') return waypoints;
  const stretches = routeLanes(roads, waypoints, start);
  if (typeof stretches === 'string') return stretches;
  // Each stretch sampled at most ROUTE_STEP apart, 1 mm inside its lane section so that its lane id is the one there.
  const vertices: { roadId: string; laneId: number; s: number; x: number; y: number }[] = [];
  for (const stretch of stretches) {
    const length = Math.abs(stretch.to - stretch.from);
    const count = Math.max(1, Math.ceil(length / ROUTE_STEP - 1e-9));
    const inward = Math.min(0.001, length / 2) * Math.sign(stretch.to - stretch.from);
    for (let index = 0; index <= count; index++) {
      const s = stretch.from + ((stretch.to - stretch.from) * index) / count + (index === 0 ? inward : index === count ? -inward : 0);
      const position = makeNode('LanePosition', [
        ['roadId', stretch.roadId],
        ['laneId', String(stretch.laneId)],
        ['offset', fourDecimals(start.offset)],
        ['s', fourDecimals(s)],
      ]);
      const pose = roadPositionPose(position, roads);
      if (typeof pose === 'string') return pose;
      const previous = vertices.at(-1);
      // Where a stretch ends, the next begins: one vertex there.
      if (previous && Math.hypot(pose.x - previous.x, pose.y - previous.y) < 0.01) continue;
      vertices.push({ roadId: stretch.roadId, laneId: stretch.laneId, s: Number(fourDecimals(s)), x: pose.x, y: pose.y });
    }
  }
  if (vertices.length < 2) return `'${actor}' starts where its route ends`;
  let along = 0;
  const polyline = makeNode(
    'Polyline',
    [],
    vertices.map((vertex, index) => {
      if (index > 0) along += Math.hypot(vertex.x - vertices[index - 1].x, vertex.y - vertices[index - 1].y);
      const lane = makeNode('LanePosition', [
        ['roadId', vertex.roadId],
        ['laneId', String(vertex.laneId)],
        ['offset', fourDecimals(start.offset)],
        ['s', String(vertex.s)],
      ]);
      return makeNode('Vertex', [['time', fourDecimals(along / speed)]], [makeNode('Position', [], [lane])]);
    }),
  );
  const name = attr(child(action, 'Route') ?? action, 'name') ?? action.name;
  const follow = makeNode(
    'FollowTrajectoryAction',
    [],
    [
      makeNode(
        'Trajectory',
        [
          ['name', name],
          ['closed', 'false'],
        ],
        [makeNode('Shape', [], [polyline])],
      ),
      makeNode('TimeReference', [], [makeNode('None')]),
      makeNode('TrajectoryFollowingMode', [['followingMode', 'position']]),
    ],
    action.place,
  );
  const roadIds: string[] = [];
  for (const stretch of stretches) if (roadIds.at(-1) !== stretch.roadId) roadIds.push(stretch.roadId);
  return {
    follow,
    summary: `the lanes esmini drives it in from ${actor}'s start (roads ${roadIds.join(' > ')}, lane ${stretches[0].laneId} from s ${Number(start.s.toFixed(3))}, ${Number(along.toFixed(2))} m): ${vertices.length} LanePositions at most ${ROUTE_STEP} m apart, timed at its speed ${fourDecimals(speed)} m/s; past the last one it drives on in its lane, as past a route's end${
      start.offset !== 0
        ? `; its offset ${fourDecimals(start.offset)} m from the lane centre is written on each vertex, but ScenarioRunner's vehicle controller drives to each vertex's lane centre (npc_vehicle_control.py _update_plan: get_waypoint, project_to_road)`
        : ''
    }`,
  };
}

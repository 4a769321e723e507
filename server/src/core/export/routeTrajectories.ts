/**
 * An Init AssignRouteAction or AcquirePositionAction written as the FollowTrajectoryAction that drives the same lanes, for
 * ScenarioRunner 0.9.16: it builds every route action as ChangeActorWaypoints without times, which raises
 * (SR_ATOMICS ChangeActorWaypoints.__init__, a regression of commit ab5996d7), but builds a FollowTrajectoryAction as
 * ChangeActorWaypoints with times and 'shortest' routing, straight lines between the vertices (SR_PARSER 1509-1513,
 * SR_SCENARIO 336-342), which its vehicle controller drives to reach each vertex at its time (npc_vehicle_control.py:103-113).
 * A vehicle's, alone in its Init (CARLA_FACTS.initActorSequence: one routing or lateral atomic per actor, its start speed set
 * after it ends); a pedestrian's in a story only: its walker controller walks to the vertices at the speed its story set, reading
 * no times (CARLA_FACTS.walkerWalksAtSetSpeed), on the driving lane esmini snaps it to from its sidewalk (snappedLaneAtPoint). The lanes are those esmini drives the route in (core/opendrive/route.ts routeLanes), the vertices LanePositions
 * (ScenarioRunner converts one with CARLA's own map, get_waypoint_xodr, SR_PARSER convert_position_to_transform) at most
 * ROUTE_STEP apart, timed at the actor's speed, which must be certain over the whole run (scenarioTree constantSpeedOf).
 */
import { isDrivingLane, type RoadNetwork } from '../opendrive/road';
import { laneAtPoint, snappedLaneAtPoint } from '../opendrive/lanePosition';
import { LaneOnwards, laneOnwards, LaneStretch, routeLanes, RouteWaypoint } from '../opendrive/route';
import { CARLA_FACTS } from '../profiles/carla';
import { SR_ATOMICS, SR_PARSER } from '../profiles/scenarioRunner';
import { roadPositionPose } from './trajectoryPoint';
import {
  describeProfile,
  distanceAt,
  FROM_TIME_ON,
  lineOf,
  routeSpeedProfile,
  runStopTime,
  speedAt,
  SpeedProfile,
  startsAtZero,
  timeAt,
} from './routeSpeedProfile';
import { actorsOf, constantSpeedOf, mayActOn, scenarioObjectOf, startSpeedOf, storySpeedOf } from './scenarioTree';
import { ancestor, attr, child, childrenNamed, fourDecimals, makeNode, named, Node, numberAttr } from './tree';

/** The longest straight segment between two vertices: its sagitta on a 10 m radius (a tight junction turn) is 1.25 cm. */
export const ROUTE_STEP = 1;

/** An element's name after 'a' or 'an'. */
function withArticle(name: string): string {
  return `${/^[AEIOU]/.test(name) ? 'an' : 'a'} ${name}`;
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

/** The route actions 0.9.16 crashes on, which the export writes as trajectories. */
const ROUTES: ReadonlySet<string> = new Set(['AssignRouteAction', 'AcquirePositionAction']);

/** Actions of a story that move an actor across or along other ways than its lane: while a trajectory runs, they would end it (ScenarioRunner) or fight it (esmini). */
const MOVING: ReadonlySet<string> = new Set(['LateralAction', 'RoutingAction', 'TeleportAction']);

/** How the road reads a WorldPosition: in CARLA's left-handed frame (y and heading negated from OpenDRIVE's) when the file says so and stays on a CARLA town. */
export interface RouteRoad {
  roads: RoadNetwork;
  /** The FileHeader description starts with 'CARLA:' and the road is a CARLA town: ScenarioRunner reads positions in CARLA's coordinates. */
  carlaFrame: boolean;
}

/** A WorldPosition in the road's frame: x, y and the heading. */
function worldPoint(position: Node, road: RouteRoad): { x: number; y: number; h: number } {
  // ScenarioRunner negates y and the heading of a file not in CARLA's frame (SR_PARSER convert_position_to_transform).
  const sign = road.carlaFrame ? -1 : 1;
  return { x: numberAttr(position, 'x', NaN), y: sign * numberAttr(position, 'y', NaN), h: sign * numberAttr(position, 'h', 0) };
}

/**
 * A WorldPosition's lane on the road (core/opendrive/lanePosition.ts), as ScenarioRunner places it, or why there is none. A
 * walker's is the driving lane esmini snaps it to, however far off (it walks on a sidewalk), with the way it heads.
 */
function worldLane(position: Node, road: RouteRoad, what: string, walker: boolean): (RouteWaypoint & { offset: number }) | string {
  const { x, y, h } = worldPoint(position, road);
  if (![x, y, h].every(Number.isFinite)) return `${what} is a WorldPosition whose x, y or h is not a number`;
  const lane = walker ? snappedLaneAtPoint(road.roads, x, y, h) : laneAtPoint(road.roads, x, y, h, isDrivingLane);
  if (typeof lane === 'string')
    return `${what} is a WorldPosition in no ${walker ? 'road with a driving lane' : 'driving lane headed its way'}: ${lane}`;
  // To the tenth of a millimetre, as written: down, so that a point at a road's end stays on it; a point within a millimetre of the centre on it.
  return { ...lane, s: Math.floor(lane.s * 1e4) / 1e4, offset: Math.abs(lane.offset) < 1e-3 ? 0 : Number(lane.offset.toFixed(4)) };
}

/** The actor's last Init TeleportAction, where it starts. */
function initTeleport(tree: Node, actor: string): Node | undefined {
  const init = named(tree, 'Init')[0];
  return init
    ? named(init, 'TeleportAction')
        .filter((each) => attr(ancestor(each, 'Private') ?? each, 'entityRef') === actor)
        .at(-1)
    : undefined;
}

/** The actor's start: the Lane or WorldPosition of its last Init TeleportAction (routePositions has written a RoutePosition as a LanePosition by now). */
function startOf(tree: Node, actor: string, road: RouteRoad, walker: boolean): (RouteWaypoint & { offset: number }) | string {
  const teleport = initTeleport(tree, actor);
  if (!teleport) return `'${actor}' has no TeleportAction in the Init to start the route from`;
  const placed = child(teleport, 'Position')?.children[0];
  if (placed?.name === 'WorldPosition') {
    const lane = worldLane(placed, road, `the start of '${actor}'`, walker);
    return typeof lane === 'string' ? lane : { ...lane, name: `${actor}'s start (${lineOf(placed)})` };
  }
  if (placed?.name !== 'LanePosition')
    return `'${actor}' starts at a ${placed?.name ?? 'Position'}, and the export plans a route from a Lane or WorldPosition only`;
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
function waypointsOf(action: Node, start: RouteWaypoint, road: RouteRoad, walker: boolean): RouteWaypoint[] | string {
  if (action.name === 'AssignRouteAction') {
    const route = child(action, 'Route');
    return route ? routeWaypoints(route) : 'its route is not written in the scenario or a catalog it loads';
  }
  const target = child(action, 'Position')?.children[0];
  if (target?.name === 'WorldPosition') {
    const lane = worldLane(target, road, 'its target', walker);
    return typeof lane === 'string' ? lane : [start, { ...lane, name: `its target (${lineOf(target)})` }];
  }
  if (target?.name !== 'LanePosition')
    return `its target is a ${target?.name ?? 'Position'}, and the export plans to a Lane or WorldPosition only`;
  const laneId = numberAttr(target, 'laneId', NaN);
  const s = numberAttr(target, 's', NaN);
  if (!Number.isInteger(laneId) || laneId === 0 || !Number.isFinite(s)) return "its target's laneId or s is not a number";
  // esmini plans from where the actor is, heading as it drives (AcquirePositionAction::Start).
  return [start, { roadId: attr(target, 'roadId') ?? '', laneId, s, name: `its target (${lineOf(target)})` }];
}

export interface RouteTrajectory {
  /** The FollowTrajectoryAction that replaces the route action. */
  follow: Node;
  /** A pedestrian's: ScenarioRunner walks it to the vertices at the speed set (CARLA_FACTS.walkerWalksAtSetSpeed), not by their times. */
  walker: boolean;
  /** What the report says it drives: roads, lanes, vertices, speed. */
  summary: string;
}

/** Where the route's road comes from, for a message: a CARLA town whose OpenDRIVE the export did not find, or no road read. */
export interface RouteRoadSource {
  road?: RouteRoad;
  /** The CARLA town the scenario names, when its road is one. */
  town?: string;
}

/** The route action as a FollowTrajectoryAction along the lanes esmini drives it, or why the export cannot write it so. */
export function routeTrajectory(tree: Node, action: Node, source: RouteRoadSource): RouteTrajectory | string {
  const road = source.road;
  if (!road)
    return source.town
      ? `the road is the CARLA town ${source.town}, and no OpenDRIVE file of that name was found to plan its lanes on: add the folder that holds it to the road path (--road-path DIR, the modular2simple.esmini.roadPath setting)`
      : 'the road is no .xodr file the export read, whose lanes the export could plan';
  const roads = road.roads;
  const inInit = ancestor(action, 'Init') !== undefined;
  const actors = actorsOf(action);
  if (actors.length !== 1) return `its ManeuverGroup acts on ${actors.length} actors, and a trajectory is planned for one`;
  const actor = actors[0];
  const object = scenarioObjectOf(tree, actor);
  const sequence = CARLA_FACTS.initActorSequence;
  const walker = object !== undefined && child(object, 'Pedestrian') !== undefined;
  if (!object || !(child(object, 'Vehicle') || walker))
    return `'${actor}' is neither a vehicle nor a pedestrian, which ScenarioRunner's controllers move along a trajectory`;
  // The walker controller walks to the vertices at the speed set, reading no times; in the Init that speed comes only after the trajectory.
  if (walker && inInit)
    return `'${actor}' is a pedestrian: ScenarioRunner's walker controller walks to the vertices at the speed set, reading no vertex times (${CARLA_FACTS.walkerWalksAtSetSpeed.source}), and ScenarioRunner ${sequence.does} (${sequence.source}), so it would stand at its start`;
  if (inInit) {
    const init = ancestor(action, 'Init') as Node;
    const other = named(init, INIT_ATOMICS).find(
      (each) => each !== action && attr(ancestor(each, 'Private') ?? each, 'entityRef') === actor,
    );
    if (other)
      return `the Init of '${actor}' has ${withArticle(other.name)} too (${lineOf(other) || 'in the Init'}), and ScenarioRunner ${sequence.does} (${sequence.source})`;
  }
  const starts = inInit ? initRouteStart(tree, actor, action) : storyRouteStart(tree, action, actor, walker);
  // A route whose start is known only as the run goes (the case study's second routes, after a stop) is refused for that first.
  if (typeof starts === 'string' && starts.includes(PLACE_UNKNOWN)) return starts;
  for (const story of named(tree, 'Story'))
    for (const moving of named(story, MOVING)) {
      if (moving === action.parent || !mayActOn(moving, actor)) continue;
      const other = moving.children[0];
      // Another route of the actor: a trajectory could follow this one only where that one's start is known too.
      const otherStarts =
        other && ROUTES.has(other.name) && ancestor(other, 'Init') === undefined ? storyRouteStart(tree, other, actor, walker) : undefined;
      return `its story moves '${actor}' too (${withArticle(other?.name ?? moving.name)} at ${lineOf(moving) || 'a story line'}), which would end the trajectory in ScenarioRunner and fight it in esmini${
        typeof otherStarts === 'string' ? `, and that one cannot be written as a trajectory either: ${otherStarts}` : ''
      }`;
    }
  if (typeof starts === 'string') return starts;
  const { speed, along, profile } = starts;
  const startTime = starts.startTime ?? 0;
  if (!(speed > 0)) return `'${actor}' keeps the speed ${speed}, and a trajectory at that speed has no times`;
  const start = startOf(tree, actor, road, walker);
  if (typeof start === 'string') return start;
  const waypoints = waypointsOf(action, start, road, walker);
  if (typeof waypoints === 'string') return waypoints;
  const stretches = routeLanes(roads, waypoints, start);
  if (typeof stretches === 'string') return stretches;
  const sampling: Sampling = {
    alongS: stretchAlongS(stretches[0], start),
    startAlongS: stretchAlongS(stretches[0], start),
    offset: start.offset,
  };
  const vertices: Vertex[] = [];
  const sampled = sampleStretches(stretches, sampling, roads, vertices);
  if (sampled) return sampled;
  const line = walker && vertices.length > 0 ? walkerLine(tree, actor, road, vertices) : undefined;
  const expected = along > 0 ? fromWhereExpected(vertices, along, start, actor, roads, line) : { rest: vertices, strayed: 0 };
  if (typeof expected === 'string') return expected;
  const driven = [...expected.rest];
  if (driven.length < 2) return `'${actor}' ${along > 0 ? 'is expected where' : 'starts where'} its route ends`;
  let routeLength = 0;
  for (let index = 1; index < driven.length; index++)
    routeLength += Math.hypot(driven[index].x - driven[index - 1].x, driven[index].y - driven[index - 1].y);
  // A vehicle's trajectory goes on along its lane past the route's end until the run stops: ScenarioRunner raises past its last vertex.
  const routeVertices = driven.length;
  const past = walker
    ? undefined
    : pastRouteEnd(tree, action, { speed, along, profile, startTime, known: starts.startTime !== undefined }, routeLength);
  if (past?.length) {
    const last = stretches[stretches.length - 1];
    const direction = last.to !== last.from ? (last.to > last.from ? 1 : -1) : sampling.alongS ? 1 : -1;
    const onwards = laneOnwards(roads, last.roadId, last.laneId, last.to, direction, past.length);
    past.onwards = onwards;
    const extended = sampleStretches(onwards.stretches, sampling, roads, driven);
    if (extended) return extended;
  }
  let length = 0;
  const polyline = makeNode(
    'Polyline',
    [],
    driven.map((vertex, index) => {
      if (index > 0) length += Math.hypot(vertex.x - driven[index - 1].x, vertex.y - driven[index - 1].y);
      const lane = makeNode('LanePosition', [
        ['roadId', vertex.roadId],
        ['laneId', String(vertex.laneId)],
        ['offset', fourDecimals(vertex.offset)],
        ['s', String(vertex.s)],
      ]);
      // Times from the action's start: ScenarioRunner's controller counts them from the atomic's start (npc_vehicle_control.py run_step).
      return makeNode(
        'Vertex',
        [['time', fourDecimals(profile ? Math.max(0, timeAt(profile, along + length) - startTime) : length / speed)]],
        [makeNode('Position', [], [lane])],
      );
    }),
  );
  let timing = `timed at its speed ${fourDecimals(speed)} m/s`;
  if (profile) {
    // ScenarioRunner sets the Init speed again once the Init trajectory ends; esmini keeps the speed the story set.
    const ends = timeAt(profile, along + length);
    const endSpeed = speedAt(profile, ends);
    const stop = runStopTime(tree);
    const stopsBefore = stop !== undefined && stop <= ends;
    const routeEnds = timeAt(profile, along + routeLength);
    const fact = CARLA_FACTS.vehicleSpeedChangeOnTrajectory;
    // esmini's FollowTrajectoryAction takes the longitudinal domain too (OSCPrivateAction.hpp FollowTrajectory), ending a speed change still running.
    const cut = profile.changes.find(({ at, takes }) => at < startTime - 1e-9 && startTime < at + takes - 1e-9);
    const esminiCut = cut
      ? `; the SpeedAction at ${lineOf(cut.action) || 'a story line'} is still changing the speed when the action starts, and esmini ends it there when it runs the export (its FollowTrajectoryAction takes the longitudinal domain too: OSCPrivateAction.hpp FollowTrajectory), keeping ${fourDecimals(speed)} m/s, where ScenarioRunner drives by the times`
      : '';
    timing = `timed by its speed as esmini drives it, ${describeProfile(profile)}: ScenarioRunner ${fact.does} (${fact.source})${esminiCut}${
      stop !== undefined && stop <= routeEnds
        ? `; the run stops at ${fourDecimals(stop)} s, before the route ends at ${fourDecimals(routeEnds)} s${inInit ? '' : " from the run's start, its times counted"}`
        : ''
    }`;
    if (inInit && Math.abs(endSpeed - profile.start) > 1e-9 && !stopsBefore)
      return `'${actor}' ends its trajectory (its route${length > routeLength ? ', then its lane on past it' : ''}) at ${fourDecimals(ends)} s at ${fourDecimals(endSpeed)} m/s (its speed ${describeProfile(profile)}), and ScenarioRunner ${CARLA_FACTS.vehicleSpeedChangeOnTrajectory.does} (${CARLA_FACTS.vehicleSpeedChangeOnTrajectory.source}), ${fourDecimals(profile.start)} m/s, where esmini keeps ${fourDecimals(endSpeed)} m/s: the run would have to stop by then (a Storyboard StopTrigger of one SimulationTimeCondition), or the story bring it back to its Init speed`;
  }
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
  for (const vertex of driven.slice(0, routeVertices)) if (roadIds.at(-1) !== vertex.roadId) roadIds.push(vertex.roadId);
  const first = driven[0];
  const from = inInit
    ? `from ${actor}'s start (roads ${roadIds.join(' > ')}, lane ${first.laneId} from s ${Number(start.s.toFixed(3))}, ${Number(routeLength.toFixed(2))} m)`
    : `from where '${actor}' is expected when the action starts, ${starts.how} (roads ${roadIds.join(' > ')}, lane ${first.laneId} from s ${Number(first.s.toFixed(3))}, ${Number(routeLength.toFixed(2))} m)`;
  const later = starts.later ?? [];
  const changes =
    later.length > 0
      ? `, then at the speed ${later.length === 1 ? 'the SpeedAction' : 'the SpeedActions'} at ${later.map((each) => lineOf(each) || 'a story line').join(', ')} ${later.length === 1 ? 'sets' : 'set'} once the route has started, as esmini walks it (${CARLA_FACTS.walkerSpeedChangeOnTrajectory.source})`
      : '';
  if (walker)
    return {
      follow,
      walker,
      summary: `the lanes esmini moves it in ${from.replace('along its lane', 'straight ahead')}: ${driven.length} LanePositions at most ${ROUTE_STEP} m apart, each at its offset ${fourDecimals(start.offset)} m from the centre of the driving lane esmini places it by (it walks off the driving lanes), timed at its speed ${fourDecimals(speed)} m/s for esmini; ScenarioRunner walks it to each vertex at the speed its story set, ${fourDecimals(speed)} m/s${changes}, whatever the times${
        along > 0
          ? `, from where it is when the action starts: it walks straight ahead until then, where esmini moves it along its lane, ${Number(expected.strayed.toFixed(2))} m off that line at most (ScenarioRunner takes a vertex within 1 m as reached)`
          : ''
      }; past the last one it walks on straight ahead (esmini: on in its lane, as past a route's end)`,
    };
  return {
    follow,
    walker,
    summary: `the lanes esmini drives it in ${from}: ${routeVertices} LanePositions at most ${ROUTE_STEP} m apart, ${timing}${
      inInit
        ? ''
        : " from the action's start; it reaches each vertex at its time from where it is expected when the action starts, and catches up or waits if it is elsewhere"
    }; ${pastEndSummary(past, driven.length - routeVertices, length - routeLength, { last: profile ? timeAt(profile, along + length) - startTime : length / speed, startTime: starts.startTime }, driven.slice(routeVertices - 1))}${
      start.offset !== 0
        ? `; its offset ${fourDecimals(start.offset)} m from the lane centre is written on each vertex, but ScenarioRunner's vehicle controller drives to each vertex's lane centre (npc_vehicle_control.py _update_plan: get_waypoint, project_to_road)`
        : ''
    }`,
  };
}

/** How sampling goes on from stretch to stretch: the way the actor moves along s, its start's, and its offset from the lane centre. */
interface Sampling {
  alongS: boolean;
  startAlongS: boolean;
  offset: number;
}

/**
 * Each stretch sampled into `vertices` at most ROUTE_STEP apart, 1 mm inside its lane section so that its lane id is the one
 * there, or why a point is not on the road. esmini keeps the offset to the same side of the way the entity moves: its sign
 * turns where it moves against s and did not at its start.
 */
function sampleStretches(stretches: LaneStretch[], sampling: Sampling, roads: RoadNetwork, vertices: Vertex[]): string | undefined {
  for (const stretch of stretches) {
    if (stretch.to !== stretch.from) sampling.alongS = stretch.to > stretch.from;
    const length = Math.abs(stretch.to - stretch.from);
    const count = Math.max(1, Math.ceil(length / ROUTE_STEP - 1e-9));
    const inward = Math.min(0.001, length / 2) * Math.sign(stretch.to - stretch.from);
    for (let index = 0; index <= count; index++) {
      const s = stretch.from + ((stretch.to - stretch.from) * index) / count + (index === 0 ? inward : index === count ? -inward : 0);
      const offset = sampling.alongS === sampling.startAlongS ? sampling.offset : -sampling.offset;
      const vertex = vertexAt(stretch.roadId, stretch.laneId, s, offset, roads);
      if (typeof vertex === 'string') return vertex;
      const previous = vertices.at(-1);
      // Where a stretch ends, the next begins: one vertex there.
      if (previous && Math.hypot(vertex.x - previous.x, vertex.y - previous.y) < 0.01) continue;
      vertices.push(vertex);
    }
  }
  return undefined;
}

/** How far past the route's end a vehicle's trajectory must go so that the run stops before its last vertex, and the lane found. */
interface PastEnd {
  /** When the run stops, from its start (a Storyboard StopTrigger of one SimulationTimeCondition); undefined when not known. */
  stop: number | undefined;
  /** Metres past the route's end to the point the vehicle reaches a second after the run stops (0: the run stops first). */
  length: number;
  /** A condition that waits for the route action (or an element it ends) to end, which going on past the route would delay. */
  waiting?: Node;
  onwards?: LaneOnwards;
}

/** ScenarioRunner's run goes on this long past the stop condition's time at most: its Storyboard StopTrigger is ticked once a frame. */
const PAST_STOP_SECONDS = 1;

/**
 * How far past its route's end a vehicle drives until the run stops: at its profile's speeds, or at its one speed from when the
 * action starts (the run's start where that is not known: a bound). None when the run's stop time is not known.
 */
function pastRouteEnd(
  tree: Node,
  action: Node,
  drive: { speed: number; along: number; profile: SpeedProfile | undefined; startTime: number; known: boolean },
  routeLength: number,
): PastEnd {
  const stop = runStopTime(tree);
  const waiting = endWaitedFor(tree, action);
  if (stop === undefined || waiting) return { stop, length: 0, waiting };
  const until = stop + PAST_STOP_SECONDS;
  const beyond = drive.profile
    ? distanceAt(drive.profile, until) - (drive.along + routeLength)
    : drive.speed * (until - (drive.known ? drive.startTime : 0)) - routeLength;
  return { stop, length: Math.max(0, beyond) };
}

/** The states in which a storyboard element has ended. */
const ENDED_STATES: ReadonlySet<string> = new Set(['endTransition', 'completeState', 'stopTransition']);

/** A StoryboardElementStateCondition that waits for the end of the route's Action or of a story element holding it. */
function endWaitedFor(tree: Node, action: Node): Node | undefined {
  const ends = new Map<string, string>();
  for (const [type, element] of [
    ['action', 'Action'],
    ['event', 'Event'],
    ['maneuver', 'Maneuver'],
    ['maneuverGroup', 'ManeuverGroup'],
    ['act', 'Act'],
    ['story', 'Story'],
  ] as const) {
    const holding = ancestor(action, element);
    const name = holding ? attr(holding, 'name') : undefined;
    if (name !== undefined) ends.set(type, name);
  }
  if (ends.size === 0) return undefined;
  return named(tree, 'StoryboardElementStateCondition').find(
    (condition) =>
      ENDED_STATES.has(attr(condition, 'state') ?? '') &&
      ends.get(attr(condition, 'storyboardElementType') ?? '') === attr(condition, 'storyboardElementRef'),
  );
}

/** What the report says of the trajectory past the route's end: how far it goes on, and where ScenarioRunner would raise. */
function pastEndSummary(
  past: PastEnd | undefined,
  vertices: number,
  length: number,
  times: { last: number; startTime: number | undefined },
  onwards: Vertex[],
): string {
  const lastTime = times.last;
  const fact = CARLA_FACTS.trajectoryEndRaises;
  const raises = `ScenarioRunner ${fact.does} (${fact.source})`;
  if (past?.waiting)
    return `past the last one esmini drives it on in its lane, as past a route's end, but ${raises}; the trajectory is not written on past the route's end, since the condition at ${lineOf(past.waiting) || 'a story line'} waits for the route's action to end, so ScenarioRunner ends the run with that error if it lasts past ${fourDecimals(lastTime)} s from the action's start`;
  if (!past || past.stop === undefined)
    return `past the last one esmini drives it on in its lane, as past a route's end, but ${raises}: the run has no stop time the export knows (a Storyboard StopTrigger of one SimulationTimeCondition), so ScenarioRunner ends it with that error if it lasts past ${fourDecimals(lastTime)} s from the action's start`;
  if (past.length === 0 || !past.onwards)
    return `the run stops at ${fourDecimals(past.stop)} s, before it reaches the last vertex, past which ${raises}`;
  const roadIds: string[] = [];
  for (const vertex of onwards) if (roadIds.at(-1) !== vertex.roadId) roadIds.push(vertex.roadId);
  const goesOn = `then ${vertices} more along its lane past the route's end (${Number(length.toFixed(2))} m, roads ${roadIds.join(' > ')}), as esmini drives on past a route's end, to its last vertex at ${fourDecimals(lastTime)} s from the action's start`;
  // Known from the run's start: the lane ending after the run stops does not matter.
  const lastFromRunStart = times.startTime === undefined ? undefined : times.startTime + lastTime;
  if (!past.onwards.endsBecause || (lastFromRunStart !== undefined && lastFromRunStart >= past.stop))
    return `${goesOn}, after the run stops at ${fourDecimals(past.stop)} s: past the last vertex ${raises}`;
  return `${goesOn}, where ${past.onwards.endsBecause}; past it ${raises}, so ScenarioRunner ends the run with that error there if the run, which stops at ${fourDecimals(past.stop)} s, has not stopped by then`;
}

interface Vertex {
  roadId: string;
  laneId: number;
  s: number;
  offset: number;
  x: number;
  y: number;
}

/** Whether a stretch runs towards growing s; a stretch of no length runs the way the start heads (its lane's driving direction unless given). */
function stretchAlongS(stretch: LaneStretch, start: RouteWaypoint): boolean {
  if (stretch.to !== stretch.from) return stretch.to > stretch.from;
  return start.direction === undefined ? start.laneId < 0 : start.direction === 1;
}

/**
 * The line a pedestrian walks before a story route starts: from its start the way it faces, which ScenarioRunner's walker
 * controller walks without waypoints (CARLA_FACTS.walkerWalksAtSetSpeed): a WorldPosition's heading, else (a LanePosition,
 * where both simulators face it along its lane) the route's first stretch.
 */
function walkerLine(tree: Node, actor: string, road: RouteRoad, vertices: Vertex[]): WalkerLine {
  const teleport = initTeleport(tree, actor);
  const placed = teleport ? child(teleport, 'Position')?.children[0] : undefined;
  if (placed?.name === 'WorldPosition') {
    const { x, y, h } = worldPoint(placed, road);
    if ([x, y, h].every(Number.isFinite)) return { x, y, h };
  }
  const [first, second] = vertices;
  return { x: first.x, y: first.y, h: second ? Math.atan2(second.y - first.y, second.x - first.x) : 0 };
}

/** Where a walker starts and the way it faces, in the road's frame. */
interface WalkerLine {
  x: number;
  y: number;
  h: number;
}

/** ScenarioRunner's walker controller takes a waypoint within this distance as reached (pedestrian_control.py:71). */
const WALKER_REACH = 1;

/** A vertex on a lane at s with the actor's offset, in world coordinates; or why the road has no such point. */
function vertexAt(roadId: string, laneId: number, s: number, offset: number, roads: RoadNetwork): Vertex | string {
  const position = makeNode('LanePosition', [
    ['roadId', roadId],
    ['laneId', String(laneId)],
    ['offset', fourDecimals(offset)],
    ['s', fourDecimals(s)],
  ]);
  const pose = roadPositionPose(position, roads);
  return typeof pose === 'string' ? pose : { roadId, laneId, s: Number(fourDecimals(s)), offset, x: pose.x, y: pose.y };
}

/**
 * The route's vertices from the point `along` metres down it, where the actor is expected when a story action starts: it has
 * driven its lane from its start so far. Refused where that stretch leaves its start's road for a junction: before the action
 * the actor drives no route, and which way it takes through a junction is not known.
 */
function fromWhereExpected(
  vertices: Vertex[],
  along: number,
  start: RouteWaypoint,
  actor: string,
  roads: RoadNetwork,
  line?: WalkerLine,
): { rest: Vertex[]; strayed: number } | string {
  let covered = 0;
  // How far esmini's way strays from the line a walker walks before the action (ScenarioRunner: straight ahead).
  let strayed = 0;
  const off = (x: number, y: number): number => (line ? Math.abs(-(x - line.x) * Math.sin(line.h) + (y - line.y) * Math.cos(line.h)) : 0);
  const walked = (rest: Vertex[]): { rest: Vertex[]; strayed: number } | string => {
    strayed = Math.max(strayed, off(rest[0].x, rest[0].y));
    if (line && strayed >= WALKER_REACH)
      return `'${actor}' is a pedestrian, which ScenarioRunner walks straight ahead until the action starts (${CARLA_FACTS.walkerWalksAtSetSpeed.source}), and esmini along its lane, which leaves that line by ${Number(strayed.toFixed(2))} m by then, more than the ${WALKER_REACH} m ScenarioRunner's walker takes as reaching a vertex`;
    return { rest, strayed };
  };
  for (let index = 1; index < vertices.length; index++) {
    const [before, after] = [vertices[index - 1], vertices[index]];
    const step = Math.hypot(after.x - before.x, after.y - before.y);
    strayed = Math.max(strayed, off(before.x, before.y));
    if (after.roadId !== start.roadId) {
      const junction = roads.byId.get(after.roadId)?.junction ?? '-1';
      // Without a route esmini takes a connection by its junction selector (Entities.cpp: SELECTOR_ANGLE), a walker too, where ScenarioRunner walks it straight ahead.
      if (junction !== '-1')
        return `'${actor}' is expected ${Number(along.toFixed(2))} m along its lane from its start when the action starts, past the end of road ${start.roadId} into junction ${junction}, where the way it ${
          line
            ? `walks before the action is not known (esmini moves it on by a connection of the driving lane it places it by, or stops it at the road's end where that lane has none; ScenarioRunner's walker walks straight ahead: ${CARLA_FACTS.walkerWalksAtSetSpeed.source})`
            : 'drives before the action is not known'
        }`;
    }
    if (covered + step < along - 1e-9) {
      covered += step;
      continue;
    }
    const fraction = step > 0 ? (along - covered) / step : 0;
    const rest = vertices.slice(index);
    if (fraction >= 1 - 1e-6) return walked(rest);
    // The point itself, on the later vertex's lane: vertices 1 m apart lie on one lane stretch but where a stretch ends.
    const s = before.roadId === after.roadId && before.laneId === after.laneId ? before.s + (after.s - before.s) * fraction : after.s;
    const point = vertexAt(after.roadId, after.laneId, s, after.offset, roads);
    if (typeof point === 'string') return point;
    return walked([{ ...point, x: before.x + (after.x - before.x) * fraction, y: before.y + (after.y - before.y) * fraction }, ...rest]);
  }
  return `'${actor}' is expected ${Number(along.toFixed(2))} m along its lane from its start when the action starts, past its route's end (${Number(covered.toFixed(2))} m)`;
}

/** Where a route action finds its actor (a distance along its lane from its start), its speed then, and a walker's SpeedActions that start only after it. */
interface RouteStart {
  speed: number;
  /** A vehicle's speed from the run's start when its story changes it at known times: the route's vertices are timed by it. */
  profile?: SpeedProfile;
  /** When the route action starts, in seconds from the run's start, where that is known (always with a profile). */
  startTime?: number;
  along: number;
  how: string;
  later?: Node[];
}

/** An Init route starts where the actor starts, at the speed it keeps over the whole run, or a vehicle's by a profile known beforehand. */
function initRouteStart(tree: Node, actor: string, action: Node): RouteStart | string {
  const speed = constantSpeedOf(tree, actor, action);
  if (speed !== undefined) return { speed, along: 0, how: 'its start', startTime: 0 };
  const profile = routeSpeedProfile(tree, actor, action);
  if (typeof profile === 'string')
    return `the speed of '${actor}' is not certain over the route (none set at once in the Init, a controller of its own, or an action of its story changes it): ${profile}; ScenarioRunner would drive to the vertices by times computed beforehand (${CARLA_FACTS.vehicleSpeedChangeOnTrajectory.source})`;
  return { speed: profile.start, along: 0, how: 'its start', profile, startTime: 0 };
}

/**
 * Where a story route action finds its actor, as a distance driven along its lane from its start, and its speed then; or why
 * that is known only as the scenario runs. Known for an Event started by one condition: the actor's own TraveledDistanceCondition
 * (the actor standing until a step SpeedAction of the same Act sets its one speed, or keeping its Init speed from an Act that starts
 * at the run's start), or a SimulationTimeCondition at a speed kept from the Init, in an Act that starts at the run's start; for a
 * vehicle whose story changes its speed at known times (routeSpeedProfile), either condition, the profile fixing where and when:
 * ScenarioRunner counts both from when the condition is first ticked (CARLA_FACTS.conditionsCountFromTheirStart), esmini from the run's.
 */
function storyRouteStart(tree: Node, action: Node, actor: string, walker: boolean): RouteStart | string {
  if (!walker) return storyRouteStartAt(tree, action, actor, new Set([action]), false);
  // A walker walks the trajectory at whatever speed it has (both simulators): SpeedActions that start only once the route has are left out.
  const event = ancestor(action, 'Event');
  const route = { action, event, act: ancestor(action, 'Act'), actor };
  const timed = routeStartTime(action);
  // A route started by a distance starts at a known time where the speed the walker walks there at is set at a known time.
  const byDistance = timed === undefined ? distanceStartTime(tree, action, actor) : undefined;
  const attempt = (routeTime: number | undefined): { first: Node[]; starts: RouteStart | string } => {
    // First with the least distance the route can start at; then checked at the distance the speed gives.
    const first = laterSpeedActions(tree, route, { along: routeTraveled(action) ?? 0, time: routeTime });
    return { first, starts: storyRouteStartAt(tree, action, actor, new Set([action, ...first]), true) };
  };
  let routeTime = timed ?? byDistance?.time;
  let { first, starts } = attempt(routeTime);
  // Another speed than the one the time was computed at: that time does not hold, and no SpeedAction counts as later by its time.
  if (byDistance && (typeof starts === 'string' || Math.abs(starts.speed - byDistance.speed) > 1e-9)) {
    routeTime = undefined;
    ({ first, starts } = attempt(routeTime));
  }
  if (typeof starts === 'string' || first.length === 0) return starts;
  const later = laterSpeedActions(tree, route, { along: starts.along, time: routeTime });
  if (later.length !== first.length)
    return `a SpeedAction of '${actor}' (${first
      .filter((each) => !later.includes(each))
      .map((each) => lineOf(each) || 'a story line')
      .join(
        ', ',
      )}) may start before its route does (its distance lies before the ${Number(starts.along.toFixed(3))} m at which the route starts), so where '${actor}' is when the action starts is not certain`;
  return { ...starts, later };
}

/**
 * When a walker's route started by its own TraveledDistanceCondition starts, from the run's start, and the speed that time
 * is computed at: its Init's, walked from the start; or, standing until then, that of the earliest step SpeedAction of the
 * route's Act that one SimulationTimeCondition starts. The route's Act starts at the run's start, so ScenarioRunner counts
 * its conditions from there too (CARLA_FACTS.conditionsCountFromTheirStart). storyRouteStart checks the speed it finds.
 */
function distanceStartTime(tree: Node, action: Node, actor: string): { time: number; speed: number } | undefined {
  const traveled = routeTraveled(action);
  const act = ancestor(action, 'Act');
  const event = ancestor(action, 'Event');
  const condition = event ? named(child(event, 'StartTrigger') ?? event, 'Condition')[0] : undefined;
  const delay = condition ? numberAttr(condition, 'delay', 0) : NaN;
  if (traveled === undefined || !(traveled >= 0) || !act || !startsAtZero(act) || !(delay >= 0)) return undefined;
  const initial = startSpeedOf(tree, actor);
  if (initial !== undefined) return initial > 0 ? { time: traveled / initial + delay, speed: initial } : undefined;
  let earliest: { at: number; speed: number } | undefined;
  for (const speedAction of named(act, 'SpeedAction')) {
    const target = named(speedAction, 'AbsoluteTargetSpeed')[0];
    const dynamics = named(speedAction, 'SpeedActionDynamics')[0];
    const at = routeStartTime(speedAction);
    const speed = target ? numberAttr(target, 'value', NaN) : NaN;
    if (!mayActOn(speedAction, actor) || at === undefined || !(speed > 0) || !dynamics || attr(dynamics, 'dynamicsShape') !== 'step')
      continue;
    if (!earliest || at < earliest.at) earliest = { at, speed };
  }
  return earliest ? { time: earliest.at + traveled / earliest.speed + delay, speed: earliest.speed } : undefined;
}

/** What a refusal says of a route whose start is known only as the scenario runs. */
const PLACE_UNKNOWN = 'is known only as the scenario runs';

/** Why ScenarioRunner 0.9.16 has no other way to a place from where the run leaves an actor. */
const NO_TRAJECTORY_FROM_ANYWHERE = `the one 1.0 action that ScenarioRunner 0.9.16 builds with waypoints, a FollowTrajectoryAction, takes its vertices as written, placed once when it starts, and its vehicle controller drives to each by its time counted from then: ${SR_ATOMICS}:796-803, ${SR_PARSER}:1509-1513, ${CARLA_FACTS.trajectoryTimesSetSpeed.source.split(',')[0]}`;

/** What a walker's refusal for its speed adds: the speed changes it walks in both simulators. */
const WALKER_LATER = `a walker's SpeedAction to an absolute speed that starts only once its route has (on the route's Action or Event state, or in the route's Act on its own TraveledDistanceCondition at or past where the route starts, or a SimulationTimeCondition at or after the route's start, known from its own time or from its distance at a speed set at a known time) is kept: both simulators walk the trajectory at the speed it sets (${CARLA_FACTS.walkerSpeedChangeOnTrajectory.source})`;

/** The states a storyboard element reaches only once it has started. */
const STARTED_STATES: ReadonlySet<string> = new Set(['startTransition', 'runningState', 'endTransition', 'completeState']);

/** The distance of the route Event's one TraveledDistanceCondition, if it starts on one. */
function routeTraveled(action: Node): number | undefined {
  const event = ancestor(action, 'Event');
  const trigger = event ? child(event, 'StartTrigger') : undefined;
  const traveled = trigger ? named(trigger, 'TraveledDistanceCondition') : [];
  return traveled.length === 1 ? numberAttr(traveled[0], 'value', NaN) : undefined;
}

/** When an action's Event starts (a route's, a SpeedAction's), from its Act's start, if it starts on one SimulationTimeCondition. */
function routeStartTime(action: Node): number | undefined {
  const event = ancestor(action, 'Event');
  const trigger = event ? child(event, 'StartTrigger') : undefined;
  const conditions = trigger ? named(trigger, 'Condition') : [];
  const time = conditions.length === 1 ? named(conditions[0], 'SimulationTimeCondition')[0] : undefined;
  return time && FROM_TIME_ON.has(attr(time, 'rule') ?? '')
    ? numberAttr(time, 'value', NaN) + numberAttr(conditions[0], 'delay', 0)
    : undefined;
}

/**
 * The walker's story SpeedActions (to an absolute speed, not negative: its controller raises on a negative one,
 * pedestrian_control.py:60-62) whose Event starts only once the route action has: in each of its condition groups, a
 * condition that the route's Action or Event has started, or, in the route's Act (so counted from the same first tick in
 * ScenarioRunner, CARLA_FACTS.conditionsCountFromTheirStart), the walker's own TraveledDistanceCondition at the distance the
 * route starts at or beyond, or a SimulationTimeCondition at the route's start time or later.
 */
function laterSpeedActions(
  tree: Node,
  route: { action: Node; event: Node | undefined; act: Node | undefined; actor: string },
  from: { along: number; time: number | undefined },
): Node[] {
  const routeAction = ancestor(route.action, 'Action');
  const startedLater = (condition: Node, act: Node | undefined): boolean => {
    if (!(numberAttr(condition, 'delay', 0) >= 0)) return false;
    const state = named(condition, 'StoryboardElementStateCondition')[0];
    if (state) {
      const ref = attr(state, 'storyboardElementRef');
      const type = attr(state, 'storyboardElementType');
      const element = type === 'action' ? routeAction : type === 'event' ? route.event : undefined;
      return element !== undefined && ref === attr(element, 'name') && STARTED_STATES.has(attr(state, 'state') ?? '');
    }
    if (act !== route.act) return false;
    const traveled = named(condition, 'TraveledDistanceCondition')[0];
    if (traveled) {
      const triggering = named(condition, 'EntityRef').map((each) => attr(each, 'entityRef'));
      return triggering.length === 1 && triggering[0] === route.actor && numberAttr(traveled, 'value', NaN) >= from.along - 1e-9;
    }
    const time = named(condition, 'SimulationTimeCondition')[0];
    return (
      time !== undefined &&
      from.time !== undefined &&
      FROM_TIME_ON.has(attr(time, 'rule') ?? '') &&
      numberAttr(time, 'value', NaN) >= from.time - 1e-9
    );
  };
  const found: Node[] = [];
  for (const story of named(tree, 'Story'))
    for (const speed of named(story, 'SpeedAction')) {
      const event = ancestor(speed, 'Event');
      if (!event || event === route.event || !mayActOn(speed, route.actor)) continue;
      const absolute = named(speed, 'AbsoluteTargetSpeed')[0];
      if (!absolute || !(numberAttr(absolute, 'value', NaN) >= 0)) continue;
      const trigger = child(event, 'StartTrigger');
      const groups = trigger ? childrenNamed(trigger, 'ConditionGroup') : [];
      const act = ancestor(event, 'Act');
      if (groups.length > 0 && groups.every((group) => childrenNamed(group, 'Condition').some((each) => startedLater(each, act))))
        found.push(speed);
    }
  return found;
}

/** A vehicle's story route that starts at `time` s from the run's start on its speed profile: where it is then, and at what speed. */
function profiledStart(profile: SpeedProfile, time: number, condition: string): RouteStart {
  const along = distanceAt(profile, time);
  return {
    speed: speedAt(profile, time),
    along,
    profile,
    startTime: time,
    how: `${Number(along.toFixed(3))} m along its lane from its start (${condition}, at ${fourDecimals(time)} s)`,
  };
}

/** storyRouteStart for the actor's speed without the actions `except` holds (the route action, a walker's later speeds). */
function storyRouteStartAt(tree: Node, action: Node, actor: string, except: ReadonlySet<Node>, walker: boolean): RouteStart | string {
  const event = ancestor(action, 'Event');
  const act = ancestor(action, 'Act');
  const trigger = event ? child(event, 'StartTrigger') : undefined;
  const conditions = trigger ? childrenNamed(trigger, 'ConditionGroup').flatMap((group) => childrenNamed(group, 'Condition')) : [];
  const unknown = `where '${actor}' is when the action starts ${PLACE_UNKNOWN}, so no trajectory can start there (${NO_TRAJECTORY_FROM_ANYWHERE})`;
  if (!event || !act || conditions.length !== 1)
    return `its Event starts on ${conditions.length === 0 ? 'no condition' : `${conditions.length} conditions`}: ${unknown}`;
  const condition = conditions[0];
  const kind = named(condition, new Set(['EntityCondition', 'ByValueCondition']))[0]?.children[0]?.name ?? 'a condition';
  const delay = numberAttr(condition, 'delay', 0);
  if (!Number.isFinite(delay) || delay < 0) return `its start condition's delay is not a number of seconds: ${unknown}`;
  const counted = CARLA_FACTS.conditionsCountFromTheirStart;
  const fromItsStart = `ScenarioRunner ${counted.does} (${counted.source}), esmini from the run's start, and its Act starts later or on another condition`;
  const kept = constantSpeedOf(tree, actor, except);
  if (kind === 'TraveledDistanceCondition') {
    const traveled = named(condition, kind)[0];
    const triggering = named(condition, 'EntityRef').map((each) => attr(each, 'entityRef') ?? '');
    if (triggering.length !== 1 || triggering[0] !== actor)
      return `its Event starts when ${triggering.join(', ') || 'no entity'} has traveled a distance, not '${actor}' alone: ${unknown}`;
    const distance = numberAttr(traveled, 'value', NaN);
    if (!(distance >= 0)) return `its TraveledDistanceCondition's value is not a distance: ${unknown}`;
    const story = kept === undefined ? storySpeedOf(tree, actor, except) : undefined;
    const speed = kept ?? (story && ancestor(story.action, 'Act') === act ? story.speed : undefined);
    // A vehicle whose story changes its speed at known times reaches the distance at a known time too.
    const profile = speed === undefined && !walker ? routeSpeedProfile(tree, actor, action) : undefined;
    if (profile !== undefined && typeof profile !== 'string') {
      if (!startsAtZero(act)) return `'${actor}' drives from the run's start and ${fromItsStart}: ${unknown}`;
      return profiledStart(
        profile,
        timeAt(profile, distance) + delay,
        `its TraveledDistanceCondition ${distance} m${delay > 0 ? ` and ${delay} s delay` : ''}`,
      );
    }
    if (speed === undefined)
      return walker
        ? `the speed of '${actor}' until the action starts is not certain (neither kept from the Init nor set once by a step SpeedAction of the same Act with the actor standing until then), so where it is then is not known; ${WALKER_LATER}`
        : `the speed of '${actor}' is not certain from the action's start (neither kept from the Init nor set once by a step SpeedAction of the same Act with the actor standing until then, nor changed only at known times: ${profile ?? 'no speed'}), and ScenarioRunner would drive to the vertices by times computed at one speed`;
    if (kept !== undefined && !startsAtZero(act)) return `'${actor}' drives from the run's start and ${fromItsStart}: ${unknown}`;
    const along = distance + speed * delay;
    return {
      speed,
      along,
      ...(kept !== undefined ? { startTime: distance / kept + delay } : {}),
      how: `${Number(along.toFixed(3))} m along its lane from its start (its TraveledDistanceCondition ${distance} m${delay > 0 ? ` and ${delay} s delay` : ''})`,
    };
  }
  if (kind === 'SimulationTimeCondition') {
    const time = named(condition, kind)[0];
    const seconds = numberAttr(time, 'value', NaN);
    if (!FROM_TIME_ON.has(attr(time, 'rule') ?? '') || !(seconds >= 0))
      return `its SimulationTimeCondition does not name a time from which on it holds: ${unknown}`;
    const profile = kept === undefined && !walker ? routeSpeedProfile(tree, actor, action) : undefined;
    if (kept === undefined && typeof profile !== 'object')
      return `the speed of '${actor}' is not certain from the run's start to the action's (none set at once in the Init, a controller of its own, or an action of its story changes it${profile ? `, not only at known times: ${profile}` : ''}): ${unknown}${walker ? `; ${WALKER_LATER}` : ''}`;
    if (!startsAtZero(act)) return `${fromItsStart}: ${unknown}`;
    if (typeof profile === 'object') return profiledStart(profile, seconds + delay, `its SimulationTimeCondition ${seconds + delay} s`);
    if (kept === undefined) return `the speed of '${actor}' is not certain: ${unknown}`;
    const along = kept * (seconds + delay);
    return {
      speed: kept,
      along,
      startTime: seconds + delay,
      how: `${Number(along.toFixed(3))} m along its lane from its start (${seconds + delay} s at ${fourDecimals(kept)} m/s)`,
    };
  }
  return `its Event starts on ${withArticle(kind)}: ${unknown}`;
}

/**
 * The export's mapping rules, one function each: a 1.1-1.3 form written in its 1.0 form where the meaning is
 * kept, or what ScenarioRunner refuses, ignores or crashes on dropped, approximated or refused, each reported.
 * Every rule names the ScenarioRunner code it follows (revision SR_REVISION of carlaFacts.ts).
 */
import type { RoadNetwork } from '../opendrive/road';
import type { RoadXY } from '../opendrive/geo';
import { pointAlongRoute } from '../opendrive/route';
import { CarlaRelease, SR_ATOMICS, SR_CONFIGURATION, SR_PARSER, SR_SCENARIO } from './carlaFacts';
import { CARLA_FACTS, CARLA_PROFILE } from '../profiles/carla';
import { runStopTime } from './routeSpeedProfile';
import { ESMINI_SMALL_NUMBER } from '../profiles/esmini';
import { breaks } from '../profiles/checks';
import {
  allNodes,
  ancestor,
  appendChild,
  attr,
  child,
  childrenNamed,
  cloneNode,
  fourDecimals,
  makeNode,
  numberAttr,
  named,
  Node,
  removeAttr,
  removeChildren,
  removeNode,
  renameAttr,
  replaceNode,
  setAttr,
} from './tree';
import { sampledShape, sampledWorldPoints, TrajectoryEnds } from './carlaTrajectories';
import { dropUnit } from './carlaLosses';
import type { CarlaLoss, LossSink } from './carlaLosses';
import { variables } from './carlaVariables';
import { actorsOf, constantSpeedOf, scenarioObjectOf, startSpeedOf } from './scenarioTree';
import { speedProfiles } from './speedProfiles';
import { absoluteTargetLanes, laneChangesByDistance, PEAK_FACTOR } from './laneChanges';
import { polylinePoints, trajectoryPoint } from './trajectoryPoint';
import { actsOf, ElementShape, storyboardStopGroups } from '../semantics/storyboardStop';
import { initStarts } from './initStarts';
import { synchronizeSteadyStates } from './steadyStates';
import { lateralDistances } from './lateralDistances';
import { laneOffsets } from './laneOffsets';
import { SAMPLE_STEP } from './shapes';
import { routeTrajectory, routeWaypoints } from './routeTrajectories';

export type { CarlaLoss, LossSink };

export interface RuleContext {
  release: CarlaRelease;
  sink: LossSink;
  /** The scenario's OpenDRIVE roads when the road is an `.xodr` file the export read, or a CARLA town's found in the road path (route positions need their lengths). */
  roads?: RoadNetwork;
  /** The CARLA town the export names as the road, when it names one: ScenarioRunner reads a 'CARLA:' file's positions in its frame there. */
  town?: string;
  /** Each GeoPosition's x, y by the road's geoReference, or why there is none (computed before the rules: proj4js loads lazily). */
  geoPlaces?: Map<Node, RoadXY | string>;
  /** Filled with the Polylines the rules sampled from a uniform shape (SampledShape.uniform), for the schema check. */
  sampledPolylines?: Set<Node>;
}

/** The 1.1 `ControllerAction/ActivateControllerAction` is the 1.0 `PrivateAction/ActivateControllerAction` (SR_PARSER convert_maneuver_to_atomic: ChangeAutoPilot). */
function activateControllerAction(tree: Node, context: RuleContext): void {
  for (const controllerAction of named(tree, 'ControllerAction')) {
    const activate = child(controllerAction, 'ActivateControllerAction');
    if (!activate) continue;
    for (const extra of ['controllerRef', 'objectControllerRef', 'animation', 'lighting']) {
      const value = attr(activate, extra);
      if (
        value !== undefined &&
        removeAttr(activate, extra) &&
        (extra === 'controllerRef' || extra === 'objectControllerRef' || value === 'true')
      )
        context.sink.dropped(
          activate,
          `ActivateControllerAction/@${extra}`,
          'is not in 1.0: dropped',
          `ScenarioRunner toggles the autopilot of the actor itself (${SR_PARSER} ChangeAutoPilot)`,
        );
    }
    const others = controllerAction.children.filter((each) => each !== activate);
    replaceNode(controllerAction, activate);
    // A 1.1 ControllerAction holds one of its actions; others beside it would be a second PrivateAction.
    for (const other of others)
      context.sink.dropped(
        other,
        other.name,
        'written beside an ActivateControllerAction: dropped',
        'a 1.0 PrivateAction holds one action',
      );
  }
}

/** 1.0 needs both halves of a ControllerAction (SR's schema); an inactive override changes nothing (SR_PARSER get_controller refuses only active ones). */
function controllerActionHalves(tree: Node, context: RuleContext): void {
  for (const assign of named(tree, 'AssignControllerAction')) {
    const objectController = child(assign, 'ObjectController');
    if (objectController) replaceNode(objectController, objectController.children[0] ?? makeNode('Controller'));
    for (const extra of ['activateLateral', 'activateLongitudinal', 'activateAnimation', 'activateLighting']) {
      const value = attr(assign, extra);
      if (value === undefined) continue;
      removeAttr(assign, extra);
      if (value === 'true')
        context.sink.approximated(
          assign,
          `AssignControllerAction/@${extra}`,
          'is not in 1.0: dropped',
          `ScenarioRunner activates the module it assigns at once (${SR_PARSER} get_controller, ChangeActorControl)`,
        );
    }
  }
  for (const controllerAction of named(tree, 'ControllerAction')) {
    const assign = child(controllerAction, 'AssignControllerAction');
    let override = child(controllerAction, 'OverrideControllerValueAction');
    if (!assign) {
      dropUnit(
        controllerAction,
        context,
        'ControllerAction',
        `a 1.0 ControllerAction assigns a controller; an override alone has no 1.0 form (${SR_PARSER} get_controller)`,
      );
      continue;
    }
    if (!override) {
      override = appendChild(controllerAction, makeNode('OverrideControllerValueAction'));
    }
    const parts: [string, [string, string][]][] = [
      [
        'Throttle',
        [
          ['value', '0'],
          ['active', 'false'],
        ],
      ],
      [
        'Brake',
        [
          ['value', '0'],
          ['active', 'false'],
        ],
      ],
      [
        'Clutch',
        [
          ['value', '0'],
          ['active', 'false'],
        ],
      ],
      [
        'ParkingBrake',
        [
          ['value', '0'],
          ['active', 'false'],
        ],
      ],
      [
        'SteeringWheel',
        [
          ['value', '0'],
          ['active', 'false'],
        ],
      ],
      [
        'Gear',
        [
          ['number', '0'],
          ['active', 'false'],
        ],
      ],
    ];
    if (override.children.some((each) => attr(each, 'active') === 'true')) {
      dropUnit(
        override,
        context,
        'OverrideControllerValueAction',
        `ScenarioRunner refuses an active override (${SR_PARSER} get_controller: "not yet supported")`,
      );
      continue;
    }
    for (const [name, attributes] of parts) {
      const existing = child(override, name);
      if (existing) {
        removeChildren(existing);
        for (const [key, value] of attributes) if (attr(existing, key) === undefined) setAttr(existing, key, value);
        existing.attributes = existing.attributes.filter(([key]) => attributes.some(([wanted]) => wanted === key));
      } else
        appendChild(
          override,
          makeNode(
            name,
            attributes.map(([key, value]) => [key, value]),
          ),
        );
    }
  }
}

const OKTAS: Record<string, string> = {
  zeroOktas: 'free',
  oneOktas: 'free',
  twoOktas: 'free',
  threeOktas: 'cloudy',
  fourOktas: 'cloudy',
  fiveOktas: 'cloudy',
  sixOktas: 'overcast',
  sevenOktas: 'overcast',
  eightOktas: 'overcast',
  nineOktas: 'overcast',
};

/** A 1.1 attribute in physical units written as the 1.0 attribute of 0..1 (`full` units = 1), where 1.0 has none yet. */
function scaledRename(node: Node, from: string, to: string, full: number, unit: string, context: RuleContext, carla: string): void {
  const written = attr(node, from);
  if (written === undefined) return;
  removeAttr(node, from);
  if (attr(node, to) !== undefined) return;
  const scaled = Number(Math.min(1, Math.max(0, Number(written) / full)).toFixed(4));
  setAttr(node, to, String(scaled));
  if (Number(written) !== 0)
    context.sink.approximated(
      node,
      `${node.name}/@${from}`,
      `${written} ${unit} is written as ${to} ${scaled} (${full} ${unit} = 1)`,
      carla,
    );
}

/** The 1.1 weather in 1.0 words, as far as ScenarioRunner reads them (SR_PARSER get_weather: sun intensity 0..1, rain intensity 0..1, fog range). */
function weather(tree: Node, context: RuleContext): void {
  for (const environment of named(tree, 'Environment')) {
    if (!child(environment, 'TimeOfDay'))
      appendChild(
        environment,
        makeNode('TimeOfDay', [
          ['animation', 'false'],
          ['dateTime', '2020-01-01T12:00:00'],
        ]),
        environment.children[0],
      );
    if (!child(environment, 'Weather')) appendChild(environment, makeNode('Weather'));
    if (!child(environment, 'RoadCondition')) appendChild(environment, makeNode('RoadCondition', [['frictionScaleFactor', '1']]));
    const timeOfDay = child(environment, 'TimeOfDay') as Node;
    const dateTime = attr(timeOfDay, 'dateTime') ?? '';
    const plain = /^(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d)/.exec(dateTime);
    if (plain && plain[1] !== dateTime) {
      setAttr(timeOfDay, 'dateTime', plain[1]);
      context.sink.approximated(
        timeOfDay,
        'TimeOfDay/@dateTime',
        `'${dateTime}' is written as ${plain[1]} (no time zone or fraction)`,
        `ScenarioRunner reads it with strptime "%Y-%m-%dT%H:%M:%S" (${SR_PARSER} get_weather)`,
      );
    }
  }
  for (const node of named(tree, 'Weather')) {
    const cover = attr(node, 'fractionalCloudCover');
    if (cover !== undefined) {
      removeAttr(node, 'fractionalCloudCover');
      if (attr(node, 'cloudState') === undefined) {
        setAttr(node, 'cloudState', OKTAS[cover] ?? 'free');
        context.sink.approximated(
          node,
          'Weather/@fractionalCloudCover',
          `${cover} is written as cloudState="${OKTAS[cover] ?? 'free'}"`,
          `ScenarioRunner does not read the cloud state; its clouds follow the sun's intensity (${SR_PARSER} get_weather)`,
        );
      }
    }
    if (attr(node, 'cloudState') === undefined) setAttr(node, 'cloudState', 'free');
    for (const extra of ['atmosphericPressure', 'temperature']) {
      if (removeAttr(node, extra))
        context.sink.dropped(
          node,
          `Weather/@${extra}`,
          'is not in 1.0: dropped',
          `ScenarioRunner has no such weather parameter (${SR_PARSER} get_weather)`,
        );
    }
    for (const extra of ['Wind', 'DomeImage']) {
      const found = child(node, extra);
      if (found) {
        removeNode(found);
        context.sink.dropped(
          found,
          extra,
          'is not in 1.0: dropped',
          `ScenarioRunner sets a fixed wind and no dome image (${SR_PARSER} get_weather)`,
        );
      }
    }
    let sun = child(node, 'Sun');
    if (!sun)
      sun = appendChild(
        node,
        makeNode('Sun', [
          ['azimuth', '0'],
          ['elevation', '1.31'],
          ['intensity', '1'],
        ]),
      );
    scaledRename(
      sun,
      'illuminance',
      'intensity',
      100000,
      'lx',
      context,
      `ScenarioRunner reads the intensity as 0..1, cloudiness = 100 - 100 x intensity (${SR_PARSER} get_weather)`,
    );
    for (const [key, value] of [
      ['azimuth', '0'],
      ['elevation', '1.31'],
      ['intensity', '1'],
    ])
      if (attr(sun, key) === undefined) setAttr(sun, key, value);
    if (!child(node, 'Fog')) appendChild(node, makeNode('Fog', [['visualRange', '100000']]));
    let precipitation = child(node, 'Precipitation');
    if (!precipitation)
      precipitation = appendChild(
        node,
        makeNode('Precipitation', [
          ['precipitationType', 'dry'],
          ['intensity', '0'],
        ]),
      );
    scaledRename(
      precipitation,
      'precipitationIntensity',
      'intensity',
      10,
      'mm/h',
      context,
      `ScenarioRunner reads the intensity as 0..1 (${SR_PARSER} get_weather)`,
    );
    if (attr(precipitation, 'intensity') === undefined) setAttr(precipitation, 'intensity', '0');
    // The 1.0 Weather is an xsd:all of Sun, Fog, Precipitation: any order is valid.
  }
}

/** `timeGap` is refused (SR_PARSER: "LongitudinalDistanceAction: timeGap is not implemented"): a distance at the actor's start speed. */
function longitudinalTimeGap(tree: Node, context: RuleContext): void {
  for (const action of named(tree, 'LongitudinalDistanceAction')) {
    const displacement = attr(action, 'displacement');
    for (const extra of ['coordinateSystem', 'displacement']) {
      const value = attr(action, extra);
      if (value === undefined || !removeAttr(action, extra)) continue;
      if (!['entity', 'trailingReferencedEntity', 'any', 'leadingReferencedEntity'].includes(value))
        context.sink.approximated(
          action,
          `LongitudinalDistanceAction/@${extra}`,
          `${value} is not in 1.0: dropped`,
          `ScenarioRunner keeps the distance behind or ahead as the actors stand (${SR_PARSER} KeepLongitudinalGap)`,
        );
    }
    const gap = attr(action, 'timeGap');
    if (gap !== undefined) {
      const actors = actorsOf(action);
      const speed =
        actors.length === 1 ? (startSpeedOf(tree, attr(action, 'entityRef') ?? actors[0]) ?? startSpeedOf(tree, actors[0])) : undefined;
      const carla = `ScenarioRunner refuses a time gap ("timeGap is not implemented", ${SR_PARSER} convert_maneuver_to_atomic)`;
      if (speed === undefined || !(speed > 0)) {
        dropUnit(action, context, 'LongitudinalDistanceAction/@timeGap', `${carla}; no start speed to turn it into a distance`);
        continue;
      }
      const distance = Number((Number(gap) * speed).toFixed(3));
      removeAttr(action, 'timeGap');
      setAttr(action, 'distance', String(distance));
      context.sink.approximated(
        action,
        'LongitudinalDistanceAction/@timeGap',
        `${gap} s is written as ${distance} m (at the start speed ${speed} m/s)`,
        carla,
      );
    }
    if (displacement === 'leadingReferencedEntity') leadingGap(action, context);
  }
}

/**
 * 1.0 has no `displacement`: an actor that leads its reference is a negative distance there, as esmini reads a 1.0 file
 * (OSCPrivateAction.cpp LongDistanceAction::Step: the requested distance keeps its sign before 1.1); ScenarioRunner keeps no such gap.
 */
function leadingGap(action: Node, context: RuleContext): void {
  const distance = Number(attr(action, 'distance'));
  if (!Number.isFinite(distance)) return;
  setAttr(action, 'distance', fourDecimals(-Math.abs(distance)));
  const fact = CARLA_FACTS.longitudinalGapBehindOnly;
  context.sink.approximated(
    action,
    'LongitudinalDistanceAction/@displacement',
    `leadingReferencedEntity is written as the distance ${fourDecimals(-Math.abs(distance))} m (1.0 has no displacement: a negative distance puts the actor ahead, as esmini reads 1.0)`,
    `ScenarioRunner ${fact.does} (${fact.source})`,
  );
}

/**
 * The 1.1 TrajectoryRef wraps what 1.0 writes directly; Clothoid, ClothoidSpline and Nurbs, which ScenarioRunner
 * refuses (SR_PARSER get_trajectory: "Clothoid shapes are currently unsupported"), are sampled into Polylines
 * (carlaTrajectories.ts), or dropped naming why not.
 */
function trajectories(tree: Node, context: RuleContext): void {
  const ends: TrajectoryEnds = new Map();
  for (const action of named(tree, 'FollowTrajectoryAction')) {
    const wrapper = child(action, 'TrajectoryRef');
    if (wrapper) {
      const inner = wrapper.children[0];
      if (inner) replaceNode(wrapper, inner);
      else removeNode(wrapper);
    }
    const offset = attr(action, 'initialDistanceOffset');
    // In the Init, init-starts starts the trajectory there once it is a Polyline.
    if (offset !== undefined && !ancestor(action, 'Init')) {
      removeAttr(action, 'initialDistanceOffset');
      if (Number(offset) !== 0)
        context.sink.approximated(
          action,
          'FollowTrajectoryAction/@initialDistanceOffset',
          'is not in 1.0: the trajectory is followed from its start',
          `${SR_PARSER} get_trajectory reads the vertices only`,
        );
    }
    if (!child(action, 'TimeReference')) appendChild(action, makeNode('TimeReference', [], [makeNode('None')]));
    const mode = child(action, 'TrajectoryFollowingMode');
    if (!mode) appendChild(action, makeNode('TrajectoryFollowingMode', [['followingMode', 'position']]));
    else for (const extra of ['lateralControlStrategy']) removeAttr(mode, extra);
    const shape = allNodes(action).find((each) => each.name === 'Clothoid' || each.name === 'Nurbs' || each.name === 'ClothoidSpline');
    if (shape) {
      const carla = `ScenarioRunner follows polylines only and refuses a ${shape.name} (${SR_PARSER} get_trajectory)`;
      const sampled = sampledShape(action, shape, tree, context.roads, ends);
      if (typeof sampled === 'string') {
        dropUnit(action, context, shape.name, `${carla}; the export cannot sample it: ${sampled}`);
        continue;
      }
      replaceNode(shape, sampled.polyline);
      if (sampled.uniform) context.sampledPolylines?.add(sampled.polyline);
      const relative = sampled.relative;
      context.sink.approximated(
        sampled.polyline,
        shape.name,
        `sampled into a Polyline of ${sampled.vertices} vertices ${SAMPLE_STEP} m apart, as esmini samples it${
          relative
            ? `, placed from where '${relative.entity}' is when the action starts, assuming it heads ${Number(((relative.heading * 180) / Math.PI).toFixed(2))}° then (${relative.from})`
            : ''
        }`,
        carla,
      );
    }
    const timing = child(child(action, 'TimeReference') ?? action, 'Timing');
    for (const polyline of named(action, 'Polyline')) {
      if (!timing && untimedVertices(tree, action, polyline, context)) continue;
      const vertices = childrenNamed(polyline, 'Vertex');
      const missing = vertices.filter((vertex) => attr(vertex, 'time') === undefined);
      if (missing.length === 0) continue;
      for (const vertex of vertices) if (attr(vertex, 'time') === undefined) setAttr(vertex, 'time', '0');
      context.sink.approximated(
        polyline,
        'Vertex/@time',
        `${missing.length} vertices without a time are given time 0`,
        `1.0 requires a vertex time; ScenarioRunner ${timing ? 'reads the times' : untimedReading(tree, action)} (${SR_PARSER} get_trajectory)`,
      );
    }
    trajectoryEnd(tree, action, context);
  }
}

/**
 * Past a vehicle's trajectory's last vertex ScenarioRunner raises, which ends the run (CARLA_FACTS.trajectoryEndRaises):
 * named on the trajectory, unless it starts with the run and the run stops by its last vertex's time.
 */
function trajectoryEnd(tree: Node, action: Node, context: RuleContext): void {
  const vehicles = actorsOf(action).filter((actor) => isVehicle(tree, actor));
  const polyline = named(action, 'Polyline')[0];
  const lastVertex = polyline ? childrenNamed(polyline, 'Vertex').at(-1) : undefined;
  const last = lastVertex ? Number(attr(lastVertex, 'time')) : NaN;
  if (!polyline || vehicles.length === 0 || !Number.isFinite(last)) return;
  const stop = runStopTime(tree);
  if (ancestor(action, 'Init') && stop !== undefined && last >= stop) return;
  const fact = CARLA_FACTS.trajectoryEndRaises;
  context.sink.approximated(
    polyline,
    'Polyline/Vertex',
    `written as it is; by its times ${vehicles.map((vehicle) => `'${vehicle}'`).join(', ')} ${vehicles.length === 1 ? 'reaches' : 'reach'} the last vertex ${last > 0 ? `${fourDecimals(last)} s after the action starts` : 'as fast as the controller drives (its times are 0)'}, where ScenarioRunner's controller raises and ends the run with an error unless it has stopped by then${stop === undefined ? ' (the export knows no stop time)' : ` (it stops at ${fourDecimals(stop)} s at the latest)`}`,
    `ScenarioRunner ${fact.does} (${fact.source})`,
  );
}

/**
 * A trajectory without timing is followed at the actor's speed (the standard ignores its vertex times; so does esmini), but
 * ScenarioRunner's vehicle controller drives to each vertex by its time (CARLA_FACTS.trajectoryTimesSetSpeed): a vehicle's
 * vertices are given the times its speed reaches them in. Returns whether it wrote them.
 */
function untimedVertices(tree: Node, action: Node, polyline: Node, context: RuleContext): boolean {
  const actors = actorsOf(action);
  if (actors.length !== 1 || !isVehicle(tree, actors[0])) return false;
  const constant = constantSpeedOf(tree, actors[0], action);
  const speed = Math.abs(constant ?? startSpeedOf(tree, actors[0]) ?? 0);
  const points = speed > 0 ? vertexDistances(polyline, context.roads) : undefined;
  if (!points) return false;
  const vertices = childrenNamed(polyline, 'Vertex');
  const written = vertices.filter((vertex) => attr(vertex, 'time') !== undefined).length;
  vertices.forEach((vertex, index) => setAttr(vertex, 'time', fourDecimals(points[index] / speed)));
  const fact = CARLA_FACTS.trajectoryTimesSetSpeed;
  context.sink.approximated(
    polyline,
    'Vertex/@time',
    `the trajectory has no timing: its ${vertices.length} vertices are given the times the actor reaches them in at ${
      constant === undefined ? `its start speed ${speed} m/s (its speed may change before or on the way)` : `its speed ${speed} m/s`
    }${written > 0 ? ` (${written === 1 ? 'the time' : `the ${written} times`} written, which no timing reads, replaced)` : ''}`,
    `ScenarioRunner ${fact.does} (${fact.source})`,
  );
  return true;
}

/** What ScenarioRunner does with the times of a trajectory without timing: its vehicle controller drives by them, its pedestrian controller ignores them. */
function untimedReading(tree: Node, action: Node): string {
  if (scenarioObjectOf(tree, actorsOf(action)[0]) && !isVehicle(tree, actorsOf(action)[0]))
    return 'passes the times on, and its pedestrian controller does not read them (pedestrian_control.py)';
  return `${CARLA_FACTS.trajectoryTimesSetSpeed.does} (${CARLA_FACTS.trajectoryTimesSetSpeed.source})`;
}

/** Whether the entity is a Vehicle (a catalog entry is inlined by now). */
function isVehicle(tree: Node, name: string): boolean {
  const object = scenarioObjectOf(tree, name);
  return object !== undefined && child(object, 'Vehicle') !== undefined;
}

/** How far along the polyline each vertex lies, where the places are known: world, lane or road positions, or offsets from one entity. */
function vertexDistances(polyline: Node, roads: RoadNetwork | undefined): number[] | undefined {
  const positions = childrenNamed(polyline, 'Vertex').map((vertex) => child(vertex, 'Position')?.children[0]);
  let points: { x: number; y: number }[] | string;
  const references = new Set(positions.map((position) => (position ? attr(position, 'entityRef') : undefined)));
  if (
    positions.every((position) => position?.name === 'RelativeWorldPosition' || position?.name === 'RelativeObjectPosition') &&
    references.size === 1
  )
    points = positions.map((position) => ({ x: numberAttr(position as Node, 'dx', NaN), y: numberAttr(position as Node, 'dy', NaN) }));
  else points = polylinePoints(polyline, roads);
  if (typeof points === 'string' || points.some((point) => !Number.isFinite(point.x) || !Number.isFinite(point.y))) return undefined;
  let along = 0;
  return points.map(
    (point, index) => (along += index === 0 ? 0 : Math.hypot(point.x - points[index - 1].x, point.y - points[index - 1].y)),
  );
}

/** A position ScenarioRunner cannot convert: refused where it places an actor at the start, else its condition or action dropped. */
function unconvertiblePosition(node: Node, name: string, context: RuleContext, why = ''): void {
  if (ancestor(node, 'Init') && ancestor(node, 'TeleportAction')) {
    context.sink.refuse(
      node,
      name,
      `places an actor at the start, and ScenarioRunner cannot place it${why}`,
      `${SR_PARSER} convert_position_to_transform has no ${name}`,
    );
    return;
  }
  dropUnit(node, context, name, `ScenarioRunner has no ${name} (${SR_PARSER} convert_position_to_transform)${why}`);
}

/**
 * A RoutePosition written as the LanePosition (FromLaneCoordinates) or RoadPosition (FromRoadCoordinates) of
 * the point it names: ScenarioRunner has no RoutePosition (SR_PARSER convert_position_to_transform raises
 * NotImplementedError) but converts both (same function). The point is where esmini puts it
 * (core/opendrive/route.ts: the roads between the waypoints planned as esmini's RoadPath plans them,
 * then Route::SetPathS), on the lane and with the offset the position names; the heading follows the lane as
 * for a LanePosition (OSCPosition.cpp SetRouteRefLaneCoord). A route esmini's planning leaves ambiguous, or
 * that has no way through the network, is named why.
 */
function routePositions(tree: Node, context: RuleContext): void {
  for (const position of named(tree, 'RoutePosition')) {
    if (!position.parent) continue;
    const mapped = routePositionAsLane(position, context.roads);
    if (typeof mapped === 'string') {
      unconvertiblePosition(position, 'RoutePosition', context, `; the export cannot write it otherwise: ${mapped}`);
      continue;
    }
    replaceNode(position, mapped.node);
    context.sink.approximated(
      mapped.node,
      'RoutePosition',
      `written as the ${mapped.node.name} it names (${mapped.summary})`,
      `ScenarioRunner has no RoutePosition (${SR_PARSER} convert_position_to_transform) and converts a ${mapped.node.name}; the point is where esmini puts it (RoadManager.cpp RoadPath::Calculate, Route::SetPathS)`,
    );
  }
}

function routePositionAsLane(position: Node, roads: RoadNetwork | undefined): { node: Node; summary: string } | string {
  const route = child(child(position, 'RouteRef') ?? position, 'Route');
  if (!route) return 'its route is not written in the scenario or a catalog it loads';
  const waypoints = routeWaypoints(route);
  if (typeof waypoints === 'string') return waypoints;
  if (waypoints.length === 0) return 'its route has no waypoint';
  const inRoute = child(position, 'InRoutePosition');
  const coordinates = inRoute?.children[0];
  if (!coordinates || (coordinates.name !== 'FromLaneCoordinates' && coordinates.name !== 'FromRoadCoordinates'))
    return `${coordinates?.name ?? 'an empty InRoutePosition'} is where the entity is when the scenario runs`;
  const pathS = Number(attr(coordinates, 'pathS'));
  if (!Number.isFinite(pathS) || pathS < 0) return 'its pathS is not a number of metres along the route';
  let roadId = waypoints[0].roadId;
  let s = waypoints[0].s;
  let via = '';
  if (pathS > 0) {
    if (!roads) return 'the road is a CARLA town, whose roads the export cannot read';
    const point = pointAlongRoute(roads, waypoints, pathS);
    if (typeof point === 'string') return point;
    ({ roadId, s } = point);
    const index = point.roads.indexOf(roadId);
    if (index > 0) via = `, the route's road ${index + 1} (${point.roads.slice(0, index + 1).join(' > ')})`;
  }
  const written = String(Number(s.toFixed(6)));
  const orientation = child(position, 'Orientation');
  const extra = orientation ? [cloneNode(orientation)] : [];
  if (coordinates.name === 'FromRoadCoordinates') {
    const t = attr(coordinates, 't') ?? '0';
    return {
      node: makeNode(
        'RoadPosition',
        [
          ['roadId', roadId],
          ['s', written],
          ['t', t],
        ],
        extra,
        position.place,
      ),
      summary: `road ${roadId}, s ${written}, t ${t}${via}`,
    };
  }
  const laneId = attr(coordinates, 'laneId') ?? '';
  const offset = attr(coordinates, 'laneOffset') ?? '0';
  return {
    node: makeNode(
      'LanePosition',
      [
        ['roadId', roadId],
        ['laneId', laneId],
        ['offset', offset],
        ['s', written],
      ],
      extra,
      position.place,
    ),
    summary: `road ${roadId}, lane ${laneId}, s ${written}${offset !== '0' ? `, offset ${offset}` : ''}${via}`,
  };
}

/** A GeoPosition's latitude and longitude in degrees (1.2 `latitudeDeg`; 1.1 `latitude` in radians), or undefined when not numbers. */
export function geoPositionDegrees(position: Node): { latitude: number; longitude: number } | undefined {
  const degrees = (name: string, radians: string): number => {
    const value = attr(position, name);
    return value !== undefined ? Number(value) : (Number(attr(position, radians)) * 180) / Math.PI;
  };
  const latitude = degrees('latitudeDeg', 'latitude');
  const longitude = degrees('longitudeDeg', 'longitude');
  return Number.isFinite(latitude) && Number.isFinite(longitude) ? { latitude, longitude } : undefined;
}

/**
 * A GeoPosition (1.1+) written as the WorldPosition its road's geoReference gives (core/opendrive/geo.ts). ScenarioRunner
 * has none: its 1.0 schema has no GeoPosition and convert_position_to_transform raises "Unknown position"
 * (SR_PARSER); its only geo code, srunner/tools/route_manipulation.py, turns locations into GPS for route scenarios.
 * Its altitude is not kept (a WorldPosition's z is the height ScenarioRunner spawns at, not above the ellipsoid);
 * an absolute Orientation becomes h, p, r; a relative one is relative to the road there, which the export does not compute.
 */
function geoPositions(tree: Node, context: RuleContext): void {
  for (const position of named(tree, 'GeoPosition')) {
    if (!position.parent) continue;
    const orientation = child(position, 'Orientation');
    let placed =
      context.geoPlaces?.get(position) ??
      (context.roads ? 'its latitude or longitude is not a number' : 'the road is not an .xodr file the export read');
    if (typeof placed !== 'string' && orientation && attr(orientation, 'type') === 'relative')
      placed = 'its Orientation is relative to the road at that point, which the export does not compute';
    if (typeof placed === 'string') {
      unconvertiblePosition(position, 'GeoPosition', context, `; the export cannot write it otherwise: ${placed}`);
      continue;
    }
    const angles = (['h', 'p', 'r'] as const).flatMap((name): [string, string][] => {
      const value = orientation ? attr(orientation, name) : undefined;
      return value !== undefined ? [[name, value]] : [];
    });
    const world = makeNode('WorldPosition', [['x', fourDecimals(placed.x)], ['y', fourDecimals(placed.y)], ...angles], [], position.place);
    replaceNode(position, world);
    const altitude = attr(position, 'altitude') ?? attr(position, 'height');
    const carla = placed.carla
      ? `; CARLA's own geolocation of this map (its GNSS; LibCarla GeoLocation with +lat_0/+lon_0 only) puts that latitude/longitude at x ${fourDecimals(placed.carla.x)}, y ${fourDecimals(placed.carla.y)}, ${Math.hypot(placed.carla.x - placed.x, placed.carla.y - placed.y).toFixed(1)} m away`
      : '';
    context.sink.approximated(
      world,
      'GeoPosition',
      `written as WorldPosition x ${fourDecimals(placed.x)}, y ${fourDecimals(placed.y)} by ${placed.how}${altitude !== undefined ? `; its altitude ${altitude} is not kept` : ''}${carla}`,
      `ScenarioRunner has no GeoPosition (not in its 1.0 schema; ${SR_PARSER} convert_position_to_transform raises "Unknown position") and converts a WorldPosition`,
    );
  }
}

/**
 * A negative start speed (an Init SpeedAction's AbsoluteTargetSpeed: an actor driving backwards, as Euro NCAP's
 * reverse tests start) is refused: ScenarioRunner reads each actor's start speed while loading and raises
 * AttributeError on one below 0 (SR_CONFIGURATION _get_actor_speed), so nothing of the scenario would run.
 */
function negativeStartSpeeds(tree: Node, context: RuleContext): void {
  const init = named(tree, 'Init')[0];
  if (!init) return;
  for (const target of named(init, 'AbsoluteTargetSpeed')) {
    const value = Number(attr(target, 'value'));
    const owner = ancestor(target, 'Private');
    if (!target.parent || !owner || !(value < 0)) continue;
    context.sink.refuse(
      target,
      'Init/SpeedAction/AbsoluteTargetSpeed',
      `the start speed ${attr(target, 'value') ?? ''} of ${attr(owner, 'entityRef') ?? 'an actor'} is negative (backwards), which ScenarioRunner refuses while loading`,
      `ScenarioRunner ${CARLA_FACTS.negativeStartSpeed.does} (${CARLA_FACTS.negativeStartSpeed.source})`,
    );
  }
}

/** How the trajectory of a TrajectoryPosition was read: its polyline, or the curve sampled as esmini samples it. */
function sampledNote(position: Node): string {
  const shape = child(child(child(position, 'TrajectoryRef') ?? position, 'Trajectory') ?? position, 'Shape')?.children[0];
  return !shape || shape.name === 'Polyline' ? "'s polyline" : ` (a ${shape.name}, sampled as esmini samples it, ${SAMPLE_STEP} m apart)`;
}

/**
 * A TrajectoryPosition written as the WorldPosition of its point (trajectoryPoint.ts): ScenarioRunner has no
 * TrajectoryPosition (SR_PARSER convert_position_to_transform raises "Unknown position") but converts a
 * WorldPosition. Euro NCAP's scenarios synchronize a VRU or a crossing car to such a point; one that has no point
 * without running the scenario is dropped or refused, naming why.
 */
function trajectoryPositions(tree: Node, context: RuleContext): void {
  for (const position of named(tree, 'TrajectoryPosition')) {
    if (!position.parent) continue;
    const point = trajectoryPoint(position, context.roads, sampledWorldPoints);
    if (typeof point === 'string') {
      unconvertiblePosition(position, 'TrajectoryPosition', context, `; the export cannot write it otherwise: ${point}`);
      continue;
    }
    const world = makeNode(
      'WorldPosition',
      [
        ['x', fourDecimals(point.x)],
        ['y', fourDecimals(point.y)],
        ['h', fourDecimals(point.h)],
      ],
      [],
      position.place,
    );
    replaceNode(position, world);
    context.sink.approximated(
      world,
      'TrajectoryPosition',
      `written as WorldPosition x ${fourDecimals(point.x)}, y ${fourDecimals(point.y)}, h ${fourDecimals(point.h)}: the point s ${attr(position, 's') ?? '0'} along its trajectory${sampledNote(position)}, t ${attr(position, 't') ?? '0'} to the left; its height is ScenarioRunner's spawn height, not the road's`,
      `ScenarioRunner has no TrajectoryPosition (${SR_PARSER} convert_position_to_transform) and converts a WorldPosition`,
    );
  }
}

/** ScenarioRunner refuses these positions (SR_PARSER convert_position_to_transform). */
function unsupportedPositions(tree: Node, context: RuleContext): void {
  // RoutePosition, GeoPosition and TrajectoryPosition: the rules route-positions, geo-positions and trajectory-positions write or name every one.
  for (const node of named(tree, 'RoadRange')) {
    if (!node.parent) continue;
    unconvertiblePosition(node, 'RoadRange', context);
  }
  for (const position of named(tree, 'RelativeLanePosition')) {
    const dsLane = attr(position, 'dsLane');
    if (dsLane !== undefined) {
      removeAttr(position, 'dsLane');
      if (attr(position, 'ds') === undefined) setAttr(position, 'ds', dsLane);
      context.sink.approximated(
        position,
        'RelativeLanePosition/@dsLane',
        `the distance along the lane ${dsLane} is written as ds (along the road)`,
        `${SR_PARSER} convert_position_to_transform reads ds`,
      );
    }
  }
}

/** Actions ScenarioRunner refuses while building (SR_PARSER convert_maneuver_to_atomic) or that are not 1.0. */
const REFUSED_ACTIONS: Record<string, string> = {
  TrafficAction: `ScenarioRunner refuses global traffic actions ("Global actions are not yet supported", ${SR_PARSER} convert_maneuver_to_atomic)`,
  VisibilityAction: `ScenarioRunner refuses it ("Visibility actions are not yet supported", ${SR_PARSER} convert_maneuver_to_atomic)`,
  SetMonitorAction: 'monitors are not in 1.0',
  LightStateAction: 'vehicle lights are not in 1.0',
  AnimationAction: 'animations are not in 1.0',
  AppearanceAction: 'appearance actions are not in 1.0',
  ConnectTrailerAction: 'trailers are not in 1.0',
  DisconnectTrailerAction: 'trailers are not in 1.0',
  RandomRouteAction: 'random routes are not in 1.0',
  SpeedProfileAction: 'speed profiles are not in 1.0',
  TrafficAreaAction: 'traffic areas are not in 1.0',
  TrafficStopAction: 'traffic actions are not in 1.0',
  UserDefinedAction: `ScenarioRunner does not run user-defined actions other than a CustomCommandAction (${SR_PARSER} convert_maneuver_to_atomic)`,
};

const REFUSED_ACTION_NAMES: ReadonlySet<string> = new Set(Object.keys(REFUSED_ACTIONS));

/** Of the refused actions, those the Init passes over rather than refuses (CARLA_PROFILE: support 'ignored' in the Init). */
const PASSED_OVER_IN_INIT: ReadonlyMap<string, string> = new Map(
  CARLA_PROFILE.elements
    .filter((fact) => fact.support === 'ignored' && fact.in === 'init')
    .map((fact) => [fact.element, `ScenarioRunner passes over it in the Init: ${fact.note ?? 'it is not run there'} (${fact.source})`]),
);

function refusedActions(tree: Node, context: RuleContext): void {
  for (const node of named(tree, REFUSED_ACTION_NAMES)) {
    if (!node.parent || !ancestor(node, 'OpenSCENARIO')) continue;
    // Dropped all the same (a 1.2 TrafficSwarmAction kept would fail the 1.0 schema), but worded as what ScenarioRunner does there.
    const passedOver = ancestor(node, 'Init') ? PASSED_OVER_IN_INIT.get(node.name) : undefined;
    if (passedOver !== undefined) {
      dropUnit(node, context, node.name, passedOver);
      continue;
    }
    if (node.name === 'UserDefinedAction' && child(node, 'CustomCommandAction')) continue;
    dropUnit(node, context, node.name, REFUSED_ACTIONS[node.name]);
  }
}

/** An Init action ScenarioRunner passes over (CARLA_PROFILE.elements, support 'ignored' in the Init) is kept as written, and reported; those dropped as refused above are gone by now. */
function initActionsPassedOver(tree: Node, context: RuleContext): void {
  const init = named(tree, 'Init')[0];
  if (!init) return;
  for (const fact of CARLA_PROFILE.elements) {
    if (fact.support !== 'ignored' || fact.in !== 'init') continue;
    for (const node of named(init, fact.element)) {
      if (!node.parent) continue;
      context.sink.approximated(
        node,
        `Init/${fact.element}`,
        'is kept as written, but not run: ScenarioRunner passes over it in the Init',
        `ScenarioRunner passes over it: ${fact.note ?? 'it is not run in the Init'} (${fact.source})`,
      );
    }
  }
}

/**
 * ScenarioRunner 0.9.16 builds every AssignRouteAction and AcquirePositionAction as ChangeActorWaypoints without times, which
 * raises (SR_ATOMICS ChangeActorWaypoints.__init__, commit ab5996d7): written as the FollowTrajectoryAction that drives the same
 * lanes where the export can plan them (routeTrajectories.ts), else refused naming why not.
 */
function routeActionCrash(tree: Node, context: RuleContext): void {
  if (context.release !== '0.9.16') return;
  const crash = `0.9.16 creates ChangeActorWaypoints without times for it, which raises "object of type 'NoneType' has no len()" (${SR_ATOMICS} ChangeActorWaypoints.__init__, a regression of commit ab5996d7)`;
  const builds = `ScenarioRunner 0.9.16 crashes on it (${SR_ATOMICS} ChangeActorWaypoints.__init__, commit ab5996d7) but builds a FollowTrajectoryAction as ChangeActorWaypoints with times, straight lines between the vertices (${SR_PARSER}:1509-1513, ${SR_SCENARIO}:336-342), and drives to each vertex by its time (${CARLA_FACTS.trajectoryTimesSetSpeed.source})`;
  const walker = CARLA_FACTS.walkerWalksAtSetSpeed;
  const walks = `ScenarioRunner 0.9.16 crashes on it (${SR_ATOMICS} ChangeActorWaypoints.__init__, commit ab5996d7) but builds a FollowTrajectoryAction as ChangeActorWaypoints, straight lines between the vertices (${SR_PARSER}:1509-1513, ${SR_SCENARIO}:336-342), and ${walker.does} (${walker.source})`;
  const description = attr(child(tree, 'FileHeader') ?? tree, 'description') ?? '';
  // A 'CARLA:' description keeps ScenarioRunner in CARLA's frame only on a town: on an .xodr file the export has removed it.
  const road = context.roads
    ? { roads: context.roads, carlaFrame: context.town !== undefined && description.startsWith('CARLA:') }
    : undefined;
  for (const name of ['AssignRouteAction', 'AcquirePositionAction']) {
    for (const node of named(tree, name)) {
      if (!node.parent) continue;
      const written = routeTrajectory(tree, node, { road, town: context.town });
      if (typeof written !== 'string') {
        replaceNode(node, written.follow);
        context.sink.approximated(
          written.follow,
          name,
          `written as a FollowTrajectoryAction along ${written.summary}`,
          written.walker ? walks : builds,
        );
        continue;
      }
      const init = ancestor(node, 'Init') !== undefined;
      context.sink.refuse(
        node,
        name,
        'crashes ScenarioRunner 0.9.16 while it builds the scenario',
        `${init ? `the Init route is built as ChangeActorWaypoints without times, which raises (${SR_SCENARIO} _create_init_behavior, ${SR_ATOMICS} ChangeActorWaypoints.__init__, commit ab5996d7)` : crash}; the export cannot write it as a FollowTrajectoryAction: ${written}; export with --carla 0.9.15 for ScenarioRunner 0.9.15`,
      );
    }
  }
}

/**
 * Under 0.9.15 an Init route builds, but in the actor's Init sequence (CARLA_FACTS.initActorSequence): its controller,
 * the route's ChangeActorWaypoints, then its start speed, which is set only once the route has ended. Until then the
 * controller's target speed is 0 (SR_ACTOR_CONTROLS basic_control.py _target_speed), so an actor the Init starts at a
 * speed stands at its start until a story action sets one.
 */
function initRoutesBeforeStartSpeed(tree: Node, context: RuleContext): void {
  if (context.release !== '0.9.15') return;
  const init = named(tree, 'Init')[0];
  if (!init) return;
  const fact = CARLA_FACTS.initActorSequence;
  for (const name of ['AssignRouteAction', 'AcquirePositionAction']) {
    for (const node of named(init, name)) {
      const privateNode = ancestor(node, 'Private');
      const actor = attr(privateNode ?? node, 'entityRef') ?? '';
      const speed = startSpeedOf(tree, actor);
      // A controller of its own (the entity's or the Init's) drives it, not the default one whose target speed this is about.
      const object = scenarioObjectOf(tree, actor);
      const ownController =
        (object && child(object, 'ObjectController')) || (privateNode && named(privateNode, 'ControllerAction').length > 0);
      if (speed === undefined || !(speed > 0) || ownController) continue;
      context.sink.approximated(
        node,
        `Init/${name}`,
        `is kept, but '${actor}' stands at its start in ScenarioRunner 0.9.15: its start speed ${fourDecimals(speed)} m/s is set only once the route has ended, and at speed 0 it does not move along it (a story SpeedAction starts it)`,
        `ScenarioRunner ${fact.does} (${fact.source}); a controller's target speed is 0 until one is set (srunner/scenariomanager/actorcontrols/basic_control.py:50)`,
      );
    }
  }
}

/** 1.1-1.3 conditions that are not 1.0, and the UserDefinedValueCondition SR refuses ("not yet supported", SR_PARSER convert_condition_to_atomic). */
const REFUSED_CONDITIONS: Record<string, string> = {
  UserDefinedValueCondition: `ScenarioRunner refuses it ("ByValue UserDefinedValue conditions are not yet supported", ${SR_PARSER} convert_condition_to_atomic)`,
  AngleCondition: 'angle conditions are not in 1.0',
  RelativeAngleCondition: 'angle conditions are not in 1.0',
  RelativeClearanceCondition: 'clearance conditions are not in 1.0',
};

const RULE_VALUES: Record<string, string> = { greaterOrEqual: 'greaterThan', lessOrEqual: 'lessThan' };

/** Conditions that compare a measured number with `value` (ParameterCondition may compare text; TimeOfDayCondition a date). */
const NUMBER_CONDITIONS: ReadonlySet<string> = new Set([
  'SimulationTimeCondition',
  'SpeedCondition',
  'RelativeSpeedCondition',
  'AccelerationCondition',
  'DistanceCondition',
  'RelativeDistanceCondition',
  'TimeHeadwayCondition',
  'TimeToCollisionCondition',
]);

/**
 * A number condition's `greaterOrEqual v` is 1.0's `greaterThan v - 2e-6` (and `lessOrEqual` the mirror): esmini holds the two at
 * the same values, and ScenarioRunner (no tolerance) at v itself, where a simulation time lands exactly; returns whether it wrote one.
 */
function strictThreshold(node: Node, rule: string): boolean {
  const value = Number(attr(node, 'value'));
  if (!NUMBER_CONDITIONS.has(node.name) || attr(node, 'value') === undefined || !Number.isFinite(value)) return false;
  // esmini compares within SMALL_NUMBER (OSCCondition.cpp EvaluateRule: a >= b - SMALL_NUMBER, a > b + SMALL_NUMBER).
  const shift = 2 * ESMINI_SMALL_NUMBER * (rule === 'greaterOrEqual' ? -1 : 1);
  setAttr(node, 'rule', RULE_VALUES[rule]);
  setAttr(node, 'value', String(Number((value + shift).toFixed(9))));
  return true;
}

function conditions(tree: Node, context: RuleContext): void {
  for (const [name, carla] of Object.entries(REFUSED_CONDITIONS))
    for (const node of named(tree, name))
      if (node.parent) dropUnit(node, context, name, `${carla}; the condition group waits for its other conditions`);
  for (const node of allNodes(tree)) {
    const rule = attr(node, 'rule');
    if (rule && RULE_VALUES[rule] && strictThreshold(node, rule)) continue;
    if (rule && RULE_VALUES[rule]) {
      setAttr(node, 'rule', RULE_VALUES[rule]);
      context.sink.approximated(
        node,
        `${node.name}/@rule`,
        `${rule} is written as ${RULE_VALUES[rule]} (1.0 has no ${rule}; they differ only at equality)`,
        `ScenarioRunner compares with ${RULE_VALUES[rule]} (${SR_PARSER} operators)`,
      );
    } else if (rule === 'notEqualTo') dropUnit(node, context, `${node.name}/@rule`, `1.0 has no notEqualTo (${SR_PARSER} operators)`);
  }
  for (const name of ['DistanceCondition', 'TimeHeadwayCondition', 'TimeToCollisionCondition', 'RelativeDistanceCondition']) {
    for (const node of named(tree, name)) {
      const system = attr(node, 'coordinateSystem');
      removeAttr(node, 'coordinateSystem');
      removeAttr(node, 'routingAlgorithm');
      const distanceType = attr(node, 'relativeDistanceType');
      if (name !== 'RelativeDistanceCondition') removeAttr(node, 'relativeDistanceType');
      else if (distanceType === 'euclidianDistance') setAttr(node, 'relativeDistanceType', 'cartesianDistance');
      if (name !== 'RelativeDistanceCondition' && attr(node, 'alongRoute') === undefined) {
        const alongRoute = system === 'road' || system === 'lane';
        setAttr(node, 'alongRoute', String(alongRoute));
        // 1.0 knows the distance along the road (alongRoute) or the straight one between the entities; not a longitudinal or lateral part of it.
        const changed = alongRoute
          ? distanceType === 'lateral' && 'the distance along the road, not across it'
          : distanceType !== undefined &&
            distanceType !== 'euclidianDistance' &&
            distanceType !== 'cartesianDistance' &&
            'the distance between the entities';
        if (changed)
          context.sink.approximated(
            node,
            `${name}/@relativeDistanceType`,
            `${distanceType} in ${system ?? 'entity'} coordinates has no 1.0 form: written as alongRoute="${alongRoute}", ${changed}`,
            `${SR_PARSER} convert_condition_to_atomic reads alongRoute`,
          );
      }
      if (attr(node, 'freespace') === undefined) setAttr(node, 'freespace', 'false');
      if (system && system !== 'entity' && name === 'RelativeDistanceCondition')
        context.sink.approximated(
          node,
          `${name}/@coordinateSystem`,
          `${system} is not in 1.0: the distance is measured between the entities`,
          `${SR_PARSER} convert_condition_to_atomic measures ${name} in CARLA's world`,
        );
    }
  }
  for (const node of named(tree, 'StoryboardElementStateCondition')) {
    const state = attr(node, 'state');
    if (state === 'runningState' || state === 'startTransition') {
      if (state === 'runningState') {
        setAttr(node, 'state', 'startTransition');
        context.sink.approximated(
          node,
          'StoryboardElementStateCondition/@state',
          'runningState is written as startTransition (a condition holds from the moment it is first true)',
          `ScenarioRunner knows start, stop and end transitions and completeState only (${SR_PARSER} convert_condition_to_atomic, issue #1067)`,
        );
      }
    } else if (state && !['stopTransition', 'endTransition', 'completeState'].includes(state))
      dropUnit(
        node,
        context,
        'StoryboardElementStateCondition',
        `ScenarioRunner refuses the state ${state} (${SR_PARSER} convert_condition_to_atomic)`,
      );
  }
  for (const reach of named(tree, 'ReachPositionCondition')) removeAttr(reach, 'coordinateSystem');
}

/** Storyboard semantics ScenarioRunner does not keep (FACTS: priority, conditionEdge, maximumExecutionCount of an event, triggeringEntitiesRule): reported, once per kind and file. */
function ignoredSemantics(tree: Node, context: RuleContext): void {
  const events = named(tree, 'Event');
  for (const event of events) {
    const priority = attr(event, 'priority');
    if (priority === 'override') setAttr(event, 'priority', 'overwrite');
  }
  const reportFirst = (nodes: Node[], element: string, what: (count: number) => string, carla: string): void => {
    if (nodes.length > 0) context.sink.approximated(nodes[0], element, what(nodes.length), carla);
  };
  reportFirst(
    events.filter((event) => attr(event, 'priority') !== 'parallel'),
    'Event/@priority',
    (count) => `${count} event${count === 1 ? '' : 's'} with priority overwrite or skip (here and after)`,
    `ScenarioRunner runs every event in parallel: a later event neither stops nor waits for a running one (${SR_PARSER}, issues #555, #935)`,
  );
  reportFirst(
    events.filter((event) => Number(attr(event, 'maximumExecutionCount') ?? '1') > 1),
    'Event/@maximumExecutionCount',
    (count) => `${count} event${count === 1 ? '' : 's'} meant to run more than once`,
    `ScenarioRunner runs an event once (${SR_SCENARIO})`,
  );
  const edged = named(tree, 'Condition').filter((condition) =>
    ['falling', 'risingOrFalling'].includes(attr(condition, 'conditionEdge') ?? ''),
  );
  for (const condition of edged)
    context.sink.approximated(
      condition,
      'Condition/@conditionEdge',
      `${attr(condition, 'conditionEdge')} is not kept: the condition fires when it is first true`,
      `ScenarioRunner ignores conditionEdge; every condition latches once (${SR_PARSER} convert_condition_to_atomic)`,
    );
  reportFirst(
    named(tree, 'Condition').filter((condition) => attr(condition, 'conditionEdge') === 'rising'),
    'Condition/@conditionEdge',
    (count) => `${count} condition${count === 1 ? '' : 's'} with conditionEdge rising fire when first true, also when true from the start`,
    `ScenarioRunner ignores conditionEdge (${SR_PARSER} convert_condition_to_atomic)`,
  );
  reportFirst(
    named(tree, 'TriggeringEntities').filter(
      (node) => attr(node, 'triggeringEntitiesRule') === 'all' && childrenNamed(node, 'EntityRef').length > 1,
    ),
    'TriggeringEntities/@triggeringEntitiesRule',
    () => "'all' over several entities is decided by the last entity listed",
    `ScenarioRunner ignores the rule and uses the last EntityRef (${SR_PARSER} convert_condition_to_atomic)`,
  );
}

/**
 * A SpeedAction's rate (ScenarioRunner reads it as a duration, CARLA_FACTS.speedRateAsDuration) is written as the time the
 * change takes where the speed it starts from is certain (scenarioTree constantSpeedOf); elsewhere it is kept as written, and reported.
 */
function speedRates(tree: Node, context: RuleContext): void {
  const fact = CARLA_FACTS.speedRateAsDuration;
  for (const dynamics of named(tree, 'SpeedActionDynamics')) {
    if (attr(dynamics, 'dynamicsDimension') !== 'rate') continue;
    const value = attr(dynamics, 'value') ?? '';
    const seconds = rateAsSeconds(tree, dynamics, Number(value));
    if (seconds !== undefined) {
      setAttr(dynamics, 'dynamicsDimension', 'time');
      setAttr(dynamics, 'value', fourDecimals(seconds));
      continue;
    }
    const negative = Number(value) < 0;
    context.sink.approximated(
      dynamics,
      'SpeedActionDynamics/@dynamicsDimension',
      `the rate ${value} is kept as written, but runs as a duration of ${value} s${negative ? ': the action ends at its first tick (a negative rate)' : ''}`,
      `ScenarioRunner ${fact.does} (${fact.source})`,
    );
  }
}

/** The seconds a rate's change takes, where the speed it starts from is certain: one Event run, an absolute target, every actor at one constant speed before. */
function rateAsSeconds(tree: Node, dynamics: Node, rate: number): number | undefined {
  const action = ancestor(dynamics, 'SpeedAction');
  const target = action ? named(action, 'AbsoluteTargetSpeed')[0] : undefined;
  const factor = PEAK_FACTOR[attr(dynamics, 'dynamicsShape') ?? ''];
  const event = action ? ancestor(action, 'Event') : undefined;
  if (!action || !target || factor === undefined || !event || !(rate !== 0 && Number.isFinite(rate))) return undefined;
  if (Number(attr(event, 'maximumExecutionCount') ?? 1) !== 1) return undefined;
  const actors = actorsOf(action);
  const starts = actors.map((actor) => constantSpeedOf(tree, actor, action));
  const start = starts[0];
  if (start === undefined || starts.some((each) => each !== start)) return undefined;
  const change = Math.abs(Number(attr(target, 'value')) - start);
  return Number.isFinite(change) && change > 0 ? (factor * change) / Math.abs(rate) : undefined;
}

/** A SpeedAction's shape other than step is kept as written, and reported at its line: ScenarioRunner never reads it (CARLA_FACTS.speedShapeIgnored). */
function speedShapes(tree: Node, context: RuleContext): void {
  const fact = CARLA_FACTS.speedShapeIgnored;
  for (const dynamics of named(tree, 'SpeedActionDynamics')) {
    const shape = attr(dynamics, 'dynamicsShape');
    if (shape === undefined || shape === 'step') continue;
    context.sink.approximated(
      dynamics,
      'SpeedActionDynamics/@dynamicsShape',
      `the ${shape} shape is kept as written, but not followed: the speed changes as the actor's controller drives`,
      `ScenarioRunner ${fact.does} (${fact.source})`,
    );
  }
}

/** An attribute ScenarioRunner reads otherwise than written, the values it does not follow, and what it does instead (with its source). */
interface AttributeRunOtherwise {
  element: string;
  attribute: string;
  breaks: (value: string) => boolean;
  carla: string;
}

/** From the profile fact (CARLA_PROFILE.attributes) of `element`'s `attribute`, which the editor reports too. */
function fromProfile(element: string, attribute: string): AttributeRunOtherwise {
  const fact = CARLA_PROFILE.attributes.find((each) => each.element === element && each.attribute === attribute);
  if (!fact) throw new Error(`CARLA_PROFILE has no fact for ${element}/@${attribute}`);
  return { element, attribute, breaks: (value) => breaks(fact, value), carla: `ScenarioRunner ignores it: ${fact.note} (${fact.source})` };
}

/** The attributes kept as written but not followed that no other rule reports; SR's own example of a linear lane offset keeps the editor's warning off it (CARLA_FACTS only). */
function attributesRunOtherwiseList(): AttributeRunOtherwise[] {
  const laneOffset = CARLA_FACTS.laneOffsetShapeIgnored;
  return [
    fromProfile('DistanceCondition', 'freespace'),
    fromProfile('LaneChangeActionDynamics', 'dynamicsShape'),
    fromProfile('LaneChangeActionDynamics', 'dynamicsDimension'),
    {
      element: 'LaneOffsetActionDynamics',
      attribute: 'dynamicsShape',
      breaks: (value) => value !== 'step',
      carla: `ScenarioRunner ${laneOffset.does} (${laneOffset.source})`,
    },
    {
      element: 'LaneOffsetActionDynamics',
      attribute: 'maxLateralAcc',
      breaks: () => true,
      carla: `ScenarioRunner ${CARLA_FACTS.laneOffsetMaxLateralAccIgnored.does} (${CARLA_FACTS.laneOffsetMaxLateralAccIgnored.source})`,
    },
  ];
}

/** Each attribute of attributesRunOtherwiseList with a value ScenarioRunner does not follow: kept as written, and reported at its line. */
function attributesRunOtherwise(tree: Node, context: RuleContext): void {
  for (const { element, attribute, breaks: notFollowed, carla } of attributesRunOtherwiseList())
    for (const node of named(tree, element)) {
      const value = attr(node, attribute);
      if (value === undefined || !notFollowed(value)) continue;
      context.sink.approximated(node, `${element}/@${attribute}`, `${attribute}="${value}" is kept as written, but not followed`, carla);
    }
}

/** An Act's own StopTrigger group of several conditions is kept as written, and reported: ScenarioRunner ORs them (CARLA_FACTS.actStopTrigger); runs before storyboardStop adds the Storyboard's groups, which it reports itself. */
function actStopGroups(tree: Node, context: RuleContext): void {
  const fact = CARLA_FACTS.actStopTrigger;
  for (const act of named(tree, 'Act')) {
    const stop = child(act, 'StopTrigger');
    if (!stop) continue;
    for (const group of childrenNamed(stop, 'ConditionGroup')) {
      const count = childrenNamed(group, 'Condition').length;
      if (count < 2) continue;
      context.sink.approximated(
        group,
        'Act/StopTrigger',
        `the act '${attr(act, 'name') ?? ''}' stops when any one of this group's ${count} conditions holds, not when all hold`,
        `ScenarioRunner ${fact.does} (${fact.source})`,
      );
    }
  }
}

/** The export's element as the Storyboard stop check (semantics/storyboardStop.ts) reads it. */
const NODE_SHAPE: ElementShape<Node> = {
  name: (node) => node.name,
  attributes: (node) => node.attributes,
  children: (node) => node.children,
};

/**
 * The Storyboard's StopTrigger is ignored but for `criteria_` conditions (SR_SCENARIO _create_test_criteria):
 * its groups are added to every Act's StopTrigger (ending every act ends the story), the original kept for criteria.
 * The copies leave the criteria out: ScenarioRunner makes a criterion of one in any StopTrigger, and in an Act's it
 * never succeeds, so its group would never stop the act. A group an Act's StopTrigger already holds (a file this
 * export wrote) is not added to it again.
 */
function storyboardStop(tree: Node, context: RuleContext): void {
  const storyboard = named(tree, 'Storyboard')[0];
  if (!storyboard) return;
  let stop = child(storyboard, 'StopTrigger');
  if (!stop) stop = appendChild(storyboard, makeNode('StopTrigger'));
  else {
    removeNode(stop);
    appendChild(storyboard, stop);
  }
  const acts = actsOf(storyboard, NODE_SHAPE);
  const stopping = storyboardStopGroups(storyboard, NODE_SHAPE).filter(({ stopping }) => stopping.length > 0);
  const carla = `ScenarioRunner ignores the Storyboard's StopTrigger but for criteria_ conditions (${SR_SCENARIO} _create_test_criteria); the scenario ends when its acts end`;
  if (acts.length === 0 && stopping.length > 0) {
    context.sink.approximated(
      stop,
      'Storyboard/StopTrigger',
      'kept as written, but not followed: the scenario has no act to hold its conditions (the one added for 1.0 has nothing to do)',
      carla,
    );
    return;
  }
  const added = stopping.filter(({ missingFrom }) => missingFrom.length > 0);
  if (added.length === 0) return;
  for (const { group, stopping, missingFrom } of added)
    for (const act of missingFrom)
      appendChild(
        child(act, 'StopTrigger') ?? appendChild(act, makeNode('StopTrigger')),
        makeNode(
          group.name,
          group.attributes.map(([key, value]) => [key, value]),
          stopping.map(cloneNode),
          group.place,
        ),
      );
  const anded = added.some(({ stopping }) => stopping.length > 1);
  const criteriaLeft = added.some(({ group, stopping }) => stopping.length < group.children.length);
  context.sink.approximated(
    stop,
    'Storyboard/StopTrigger',
    `its condition groups are added to the StopTrigger of ${acts.length === 1 ? 'the one act' : `each of the ${acts.length} acts`}${criteriaLeft ? ", without their criteria_ conditions (ScenarioRunner makes one test criterion of each, from the Storyboard's)" : ''}${anded ? ' (ScenarioRunner ORs the conditions inside an act stop group, where the standard ANDs them)' : ''}`,
    carla,
  );
}

/** 1.0 entity parts that 1.1+ made optional or added. */
function entities(tree: Node, context: RuleContext): void {
  for (const vehicle of named(tree, 'Vehicle')) {
    for (const extra of ['mass', 'model3d', 'role']) removeAttr(vehicle, extra);
    // A Trailer that names no entity pulls nothing: it, and the hitch and coupler then, mean nothing to drop (1.2+, not 1.0).
    const trailer = child(vehicle, 'Trailer');
    const reference = trailer ? child(trailer, 'TrailerRef') : undefined;
    if (trailer && trailer.children.length <= 1 && (!reference || !attr(reference, 'entityRef'))) removeNode(trailer);
    if (!child(vehicle, 'Trailer'))
      for (const part of ['TrailerHitch', 'TrailerCoupler']) for (const each of childrenNamed(vehicle, part)) removeNode(each);
    const performance = child(vehicle, 'Performance');
    if (performance) {
      for (const extra of ['maxAccelerationRate', 'maxDecelerationRate']) removeAttr(performance, extra);
      if (attr(performance, 'maxDeceleration') === undefined)
        setAttr(performance, 'maxDeceleration', attr(performance, 'maxAcceleration') ?? '10');
    }
    const axles = child(vehicle, 'Axles');
    if (axles && !child(axles, 'FrontAxle')) {
      const rear = child(axles, 'RearAxle');
      if (rear) appendChild(axles, Object.assign(cloneNode(rear), { name: 'FrontAxle' }), rear);
    }
    if (!child(vehicle, 'Properties')) appendChild(vehicle, makeNode('Properties'));
  }
  for (const pedestrian of named(tree, 'Pedestrian')) {
    for (const extra of ['model3d', 'role']) removeAttr(pedestrian, extra);
    if (attr(pedestrian, 'mass') === undefined) setAttr(pedestrian, 'mass', '80');
    if (attr(pedestrian, 'model') === undefined) setAttr(pedestrian, 'model', attr(pedestrian, 'name') ?? '');
    if (!child(pedestrian, 'Properties')) appendChild(pedestrian, makeNode('Properties'));
  }
  for (const misc of named(tree, 'MiscObject')) {
    removeAttr(misc, 'model3d');
    if (!child(misc, 'Properties')) appendChild(misc, makeNode('Properties'));
  }
  for (const object of named(tree, 'ScenarioObject')) {
    const external = child(object, 'ExternalObjectReference');
    if (external)
      context.sink.refuse(
        external,
        'ExternalObjectReference',
        'names an object ScenarioRunner cannot spawn',
        `${SR_CONFIGURATION} _set_actor_information spawns Vehicles, Pedestrians and MiscObjects only`,
      );
  }
}

/** Parameters are evaluated by the export; declarations stay for ParameterConditions and ParameterActions, in 1.0's types. */
function parameters(tree: Node): void {
  for (const declaration of named(tree, 'ParameterDeclaration')) {
    if (attr(declaration, 'parameterType') === 'int') setAttr(declaration, 'parameterType', 'integer');
    for (const constraint of childrenNamed(declaration, 'ConstraintGroup')) removeNode(constraint);
  }
  for (const node of allNodes(tree)) {
    if (attr(node, 'parameterType') === 'int') setAttr(node, 'parameterType', 'integer');
  }
  // A ParameterDeclarations that only the entry's own values used is empty once they are evaluated.
  for (const declarations of named(tree, 'ParameterDeclarations'))
    if (declarations.parent?.name !== 'OpenSCENARIO') removeNode(declarations);
}

function renamedValues(tree: Node): void {
  for (const node of allNodes(tree)) {
    for (const entry of node.attributes) if (entry[1] === 'euclidianDistance') entry[1] = 'cartesianDistance';
    renameAttr(node, 'curvaturePrime', 'curvatureDot');
  }
}

/** A trigger that fires at the first step: what a 1.2 Act or Event without a StartTrigger means (it starts with its parent). */
function startAtOnce(): Node {
  return makeNode(
    'StartTrigger',
    [],
    [
      makeNode(
        'ConditionGroup',
        [],
        [
          makeNode(
            'Condition',
            [
              ['name', 'start'],
              ['delay', '0'],
              ['conditionEdge', 'none'],
            ],
            [
              makeNode(
                'ByValueCondition',
                [],
                [
                  makeNode('SimulationTimeCondition', [
                    ['value', '0'],
                    ['rule', 'greaterThan'],
                  ]),
                ],
              ),
            ],
          ),
        ],
      ),
    ],
  );
}

/** Parts 1.0 requires that 1.1-1.3 made optional, written with the meaning the later standard gives their absence. */
function requiredParts(tree: Node): void {
  const storyboard = named(tree, 'Storyboard')[0];
  if (storyboard && childrenNamed(storyboard, 'Story').length === 0) {
    // An Init-only scenario: one story with an act that has nothing to do, so that the 1.0 Storyboard has its Story.
    const story = makeNode(
      'Story',
      [['name', 'init_only']],
      [
        makeNode(
          'Act',
          [['name', 'init_only']],
          [
            makeNode(
              'ManeuverGroup',
              [
                ['name', 'init_only'],
                ['maximumExecutionCount', '1'],
              ],
              [makeNode('Actors', [['selectTriggeringEntities', 'false']])],
            ),
            startAtOnce(),
          ],
        ),
      ],
    );
    appendChild(storyboard, story, child(storyboard, 'StopTrigger'));
  }
  for (const holder of [...named(tree, 'Act'), ...named(tree, 'Event')]) {
    if (child(holder, 'StartTrigger')) continue;
    appendChild(holder, startAtOnce(), child(holder, 'StopTrigger'));
  }
  for (const controller of named(tree, 'Controller')) if (!child(controller, 'Properties')) appendChild(controller, makeNode('Properties'));
}

/**
 * ScenarioRunner finds a traffic light by `id=N` (CARLA's actor id) or `pos=X,Y` only, in the states Green, Red,
 * Yellow and Off (SR_PARSER get_traffic_light_from_osc_name, tl_states); any other name or state raises while
 * the scenario is built, so such an action or condition is dropped, named.
 */
function trafficSignals(tree: Node, context: RuleContext): void {
  for (const name of ['TrafficSignalStateAction', 'TrafficSignalCondition']) {
    for (const node of named(tree, name)) {
      if (!node.parent) continue;
      const signal = attr(node, 'name') ?? '';
      const state = attr(node, 'state') ?? '';
      if (!/^(id=\d+|pos=-?[\d.]+,-?[\d.]+)$/.test(signal))
        dropUnit(
          node,
          context,
          name,
          `ScenarioRunner names a traffic light by its CARLA actor id=N or pos=X,Y; '${signal}' (an OpenDRIVE signal id) raises "Unknown traffic light" (${SR_PARSER} get_traffic_light_from_osc_name)`,
        );
      else if (!['GREEN', 'RED', 'YELLOW', 'OFF'].includes(state.toUpperCase()))
        dropUnit(
          node,
          context,
          name,
          `ScenarioRunner knows the states Green, Red, Yellow and Off; '${state}' raises (${SR_PARSER} tl_states)`,
        );
    }
  }
}

/**
 * An Action with nothing in it (ScenarioRunner's ChangingWeather.xosc has one) is built as `Idle(duration=0)`
 * (SR_PARSER convert_maneuver_to_atomic): it does nothing. 1.0 has no empty Action, so it is dropped, named;
 * its Event goes with it when it has no other action.
 */
function emptyActions(tree: Node, context: RuleContext): void {
  for (const action of named(tree, 'Action')) {
    if (action.children.length > 0 || !ancestor(action, 'Story')) continue;
    const event = action.parent;
    const alone = event !== undefined && childrenNamed(event, 'Action').length === 1;
    context.sink.dropped(
      action,
      'Action',
      `'${attr(action, 'name') ?? ''}' holds no action: dropped${alone ? `, and with it its Event '${attr(event, 'name') ?? ''}', which has no other` : ''}`,
      `ScenarioRunner builds an empty Action as Idle(duration=0), which does nothing (${SR_PARSER} convert_maneuver_to_atomic)`,
    );
    removeNode(action);
  }
}

/** Every rule, in the order they apply. */
export const CARLA_RULES: readonly { name: string; apply: (tree: Node, context: RuleContext) => void }[] = [
  { name: 'variables', apply: variables },
  { name: 'parameters', apply: (tree) => parameters(tree) },
  { name: 'empty-actions', apply: emptyActions },
  { name: 'entities', apply: entities },
  { name: 'activate-controller', apply: activateControllerAction },
  { name: 'controller-halves', apply: controllerActionHalves },
  { name: 'weather', apply: weather },
  { name: 'absolute-target-lane', apply: (tree, context) => absoluteTargetLanes(tree, context.sink, context.roads) },
  { name: 'time-gap', apply: longitudinalTimeGap },
  { name: 'lateral-distances', apply: (tree, context) => lateralDistances(tree, context.sink) },
  // Before any position is converted: it moves the targets back along their routes, trajectories and lanes.
  { name: 'synchronize-steady-states', apply: (tree, context) => synchronizeSteadyStates(tree, context.sink, context.roads) },
  { name: 'trajectories', apply: trajectories },
  { name: 'init-starts', apply: initStarts },
  { name: 'route-positions', apply: routePositions },
  { name: 'geo-positions', apply: geoPositions },
  { name: 'negative-start-speeds', apply: negativeStartSpeeds },
  { name: 'trajectory-positions', apply: trajectoryPositions },
  { name: 'speed-profiles', apply: speedProfiles },
  { name: 'positions', apply: unsupportedPositions },
  { name: 'refused-actions', apply: refusedActions },
  { name: 'route-crash', apply: routeActionCrash },
  { name: 'init-routes-before-start-speed', apply: initRoutesBeforeStartSpeed },
  { name: 'init-actions-passed-over', apply: initActionsPassedOver },
  { name: 'traffic-signals', apply: trafficSignals },
  { name: 'conditions', apply: conditions },
  { name: 'ignored-semantics', apply: ignoredSemantics },
  { name: 'speed-rates', apply: speedRates },
  { name: 'lane-changes-by-distance', apply: (tree, context) => laneChangesByDistance(tree, context.sink, context.roads) },
  { name: 'speed-shapes', apply: speedShapes },
  { name: 'attributes-run-otherwise', apply: attributesRunOtherwise },
  { name: 'act-stop-groups', apply: actStopGroups },
  { name: 'storyboard-stop', apply: storyboardStop },
  // Last of the position rules: every LanePosition written by those before is in esmini's reading until here.
  { name: 'lane-offsets', apply: (tree, context) => laneOffsets(tree, context.sink, context.roads) },
  { name: 'renamed-values', apply: (tree) => renamedValues(tree) },
  { name: 'required-parts', apply: (tree) => requiredParts(tree) },
];

export function applyCarlaRules(tree: Node, context: RuleContext): void {
  for (const rule of CARLA_RULES) rule.apply(tree, context);
  tidyEmptyContainers(tree);
}

/**
 * What dropping left empty goes too: an Event without actions, a Maneuver without events, a ConditionGroup
 * without conditions, a Private without actions (a ManeuverGroup may be empty in 1.0).
 */
export function tidyEmptyContainers(tree: Node): void {
  let changed = true;
  while (changed) {
    changed = false;
    for (const node of allNodes(tree)) {
      if (!node.parent) continue;
      const empty =
        (node.name === 'Event' && childrenNamed(node, 'Action').length === 0) ||
        (node.name === 'Maneuver' && childrenNamed(node, 'Event').length === 0) ||
        (node.name === 'ConditionGroup' && childrenNamed(node, 'Condition').length === 0) ||
        (node.name === 'Private' && childrenNamed(node, 'PrivateAction').length === 0) ||
        (node.name === 'Action' && node.children.length === 0) ||
        (node.name === 'PrivateAction' && node.children.length === 0) ||
        (node.name === 'GlobalAction' && node.children.length === 0);
      if (empty) {
        removeNode(node);
        changed = true;
      }
    }
  }
}

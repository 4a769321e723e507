/**
 * A LaneChangeAction by time or rate, which ScenarioRunner plans over an infinite distance (SR_PARSER:1386-1399:
 * `distance_lane_change=inf` for any dimension but distance), written by distance: the ground the actor covers
 * along the road while esmini moves it across (OSCPrivateAction.cpp LatLaneChangeAction::Step).
 */
import type { RoadNetwork } from '../opendrive/road';
import { drivesAlongS, laneCenterT, laneSectionIndexAt } from '../opendrive/road';
import { SR_PARSER } from './carlaFacts';
import type { LossSink } from './carlaLosses';
import { dropUnit } from './carlaLosses';
import { actorsOf, constantSpeedOf, fromInit, startSpeedOf } from './scenarioTree';
import { ancestor, attr, fourDecimals, makeNode, named, Node, replaceNode, setAttr } from './tree';

/** Where the Init places an actor, when it is a LanePosition of its TeleportAction. */
export interface StartLane {
  roadId: string;
  laneId: number;
  s: number;
  offset: number;
}

/** The LanePosition the Init teleports the actor to, or a RelativeLanePosition from an entity it places so (esmini counts dLane as a lane change counts, ds along the reference's direction). */
export function startLanePositionOf(tree: Node, actor: string, through: ReadonlySet<string> = new Set()): StartLane | undefined {
  return fromInit(tree, actor, (privateNode): StartLane | undefined => {
    const position = named(privateNode, new Set(['LanePosition', 'RelativeLanePosition'])).find((each) => ancestor(each, 'TeleportAction'));
    if (!position) return undefined;
    const offset = Number(attr(position, 'offset') ?? 0);
    if (position.name === 'LanePosition')
      return { roadId: attr(position, 'roadId') ?? '', laneId: Number(attr(position, 'laneId')), s: Number(attr(position, 's')), offset };
    const reference = attr(position, 'entityRef') ?? '';
    const from = through.has(reference) ? undefined : startLanePositionOf(tree, reference, new Set([...through, actor]));
    const dLane = Number(attr(position, 'dLane'));
    const ds = Number(attr(position, 'ds') ?? 0);
    if (!from || !Number.isInteger(dLane) || !Number.isFinite(ds) || from.laneId === 0) return undefined;
    return {
      roadId: from.roadId,
      laneId: dLane === 0 ? from.laneId : relativeTargetLane(from.laneId, dLane),
      s: from.s + (from.laneId < 0 ? ds : -ds),
      offset,
    };
  });
}

/** The lateral speed of esmini's transition shapes at u in [0, 1] for a change `across` over `seconds` (OSCPrivateAction.cpp TransitionDynamics). */
const LATERAL_SPEED: Readonly<Record<string, (u: number, across: number, seconds: number) => number>> = {
  linear: (_u, across, seconds) => across / seconds,
  sinusoidal: (u, across, seconds) => (across * Math.PI * Math.sin(Math.PI * u)) / (2 * seconds),
  cubic: (u, across, seconds) => (6 * across * u * (1 - u)) / seconds,
};

/** How long a change takes at a peak rate, × change / rate: esmini reads a rate as the shape's peak slope (OSCPrivateAction.cpp EvaluatePrimPeak), of a speed change as of a lane change. */
export const PEAK_FACTOR: Readonly<Record<string, number>> = { linear: 1, sinusoidal: Math.PI / 2, cubic: 3 / 2 };

/**
 * The distance along the road covered in `seconds` at `speed` while moving `across` in `shape`: esmini's time dimension takes
 * each step's lateral move out of the step's length (delta_long = sqrt(step² - lateral²)); without `across`, speed × time.
 */
function groundCovered(seconds: number, speed: number, shape: string, across: number | undefined): number {
  const lateral = LATERAL_SPEED[shape];
  if (across === undefined || !lateral) return seconds * speed;
  const steps = 400;
  let total = 0;
  for (let step = 0; step < steps; step++) {
    const sideways = lateral((step + 0.5) / steps, across, seconds);
    total += Math.sqrt(Math.max(0, speed * speed - sideways * sideways)) * (seconds / steps);
  }
  return total;
}

/**
 * esmini's target lane of a RelativeTargetLane (LatLaneChangeAction::Start): counted to the left of the reference's driving
 * direction, skipping lane 0; `forward` when the reference drives along s (its lane is negative on a right-hand-traffic road).
 */
export function relativeTargetLane(reference: number, value: number, forward = reference < 0): number {
  const target = reference + value * (forward ? 1 : -1);
  return target === 0 || Math.sign(target) !== Math.sign(reference) ? Math.sign(target - reference) * (Math.abs(target) + 1) : target;
}

/** The RelativeTargetLane value that takes an actor from lane `from` to lane `to` (its inverse), if one of up to 8 lanes does. */
function relativeValueTo(from: number, to: number, forward: boolean): number | undefined {
  for (let value = -8; value <= 8; value++) if (relativeTargetLane(from, value, forward) === to) return value;
  return undefined;
}

/** Whether the actor drives along s where the Init places it: by its lane's side and the road's traffic rule (esmini's default heading), unless a relative Orientation turns it round. */
function actorDrivesAlongS(tree: Node, actor: string, start: StartLane, roads: RoadNetwork | undefined): boolean {
  const turned =
    fromInit(tree, actor, (privateNode) => {
      const lane = named(privateNode, 'LanePosition').find((each) => ancestor(each, 'TeleportAction'));
      const orientation = lane ? named(lane, 'Orientation')[0] : undefined;
      return orientation ? attr(orientation, 'type') === 'relative' && Math.cos(Number(attr(orientation, 'h') ?? 0)) < 0 : undefined;
    }) ?? false;
  const road = roads?.byId.get(start.roadId);
  return (road ? drivesAlongS(road, start.laneId) : start.laneId < 0) !== turned;
}

/** How far the actor moves across, from where its Init places it to the target lane's centre there; undefined where the road or a lane is not known. */
function acrossOf(
  tree: Node,
  dynamics: Node,
  actor: string,
  roads: RoadNetwork | undefined,
): { across: number; target: number } | undefined {
  const action = ancestor(dynamics, 'LaneChangeAction');
  const relative = action ? named(action, 'RelativeTargetLane')[0] : undefined;
  const start = startLanePositionOf(tree, actor);
  const road = start && roads?.byId.get(start.roadId);
  // Which side a LanePosition's offset lies is read differently by tools: only a start on the lane's centre is taken.
  if (
    !relative ||
    !start ||
    !road ||
    !Number.isFinite(start.s) ||
    !Number.isInteger(start.laneId) ||
    start.laneId === 0 ||
    start.offset !== 0
  )
    return undefined;
  const reference = startLanePositionOf(tree, attr(relative, 'entityRef') ?? actor);
  const value = Number(attr(relative, 'value'));
  if (!reference || reference.roadId !== start.roadId || !Number.isInteger(value) || reference.laneId === 0) return undefined;
  const target = relativeTargetLane(
    reference.laneId,
    value,
    actorDrivesAlongS(tree, attr(relative, 'entityRef') ?? actor, reference, roads),
  );
  const section = road.laneSections[laneSectionIndexAt(road, start.s)];
  if (!section?.lanes.some((lane) => lane.id === target) || !section.lanes.some((lane) => lane.id === start.laneId)) return undefined;
  const sectionIndex = laneSectionIndexAt(road, start.s);
  const across = Math.abs(laneCenterT(road, sectionIndex, target, start.s) - laneCenterT(road, sectionIndex, start.laneId, start.s));
  return { across, target };
}

/**
 * Each lane change by time, or by rate where the road gives the distance across, written by distance (silent where the actor's
 * speed is certain and the change is by time; reported elsewhere); a rate without a road, or no speed at all, stays as written.
 */
export function laneChangesByDistance(tree: Node, sink: LossSink, roads: RoadNetwork | undefined): void {
  const carla = `ScenarioRunner plans a lane change over a distance only; by time or rate it plans it over an infinite distance (${SR_PARSER}:1386-1399)`;
  for (const dynamics of named(tree, 'LaneChangeActionDynamics')) {
    const dimension = attr(dynamics, 'dynamicsDimension');
    const shape = attr(dynamics, 'dynamicsShape') ?? '';
    const value = Number(attr(dynamics, 'value'));
    const actors = actorsOf(dynamics);
    if ((dimension !== 'time' && dimension !== 'rate') || shape === 'step' || actors.length !== 1 || !(value > 0)) continue;
    // ScenarioRunner passes over a lane change in the Init (initActionsPassedOver reports it).
    if (!ancestor(dynamics, 'Story')) continue;
    const actor = actors[0];
    const constant = constantSpeedOf(tree, actor);
    const speed = Math.abs(constant ?? startSpeedOf(tree, actor) ?? 0);
    if (!(speed > 0)) continue;
    const across = acrossOf(tree, dynamics, actor, roads);
    const factor = PEAK_FACTOR[shape];
    const seconds = dimension === 'time' ? value : across && factor !== undefined ? (factor * across.across) / value : undefined;
    if (seconds === undefined) continue;
    const distance = fourDecimals(groundCovered(seconds, speed, shape, across?.across));
    setAttr(dynamics, 'dynamicsDimension', 'distance');
    setAttr(dynamics, 'value', distance);
    const atSpeed =
      constant === undefined
        ? `at the actor's start speed ${speed} m/s: its speed may change before or during the lane change`
        : `at ${speed} m/s`;
    if (dimension === 'rate' && across)
      sink.approximated(
        dynamics,
        'LaneChangeActionDynamics/@value',
        `a lateral rate of ${value} m/s is written as ${distance} m: ${fourDecimals(across.across)} m across to lane ${across.target} (as the lanes are where the Init places the actor) in ${fourDecimals(seconds)} s, ${atSpeed}`,
        carla,
      );
    else if (constant === undefined)
      sink.approximated(dynamics, 'LaneChangeActionDynamics/@value', `${value} s is written as ${distance} m, ${atSpeed}`, carla);
  }
}

/**
 * `AbsoluteTargetLane` crashes ScenarioRunner (SR_PARSER convert_maneuver_to_atomic reads `value` of a RelativeTargetLane only):
 * written as the RelativeTargetLane esmini and ScenarioRunner count to the driver's left, from the lane the actor's previous absolute
 * lane change in document order leaves it in, else its Init lane.
 */
export function absoluteTargetLanes(tree: Node, sink: LossSink, roads: RoadNetwork | undefined): void {
  const carla = `ScenarioRunner changes lanes relative to the actor's lane only; an AbsoluteTargetLane crashes it (${SR_PARSER} convert_maneuver_to_atomic)`;
  const lastLane = new Map<string, { lane: number; line: number }>();
  for (const target of named(tree, 'AbsoluteTargetLane')) {
    const actors = actorsOf(target);
    const actor = actors.length === 1 ? actors[0] : undefined;
    const start = actor === undefined ? undefined : startLanePositionOf(tree, actor);
    const wanted = Number(attr(target, 'value'));
    const before = actor === undefined ? undefined : lastLane.get(actor);
    const from = before?.lane ?? start?.laneId;
    // esmini keeps an actor's heading along or against s through its lane changes (Position::SetHeadingRelativeRoadDirection): left is the Init's.
    const forward = start && actor !== undefined ? actorDrivesAlongS(tree, actor, start, roads) : undefined;
    const value =
      from !== undefined && forward !== undefined && Number.isInteger(wanted) && wanted !== 0 && from !== 0
        ? relativeValueTo(from, wanted, forward)
        : undefined;
    if (value === undefined || actor === undefined) {
      dropUnit(
        target,
        { sink },
        'AbsoluteTargetLane',
        `${carla}; the actor's start lane is not known, so no relative change can be computed`,
      );
      continue;
    }
    const relativeNode = makeNode(
      'RelativeTargetLane',
      [
        ['entityRef', actor],
        ['value', String(value)],
      ],
      [],
      target.place,
    );
    replaceNode(target, relativeNode);
    const origin = before
      ? `lane ${from}, where its lane change at line ${before.line} leaves it (if that one ran first)`
      : `its start lane ${from}`;
    sink.approximated(
      relativeNode,
      'AbsoluteTargetLane',
      `lane ${wanted} is written as a change of ${value} to the driver's left from ${origin}`,
      carla,
    );
    lastLane.set(actor, { lane: wanted, line: (target.place?.range.start.line ?? -1) + 1 });
  }
}

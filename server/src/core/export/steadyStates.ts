/**
 * A SynchronizeAction's steady state (1.1+: TargetDistanceSteadyState, TargetTimeSteadyState) in 1.0 terms.
 * esmini (3.6.0, OSCPrivateAction.cpp SynchronizeAction::Step) synchronizes the entity to a point the steady-state
 * distance D before its target, reached when the master's time to its own target equals the time that distance takes
 * at the final speed (D / final speed), and then holds the final speed to the target. Where the master's speed is
 * certain for the whole run, that is a 1.0 SynchronizeAction to targets moved back along each one's path: the entity's
 * by D, the master's by what the master covers in that time. ScenarioRunner's SyncArrivalOSC then also reaches the final
 * speed D before the target (it sets it when the synchronization ends, srunner/scenariomanager/scenarioatomics/
 * atomic_behaviors.py SyncArrivalOSC.terminate), where with the steady state dropped it reached it at the target.
 */
import type { Road, RoadNetwork } from '../opendrive/road';
import { drivesAlongS } from '../opendrive/road';
import { SR_PARSER } from './carlaFacts';
import type { LossSink } from './carlaLosses';
import { actorsOf, constantSpeedOf, fromInit } from './scenarioTree';
import { ancestor, attr, child, fourDecimals, named, Node, removeNode, setAttr } from './tree';

const STEADY_STATES = ['TargetDistanceSteadyState', 'TargetTimeSteadyState'] as const;

/** A target moved back along a path: the attribute to write and its new value. */
interface Move {
  node: Node;
  attribute: string;
  value: number;
  /** How the report names the moved target (`s 40 → 30 along road 1`). */
  summary: string;
}

export function synchronizeSteadyStates(tree: Node, sink: LossSink, roads: RoadNetwork | undefined): void {
  for (const name of STEADY_STATES) {
    for (const steady of named(tree, name)) {
      const speed = steady.parent;
      const action = speed ? ancestor(speed, 'SynchronizeAction') : undefined;
      if (!speed || !action || !['AbsoluteSpeed', 'RelativeSpeedToMaster'].includes(speed.name)) continue;
      const element = `SynchronizeAction/FinalSpeed/${speed.name}/${name}`;
      const what = name === 'TargetDistanceSteadyState' ? `${attr(steady, 'distance') ?? ''} m` : `${attr(steady, 'time') ?? ''} s`;
      const moves = movedTargets(tree, action, speed, steady, roads);
      removeNode(steady);
      if (typeof moves === 'string') {
        sink.approximated(
          speed,
          element,
          `the steady state (the final speed held over the last ${what} before the target) is dropped, because ${moves}; the final speed ${attr(speed, 'value') ?? ''} is kept`,
          `ScenarioRunner reads only the final speed's value and reaches it at the target (${SR_PARSER} convert_maneuver_to_atomic, SynchronizeAction: SyncArrivalOSC)`,
        );
        continue;
      }
      const { entity, master, seconds, waiting } = moves;
      for (const move of [entity, master]) setAttr(move.node, move.attribute, fourDecimals(move.value));
      for (const condition of waiting) setAttr(condition, 'delay', fourDecimals(Number(attr(condition, 'delay') ?? 0) + seconds));
      const delayed =
        waiting.length > 0
          ? `, and the ${waiting.length === 1 ? 'condition waiting for its end waits' : `${waiting.length} conditions waiting for its end wait`} ${fourDecimals(seconds)} s longer, as long as the steady state lasts`
          : '';
      sink.approximated(
        speed,
        element,
        `written as a synchronization to targets moved back (the entity's ${entity.summary}, the master's ${master.summary}), from where the entity holds the final speed as esmini does over the last ${what}; the action now ends there rather than at the target${delayed}`,
        `ScenarioRunner's SyncArrivalOSC reaches the final speed where the synchronization ends (${SR_PARSER} convert_maneuver_to_atomic, SynchronizeAction; atomic_behaviors.py SyncArrivalOSC.terminate), and 1.0 has no steady state`,
      );
    }
  }
}

/** The targets moved back, the steady state's time, and the conditions that wait for the synchronization's end. */
interface SteadyStateMapping {
  entity: Move;
  master: Move;
  seconds: number;
  waiting: Node[];
}

/** The entity's and the master's targets moved back, or why they cannot be. */
function movedTargets(tree: Node, action: Node, speed: Node, steady: Node, roads: RoadNetwork | undefined): SteadyStateMapping | string {
  const actors = actorsOf(action);
  if (actors.length !== 1) return `it acts on ${actors.length} entities, each on a path of its own`;
  const [entity] = actors;
  const masterName = attr(action, 'masterEntityRef') ?? '';
  const masterSpeed = constantSpeedOf(tree, masterName);
  if (masterSpeed === undefined || masterSpeed <= 0)
    return `the master ${masterName}'s speed is not certain for the whole run (how far it moves in the steady state's time depends on it)`;
  const finalSpeed = finalSpeedOf(speed, masterSpeed);
  if (finalSpeed === undefined || finalSpeed <= 0) return 'its final speed is not a positive number';
  const distance =
    steady.name === 'TargetDistanceSteadyState' ? Number(attr(steady, 'distance')) : Number(attr(steady, 'time')) * finalSpeed;
  if (!Number.isFinite(distance) || distance <= 0) return 'its steady state is not a positive number';
  const target = child(action, 'TargetPosition')?.children[0];
  const masterTarget = child(action, 'TargetPositionMaster')?.children[0];
  if (!target || !masterTarget) return 'a target position is missing';
  const entityMove = movedBack(tree, target, distance, entity, roads);
  if (typeof entityMove === 'string') return `the entity's target ${entityMove}`;
  const masterMove = movedBack(tree, masterTarget, (masterSpeed * distance) / finalSpeed, masterName, roads);
  if (typeof masterMove === 'string') return `the master's target ${masterMove}`;
  const waiting = conditionsOnItsEnd(tree, action);
  if (typeof waiting === 'string') return waiting;
  return { entity: entityMove, master: masterMove, seconds: distance / finalSpeed, waiting };
}

/** The storyboard element types a StoryboardElementStateCondition names, as the element names. */
const ELEMENT_TYPES: Record<string, string> = {
  action: 'Action',
  event: 'Event',
  maneuver: 'Maneuver',
  maneuverGroup: 'ManeuverGroup',
  act: 'Act',
  story: 'Story',
};

/** States a storyboard element reaches when it ends: the synchronization now ends a steady state's time sooner. */
const END_STATES: ReadonlySet<string> = new Set(['endTransition', 'completeState']);

/**
 * The conditions waiting for the end of the synchronization's Action, or of an Event or Maneuver that ends with it
 * (their delay then keeps the original's moment), or why one cannot be kept so (an element that ends with more than it).
 */
function conditionsOnItsEnd(tree: Node, action: Node): Node[] | string {
  const own = ancestor(action, 'Action');
  const event = own ? ancestor(own, 'Event') : undefined;
  const maneuver = event ? ancestor(event, 'Maneuver') : undefined;
  const endsWithIt = new Set<Node>();
  if (own) endsWithIt.add(own);
  if (own && event && named(event, 'Action').length === 1) endsWithIt.add(event);
  if (endsWithIt.has(event as Node) && maneuver && named(maneuver, 'Event').length === 1) endsWithIt.add(maneuver as Node);
  const waiting: Node[] = [];
  for (const state of named(tree, 'StoryboardElementStateCondition')) {
    const type = ELEMENT_TYPES[attr(state, 'storyboardElementType') ?? ''];
    const reference = attr(state, 'storyboardElementRef');
    const condition = ancestor(state, 'Condition');
    if (!type || !condition) continue;
    let holder: Node | undefined = action;
    while (holder && !(holder.name === type && attr(holder, 'name') === reference)) holder = holder.parent;
    if (!holder) continue;
    const ending = END_STATES.has(attr(state, 'state') ?? '');
    if (!ending && attr(state, 'state') !== 'standbyState') continue;
    if (!ending || !endsWithIt.has(holder))
      return `the condition '${attr(condition, 'name') ?? ''}' waits for the ${attr(state, 'state') ?? ''} of the ${type} '${reference ?? ''}', which the synchronization's earlier end would move otherwise than by the steady state's time`;
    waiting.push(condition);
  }
  return waiting;
}

/** AbsoluteSpeed's value, or RelativeSpeedToMaster's from the master's speed (esmini: delta added, factor applied). */
function finalSpeedOf(speed: Node, masterSpeed: number): number | undefined {
  const value = Number(attr(speed, 'value'));
  if (!Number.isFinite(value)) return undefined;
  if (speed.name === 'AbsoluteSpeed') return value;
  return attr(speed, 'speedTargetValueType') === 'factor' ? masterSpeed * value : masterSpeed + value;
}

/** The position moved `distance` back along the path an entity takes to it, or why that path is not known. */
function movedBack(tree: Node, position: Node, distance: number, entity: string, roads: RoadNetwork | undefined): Move | string {
  if (position.name === 'RoutePosition') {
    // esmini measures along the road network, which is the route's path.
    const along = named(position, new Set(['FromRoadCoordinates', 'FromLaneCoordinates']))[0];
    return along ? movedAlong(along, 'pathS', distance, 'its route', '') : 'is a RoutePosition without a pathS';
  }
  // An entity on a trajectory is measured along it (CS_TRAJECTORY); the NCAP protocols synchronize on the one each follows.
  if (position.name === 'TrajectoryPosition') return movedAlong(position, 's', distance, 'its trajectory', ' along its trajectory');
  if (position.name === 'LanePosition') {
    const roadId = attr(position, 'roadId') ?? '';
    const s = Number(attr(position, 's'));
    const road = roads?.byId.get(roadId);
    if (!road) return `is on road ${roadId}, which the export could not read from the road file`;
    if (!Number.isFinite(s)) return 'is a LanePosition whose s is not a number';
    const direction = travelDirection(tree, entity, road, Number(attr(position, 'laneId')), s);
    const moved = s - direction * distance;
    if (moved < 0 || moved > road.length)
      return `is ${fourDecimals(direction > 0 ? s : road.length - s)} m from the end of road ${roadId}, less than the ${fourDecimals(distance)} m to move it back`;
    return { node: position, attribute: 's', value: moved, summary: `s ${fourDecimals(s)} → ${fourDecimals(moved)} on road ${roadId}` };
  }
  return `is a ${position.name}, which the export moves along no path`;
}

/** A distance along a route or trajectory (`attribute`, 0 when absent) less `distance`, or why it cannot be. */
function movedAlong(node: Node, attribute: string, distance: number, path: string, where: string): Move | string {
  const at = Number(attr(node, attribute) ?? 0);
  if (!Number.isFinite(at)) return `has a ${attribute} that is not a number`;
  if (at - distance < 0) return `lies ${fourDecimals(at)} m along ${path}, less than the ${fourDecimals(distance)} m to move it back`;
  return { node, attribute, value: at - distance, summary: `${attribute} ${fourDecimals(at)} → ${fourDecimals(at - distance)}${where}` };
}

/** +1 where the entity drives toward growing s on that road: from where its Init places it on the same road, else its lane's driving direction. */
function travelDirection(tree: Node, entity: string, road: Road, laneId: number, targetS: number): 1 | -1 {
  const startS = fromInit(tree, entity, (privateNode) => {
    for (const start of named(privateNode, new Set(['LanePosition', 'RoadPosition'])))
      if (attr(start, 'roadId') === road.id && ancestor(start, 'TeleportAction')) return Number(attr(start, 's'));
    return undefined;
  });
  if (startS !== undefined && Number.isFinite(startS) && startS !== targetS) return targetS > startS ? 1 : -1;
  return drivesAlongS(road, laneId) ? 1 : -1;
}

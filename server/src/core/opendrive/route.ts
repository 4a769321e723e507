/**
 * Where a point `pathS` metres along an OpenSCENARIO Route lies, as esmini places it (esmini 3.6.0,
 * RoadManager.cpp: Route::AddWaypoint, RoadPath::Calculate and CheckRoad, Route::SetPathS;
 * Position::SetRouteLanePosition). esmini plans the roads between two waypoints with its own Dijkstra
 * over road ends, forward from the earlier waypoint the way the entity heads (its lane's driving direction unless
 * given: a pedestrian walks either way), following lane links
 * (through junctions by their connections' laneLinks), and stops at the first road end it takes whose next
 * road is the target. Between the waypoints it adds one waypoint per road of the path; a point along the
 * route lies on the road of the waypoint before it, or on the next waypoint's road when it runs past the
 * end. Where that search could go two ways at equal distance (esmini then takes the one its file lists first),
 * runs into a direct junction, or finds nothing, this answers why instead of a place: the export names it
 * rather than guess. Equally near road ends that lead the same way whichever esmini takes are no ambiguity.
 */
import { JunctionConnection, laneSectionIndexAt, Road, RoadLink, RoadNetwork } from './road';

/** A route waypoint as a lane position (the only kind whose road and lane are known without the road's geometry inverted). */
export interface RouteWaypoint {
  roadId: string;
  laneId: number;
  s: number;
  /** How a message names it (`the Waypoint at line 40`); `waypoint N` (its place in the route) when not given. */
  name?: string;
  /**
   * The way the entity heads along the road there (1: growing s), which esmini plans from (RoadPath::Calculate reads the
   * heading relative to the road); when not given, its lane's driving direction (right-hand traffic).
   */
  direction?: 1 | -1;
}

/** The way an entity at a waypoint heads along its road: as given, else its lane's driving direction. */
const directionAt = (waypoint: RouteWaypoint): 1 | -1 => waypoint.direction ?? (waypoint.laneId < 0 ? 1 : -1);

/** The point on the route: the road and its s, and how the route got there. */
export interface RoutePoint {
  roadId: string;
  s: number;
  /** The roads the route runs over, in order. */
  roads: string[];
}

/** esmini's SMALL_NUMBER (CommonMini.hpp), as profiles/esmini.ts gives it: opendrive/ sits beside profiles/ and may not import it. */
const SMALL = 1e-6;
/** RoadPath::Calculate gives up after this many road ends. */
const MAX_STEPS = 100;
/** Equally near road ends whose order is tried, at most this many searches in all, before the route is called ambiguous unread. */
const MAX_ORDERS = 64;
/** Distances this close are equal: esmini takes whichever of them it inserted first. */
const SAME_DISTANCE = 1e-6;
/** Route::AddWaypoint puts the waypoint it adds on each road between two given ones this far along the road (RoadManager.cpp). */
const INTERMEDIATE_FRACTION = 0.33;

type End = 'start' | 'end';

/** A road end the search reaches: esmini's RoadPath::PathNode. */
interface PathNode {
  /** The road this node leaves, and at which end. */
  road: Road;
  exit: End;
  link: RoadLink;
  /** The lane it leaves by (0: none). */
  laneId: number;
  dist: number;
  previous: PathNode | undefined;
}

/** Minimal waypoint of esmini's Route: position, direction along its road (1: growing s) and distance along the route. */
interface Stop {
  /** The waypoint the route names; undefined for those esmini adds between them. */
  given?: RouteWaypoint;
  road: Road;
  s: number;
  laneId: number;
  direction: 1 | -1;
  routeS: number;
}

const otherEnd = (end: End): End => (end === 'start' ? 'end' : 'start');
const linkAt = (road: Road, end: End): RoadLink | undefined => (end === 'start' ? road.predecessor : road.successor);

/**
 * The lane a lane of section `index` continues as in the next section towards `direction` (esmini LaneSection::GetConnectingLaneId:
 * its link, or the same id when it names none); 0 when the section has no such lane.
 */
function nextSectionLane(road: Road, index: number, laneId: number, direction: 1 | -1): number {
  const lane = road.laneSections[index]?.lanes.find((each) => each.id === laneId);
  if (!lane || laneId === 0) return 0;
  return (direction === 1 ? lane.successor : lane.predecessor) ?? laneId;
}

/** A lane followed through its road's lane sections from s `from` to the road's end `to` (esmini Road::GetConnectedLaneIdAtS). */
function laneAtEnd(road: Road, laneId: number, from: number, to: End): number {
  const sections = road.laneSections;
  let index = laneSectionIndexAt(road, from);
  let lane = laneId;
  if (to === 'end') {
    for (; lane !== 0 && index < sections.length - 1; index++) lane = nextSectionLane(road, index, lane, 1);
  } else {
    for (; lane !== 0 && index > 0; index--) lane = nextSectionLane(road, index, lane, -1);
  }
  return lane;
}

/** The lane a road's lane at its end `end` continues in on the next road (esmini Road::GetConnectingLaneId, road links). */
function laneLinkAt(road: Road, end: End, laneId: number): number {
  const section = end === 'start' ? road.laneSections[0] : road.laneSections.at(-1);
  const lane = section?.lanes.find((each) => each.id === laneId);
  return (end === 'start' ? lane?.predecessor : lane?.successor) ?? 0;
}

/**
 * The connections of a junction from an incoming road: those the file writes, then the counter connections
 * esmini adds at load for a connecting road whose other end meets the road (RoadManager.cpp, the
 * "Add missing junction counter connection" of OpenDrive::CheckConnectedRoad), lane links from its lanes' links.
 */
function connectionsFrom(network: RoadNetwork, junctionId: string, incoming: Road): JunctionConnection[] {
  const junction = network.junctions.get(junctionId);
  if (!junction) return [];
  const written = junction.connections.filter((connection) => connection.incomingRoad === incoming.id);
  const counter: JunctionConnection[] = [];
  for (const connection of junction.connections) {
    const connecting = network.byId.get(connection.connectingRoad);
    if (!connecting || connection.incomingRoad === incoming.id) continue;
    if (written.some((each) => each.connectingRoad === connecting.id) || counter.some((each) => each.connectingRoad === connecting.id))
      continue;
    const end: End | undefined =
      connecting.predecessor?.elementType === 'road' && connecting.predecessor.elementId === incoming.id
        ? 'start'
        : connecting.successor?.elementType === 'road' && connecting.successor.elementId === incoming.id
          ? 'end'
          : undefined;
    if (!end || connection.contactPoint === end) continue;
    const section = end === 'start' ? connecting.laneSections[0] : connecting.laneSections.at(-1);
    const laneLinks: [number, number][] = [];
    for (const lane of section?.lanes ?? []) {
      const to = end === 'start' ? lane.predecessor : lane.successor;
      if (to !== undefined && lane.id !== 0) laneLinks.push([to, lane.id]);
    }
    if (laneLinks.length > 0) counter.push({ incomingRoad: incoming.id, connectingRoad: connecting.id, contactPoint: end, laneLinks });
  }
  return [...written, ...counter];
}

interface FoundPath {
  nodes: PathNode[];
  dist: number;
}

/**
 * One run of esmini's RoadPath::Calculate(dist, false) from `start` to the road of `target`: the road ends it
 * takes, with the distance from the start to the target along them, or why there is none. esmini takes the first
 * of equally near road ends in the order it inserted them; `order[k]` says which of them this run takes at the
 * k-th such choice (0 by default), and `ties` gets how many there were at each.
 */
function searchPath(
  network: RoadNetwork,
  start: RouteWaypoint,
  target: RouteWaypoint,
  order: number[],
  ties: number[],
): FoundPath | string {
  const startRoad = network.byId.get(start.roadId);
  const targetRoad = network.byId.get(target.roadId);
  if (!startRoad) return `road ${start.roadId} is not in the road network`;
  if (!targetRoad) return `road ${target.roadId} is not in the road network`;
  // Forward the way the entity heads (by default its lane's driving direction; right-hand traffic: a negative lane drives towards growing s).
  const exit: End = directionAt(start) === 1 ? 'end' : 'start';
  const firstLink = linkAt(startRoad, exit);
  if (!firstLink)
    return `road ${startRoad.id} ends without a link ${start.direction === undefined ? `in the driving direction of lane ${start.laneId}` : 'the way the entity heads'}`;
  const unvisited: PathNode[] = [
    {
      road: startRoad,
      exit,
      link: firstLink,
      laneId: laneAtEnd(startRoad, start.laneId, start.s, exit),
      dist: exit === 'start' ? start.s : startRoad.length - start.s,
      previous: undefined,
    },
  ];
  const visited: PathNode[] = [];
  const visitedLinks = new Set<RoadLink>();
  const offsetOnTarget = (entered: End): number => (entered === 'start' ? target.s : targetRoad.length - target.s);

  // A road entered from `from` at its end `entered` in lane `laneId` (esmini RoadPath::CheckRoad).
  const check = (road: Road, entered: End, laneId: number, from: PathNode): void => {
    if (laneId === 0) return;
    const exitEnd = otherEnd(entered);
    const link = linkAt(road, exitEnd);
    if (!link) return;
    const lane = laneAtEnd(road, laneId, entered === 'start' ? 0 : road.length, exitEnd);
    if (visitedLinks.has(link)) return;
    const known = unvisited.find((node) => node.link === link);
    // esmini keeps the earlier node's path and only lowers its distance.
    if (known) known.dist = Math.min(known.dist, from.dist + road.length);
    else unvisited.push({ road, exit: exitEnd, link, laneId: lane, dist: from.dist + road.length, previous: from });
  };

  for (let step = 0; step < MAX_STEPS && unvisited.length > 0; step++) {
    let nearest = 0;
    for (let each = 1; each < unvisited.length; each++) if (unvisited[each].dist < unvisited[nearest].dist) nearest = each;
    const tied: number[] = [];
    for (let each = 0; each < unvisited.length; each++)
      if (Math.abs(unvisited[each].dist - unvisited[nearest].dist) < SAME_DISTANCE) tied.push(each);
    let index = nearest;
    if (tied.length > 1) {
      index = tied[order[ties.length] ?? 0];
      ties.push(tied.length);
    }
    const node = unvisited[index];
    let found: number[] = [];
    if (node.link.elementType === 'road') {
      const next = network.byId.get(node.link.elementId);
      if (!next) return `road ${node.road.id} links to road ${node.link.elementId}, which is not in the road network`;
      const entered: End = node.link.contactPoint ?? 'start';
      if (next === targetRoad) found = [node.dist + offsetOnTarget(entered)];
      else check(next, entered, laneLinkAt(node.road, node.exit, node.laneId), node);
    } else {
      const junction = network.junctions.get(node.link.elementId);
      if (!junction) return `road ${node.road.id} links to junction ${node.link.elementId}, which is not in the road network`;
      if (junction.type === 'direct')
        return `the route runs through direct junction ${junction.id}, which the export does not plan through`;
      for (const connection of connectionsFrom(network, junction.id, node.road)) {
        const next = network.byId.get(connection.connectingRoad);
        if (!next) return `junction ${junction.id} connects road ${connection.connectingRoad}, which is not in the road network`;
        if (next === targetRoad) found.push(node.dist + offsetOnTarget(connection.contactPoint));
        else check(next, connection.contactPoint, connection.laneLinks.find(([from]) => from === node.laneId)?.[1] ?? 0, node);
      }
    }
    visited.push(node);
    visitedLinks.add(node.link);
    unvisited.splice(index, 1);
    if (found.length > 1) return `junction ${node.link.elementId} reaches road ${targetRoad.id} by ${found.length} connecting roads`;
    if (found.length === 1) {
      const nodes: PathNode[] = [];
      for (let each: PathNode | undefined = node; each; each = each.previous) nodes.unshift(each);
      return { nodes, dist: found[0] };
    }
  }
  return `no way along lane links from road ${start.roadId} lane ${start.laneId} to road ${target.roadId} ${start.direction === undefined ? 'in its driving direction' : 'the way the entity heads'}`;
}

/** The roads a path runs over, from the start's road to the target's. */
function pathRoads(path: FoundPath, target: RouteWaypoint): string[] {
  return [...path.nodes.map((node) => node.road.id), target.roadId];
}

/**
 * The road ends from `start` to the road of `target` as esmini finds them, with the distance along them; or why
 * there is no single answer. Where road ends are equally near, esmini's answer depends on the order it inserted
 * them, which the OpenSCENARIO standard does not settle (a Waypoint's routeStrategy names no tie rule): every
 * order is tried, and the way is taken only when they all give it (a tie elsewhere in the network changes
 * nothing). When two orders give two ways, the message names both and the waypoint that picks one.
 */
function findPath(network: RoadNetwork, start: RouteWaypoint, target: RouteWaypoint, between: string): FoundPath | string {
  const orders: number[][] = [[]];
  let first: FoundPath | string | undefined;
  for (let tried = 0; orders.length > 0; tried++) {
    const order = orders.pop() as number[];
    const ties: number[] = [];
    const answer = searchPath(network, start, target, order, ties);
    // Each choice after those this order fixed, taken otherwise, is another order esmini may follow.
    for (let at = order.length; at < ties.length; at++)
      for (let other = 1; other < ties[at]; other++) orders.push([...order, ...new Array<number>(at - order.length).fill(0), other]);
    if (first === undefined) {
      first = answer;
      if (ties.length === 0) return answer;
    } else if (typeof answer === 'string' || typeof first === 'string') {
      if (answer !== first)
        return `from ${between} esmini's way depends on the order its file lists equally near roads (${typeof first === 'string' ? first : pathRoads(first, target).join(' > ')}; or ${typeof answer === 'string' ? answer : pathRoads(answer, target).join(' > ')})`;
    } else {
      const one = pathRoads(first, target);
      const two = pathRoads(answer, target);
      if (one.join(' ') !== two.join(' ') || Math.abs(first.dist - answer.dist) > SAME_DISTANCE) {
        const onlyOne = one.find((road) => !two.includes(road));
        const onlyTwo = two.find((road) => !one.includes(road));
        const pick = onlyOne && onlyTwo ? `add a Waypoint on road ${onlyOne} or road ${onlyTwo} ` : 'add a Waypoint on the road to take ';
        return `from ${between} two ways are equally short (roads ${one.join(' > ')}, and ${two.join(' > ')}) and the standard names no rule to choose (esmini takes the one its file lists first): ${pick}between them to say which`;
      }
    }
    if (tried + 1 >= MAX_ORDERS && orders.length > 0)
      return `from ${between} too many road ends are equally near for the export to tell whether esmini's way depends on the order of its file; add Waypoints on the roads the route takes`;
  }
  return first as FoundPath | string;
}

/** esmini's minimal waypoints of a route (Route::AddWaypoint), with the route's length from its first waypoint; or why there are none. */
function planRoute(network: RoadNetwork, waypoints: RouteWaypoint[]): { stops: Stop[]; length: number } | string {
  if (waypoints.length < 2) return 'the route has fewer than two waypoints';
  const stops: Stop[] = [];
  const roadOf = (waypoint: RouteWaypoint): Road | undefined => network.byId.get(waypoint.roadId);
  let length = 0;
  for (const waypoint of waypoints) {
    const road = roadOf(waypoint);
    if (!road) return `road ${waypoint.roadId} of a waypoint is not in the road network`;
    if (stops.length === 0) {
      stops.push({ given: waypoint, road, s: waypoint.s, laneId: waypoint.laneId, direction: directionAt(waypoint), routeS: 0 });
      continue;
    }
    // esmini keeps the first waypoint and then the last one on each road.
    if ((stops.length === 2 && stops[0].road === stops[1].road) || (stops.length > 1 && road === stops.at(-1)?.road)) {
      stops.pop();
      length = stops.at(-1)?.routeS ?? 0;
    }
    const previous = stops.at(-1) as Stop;
    const from = previous.given;
    // esmini would plan on from the waypoint it added on the road before, heading along that road: not a waypoint the route names.
    if (!from)
      return `two waypoints follow each other on road ${road.id} after other roads; esmini re-plans from a waypoint of its own there`;
    if (previous.road === road) {
      // On the road it starts on: the distance is the difference of s, and the route runs the lane's driving direction.
      const direction = previous.direction;
      if ((waypoint.s - previous.s) * direction < 0)
        return `waypoint on road ${road.id} at s ${waypoint.s} lies behind the one before it in the driving direction`;
      length += Math.abs(waypoint.s - previous.s);
      stops.push({ given: waypoint, road, s: waypoint.s, laneId: waypoint.laneId, direction, routeS: length });
      continue;
    }
    const nameOf = (each: RouteWaypoint): string => each.name ?? `waypoint ${waypoints.indexOf(each) + 1}`;
    const path = findPath(network, from, waypoint, `${nameOf(from)} to ${nameOf(waypoint)}`);
    if (typeof path === 'string') return path;
    let along = length;
    let at = previous;
    for (const node of path.nodes.slice(1)) {
      const entered = otherEnd(node.exit);
      const s = node.road.length * INTERMEDIATE_FRACTION;
      along += (at.direction === 1 ? at.road.length - at.s : at.s) + (entered === 'start' ? s : node.road.length - s);
      at = { road: node.road, s, laneId: node.laneId, direction: entered === 'start' ? 1 : -1, routeS: along };
      stops.push(at);
    }
    const lastNode = path.nodes.at(-1) as PathNode;
    const lastLink = lastNode.link;
    const entered: End =
      lastLink.elementType === 'road'
        ? (lastLink.contactPoint ?? 'start')
        : (connectionsFrom(network, lastLink.elementId, lastNode.road).find((each) => each.connectingRoad === road.id)?.contactPoint ??
          'start');
    length += path.dist;
    stops.push({ given: waypoint, road, s: waypoint.s, laneId: waypoint.laneId, direction: entered === 'start' ? 1 : -1, routeS: length });
  }
  if (stops.length > 1 && stops[0].road === stops[1].road) stops[0].direction = stops[1].s >= stops[0].s ? 1 : -1;
  return { stops, length };
}

/** Where `pathS` metres along the route lies: esmini's minimal waypoints (Route::AddWaypoint) walked as Route::SetPathS walks them. */
export function pointAlongRoute(network: RoadNetwork, waypoints: RouteWaypoint[], pathS: number): RoutePoint | string {
  const plan = planRoute(network, waypoints);
  if (typeof plan === 'string') return plan;
  const { stops, length } = plan;
  if (pathS < 0 || pathS > length + SMALL)
    return `pathS ${pathS} lies past the route's end (the route is ${Number(length.toFixed(2))} m long from its first waypoint)`;
  let index = 0;
  while (index < stops.length && pathS > stops[index].routeS - SMALL) index++;
  if (index > 0) index--;
  const stop = stops[index];
  const ds = pathS - stop.routeS;
  const roads = [...new Set(stops.map((each) => each.road.id))];
  const pastEnd = stop.direction === 1 ? index < stops.length - 1 && stop.s + ds > stop.road.length + SMALL : stop.s < ds + SMALL;
  if (pastEnd && index + 1 < stops.length) {
    const next = stops[index + 1];
    const over = stop.direction === 1 ? stop.s + ds - stop.road.length : ds - stop.s;
    return { roadId: next.road.id, s: next.direction === 1 ? over : next.road.length - over, roads };
  }
  return { roadId: stop.road.id, s: stop.s + stop.direction * ds, roads };
}

/** A stretch of one lane of one road the route drives, from s `from` to s `to` (to < from: against s). */
export interface LaneStretch {
  roadId: string;
  laneId: number;
  from: number;
  to: number;
}

/**
 * The lanes an entity drives from `start` to the route's last waypoint, as esmini moves it along a route: in its own
 * lane (no lane change), through each road the way it heads (its lane's driving direction unless the start gives it), from road to road by lane links and through
 * junctions by the connection to the route's next road (esmini's default controller, Position::MoveAlongS with a Route);
 * split where the lane continues as another lane id (lane sections, roads). Or why the entity cannot drive it so.
 */
export function routeLanes(network: RoadNetwork, waypoints: RouteWaypoint[], start: RouteWaypoint): LaneStretch[] | string {
  const plan = planRoute(network, waypoints);
  if (typeof plan === 'string') return plan;
  const roads: Road[] = [];
  for (const stop of plan.stops) if (roads.at(-1) !== stop.road) roads.push(stop.road);
  const repeated = roads.find((road, index) => roads.indexOf(road) !== index);
  if (repeated) return `the route runs over road ${repeated.id} twice`;
  const first = roads.findIndex((road) => road.id === start.roadId);
  if (first < 0)
    return `${start.name ?? 'the start'} lies on road ${start.roadId}, which the route does not run over (${roads.map((road) => road.id).join(' > ')})`;
  const last = waypoints[waypoints.length - 1];
  const directionOn = (road: Road): 1 | -1 => (plan.stops.find((stop) => stop.road === road) as Stop).direction;
  let direction = directionOn(roads[first]);
  if (directionAt(start) !== direction)
    return `${start.direction === undefined ? `lane ${start.laneId}` : `the entity in lane ${start.laneId}`} of road ${start.roadId} ${start.direction === undefined ? 'drives' : 'heads'} against the route there (esmini keeps the lane, no U-turn)`;
  const stretches: LaneStretch[] = [];
  let laneId = start.laneId;
  let s = start.s;
  for (let index = first; index < roads.length; index++) {
    const road = roads[index];
    const end = index === roads.length - 1 ? last.s : direction === 1 ? road.length : 0;
    if (end < 0 || end > road.length + SMALL)
      return `${last.name ?? "the route's last waypoint"} (s ${last.s}) lies past the end of road ${road.id} (${Number(road.length.toFixed(3))} m)`;
    if ((end - s) * direction < -SMALL)
      return `${start.name ?? 'the start'} (road ${road.id}, s ${Number(s.toFixed(3))}) lies past the route's last waypoint (s ${last.s})`;
    // Through the road's lane sections: the lane continues as its link names in the next one.
    let section = laneSectionIndexAt(road, s);
    for (;;) {
      const sectionEnd = direction === 1 ? road.laneSections[section].s + road.laneSections[section].length : road.laneSections[section].s;
      const reaches = direction === 1 ? sectionEnd >= end - SMALL : sectionEnd <= end + SMALL;
      if (!road.laneSections[section].lanes.some((lane) => lane.id === laneId))
        return `road ${road.id} has no lane ${laneId} at s ${Number(s.toFixed(3))}`;
      stretches.push({ roadId: road.id, laneId, from: s, to: reaches ? end : sectionEnd });
      if (reaches) break;
      const next = nextSectionLane(road, section, laneId, direction);
      if (next === 0 || !road.laneSections[section + direction]?.lanes.some((each) => each.id === next))
        return `lane ${laneId} of road ${road.id} continues in no lane of the next lane section at s ${Number(sectionEnd.toFixed(3))}`;
      laneId = next;
      s = sectionEnd;
      section += direction;
    }
    if (index === roads.length - 1) break;
    const exit: End = direction === 1 ? 'end' : 'start';
    const link = linkAt(road, exit);
    const nextRoad = roads[index + 1];
    let entered: End | undefined;
    let nextLane = 0;
    if (link?.elementType === 'road' && link.elementId === nextRoad.id) {
      entered = link.contactPoint ?? 'start';
      nextLane = laneLinkAt(road, exit, laneId);
    } else if (link?.elementType === 'junction') {
      const connection = connectionsFrom(network, link.elementId, road).find((each) => each.connectingRoad === nextRoad.id);
      entered = connection?.contactPoint;
      nextLane = connection?.laneLinks.find(([from]) => from === laneId)?.[1] ?? 0;
    }
    if (!entered) return `road ${road.id} does not lead into road ${nextRoad.id}, the route's next road`;
    if (nextLane === 0) return `lane ${laneId} of road ${road.id} has no link into road ${nextRoad.id}, the route's next road`;
    laneId = nextLane;
    direction = entered === 'start' ? 1 : -1;
    s = entered === 'start' ? 0 : nextRoad.length;
  }
  return stretches;
}

/** Lane stretches onwards from a point, and why they end short of the length asked, if they do. */
export interface LaneOnwards {
  stretches: LaneStretch[];
  length: number;
  /** Why the lane cannot be followed further: its road ends, or a junction offers more than one way on. */
  endsBecause?: string;
}

/**
 * The lane an entity keeps past a route's last waypoint, `length` metres on from `roadId`/`laneId` at `s` the way `direction`
 * runs (esmini's default controller drives on in its lane, Position::MoveAlongS): through lane sections and road links by
 * lane links, through a junction only where one connection leads on from the lane (else esmini's junction selector decides).
 */
export function laneOnwards(
  network: RoadNetwork,
  roadId: string,
  laneId: number,
  s: number,
  direction: 1 | -1,
  length: number,
): LaneOnwards {
  const stretches: LaneStretch[] = [];
  let covered = 0;
  let road = network.byId.get(roadId);
  let lane = laneId;
  let at = s;
  let heading = direction;
  for (let steps = 0; road && steps < MAX_STEPS; steps++) {
    let section = laneSectionIndexAt(road, at);
    for (;;) {
      const current = road.laneSections[section];
      if (!current?.lanes.some((each) => each.id === lane))
        return { stretches, length: covered, endsBecause: `road ${road.id} has no lane ${lane} at s ${Number(at.toFixed(3))}` };
      const sectionEnd = heading === 1 ? current.s + current.length : current.s;
      const left = length - covered;
      if (Math.abs(sectionEnd - at) >= left) {
        stretches.push({ roadId: road.id, laneId: lane, from: at, to: at + heading * left });
        return { stretches, length };
      }
      if (Math.abs(sectionEnd - at) > SMALL) stretches.push({ roadId: road.id, laneId: lane, from: at, to: sectionEnd });
      covered += Math.abs(sectionEnd - at);
      at = sectionEnd;
      if (section + heading < 0 || section + heading >= road.laneSections.length) break;
      lane = nextSectionLane(road, section, lane, heading);
      section += heading;
    }
    const exit: End = heading === 1 ? 'end' : 'start';
    const link = linkAt(road, exit);
    let next: Road | undefined;
    let entered: End | undefined;
    let nextLane = 0;
    if (link?.elementType === 'road') {
      next = network.byId.get(link.elementId);
      entered = link.contactPoint ?? 'start';
      nextLane = laneLinkAt(road, exit, lane);
    } else if (link?.elementType === 'junction') {
      const ways = connectionsFrom(network, link.elementId, road).filter((each) => each.laneLinks.some(([from]) => from === lane));
      if (ways.length > 1)
        return {
          stretches,
          length: covered,
          endsBecause: `lane ${lane} of road ${road.id} enters junction ${link.elementId}, where ${ways.length} connections lead on and esmini's junction selector picks one`,
        };
      next = ways[0] ? network.byId.get(ways[0].connectingRoad) : undefined;
      entered = ways[0]?.contactPoint;
      nextLane = ways[0]?.laneLinks.find(([from]) => from === lane)?.[1] ?? 0;
    }
    if (!next || !entered || nextLane === 0)
      return { stretches, length: covered, endsBecause: `lane ${lane} of road ${road.id} leads nowhere at its ${exit}` };
    road = next;
    lane = nextLane;
    heading = entered === 'start' ? 1 : -1;
    at = entered === 'start' ? 0 : next.length;
  }
  return { stretches, length: covered, endsBecause: `the lane runs over more than ${MAX_STEPS} roads` };
}

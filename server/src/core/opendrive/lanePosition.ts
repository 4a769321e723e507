/**
 * The lane a world point (x, y in the road's frame, a heading) lies in: its road, lane, s and offset from the lane's
 * centre, as a LanePosition names it. esmini places a WorldPosition on the road this way (RoadManager.cpp
 * Position::XYZ2TrackPos: the nearest reference line the point projects onto, the lane whose borders hold its t), and
 * CARLA's map finds the waypoint of a location by the nearest lane centre (Map::GetClosestWaypointOnRoad). Where roads
 * overlap (a junction's connecting roads), the lane whose centre is nearest and whose driving direction is the heading's
 * is taken; a point in no lane of the kinds asked for, or only in lanes driven the other way, is answered why.
 */
import { normalizeAngle } from './geometry';
import {
  drivesAlongS,
  isDrivingLane,
  Lane,
  laneCenterT,
  laneSectionIndexAt,
  laneWidth,
  outerBorderT,
  referencePose,
  Road,
  RoadNetwork,
  roadCubicAt,
} from './road';

export interface PointLane {
  roadId: string;
  laneId: number;
  s: number;
  /** From the lane's centre, positive to the left of the road's reference line. */
  offset: number;
}

/** Reference lines are searched at this step before the nearest point is refined. */
const SEARCH_STEP = 2;
/** A point this far beyond a road's end still projects onto it (a road's end meets the next road's start). */
const END_MARGIN = 0.05;

/** The s of a road's reference line nearest the point, and the point's lateral t from it (positive left); undefined when the point projects past its ends. */
function projectOnRoad(road: Road, x: number, y: number): { s: number; t: number; distance: number } | undefined {
  const distanceAt = (s: number): number => {
    const pose = referencePose(road, s);
    return Math.hypot(x - pose.x, y - pose.y);
  };
  const count = Math.max(1, Math.ceil(road.length / SEARCH_STEP));
  let best = 0;
  let bestDistance = Infinity;
  for (let index = 0; index <= count; index++) {
    const s = (road.length * index) / count;
    const distance = distanceAt(s);
    if (distance < bestDistance) [best, bestDistance] = [s, distance];
  }
  // Golden-section search around the nearest sample: the reference line bends little within one step.
  let low = Math.max(0, best - road.length / count);
  let high = Math.min(road.length, best + road.length / count);
  const ratio = (Math.sqrt(5) - 1) / 2;
  for (let step = 0; step < 40; step++) {
    const a = high - ratio * (high - low);
    const b = low + ratio * (high - low);
    if (distanceAt(a) < distanceAt(b)) high = b;
    else low = a;
  }
  const s = (low + high) / 2;
  const pose = referencePose(road, s);
  const along = (x - pose.x) * Math.cos(pose.hdg) + (y - pose.y) * Math.sin(pose.hdg);
  if (Math.abs(along) > END_MARGIN) return undefined;
  const t = -(x - pose.x) * Math.sin(pose.hdg) + (y - pose.y) * Math.cos(pose.hdg);
  return { s, t, distance: Math.hypot(x - pose.x, y - pose.y) };
}

/** The lane of a section whose borders hold lateral `t` (from the lane-offset line) at s, or undefined. */
function laneHolding(road: Road, sectionIndex: number, s: number, t: number): Lane | undefined {
  const section = road.laneSections[sectionIndex];
  for (const lane of section.lanes) {
    if (lane.id === 0) continue;
    const outer = outerBorderT(section, lane.id, s);
    const inner = outerBorderT(section, lane.id - Math.sign(lane.id), s);
    if (Math.min(inner, outer) <= t && t <= Math.max(inner, outer) && inner !== outer) return lane;
  }
  return undefined;
}

/** Each road whose lanes hold world point (x, y): where the point projects on it, its lane section and the lane (any kind). */
function* lanesHolding(
  network: RoadNetwork,
  x: number,
  y: number,
): Generator<{ road: Road; projected: { s: number; t: number }; sectionIndex: number; lane: Lane }> {
  for (const road of network.roads) {
    const projected = projectOnRoad(road, x, y);
    if (!projected) continue;
    const sectionIndex = laneSectionIndexAt(road, projected.s);
    const lane = laneHolding(road, sectionIndex, projected.s, projected.t - roadCubicAt(road.laneOffsets, projected.s));
    if (lane) yield { road, projected, sectionIndex, lane };
  }
}

/**
 * The lane that holds world point (x, y), of a kind `accepts` takes, driven in the direction of `heading` (radians,
 * within a right angle), with the nearest centre where several roads hold the point; or why there is none.
 */
export function laneAtPoint(
  network: RoadNetwork,
  x: number,
  y: number,
  heading: number,
  accepts: (lane: Lane) => boolean,
): PointLane | string {
  let found: (PointLane & { fromCentre: number }) | undefined;
  const passed: string[] = [];
  for (const { road, projected, sectionIndex, lane } of lanesHolding(network, x, y)) {
    const where = `lane ${lane.id} of road ${road.id}`;
    if (!accepts(lane)) {
      passed.push(`${where} (a ${lane.type} lane)`);
      continue;
    }
    const driven = referencePose(road, projected.s).hdg + (drivesAlongS(road, lane.id) ? 0 : Math.PI);
    if (Math.abs(normalizeAngle(heading - driven)) >= Math.PI / 2) {
      passed.push(`${where} (driven the other way)`);
      continue;
    }
    const offset = projected.t - laneCenterT(road, sectionIndex, lane.id, projected.s);
    if (!found || Math.abs(offset) < found.fromCentre)
      found = { roadId: road.id, laneId: lane.id, s: projected.s, offset, fromCentre: Math.abs(offset) };
  }
  if (found) return { roadId: found.roadId, laneId: found.laneId, s: found.s, offset: found.offset };
  const at = `x ${Number(x.toFixed(3))}, y ${Number(y.toFixed(3))}`;
  return passed.length > 0 ? `${at} lies in ${passed.join(', ')} only` : `${at} lies on no road`;
}

/** A point's lane as esmini snaps it, and the way its heading points along that road (1: growing s). */
export interface SnappedLane extends PointLane {
  direction: 1 | -1;
}

/**
 * Where esmini places world point (x, y) of an entity off the driving lanes (a pedestrian on a sidewalk): on the road whose
 * lanes hold it, in the driving lane of that road whose centre is nearest, however far (Position::XYZ2TrackPos snaps to
 * LANE_TYPE_ANY_DRIVING by default, LaneSection::GetClosestLaneIdx), whichever way that lane is driven; with the way
 * `heading` points along the road, which esmini moves it and plans its route in (Object::MoveAlongS, RoadPath::Calculate).
 * Where several roads hold the point, the nearest such centre; a point on no road, or on a road without a driving lane there, is answered why.
 */
export function snappedLaneAtPoint(network: RoadNetwork, x: number, y: number, heading: number): SnappedLane | string {
  let found: (SnappedLane & { fromCentre: number }) | undefined;
  const passed: string[] = [];
  for (const { road, projected, sectionIndex } of lanesHolding(network, x, y)) {
    const section = road.laneSections[sectionIndex];
    let nearest: { laneId: number; offset: number } | undefined;
    for (const lane of section.lanes) {
      if (!isDrivingLane(lane) || !(laneWidth(section, lane, projected.s) > 1e-6)) continue;
      const offset = projected.t - laneCenterT(road, sectionIndex, lane.id, projected.s);
      if (!nearest || Math.abs(offset) < Math.abs(nearest.offset)) nearest = { laneId: lane.id, offset };
    }
    if (!nearest) {
      passed.push(`road ${road.id} (no driving lane at s ${Number(projected.s.toFixed(3))})`);
      continue;
    }
    const direction = Math.abs(normalizeAngle(heading - referencePose(road, projected.s).hdg)) < Math.PI / 2 ? 1 : -1;
    if (!found || Math.abs(nearest.offset) < found.fromCentre)
      found = { roadId: road.id, ...nearest, s: projected.s, direction, fromCentre: Math.abs(nearest.offset) };
  }
  if (found) return { roadId: found.roadId, laneId: found.laneId, s: found.s, offset: found.offset, direction: found.direction };
  const at = `x ${Number(x.toFixed(3))}, y ${Number(y.toFixed(3))}`;
  return passed.length > 0 ? `${at} lies on ${passed.join(', ')} only` : `${at} lies on no road`;
}

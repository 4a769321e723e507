/**
 * Where a TrajectoryPosition is, as world coordinates: the point `s` along its trajectory (a Polyline, or the points a
 * curve is sampled into) and `t` to its
 * left (OpenSCENARIO 1.1+: s along the trajectory, t lateral, positive to the left), heading along the segment there
 * or as its Orientation says. The export writes it as the WorldPosition ScenarioRunner converts (it has no
 * TrajectoryPosition). Only a Polyline whose vertices are World positions, or Lane and Road positions on the .xodr road
 * the export read, has such a point without running the scenario; anything else is named why.
 */
import { normalizeAngle } from '../opendrive/geometry';
import { laneById, laneCenterT, laneSectionIndexAt, referencePose, roadPoint, type RoadNetwork } from '../opendrive/road';
import { attr, child, childrenNamed, Node, numberAttr } from './tree';

export interface TrajectoryPoint {
  x: number;
  y: number;
  h: number;
}

/** A heading as a position's Orientation leaves it: set by an absolute one, turned by a relative one (or none), not normalized. */
export function orientedHeading(along: number, orientation: Node | undefined): number {
  if (!orientation) return along;
  return attr(orientation, 'type') === 'absolute' ? numberAttr(orientation, 'h') : along + numberAttr(orientation, 'h');
}

/**
 * Where a Lane or Road position of the .xodr road the export read is, in world coordinates, and its heading as
 * esmini gives it: along the road, against it on a left lane (right-hand traffic), turned by a relative
 * Orientation or set by an absolute one. Or why there is none.
 */
export function roadPositionPose(position: Node, roads: RoadNetwork | undefined, subject = 'it'): TrajectoryPoint | string {
  if (position.name !== 'LanePosition' && position.name !== 'RoadPosition')
    return `${subject} is placed by a ${position.name}, which the export does not turn into coordinates`;
  if (!roads) return `${subject} is a ${position.name} and the road is not an .xodr file the export read`;
  const road = roads.byId.get(attr(position, 'roadId') ?? '');
  const s = numberAttr(position, 's', NaN);
  if (!road) return `${subject} names road '${attr(position, 'roadId') ?? ''}', which the road network does not have`;
  if (!Number.isFinite(s) || s < 0 || s > road.length + 1e-6)
    return `${subject}'s s '${attr(position, 's') ?? ''}' is not on road ${road.id}`;
  const turned = (along: number): number => normalizeAngle(orientedHeading(along, child(position, 'Orientation')));
  if (position.name === 'RoadPosition') {
    const point = roadPoint(road, s, numberAttr(position, 't', 0));
    return { x: point.x, y: point.y, h: turned(referencePose(road, s).hdg) };
  }
  const laneId = numberAttr(position, 'laneId', NaN);
  if (!Number.isInteger(laneId)) return `${subject}'s laneId '${attr(position, 'laneId') ?? ''}' is not a lane number`;
  const section = laneSectionIndexAt(road, s);
  if (laneId !== 0 && !laneById(road.laneSections[section], laneId)) return `road ${road.id} has no lane ${laneId} at s ${s}`;
  const point = roadPoint(road, s, laneCenterT(road, section, laneId, s, numberAttr(position, 'offset', 0)));
  return { x: point.x, y: point.y, h: turned(referencePose(road, s).hdg + (laneId > 0 ? Math.PI : 0)) };
}

type Sampler = (shape: Node, roads: RoadNetwork | undefined) => { x: number; y: number }[] | string;

/**
 * A polyline vertex's position in world coordinates, or why it has none without running the scenario. A vertex on
 * another trajectory (Euro NCAP's VRU paths lie on helper trajectories) is that trajectory's point, when a sampler is given.
 */
function vertexPoint(position: Node | undefined, roads: RoadNetwork | undefined, sampled?: Sampler): { x: number; y: number } | string {
  if (!position) return 'a vertex has no position';
  if (position.name === 'WorldPosition') return { x: numberAttr(position, 'x', NaN), y: numberAttr(position, 'y', NaN) };
  if (position.name === 'TrajectoryPosition' && sampled) {
    const point = trajectoryPoint(position, roads, sampled);
    return typeof point === 'string' ? `a vertex is a TrajectoryPosition: ${point}` : point;
  }
  return roadPositionPose(position, roads, 'a vertex');
}

/** A Polyline's vertices in world coordinates, or why they have none without running the scenario. */
export function polylinePoints(polyline: Node, roads: RoadNetwork | undefined, sampled?: Sampler): { x: number; y: number }[] | string {
  const points: { x: number; y: number }[] = [];
  for (const vertex of childrenNamed(polyline, 'Vertex')) {
    const point = vertexPoint(child(vertex, 'Position')?.children[0], roads, sampled);
    if (typeof point === 'string') return point;
    if (!Number.isFinite(point.x) || !Number.isFinite(point.y)) return 'a vertex has a coordinate that is not a number';
    points.push(point);
  }
  if (points.length < 2) return 'its polyline has fewer than two vertices';
  return points;
}

/** Where `s` along the polyline through `points` lies: the segment holding it (1-based: from points[segment - 1]) and how far into it. */
export function alongPolyline(
  points: readonly { x: number; y: number }[],
  s: number,
): { segment: number; along: number; length: number } | string {
  const lengthOf = (index: number) => Math.hypot(points[index].x - points[index - 1].x, points[index].y - points[index - 1].y);
  // The segment holding s: those before the last are passed over while s lies beyond them.
  let along = s;
  let segment = 1;
  for (; segment < points.length - 1 && along > lengthOf(segment); segment++) along -= lengthOf(segment);
  const length = lengthOf(segment);
  if (along > length + 1e-6) return `its s ${s} is beyond the polyline's length`;
  if (length === 0) return 'its polyline has two vertices at one point';
  return { segment, along, length };
}

/** The point `s` along the polyline through `points` and `t` to its left, heading along its segment. */
export function pointAlong(points: readonly { x: number; y: number }[], s: number, t = 0): TrajectoryPoint | string {
  const found = alongPolyline(points, s);
  return typeof found === 'string' ? found : pointAt(points, found, t);
}

/** The point `found` (alongPolyline's answer) names on the polyline through `points`, `t` to its left, heading along its segment. */
export function pointAt(
  points: readonly { x: number; y: number }[],
  found: { segment: number; along: number; length: number },
  t = 0,
): TrajectoryPoint {
  const [from, to] = [points[found.segment - 1], points[found.segment]];
  const heading = Math.atan2(to.y - from.y, to.x - from.x);
  const fraction = found.along / found.length;
  return {
    x: from.x + (to.x - from.x) * fraction - t * Math.sin(heading),
    y: from.y + (to.y - from.y) * fraction + t * Math.cos(heading),
    h: normalizeAngle(heading),
  };
}

/** The point of a TrajectoryPosition whose trajectory is written inside it (catalogs inlined), or why there is none. */
export function trajectoryPoint(position: Node, roads: RoadNetwork | undefined, sampled: Sampler): TrajectoryPoint | string {
  const reference = child(position, 'TrajectoryRef');
  const trajectory = reference ? child(reference, 'Trajectory') : undefined;
  if (!trajectory) return 'its trajectory is not written in the scenario';
  const shape = child(trajectory, 'Shape')?.children[0];
  if (!shape) return 'its trajectory has no shape';
  // A Clothoid, ClothoidSpline or Nurbs: the points esmini samples it into.
  const points = shape.name === 'Polyline' ? polylinePoints(shape, roads, sampled) : sampled(shape, roads);
  if (typeof points === 'string') return points;
  const s = numberAttr(position, 's', NaN);
  const t = numberAttr(position, 't', 0);
  if (!Number.isFinite(s) || s < 0 || !Number.isFinite(t))
    return `its s '${attr(position, 's') ?? ''}' or t is not a number at or after the start`;
  const point = pointAlong(points, s, t);
  if (typeof point === 'string') return point;
  return { ...point, h: normalizeAngle(orientedHeading(point.h, child(position, 'Orientation'))) };
}

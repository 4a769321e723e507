/**
 * Clothoid, ClothoidSpline and Nurbs trajectories written as the Polyline ScenarioRunner follows
 * (SR_PARSER get_trajectory reads polylines only: "Clothoid shapes are currently unsupported"), sampled as
 * esmini samples them (shapes.ts). A shape placed from an entity (a Relative position, or none: the actor
 * itself) becomes vertices relative to that entity where it is when the action starts, as both ScenarioRunner
 * (ChangeActorWaypoints.initialise converts them then) and esmini (RMTrajectory::Freeze) place them; their
 * offsets need the entity's heading then, which the export takes from the end of the trajectory the event
 * follows, else from the Init: named as an assumption.
 */
import { normalizeAngle } from '../opendrive/geometry';
import type { RoadNetwork } from '../opendrive/road';
import { actorsOf, fromInit } from './scenarioTree';
import { orientedHeading, roadPositionPose } from './trajectoryPoint';
import { sampleClothoid, sampleClothoidSpline, sampleNurbs, type SampledVertex, type SplineSegment } from './shapes';
import { ancestor, attr, child, childrenNamed, fourDecimals, makeNode, named, Node, numberAttr } from './tree';

/** The heading an entity ends a sampled trajectory with, by the name of the Event (and Action) that followed it. */
export type TrajectoryEnds = Map<string, { entity: string; heading: number }>;

export interface SampledShape {
  polyline: Node;
  vertices: number;
  /** Every vertex of one make (vertexNode) with finite numbers: two of them stand for all in a schema check. */
  uniform: boolean;
  /** The entity the vertices are relative to, and the heading assumed for it when the action starts (with why). */
  relative?: { entity: string; heading: number; from: string };
}

/** Where a point is: absolute, or offsets (world axes) from an entity where it is when the action starts; h is absolute. */
interface Placed {
  x: number;
  y: number;
  h: number;
  entity?: string;
}

interface Heading {
  value: number;
  from: string;
}

/** The heading of an entity in the Init (a WorldPosition's h, or the driving direction of a LanePosition's lane on an .xodr road). */
function initHeading(tree: Node, entity: string, roads: RoadNetwork | undefined): number | undefined {
  return fromInit(tree, entity, (privateNode) => {
    const teleport = named(privateNode, 'TeleportAction')[0];
    const position = teleport ? child(teleport, 'Position')?.children[0] : undefined;
    if (!position) return undefined;
    if (position.name === 'WorldPosition') return numberAttr(position, 'h');
    const pose = roadPositionPose(position, roads);
    return typeof pose === 'string' ? undefined : pose.h;
  });
}

/** The heading `entity` has when `action` starts: the end of the sampled trajectory its Event waits for, else its Init heading. */
function headingAtStart(action: Node, entity: string, tree: Node, roads: RoadNetwork | undefined, ends: TrajectoryEnds): Heading | string {
  const event = ancestor(action, 'Event');
  const trigger = event ? child(event, 'StartTrigger') : undefined;
  for (const condition of trigger ? named(trigger, 'StoryboardElementStateCondition') : []) {
    const end = ends.get(attr(condition, 'storyboardElementRef') ?? '');
    if (end && end.entity === entity && /end|complete|stop/i.test(attr(condition, 'state') ?? ''))
      return { value: end.heading, from: `as it ends the trajectory of '${attr(condition, 'storyboardElementRef')}'` };
  }
  const init = initHeading(tree, entity, roads);
  if (init !== undefined) return { value: init, from: 'as in the Init' };
  return `the heading of '${entity}' when the action starts is not known (its Init places it neither by a WorldPosition nor by a LanePosition on an .xodr road)`;
}

/** A Position (or PositionStart) of a shape, or none: the actor where it is; placed absolutely or from an entity. */
function place(
  position: Node | undefined,
  actor: string,
  heading: (entity: string) => Heading | string,
  roads: RoadNetwork | undefined,
): (Placed & { assumed?: Heading }) | string {
  const inner = position?.children[0];
  if (!inner) {
    const own = heading(actor);
    return typeof own === 'string' ? own : { x: 0, y: 0, h: own.value, entity: actor, assumed: own };
  }
  if (inner.name === 'WorldPosition') return { x: numberAttr(inner, 'x'), y: numberAttr(inner, 'y'), h: numberAttr(inner, 'h') };
  // A lane or road point of the .xodr road the export read is a place in the world too, headed as esmini heads it.
  if (inner.name === 'LanePosition' || inner.name === 'RoadPosition') return roadPositionPose(inner, roads, 'its start');
  if (inner.name !== 'RelativeWorldPosition' && inner.name !== 'RelativeObjectPosition')
    return `it is placed by a ${inner.name}, which the export cannot turn into coordinates without running the scenario`;
  const entity = attr(inner, 'entityRef') ?? '';
  const orientation = child(inner, 'Orientation');
  const absolute = orientation !== undefined && attr(orientation, 'type') === 'absolute';
  const dx = numberAttr(inner, 'dx');
  const dy = numberAttr(inner, 'dy');
  const needsHeading = !absolute || inner.name === 'RelativeObjectPosition';
  const known = needsHeading ? heading(entity) : undefined;
  if (typeof known === 'string') return known;
  const base = known?.value ?? 0;
  // A RelativeObjectPosition's offsets are along the entity's axes (the standard; esmini), a RelativeWorldPosition's along the world's.
  const [x, y] =
    inner.name === 'RelativeObjectPosition'
      ? [dx * Math.cos(base) - dy * Math.sin(base), dx * Math.sin(base) + dy * Math.cos(base)]
      : [dx, dy];
  const h = orientedHeading(base, orientation);
  return { x, y, h, entity, ...(known ? { assumed: known } : {}) };
}

function vertexNode(vertex: SampledVertex, relative: { entity: string; heading: number } | undefined, shape: Node): Node {
  const position = relative
    ? makeNode(
        'RelativeWorldPosition',
        [
          ['entityRef', relative.entity],
          ['dx', fourDecimals(vertex.x)],
          ['dy', fourDecimals(vertex.y)],
        ],
        [
          makeNode('Orientation', [
            ['type', 'relative'],
            ['h', fourDecimals(normalizeAngle(vertex.h - relative.heading))],
          ]),
        ],
      )
    : makeNode('WorldPosition', [
        ['x', fourDecimals(vertex.x)],
        ['y', fourDecimals(vertex.y)],
        ['h', fourDecimals(vertex.h)],
      ]);
  const attributes: [string, string][] = vertex.time !== undefined ? [['time', fourDecimals(vertex.time)]] : [];
  return makeNode('Vertex', attributes, [makeNode('Position', [], [position])], shape.place);
}

function numbersOf(node: Node, names: string[]): number[] | string {
  const values = names.map((name) => Number(attr(node, name)));
  const bad = names.find((_, index) => !Number.isFinite(values[index]));
  return bad ? `its ${bad} '${attr(node, bad) ?? ''}' is not a number` : values;
}

/** The shape's vertices and the frame they are in, or why it cannot be sampled. */
function sampleOf(
  shape: Node,
  placeAt: (position: Node | undefined) => ReturnType<typeof place>,
): { vertices: SampledVertex[]; start: Placed & { assumed?: Heading } } | string {
  if (shape.name === 'Clothoid') {
    const prime = attr(shape, 'curvaturePrime') !== undefined ? 'curvaturePrime' : 'curvatureDot';
    const values = numbersOf(shape, ['curvature', prime, 'length']);
    if (typeof values === 'string') return values;
    const [curvature, curvaturePrime, length] = values;
    if (length <= 0) return `its length ${length} is not positive`;
    const start = placeAt(child(shape, 'Position'));
    if (typeof start === 'string') return start;
    const timed = attr(shape, 'startTime') !== undefined && attr(shape, 'stopTime') !== undefined;
    const times = timed ? { start: numberAttr(shape, 'startTime'), stop: numberAttr(shape, 'stopTime') } : undefined;
    return { vertices: sampleClothoid({ x: start.x, y: start.y, hdg: start.h }, curvature, curvaturePrime, length, times), start };
  }
  if (shape.name === 'ClothoidSpline') {
    const nodes = childrenNamed(shape, 'ClothoidSplineSegment');
    if (nodes.length === 0) return 'it has no segment';
    if (nodes.slice(1).some((segment) => child(segment, 'PositionStart')))
      return 'a segment after the first starts at a position of its own, which esmini jumps to';
    const segments: SplineSegment[] = [];
    for (const segment of nodes) {
      const length = Number(attr(segment, 'length'));
      if (!(length > 0)) return `a segment's length '${attr(segment, 'length') ?? ''}' is not a positive number`;
      const curvStart =
        attr(segment, 'curvatureStart') !== undefined ? numberAttr(segment, 'curvatureStart') : (segments.at(-1)?.curvEnd ?? 0);
      const curvEnd = attr(segment, 'curvatureEnd') !== undefined ? numberAttr(segment, 'curvatureEnd') : curvStart;
      const time = attr(segment, 'timeStart') !== undefined ? numberAttr(segment, 'timeStart') : undefined;
      segments.push({ curvStart, curvEnd, length, hOffset: numberAttr(segment, 'hOffset'), ...(time !== undefined ? { time } : {}) });
    }
    const start = placeAt(child(nodes[0], 'PositionStart'));
    if (typeof start === 'string') return start;
    const timeEnd = attr(shape, 'timeEnd') !== undefined ? numberAttr(shape, 'timeEnd') : undefined;
    return { vertices: sampleClothoidSpline({ x: start.x, y: start.y, hdg: start.h }, segments, timeEnd), start };
  }
  // Nurbs: every control point in one frame (all absolute, or all from one entity).
  const points: Placed[] = [];
  let first: (Placed & { assumed?: Heading }) | undefined;
  const controlPoints = childrenNamed(shape, 'ControlPoint');
  for (const controlPoint of controlPoints) {
    const at = placeAt(child(controlPoint, 'Position'));
    if (typeof at === 'string') return `a control point: ${at}`;
    first ??= at;
    if (at.entity !== first.entity) return 'its control points are placed from different entities (or some absolutely)';
    points.push(at);
  }
  if (!first) return 'it has no control point';
  const timed = controlPoints.every((point) => attr(point, 'time') !== undefined);
  const sampled = sampleNurbs(
    Number(attr(shape, 'order')),
    points.map((point, index) => ({
      x: point.x,
      y: point.y,
      weight: numberAttr(controlPoints[index], 'weight', 1),
      ...(timed ? { time: numberAttr(controlPoints[index], 'time') } : {}),
    })),
    childrenNamed(shape, 'Knot').map((knot) => numberAttr(knot, 'value', NaN)),
  );
  return typeof sampled === 'string' ? sampled : { vertices: sampled, start: first };
}

/**
 * The points of a Clothoid, ClothoidSpline or Nurbs placed in the world (World, Lane or Road positions of the
 * .xodr road), sampled as esmini samples them: the trajectory of a TrajectoryPosition, which no actor follows, so
 * one placed from an entity has no place without running the scenario.
 */
export function sampledWorldPoints(shape: Node, roads: RoadNetwork | undefined): { x: number; y: number }[] | string {
  const sample = sampleOf(shape, (position) =>
    position?.children[0] && !position.children[0].name.startsWith('Relative')
      ? place(position, '', () => 'unused', roads)
      : `it is placed from an entity (a ${position?.children[0]?.name ?? 'shape without a position'}), which has no place without running the scenario`,
  );
  return typeof sample === 'string' ? sample : sample.vertices.map((vertex) => ({ x: vertex.x, y: vertex.y }));
}

/**
 * The Polyline that stands for a Clothoid, ClothoidSpline or Nurbs `shape` of a FollowTrajectoryAction, or
 * why it cannot be written (the reason, for the loss report). Records where the actor ends heading in `ends`.
 */
export function sampledShape(
  action: Node,
  shape: Node,
  tree: Node,
  roads: RoadNetwork | undefined,
  ends: TrajectoryEnds,
): SampledShape | string {
  const actors = actorsOf(action);
  if (actors.length !== 1) return `it is followed by ${actors.length} actors, each from where it is`;
  const actor = actors[0];
  // Asked for each control point: the answer for an entity does not change while one shape is sampled.
  const headings = new Map<string, Heading | string>();
  const heading = (entity: string): Heading | string => {
    let known = headings.get(entity);
    if (known === undefined) headings.set(entity, (known = headingAtStart(action, entity, tree, roads, ends)));
    return known;
  };
  const sample = sampleOf(shape, (position) => place(position, actor, heading, roads));
  if (typeof sample === 'string') return sample;
  const { vertices, start } = sample;
  const relative =
    start.entity !== undefined ? { entity: start.entity, heading: start.assumed?.value ?? 0, from: start.assumed?.from ?? '' } : undefined;
  const polyline = makeNode(
    'Polyline',
    [],
    vertices.map((vertex) => vertexNode(vertex, relative, shape)),
    shape.place,
  );
  const last = vertices[vertices.length - 1];
  for (const holder of [ancestor(action, 'Event'), ancestor(action, 'Action')]) {
    const name = holder ? attr(holder, 'name') : undefined;
    if (name && last) ends.set(name, { entity: actor, heading: last.h });
  }
  const finite = (vertex: SampledVertex): boolean =>
    Number.isFinite(vertex.x) &&
    Number.isFinite(vertex.y) &&
    Number.isFinite(vertex.h) &&
    (vertex.time === undefined || Number.isFinite(vertex.time));
  const timed = vertices[0]?.time !== undefined;
  const uniform = vertices.every((vertex) => finite(vertex) && (vertex.time !== undefined) === timed);
  return { polyline, vertices: vertices.length, uniform, ...(relative ? { relative } : {}) };
}

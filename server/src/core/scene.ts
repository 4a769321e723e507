/**
 * What a bird's-eye view shows of a scenario before it runs: its road file, where each entity
 * starts (the Init's TeleportActions evaluated against the road), and the storyboard's events.
 */
import { expressionMessage } from './diagnostics/expressionWords';
import { laneById, laneCenterT, laneSectionIndexAt, Road, RoadNetwork, roadPoint } from './opendrive/road';
import { normalizeAngle } from './opendrive/geometry';
import { logicFileOf } from './semantics/roadFiles';
import { assignmentsOf, catalogEntryFor, DocumentSemantics, Evaluator, semanticModelOf } from './semantics';
import { attribute, attributeValue, XmlDocument, XmlElement } from './xml';

export interface EntityPlacement {
  name: string;
  /** Vehicle, Pedestrian, MiscObject, or what the declaration names (a CatalogReference). */
  kind: string;
  /** Bounding box length and width in metres (defaults for a catalog entry, whose box is not read). */
  length: number;
  width: number;
  /** Where the bounding box's center is ahead of the reference point (the rear axle for vehicles). */
  centerX: number;
  x?: number;
  y?: number;
  hdg?: number;
  /** The position as written, e.g. `LanePosition road 0, lane -1, s 50`. */
  described: string;
  /** Why there is no x/y, when there is none. */
  problem?: string;
  declaration: XmlElement;
  /** The Position element of its TeleportAction in Init. */
  position?: XmlElement;
}

export interface StoryEvent {
  name: string;
  maneuver: string;
  group: string;
  act: string;
  /** The start trigger in words, e.g. `SimulationTime greaterThan 2`. */
  trigger: string;
  /** The simulation time of a plain SimulationTimeCondition trigger, when that is all it waits for. */
  plannedTime?: number;
  /** The entities of its ManeuverGroup's Actors. */
  actors: string[];
  element: XmlElement;
  /** Its ManeuverGroup (for where an imported copy was written). */
  groupElement: XmlElement;
}

export interface ScenarioScene {
  logicFile?: { filepath: string; element: XmlElement };
  entities: EntityPlacement[];
  events: StoryEvent[];
}

/** Where road positions of an entity are known: what Relative*Positions on lanes start from. */
interface RoadCoordinates {
  road: Road;
  laneId: number;
  s: number;
  offset: number;
}

function children(element: XmlElement | undefined, name: string): XmlElement[] {
  return element ? element.children.filter((child) => child.name === name) : [];
}

function child(element: XmlElement | undefined, name: string): XmlElement | undefined {
  return element?.children.find((candidate) => candidate.name === name);
}

function path(element: XmlElement | undefined, ...names: string[]): XmlElement | undefined {
  let current = element;
  for (const name of names) current = child(current, name);
  return current;
}

/** Attribute values with `$parameters` and `${...}` expressions evaluated by the semantic model. */
class Reader {
  constructor(private readonly evaluator: Evaluator) {}

  text(element: XmlElement, name: string): string | undefined {
    const found = attribute(element, name);
    if (!found) return undefined;
    const result = this.evaluator.attributeValue(element, found);
    return result.ok ? String(result.value) : found.value;
  }

  /** A numeric attribute; throws a message naming the attribute when it is missing or cannot be evaluated. */
  number(element: XmlElement, name: string, fallback?: number): number {
    const found = attribute(element, name);
    if (!found) {
      if (fallback !== undefined) return fallback;
      throw new Error(`${element.name} has no ${name}`);
    }
    const result = this.evaluator.attributeValue(element, found);
    if (!result.ok)
      throw new Error(
        `${element.name} ${name}="${found.value}": ${result.errors[0] ? expressionMessage(result.errors[0]) : 'cannot be evaluated'}`,
      );
    const parsed = typeof result.value === 'number' ? result.value : Number(result.value);
    if (String(result.value).trim() === '' || !Number.isFinite(parsed))
      throw new Error(`${element.name} ${name}="${found.value}" is not a number`);
    return parsed;
  }
}

interface Placed {
  x: number;
  y: number;
  hdg: number;
  described: string;
  road?: RoadCoordinates;
}

function roadOf(network: RoadNetwork | undefined, id: string | undefined): Road {
  if (!network) throw new Error('the road network is not loaded');
  const road = id === undefined ? undefined : network.byId.get(id);
  if (!road) throw new Error(`road ${id ?? '(none)'} is not in the road network`);
  return road;
}

/** Heading from an Orientation child: absolute, or relative to `base` (the default). */
function orientedHeading(reader: Reader, position: XmlElement, base: number): number {
  const orientation = child(position, 'Orientation');
  if (!orientation || attributeValue(orientation, 'h') === undefined) return base;
  const h = reader.number(orientation, 'h', 0);
  return attributeValue(orientation, 'type') === 'absolute' ? h : base + h;
}

function onLane(reader: Reader, position: XmlElement, road: Road, laneId: number, s: number, offset: number, described: string): Placed {
  if (s < 0 || s > road.length + 1e-6) throw new Error(`s ${s} is outside road ${road.id} (length ${road.length})`);
  const sectionIndex = laneSectionIndexAt(road, s);
  if (!laneById(road.laneSections[sectionIndex], laneId)) throw new Error(`road ${road.id} has no lane ${laneId} at s ${s}`);
  const point = roadPoint(road, s, laneCenterT(road, sectionIndex, laneId, s, offset));
  // Left lanes run against the reference line in right-hand traffic.
  const laneHeading = laneId > 0 ? normalizeAngle(point.hdg + Math.PI) : point.hdg;
  return { x: point.x, y: point.y, hdg: orientedHeading(reader, position, laneHeading), described, road: { road, laneId, s, offset } };
}

/** The lane `delta` lanes to the left of `laneId`, skipping the center lane 0 (esmini's GetRelativeLaneId). */
function relativeLaneId(laneId: number, delta: number): number {
  const result = laneId + delta;
  if (laneId === 0 || delta === 0) return result;
  return result === 0 || Math.sign(result) !== Math.sign(laneId) ? result + Math.sign(delta) : result;
}

/** The Route a RouteRef holds or names through a catalog, with a reader for its values (the entry's parameters as the reference assigns them). */
function routeOf(reader: Reader, routeRef: XmlElement, semantics: DocumentSemantics | undefined): { route: XmlElement; reader: Reader } {
  const inline = child(routeRef, 'Route');
  if (inline) return { route: inline, reader };
  const reference = child(routeRef, 'CatalogReference');
  if (!reference) throw new Error('the RouteRef holds no Route or CatalogReference');
  const resolution = semantics ? catalogEntryFor(semantics, reference) : undefined;
  const named = `${attributeValue(reference, 'catalogName') ?? '?'}/${attributeValue(reference, 'entryName') ?? '?'}`;
  if (!semantics || !resolution?.entry) throw new Error(`the route ${named} is not found in the catalogs`);
  if (resolution.entry.element.name !== 'Route')
    throw new Error(`the catalog entry ${named} is a ${resolution.entry.element.name}, not a Route`);
  return {
    route: resolution.entry.element,
    reader: new Reader(new Evaluator(resolution.entry.file.model, assignmentsOf(resolution.reference, semantics.evaluator))),
  };
}

/** A waypoint on a road and the direction the route leaves it in (+1 along the reference line). */
interface RouteStop {
  road: Road;
  s: number;
  direction: 1 | -1;
}

function routeStops(reader: Reader, route: XmlElement, network: RoadNetwork | undefined): RouteStop[] {
  const stops = children(route, 'Waypoint').map((waypoint): RouteStop => {
    const where = path(waypoint, 'Position')?.children[0];
    if (where?.name !== 'LanePosition' && where?.name !== 'RoadPosition')
      throw new Error(
        `a waypoint of route ${attributeValue(route, 'name') ?? ''} is a ${where?.name ?? 'empty Position'}; only LanePosition and RoadPosition waypoints are followed`,
      );
    const road = roadOf(network, reader.text(where, 'roadId'));
    // As esmini's first waypoint (RoadManager.cpp, Route::AddWaypoint, 3.6.0): the route leaves it in the lane's driving direction (right-hand traffic).
    const side = reader.number(where, where.name === 'LanePosition' ? 'laneId' : 't');
    return { road, s: reader.number(where, 's'), direction: side > 0 ? -1 : 1 };
  });
  if (stops.length === 0) throw new Error(`route ${attributeValue(route, 'name') ?? ''} has no waypoints`);
  return stops;
}

/**
 * Road and s at `pathS` along a route. Without routing, only the stretch of the first road(s) is read:
 * from each waypoint along its road to the next waypoint on the same road, or to the road's end; a
 * pathS past a road whose next waypoint is on another road is refused (the roads in between need routing).
 */
function alongRoute(stops: RouteStop[], pathS: number): { road: Road; s: number } {
  if (pathS < 0) throw new Error(`pathS ${pathS} is before the route's start`);
  let start = 0;
  for (let index = 0; index < stops.length; index++) {
    const stop = stops[index];
    const next = stops[index + 1];
    const end = next?.road === stop.road ? next.s : stop.direction > 0 ? stop.road.length : 0;
    const length = Math.abs(end - stop.s);
    if (pathS <= start + length + 1e-9) return { road: stop.road, s: stop.s + stop.direction * (pathS - start) };
    if (next && next.road !== stop.road)
      throw new Error(
        `pathS ${pathS} lies past road ${stop.road.id}, ${start + length} m along the route; the roads between its waypoints need routing, which this view does not do`,
      );
    start += length;
  }
  throw new Error(`pathS ${pathS} is past the route's end (${start} m)`);
}

function onRoute(reader: Reader, kind: XmlElement, network: RoadNetwork | undefined, semantics: DocumentSemantics | undefined): Placed {
  const routeRef = child(kind, 'RouteRef');
  const inRoute = child(kind, 'InRoutePosition')?.children[0];
  if (!routeRef || !inRoute) throw new Error('the RoutePosition needs a RouteRef and an InRoutePosition');
  if (inRoute.name !== 'FromLaneCoordinates' && inRoute.name !== 'FromRoadCoordinates')
    throw new Error(`${inRoute.name} is not evaluated by this view`);
  const route = routeOf(reader, routeRef, semantics);
  const routeName = attributeValue(route.route, 'name') ?? 'route';
  const pathS = reader.number(inRoute, 'pathS');
  const { road, s } = alongRoute(routeStops(route.reader, route.route, network), pathS);
  if (inRoute.name === 'FromLaneCoordinates') {
    const laneId = Math.trunc(reader.number(inRoute, 'laneId'));
    const offset = reader.number(inRoute, 'laneOffset', 0);
    return onLane(
      reader,
      kind,
      road,
      laneId,
      s,
      offset,
      `RoutePosition ${routeName}, pathS ${pathS}, lane ${laneId} (road ${road.id}, s ${s})`,
    );
  }
  // esmini 3.6 reads this t as an integer (ScenarioReader.cpp, strtoi); the standard's double is used here.
  const t = reader.number(inRoute, 't');
  const point = roadPoint(road, s, t);
  return {
    x: point.x,
    y: point.y,
    hdg: orientedHeading(reader, kind, point.hdg),
    described: `RoutePosition ${routeName}, pathS ${pathS}, t ${t} (road ${road.id}, s ${s})`,
  };
}

function evaluatePosition(
  reader: Reader,
  position: XmlElement,
  network: RoadNetwork | undefined,
  placed: Map<string, Placed>,
  semantics: DocumentSemantics | undefined,
): Placed {
  const kind = position.children[0];
  if (!kind) throw new Error('the Position is empty');
  const reference = (): Placed => {
    const name = reader.text(kind, 'entityRef');
    const found = name === undefined ? undefined : placed.get(name);
    if (!found) throw new Error(`${kind.name} refers to ${name ?? '(no entityRef)'}, whose position is not known`);
    return found;
  };
  switch (kind.name) {
    case 'WorldPosition': {
      const x = reader.number(kind, 'x');
      const y = reader.number(kind, 'y');
      return { x, y, hdg: reader.number(kind, 'h', 0), described: `WorldPosition x ${x}, y ${y}` };
    }
    case 'LanePosition': {
      const road = roadOf(network, reader.text(kind, 'roadId'));
      const laneId = Math.trunc(reader.number(kind, 'laneId'));
      const s = reader.number(kind, 's');
      const offset = reader.number(kind, 'offset', 0);
      return onLane(
        reader,
        kind,
        road,
        laneId,
        s,
        offset,
        `LanePosition road ${road.id}, lane ${laneId}, s ${s}${offset ? `, offset ${offset}` : ''}`,
      );
    }
    case 'RoadPosition': {
      const road = roadOf(network, reader.text(kind, 'roadId'));
      const s = reader.number(kind, 's');
      const t = reader.number(kind, 't');
      const point = roadPoint(road, s, t);
      return {
        x: point.x,
        y: point.y,
        hdg: orientedHeading(reader, kind, point.hdg),
        described: `RoadPosition road ${road.id}, s ${s}, t ${t}`,
      };
    }
    case 'RelativeWorldPosition': {
      const base = reference();
      const dx = reader.number(kind, 'dx');
      const dy = reader.number(kind, 'dy');
      return {
        x: base.x + dx,
        y: base.y + dy,
        hdg: orientedHeading(reader, kind, base.hdg),
        described: `RelativeWorldPosition ${reader.text(kind, 'entityRef')} + (${dx}, ${dy})`,
      };
    }
    case 'RelativeObjectPosition': {
      const base = reference();
      const dx = reader.number(kind, 'dx');
      const dy = reader.number(kind, 'dy');
      const cos = Math.cos(base.hdg);
      const sin = Math.sin(base.hdg);
      return {
        x: base.x + dx * cos - dy * sin,
        y: base.y + dx * sin + dy * cos,
        hdg: orientedHeading(reader, kind, base.hdg),
        described: `RelativeObjectPosition ${reader.text(kind, 'entityRef')} + (${dx}, ${dy})`,
      };
    }
    case 'RelativeLanePosition': {
      const base = reference();
      if (!base.road) throw new Error(`RelativeLanePosition needs ${reader.text(kind, 'entityRef')} placed on a lane`);
      const dLane = Math.trunc(reader.number(kind, 'dLane', 0));
      const ds = attributeValue(kind, 'ds') !== undefined ? reader.number(kind, 'ds') : reader.number(kind, 'dsLane', 0);
      const offset = reader.number(kind, 'offset', 0);
      const { road, laneId } = base.road;
      // As esmini (RoadManager.cpp, Position::EvaluateRelation, 3.6.0): dLane, ds and offset count in the lane's driving direction.
      const forward = laneId <= 0;
      const target = relativeLaneId(laneId, forward ? dLane : -dLane);
      const s = base.road.s + (forward ? ds : -ds);
      return onLane(
        reader,
        kind,
        road,
        target,
        s,
        forward ? offset : -offset,
        `RelativeLanePosition ${reader.text(kind, 'entityRef')}, dLane ${dLane}, ds ${ds}`,
      );
    }
    case 'RelativeRoadPosition': {
      const base = reference();
      if (!base.road) throw new Error(`RelativeRoadPosition needs ${reader.text(kind, 'entityRef')} placed on a road`);
      const ds = reader.number(kind, 'ds');
      const dt = reader.number(kind, 'dt');
      const { road, s } = base.road;
      const t = laneCenterT(road, laneSectionIndexAt(road, s), base.road.laneId, s, base.road.offset) + dt;
      const point = roadPoint(road, s + ds, t);
      return {
        x: point.x,
        y: point.y,
        hdg: orientedHeading(reader, kind, point.hdg),
        described: `RelativeRoadPosition ${reader.text(kind, 'entityRef')}, ds ${ds}, dt ${dt}`,
      };
    }
    case 'RoutePosition':
      return onRoute(reader, kind, network, semantics);
    default:
      throw new Error(`${kind.name} is not evaluated by this view`);
  }
}

function triggerText(reader: Reader, event: XmlElement): { trigger: string; plannedTime?: number } {
  const conditions = path(event, 'StartTrigger')?.children.flatMap((group) => children(group, 'Condition')) ?? [];
  if (conditions.length === 0) return { trigger: 'starts with its maneuver' };
  const kindOf = (condition: XmlElement) => {
    const by = condition.children[0];
    return by?.name === 'ByEntityCondition' ? child(by, 'EntityCondition')?.children[0] : by?.children[0];
  };
  const words = conditions.map((condition) => {
    const kind = kindOf(condition);
    if (!kind) return attributeValue(condition, 'name') ?? 'condition';
    const name = kind.name.replace(/Condition$/, '');
    const value = reader.text(kind, 'value');
    const rule = reader.text(kind, 'rule');
    return [name, rule, value].filter(Boolean).join(' ');
  });
  const only = conditions.length === 1 ? kindOf(conditions[0]) : undefined;
  let plannedTime: number | undefined;
  if (only?.name === 'SimulationTimeCondition') {
    try {
      plannedTime = reader.number(only, 'value') + reader.number(conditions[0], 'delay', 0);
    } catch {
      plannedTime = undefined;
    }
  }
  return { trigger: words.join(words.length > 1 ? '; ' : ''), plannedTime };
}

const DEFAULT_BOX: Record<string, { length: number; width: number; centerX: number }> = {
  Vehicle: { length: 4.5, width: 1.8, centerX: 1.4 },
  Pedestrian: { length: 0.5, width: 0.5, centerX: 0 },
  MiscObject: { length: 1, width: 1, centerX: 0 },
};

function entityKind(object: XmlElement): { kind: string; body?: XmlElement } {
  const body = object.children.find((candidate) =>
    ['Vehicle', 'Pedestrian', 'MiscObject', 'CatalogReference', 'ExternalObjectReference'].includes(candidate.name),
  );
  return { kind: body?.name ?? 'Entity', body };
}

/**
 * Entities, where they start, and the storyboard's events. `network` is the loaded road file (if any);
 * `semantics`, the document's analysis with its catalogs resolved, finds routes named through catalogs.
 */
export function scenarioScene(document: XmlDocument, network: RoadNetwork | undefined, semantics?: DocumentSemantics): ScenarioScene {
  const root = document.root;
  const evaluator = semantics?.model.document === document ? semantics.evaluator : new Evaluator(semanticModelOf(document));
  const reader = new Reader(evaluator);
  const scene: ScenarioScene = { logicFile: logicFileOf(document, evaluator), entities: [], events: [] };

  const byName = new Map<string, EntityPlacement>();
  for (const object of children(child(root, 'Entities'), 'ScenarioObject')) {
    const name = attributeValue(object, 'name') ?? '';
    const { kind, body } = entityKind(object);
    const dimensions = path(body, 'BoundingBox', 'Dimensions');
    const center = path(body, 'BoundingBox', 'Center');
    const box = DEFAULT_BOX[kind] ?? DEFAULT_BOX.Vehicle;
    const measure = (element: XmlElement | undefined, attribute: string, fallback: number) => {
      try {
        return element ? reader.number(element, attribute, fallback) : fallback;
      } catch {
        return fallback;
      }
    };
    const entity: EntityPlacement = {
      name,
      kind: kind === 'CatalogReference' ? `${attributeValue(body!, 'entryName') ?? 'catalog entry'} (catalog)` : kind,
      length: measure(dimensions, 'length', box.length),
      width: measure(dimensions, 'width', box.width),
      centerX: measure(center, 'x', box.centerX),
      described: 'no TeleportAction in Init',
      declaration: object,
    };
    scene.entities.push(entity);
    byName.set(name, entity);
  }

  // Init placements in document order, so that relative positions find the entity they refer to.
  const placed = new Map<string, Placed>();
  for (const privateElement of children(path(root, 'Storyboard', 'Init', 'Actions'), 'Private')) {
    const entity = byName.get(reader.text(privateElement, 'entityRef') ?? '');
    if (!entity) continue;
    for (const action of children(privateElement, 'PrivateAction')) {
      const position = path(action, 'TeleportAction', 'Position');
      if (!position) continue;
      entity.position = position;
      try {
        const where = evaluatePosition(reader, position, network, placed, semantics);
        placed.set(entity.name, where);
        Object.assign(entity, { x: where.x, y: where.y, hdg: where.hdg, described: where.described, problem: undefined });
      } catch (error) {
        entity.described = position.children[0]?.name ?? 'Position';
        entity.problem = (error as Error).message;
      }
    }
  }

  for (const story of children(path(root, 'Storyboard'), 'Story')) {
    for (const act of children(story, 'Act')) {
      for (const group of children(act, 'ManeuverGroup')) {
        const actors = children(path(group, 'Actors'), 'EntityRef')
          .map((ref) => reader.text(ref, 'entityRef'))
          .filter((name): name is string => name !== undefined && name !== '');
        for (const maneuver of children(group, 'Maneuver')) {
          for (const event of children(maneuver, 'Event')) {
            scene.events.push({
              name: attributeValue(event, 'name') ?? '',
              maneuver: attributeValue(maneuver, 'name') ?? '',
              group: attributeValue(group, 'name') ?? '',
              act: attributeValue(act, 'name') ?? '',
              ...triggerText(reader, event),
              actors,
              element: event,
              groupElement: group,
            });
          }
        }
      }
    }
  }
  return scene;
}

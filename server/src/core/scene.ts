/**
 * What a bird's-eye view shows of a scenario before it runs: its road file, where each entity
 * starts (the Init's TeleportActions evaluated against the road), and the storyboard's events.
 */
import { laneById, laneCenterT, laneSectionIndexAt, Road, RoadNetwork, roadPoint } from './opendrive/road';
import { normalizeAngle } from './opendrive/geometry';
import { attributeValue, XmlDocument, XmlElement } from './xml';

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
  element: XmlElement;
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

/**
 * The arithmetic of an OpenSCENARIO expression `${...}` (numbers, `$name`, + - * / %, unary minus,
 * parentheses): enough to place entities; anything else throws. The project's full expression
 * evaluator can take its place.
 */
export function evaluateArithmetic(expression: string, parameters: Map<string, string>): number {
  const tokens = expression.match(/\s*((?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?|\$[A-Za-z_][\w]*|[-+*\/%()])/gy);
  if (!tokens || tokens.join('').replace(/\s/g, '') !== expression.replace(/\s/g, '')) throw new Error(`cannot evaluate \${${expression}}`);
  const list = tokens.map((token) => token.trim());
  let index = 0;
  const primary = (): number => {
    const token = list[index++];
    if (token === '-') return -primary();
    if (token === '+') return primary();
    if (token === '(') {
      const value = sum();
      if (list[index++] !== ')') throw new Error(`unbalanced parentheses in \${${expression}}`);
      return value;
    }
    if (token?.startsWith('$')) {
      const value = Number(parameters.get(token.slice(1)));
      if (!Number.isFinite(value)) throw new Error(`${token} has no numeric value`);
      return value;
    }
    const value = Number(token);
    if (token === undefined || !Number.isFinite(value)) throw new Error(`cannot evaluate \${${expression}}`);
    return value;
  };
  const product = (): number => {
    let value = primary();
    while (list[index] === '*' || list[index] === '/' || list[index] === '%') {
      const operator = list[index++];
      const right = primary();
      value = operator === '*' ? value * right : operator === '/' ? value / right : value % right;
    }
    return value;
  };
  const sum = (): number => {
    let value = product();
    while (list[index] === '+' || list[index] === '-') value = list[index++] === '+' ? value + product() : value - product();
    return value;
  };
  const result = sum();
  if (index !== list.length) throw new Error(`cannot evaluate \${${expression}}`);
  return result;
}

/** A raw value with a `$name` or `${...}` resolved against `parameters` (unresolvable ones left as written). */
function resolveValue(raw: string, parameters: Map<string, string>): string {
  if (raw.startsWith('${') && raw.endsWith('}')) {
    try {
      return String(evaluateArithmetic(raw.slice(2, -1), parameters));
    } catch {
      return raw;
    }
  }
  return raw.startsWith('$') ? parameters.get(raw.slice(1)) ?? raw : raw;
}

/** The values of the root ParameterDeclarations, each `$name` or `${...}` in a value resolved by earlier ones. */
export function rootParameters(document: XmlDocument): Map<string, string> {
  const values = new Map<string, string>();
  for (const declaration of children(child(document.root, 'ParameterDeclarations'), 'ParameterDeclaration')) {
    const name = attributeValue(declaration, 'name');
    const value = attributeValue(declaration, 'value');
    if (!name || value === undefined) continue;
    values.set(name, resolveValue(value, values));
  }
  return values;
}

class Reader {
  constructor(private readonly parameters: Map<string, string>) {}

  text(element: XmlElement, name: string): string | undefined {
    const raw = attributeValue(element, name);
    return raw === undefined ? undefined : resolveValue(raw, this.parameters);
  }

  /** A numeric attribute; throws a message naming the attribute when it is missing or unresolvable. */
  number(element: XmlElement, name: string, fallback?: number): number {
    const value = this.text(element, name);
    if (value === undefined) {
      if (fallback !== undefined) return fallback;
      throw new Error(`${element.name} has no ${name}`);
    }
    const parsed = Number(value);
    if (value.trim() === '' || !Number.isFinite(parsed)) throw new Error(`${element.name} ${name}="${attributeValue(element, name)}" is not a number this view can evaluate`);
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

function evaluatePosition(reader: Reader, position: XmlElement, network: RoadNetwork | undefined, placed: Map<string, Placed>): Placed {
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
      return onLane(reader, kind, road, laneId, s, offset, `LanePosition road ${road.id}, lane ${laneId}, s ${s}${offset ? `, offset ${offset}` : ''}`);
    }
    case 'RoadPosition': {
      const road = roadOf(network, reader.text(kind, 'roadId'));
      const s = reader.number(kind, 's');
      const t = reader.number(kind, 't');
      const point = roadPoint(road, s, t);
      return { x: point.x, y: point.y, hdg: orientedHeading(reader, kind, point.hdg), described: `RoadPosition road ${road.id}, s ${s}, t ${t}` };
    }
    case 'RelativeWorldPosition': {
      const base = reference();
      const dx = reader.number(kind, 'dx');
      const dy = reader.number(kind, 'dy');
      return { x: base.x + dx, y: base.y + dy, hdg: orientedHeading(reader, kind, base.hdg), described: `RelativeWorldPosition ${reader.text(kind, 'entityRef')} + (${dx}, ${dy})` };
    }
    case 'RelativeObjectPosition': {
      const base = reference();
      const dx = reader.number(kind, 'dx');
      const dy = reader.number(kind, 'dy');
      const cos = Math.cos(base.hdg);
      const sin = Math.sin(base.hdg);
      return { x: base.x + dx * cos - dy * sin, y: base.y + dx * sin + dy * cos, hdg: orientedHeading(reader, kind, base.hdg), described: `RelativeObjectPosition ${reader.text(kind, 'entityRef')} + (${dx}, ${dy})` };
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
      return onLane(reader, kind, road, target, s, forward ? offset : -offset, `RelativeLanePosition ${reader.text(kind, 'entityRef')}, dLane ${dLane}, ds ${ds}`);
    }
    case 'RelativeRoadPosition': {
      const base = reference();
      if (!base.road) throw new Error(`RelativeRoadPosition needs ${reader.text(kind, 'entityRef')} placed on a road`);
      const ds = reader.number(kind, 'ds');
      const dt = reader.number(kind, 'dt');
      const { road, s } = base.road;
      const t = laneCenterT(road, laneSectionIndexAt(road, s), base.road.laneId, s, base.road.offset) + dt;
      const point = roadPoint(road, s + ds, t);
      return { x: point.x, y: point.y, hdg: orientedHeading(reader, kind, point.hdg), described: `RelativeRoadPosition ${reader.text(kind, 'entityRef')}, ds ${ds}, dt ${dt}` };
    }
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
  const body = object.children.find((candidate) => ['Vehicle', 'Pedestrian', 'MiscObject', 'CatalogReference', 'ExternalObjectReference'].includes(candidate.name));
  return { kind: body?.name ?? 'Entity', body };
}

/** Entities, where they start, and the storyboard's events. `network` is the loaded road file (if any). */
export function scenarioScene(document: XmlDocument, network: RoadNetwork | undefined): ScenarioScene {
  const root = document.root;
  const reader = new Reader(rootParameters(document));
  const logic = path(root, 'RoadNetwork', 'LogicFile');
  const filepath = logic ? reader.text(logic, 'filepath') : undefined;
  const scene: ScenarioScene = { logicFile: logic && filepath ? { filepath, element: logic } : undefined, entities: [], events: [] };

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
        const where = evaluatePosition(reader, position, network, placed);
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
        for (const maneuver of children(group, 'Maneuver')) {
          for (const event of children(maneuver, 'Event')) {
            scene.events.push({
              name: attributeValue(event, 'name') ?? '',
              maneuver: attributeValue(maneuver, 'name') ?? '',
              group: attributeValue(group, 'name') ?? '',
              act: attributeValue(act, 'name') ?? '',
              ...triggerText(reader, event),
              element: event,
            });
          }
        }
      }
    }
  }
  return scene;
}

import { attributeValue, endTagStart, parseXml, XmlElement } from '../xml';
import { evaluateGeometry, Geometry, Pose } from './geometry';

/** A cubic a + b·ds + c·ds² + d·ds³ that starts at `start` (s of the road, or sOffset in a lane section). */
export interface Cubic {
  start: number;
  a: number;
  b: number;
  c: number;
  d: number;
}

export interface Lane {
  id: number;
  type: string;
  /** `width` entries sorted by sOffset (relative to the lane section's s). */
  widths: Cubic[];
  /** `border` entries (outer border measured from the center lane), used when a lane has no widths. */
  borders: Cubic[];
  /** Offsets of the `<lane>` element in the file, for messages. */
  start: number;
  /** The lane ids its `<link>` names in the section (or road) before and after; undefined when it names none. */
  predecessor?: number;
  successor?: number;
}

export interface LaneSection {
  s: number;
  /** Up to the next section, or the road's end. */
  length: number;
  /** Lanes ordered as esmini and viewers list them: left lanes from the outside in, the center lane, right lanes from the inside out. */
  lanes: Lane[];
}

/** A road's `<link><predecessor|successor>`: the road or junction at that end. */
export interface RoadLink {
  elementType: 'road' | 'junction';
  elementId: string;
  /** Which end of the linked road touches this one (road links only). */
  contactPoint?: 'start' | 'end';
}

/** A junction's `<connection>`: from the incoming road into the connecting road, entered at `contactPoint`. */
export interface JunctionConnection {
  incomingRoad: string;
  connectingRoad: string;
  contactPoint: 'start' | 'end';
  /** [incoming lane, connecting lane] pairs. */
  laneLinks: [number, number][];
}

export interface Junction {
  id: string;
  /** `default` or `direct` (OpenDRIVE 1.7 `type`). */
  type: string;
  connections: JunctionConnection[];
}

export interface Road {
  id: string;
  name: string;
  length: number;
  junction: string;
  /** Left-hand traffic (`rule="LHT"`): its positive lanes are driven along s; otherwise its negative ones. */
  leftHandTraffic: boolean;
  geometries: Geometry[];
  laneOffsets: Cubic[];
  superelevations: Cubic[];
  laneSections: LaneSection[];
  predecessor?: RoadLink;
  successor?: RoadLink;
}

export interface RoadNetwork {
  roads: Road[];
  byId: Map<string, Road>;
  junctions: Map<string, Junction>;
  /** The `<header><geoReference>` text (a PROJ string), trimmed; undefined when the file has none. */
  geoReference?: string;
  /** The `<header><offset>` (OpenDRIVE 1.6: projected coordinates shifted and turned) as written, when it is not all zero. */
  geoOffset?: string;
  /** What could not be read, with the offset of the element. */
  problems: { message: string; offset: number }[];
  /** Every signal id the file declares (a road's `<signal id>`, a `<controller>`'s `<control signalId>`): what a TrafficSignalStateAction names. */
  signalIds: Set<string>;
}

/** A road file larger than this is refused rather than read (Town05 is 3 MB): by the bird's-eye view and the road-network rules alike. */
export const MAX_ROAD_FILE_BYTES = 64 * 1024 * 1024;

/** Lane types that vehicles drive on: esmini's LANE_TYPE_ANY_DRIVING (RoadManager.hpp, esmini 3.6.0). */
const DRIVING_TYPES = new Set(['driving', 'entry', 'exit', 'offRamp', 'onRamp', 'bidirectional', 'slipLane', 'connectingRamp']);

export function isDrivingLane(lane: Lane): boolean {
  return lane.id !== 0 && DRIVING_TYPES.has(lane.type);
}

function numberOf(element: XmlElement, name: string, fallback = 0): number {
  const value = attributeValue(element, name);
  if (value === undefined || value.trim() === '') return fallback;
  const parsed = Number(value);
  return Number.isFinite(parsed) ? parsed : fallback;
}

function cubicOf(element: XmlElement, startAttribute: string): Cubic {
  return {
    start: numberOf(element, startAttribute),
    a: numberOf(element, 'a'),
    b: numberOf(element, 'b'),
    c: numberOf(element, 'c'),
    d: numberOf(element, 'd'),
  };
}

function childrenNamed(element: XmlElement | undefined, name: string): XmlElement[] {
  return element ? element.children.filter((child) => child.name === name) : [];
}

function geometryOf(element: XmlElement): Geometry | undefined {
  const start = {
    s: numberOf(element, 's'),
    x: numberOf(element, 'x'),
    y: numberOf(element, 'y'),
    hdg: numberOf(element, 'hdg'),
    length: numberOf(element, 'length'),
  };
  const shape = element.children[0];
  if (!shape) return undefined;
  switch (shape.name) {
    case 'line':
      return { ...start, kind: 'line' };
    case 'arc':
      return { ...start, kind: 'arc', curvature: numberOf(shape, 'curvature') };
    case 'spiral':
      return { ...start, kind: 'spiral', curvStart: numberOf(shape, 'curvStart'), curvEnd: numberOf(shape, 'curvEnd') };
    case 'poly3':
      return {
        ...start,
        kind: 'poly3',
        a: numberOf(shape, 'a'),
        b: numberOf(shape, 'b'),
        c: numberOf(shape, 'c'),
        d: numberOf(shape, 'd'),
      };
    case 'paramPoly3':
      return {
        ...start,
        kind: 'paramPoly3',
        aU: numberOf(shape, 'aU'),
        bU: numberOf(shape, 'bU'),
        cU: numberOf(shape, 'cU'),
        dU: numberOf(shape, 'dU'),
        aV: numberOf(shape, 'aV'),
        bV: numberOf(shape, 'bV'),
        cV: numberOf(shape, 'cV'),
        dV: numberOf(shape, 'dV'),
        pRange: attributeValue(shape, 'pRange') === 'normalized' ? 'normalized' : 'arcLength',
      };
    default:
      return undefined;
  }
}

function laneOf(element: XmlElement): Lane {
  const bySOffset = (a: Cubic, b: Cubic) => a.start - b.start;
  return {
    id: Math.trunc(numberOf(element, 'id')),
    type: attributeValue(element, 'type') ?? 'none',
    widths: childrenNamed(element, 'width')
      .map((width) => cubicOf(width, 'sOffset'))
      .sort(bySOffset),
    borders: childrenNamed(element, 'border')
      .map((border) => cubicOf(border, 'sOffset'))
      .sort(bySOffset),
    start: element.start,
    ...laneLinksOf(childrenNamed(element, 'link')[0]),
  };
}

function laneLinksOf(link: XmlElement | undefined): { predecessor?: number; successor?: number } {
  const idOf = (name: string): number | undefined => {
    const target = childrenNamed(link, name)[0];
    const value = target ? Number(attributeValue(target, 'id')) : NaN;
    return Number.isInteger(value) ? value : undefined;
  };
  return { predecessor: idOf('predecessor'), successor: idOf('successor') };
}

function roadLinkOf(link: XmlElement | undefined, name: string): RoadLink | undefined {
  const target = childrenNamed(link, name)[0];
  const elementId = target ? attributeValue(target, 'elementId') : undefined;
  if (!target || elementId === undefined) return undefined;
  const contactPoint = attributeValue(target, 'contactPoint');
  return {
    elementType: attributeValue(target, 'elementType') === 'junction' ? 'junction' : 'road',
    elementId,
    contactPoint: contactPoint === 'start' || contactPoint === 'end' ? contactPoint : undefined,
  };
}

function junctionOf(element: XmlElement): Junction {
  return {
    id: attributeValue(element, 'id') ?? '',
    type: attributeValue(element, 'type') ?? 'default',
    connections: childrenNamed(element, 'connection').map((connection) => ({
      incomingRoad: attributeValue(connection, 'incomingRoad') ?? '',
      connectingRoad: attributeValue(connection, 'connectingRoad') ?? '',
      contactPoint: attributeValue(connection, 'contactPoint') === 'end' ? 'end' : 'start',
      laneLinks: childrenNamed(connection, 'laneLink').map((laneLink): [number, number] => [
        Math.trunc(numberOf(laneLink, 'from')),
        Math.trunc(numberOf(laneLink, 'to')),
      ]),
    })),
  };
}

function roadOf(element: XmlElement, problems: RoadNetwork['problems']): Road {
  const id = attributeValue(element, 'id') ?? '';
  const length = numberOf(element, 'length');
  const planView = childrenNamed(element, 'planView')[0];
  const geometries: Geometry[] = [];
  for (const geometryElement of childrenNamed(planView, 'geometry')) {
    const geometry = geometryOf(geometryElement);
    if (geometry) geometries.push(geometry);
    else
      problems.push({
        message: `road ${id}: unsupported geometry <${geometryElement.children[0]?.name ?? '(empty)'}>`,
        offset: geometryElement.start,
      });
  }
  geometries.sort((a, b) => a.s - b.s);
  const lanesElement = childrenNamed(element, 'lanes')[0];
  const lateral = childrenNamed(element, 'lateralProfile')[0];
  const sections = childrenNamed(lanesElement, 'laneSection').map((section) => {
    const lanes: Lane[] = [];
    for (const side of ['left', 'center', 'right']) {
      const sideLanes = childrenNamed(childrenNamed(section, side)[0], 'lane').map(laneOf);
      lanes.push(...sideLanes.sort((a, b) => b.id - a.id));
    }
    return { s: numberOf(section, 's'), length: 0, lanes };
  });
  sections.sort((a, b) => a.s - b.s);
  sections.forEach((section, index) => (section.length = (index + 1 < sections.length ? sections[index + 1].s : length) - section.s));
  const link = childrenNamed(element, 'link')[0];
  return {
    id,
    name: attributeValue(element, 'name') ?? '',
    length,
    junction: attributeValue(element, 'junction') ?? '-1',
    leftHandTraffic: isLeftHandTraffic(element),
    geometries,
    laneOffsets: childrenNamed(lanesElement, 'laneOffset')
      .map((offset) => cubicOf(offset, 's'))
      .sort((a, b) => a.start - b.start),
    superelevations: childrenNamed(lateral, 'superelevation')
      .map((entry) => cubicOf(entry, 's'))
      .sort((a, b) => a.start - b.start),
    laneSections: sections,
    predecessor: roadLinkOf(link, 'predecessor'),
    successor: roadLinkOf(link, 'successor'),
  };
}

/** An element's text content, a CDATA section unwrapped and trimmed; undefined when empty or when it holds elements. */
function textOf(text: string, element: XmlElement): string | undefined {
  if (element.selfClosing || !element.closed || element.children.length > 0) return undefined;
  const inner = text.slice(element.startTagEnd, endTagStart(text, element)).trim();
  const cdata = /^<!\[CDATA\[([\s\S]*)\]\]>$/.exec(inner);
  return (cdata ? cdata[1] : inner).trim() || undefined;
}

/** Every signal id an OpenDRIVE root declares (RoadNetwork.signalIds). */
function signalIdsOf(root: XmlElement | undefined): Set<string> {
  const signalIds = new Set<string>();
  for (const road of childrenNamed(root, 'road'))
    for (const signal of childrenNamed(childrenNamed(road, 'signals')[0], 'signal')) signalIds.add(attributeValue(signal, 'id') ?? '');
  for (const controller of childrenNamed(root, 'controller'))
    for (const control of childrenNamed(controller, 'control')) signalIds.add(attributeValue(control, 'signalId') ?? '');
  signalIds.delete('');
  return signalIds;
}

/** What `openDriveSignals` reads of a road file: whether it is an OpenDRIVE file with roads, its signal ids and its roads of left-hand traffic. */
export interface OpenDriveSignals {
  hasRoads: boolean;
  signalIds: Set<string>;
  /** The ids of the roads of left-hand traffic (`rule="LHT"`). */
  leftHandRoads: Set<string>;
}

/**
 * What parseOpenDrive gives of a file's signals and traffic rules, without reading its roads' geometry and lanes (half its
 * time on esmini's Town05.xodr).
 */
export function openDriveSignals(text: string): OpenDriveSignals {
  const root = parseXml(text).root;
  const roads = root?.name === 'OpenDRIVE' ? childrenNamed(root, 'road') : [];
  return {
    hasRoads: roads.length > 0,
    signalIds: signalIdsOf(root),
    leftHandRoads: new Set(roads.filter(isLeftHandTraffic).map((road) => attributeValue(road, 'id') ?? '')),
  };
}

/** Whether a road element is of left-hand traffic (`rule="LHT"`, OpenDRIVE 1.5; right-hand where it is not given). */
function isLeftHandTraffic(road: XmlElement): boolean {
  return attributeValue(road, 'rule') === 'LHT';
}

/** Reads an OpenDRIVE file's roads. Problems are collected, never thrown: a partial network still draws. */
export function parseOpenDrive(text: string): RoadNetwork {
  const document = parseXml(text);
  const problems: RoadNetwork['problems'] = document.problems
    .filter((problem) => problem.severity === 'error')
    .slice(0, 20)
    .map((problem) => ({ message: problem.message, offset: problem.start }));
  const roads: Road[] = [];
  if (document.root?.name !== 'OpenDRIVE')
    problems.push({ message: 'not an OpenDRIVE file: the root element is not <OpenDRIVE>', offset: document.root?.start ?? 0 });
  else for (const element of childrenNamed(document.root, 'road')) roads.push(roadOf(element, problems));
  const signalIds = signalIdsOf(document.root);
  const junctions = new Map(
    childrenNamed(document.root, 'junction').map((element) => [attributeValue(element, 'id') ?? '', junctionOf(element)]),
  );
  const header = childrenNamed(document.root, 'header')[0];
  const geoReference = childrenNamed(header, 'geoReference')[0];
  const offset = childrenNamed(header, 'offset')[0];
  const offsetTerms = offset ? ['x', 'y', 'z', 'hdg'].filter((name) => numberOf(offset, name) !== 0) : [];
  return {
    roads,
    byId: new Map(roads.map((road) => [road.id, road])),
    junctions,
    geoReference: geoReference ? textOf(text, geoReference) : undefined,
    geoOffset: offset && offsetTerms.length > 0 ? offsetTerms.map((name) => `${name} ${numberOf(offset, name)}`).join(', ') : undefined,
    problems,
    signalIds,
  };
}

/** The entry of a sorted list that applies at `s`: the last one starting at or before it (the first before all). */
function entryAt<T extends { start: number }>(entries: T[], s: number): T | undefined {
  if (entries.length === 0) return undefined;
  let low = 0;
  let high = entries.length - 1;
  while (low < high) {
    const middle = (low + high + 1) >> 1;
    if (entries[middle].start <= s) low = middle;
    else high = middle - 1;
  }
  return entries[low];
}

function evaluateCubic(cubic: Cubic | undefined, ds: number): number {
  return cubic ? cubic.a + ds * (cubic.b + ds * (cubic.c + ds * cubic.d)) : 0;
}

/** Whether a lane is driven towards growing s: by its side and the road's traffic rule (right-hand traffic: the negative lanes). */
export function drivesAlongS(road: Road, laneId: number): boolean {
  return road.leftHandTraffic ? laneId > 0 : laneId < 0;
}

/** The value at road s of a road-level cubic list (laneOffset, superelevation). */
export function roadCubicAt(entries: Cubic[], s: number): number {
  const entry = entryAt(entries, s);
  return entry ? evaluateCubic(entry, s - entry.start) : 0;
}

export function geometryIndexAt(road: Road, s: number): number {
  const geometries = road.geometries;
  let low = 0;
  let high = geometries.length - 1;
  while (low < high) {
    const middle = (low + high + 1) >> 1;
    if (geometries[middle].s <= s) low = middle;
    else high = middle - 1;
  }
  return low;
}

/** The reference line's pose at road s (clamped to the road). */
export function referencePose(road: Road, s: number): Pose {
  if (road.geometries.length === 0) return { x: 0, y: 0, hdg: 0 };
  const geometry = road.geometries[geometryIndexAt(road, s)];
  const ds = Math.min(Math.max(s - geometry.s, 0), geometry.length);
  return evaluateGeometry(geometry, ds);
}

export function laneSectionIndexAt(road: Road, s: number): number {
  const sections = road.laneSections;
  let index = 0;
  while (index + 1 < sections.length && sections[index + 1].s <= s) index++;
  return index;
}

export function laneById(section: LaneSection, id: number): Lane | undefined {
  return section.lanes.find((lane) => lane.id === id);
}

/** A lane's width at road s (s clamped into its section). */
export function laneWidth(section: LaneSection, lane: Lane, s: number): number {
  if (lane.id === 0) return 0;
  const ds = Math.min(Math.max(s - section.s, 0), section.length);
  const width = entryAt(lane.widths, ds);
  return width ? evaluateCubic(width, ds - width.start) : 0;
}

/**
 * The lateral distance of a lane's outer border from the lane-offset line, positive to the left:
 * the sum of the widths from the center out to this lane (or the lane's `border` record).
 */
export function outerBorderT(section: LaneSection, laneId: number, s: number): number {
  if (laneId === 0) return 0;
  const sign = laneId > 0 ? 1 : -1;
  const ds = Math.min(Math.max(s - section.s, 0), section.length);
  let total = 0;
  for (let id = sign; id !== laneId + sign; id += sign) {
    const lane = laneById(section, id);
    if (!lane) continue;
    if (lane.widths.length === 0 && lane.borders.length > 0) {
      const border = entryAt(lane.borders, ds);
      total = Math.abs(evaluateCubic(border, ds - (border?.start ?? 0)));
      continue;
    }
    total += laneWidth(section, lane, s);
  }
  return sign * total;
}

/** The outer border offsets of all lanes of a section at s, in the section's lane order, in one pass outward from the center. */
export function outerBorderTs(section: LaneSection, s: number, into: Float64Array): Float64Array {
  const lanes = section.lanes;
  const center = lanes.findIndex((lane) => lane.id === 0);
  if (center < 0 || lanes.some((lane) => lane.borders.length > 0)) {
    lanes.forEach((lane, index) => (into[index] = outerBorderT(section, lane.id, s)));
    return into;
  }
  into[center] = 0;
  let total = 0;
  for (let index = center + 1; index < lanes.length; index++) into[index] = -(total += laneWidth(section, lanes[index], s));
  total = 0;
  for (let index = center - 1; index >= 0; index--) into[index] = total += laneWidth(section, lanes[index], s);
  return into;
}

/** The point at lateral t beside a reference-line pose, with the road's roll at that s. */
export function besidePose(pose: Pose, roll: number, t: number): Pose {
  const lateral = roll === 0 ? t : t * Math.cos(roll);
  return { x: pose.x - lateral * Math.sin(pose.hdg), y: pose.y + lateral * Math.cos(pose.hdg), hdg: pose.hdg };
}

/**
 * The point at road s and lateral t (from the reference line, positive to the left). Superelevation
 * tilts the road about the reference line, so t projects onto the ground plane as t·cos(roll).
 */
export function roadPoint(road: Road, s: number, t: number): Pose {
  return besidePose(referencePose(road, s), roadCubicAt(road.superelevations, s), t);
}

/** The lateral position of a lane's center (or, with `offset`, beside it) at road s. */
export function laneCenterT(road: Road, sectionIndex: number, laneId: number, s: number, offset = 0): number {
  const section = road.laneSections[sectionIndex];
  if (!section || laneId === 0) return roadCubicAt(road.laneOffsets, s) + offset;
  const lane = laneById(section, laneId);
  const width = lane ? laneWidth(section, lane, s) : 0;
  const outer = outerBorderT(section, laneId, s);
  return roadCubicAt(road.laneOffsets, s) + outer - (Math.sign(laneId) * width) / 2 + offset;
}

/** The point on a lane's outer border (lane 0: the lane-offset line) at road s. */
export function laneBorderPoint(road: Road, sectionIndex: number, laneId: number, s: number): Pose {
  const section = road.laneSections[sectionIndex];
  const t = roadCubicAt(road.laneOffsets, s) + (section ? outerBorderT(section, laneId, s) : 0);
  return roadPoint(road, s, t);
}

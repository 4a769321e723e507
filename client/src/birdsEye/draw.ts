/**
 * Drawing of the bird's-eye view, independent of where it goes: a canvas in the webview, or an
 * SVG document when the picture is saved. No DOM here, so that it runs (and is tested) in Node too.
 */
import type { SceneEntity, SceneResult } from '../../../common/src/sceneProtocol';
import { type Bounds, type LabelRequest, type PlacedLabel, placeLabels } from './labels';
import type { RunTracks } from './messages';

/** The few drawing operations the view needs, in screen coordinates. */
export interface Painter {
  polygon(xy: ArrayLike<number>, fill: string): void;
  polyline(xy: ArrayLike<number>, stroke: string, width: number, dash?: number[]): void;
  text(x: number, y: number, text: string, color: string, size: number): void;
  /** Limits what follows to a rectangle until `unclip` (the panes of runs side by side). */
  clip?(x: number, y: number, width: number, height: number): void;
  unclip?(): void;
}

/** A painter that draws `dx` pixels to the right: a pane's drawing in its place on a picture. */
export function shiftedPainter(painter: Painter, dx: number): Painter {
  const shift = (xy: ArrayLike<number>) => {
    const out = Array.from(xy);
    for (let i = 0; i < out.length; i += 2) out[i] += dx;
    return out;
  };
  return {
    polygon: (xy, fill) => painter.polygon(shift(xy), fill),
    polyline: (xy, stroke, width, dash) => painter.polyline(shift(xy), stroke, width, dash),
    text: (x, y, text, color, size) => painter.text(x + dx, y, text, color, size),
    clip: (x, y, width, height) => painter.clip?.(x + dx, y, width, height),
    unclip: () => painter.unclip?.(),
  };
}

/** World (metres, y up) to screen (pixels, y down). */
export interface ViewTransform {
  scale: number;
  /** World point shown at the screen's origin. */
  left: number;
  top: number;
}

export const COLORS = {
  background: '#2f3b2f',
  driving: '#55595e',
  other: '#8d8a7a',
  junction: '#5f6368',
  border: '#d8d8d8',
  center: '#e8c547',
  label: '#ffffff',
};

/** One color per entity, in order; distinguishable on the grey road. */
export const ENTITY_COLORS = ['#4fc3f7', '#ff7043', '#ba68c8', '#9ccc65', '#ffca28', '#f06292', '#4db6ac', '#e0e0e0'];

/** A lane's area in world coordinates: its inner border then its outer border reversed. */
export interface LaneShape {
  road: string;
  section: number;
  lane: number;
  type: string;
  driving: boolean;
  junction: boolean;
  polygon: Float64Array;
  /** Bounding box: minX, minY, maxX, maxY. */
  box: [number, number, number, number];
}

export interface RoadShapes {
  lanes: LaneShape[];
  borders: { xy: number[]; center: boolean }[];
  bounds: [number, number, number, number] | undefined;
}

function extend(bounds: [number, number, number, number] | undefined, xy: ArrayLike<number>): [number, number, number, number] | undefined {
  let result = bounds;
  for (let i = 0; i + 1 < xy.length; i += 2) {
    const x = xy[i];
    const y = xy[i + 1];
    if (!result) result = [x, y, x, y];
    else {
      if (x < result[0]) result[0] = x;
      if (y < result[1]) result[1] = y;
      if (x > result[2]) result[2] = x;
      if (y > result[3]) result[3] = y;
    }
  }
  return result;
}

/** Lane areas between neighbouring borders of each lane section. */
export function roadShapes(scene: SceneResult): RoadShapes {
  const lanes: LaneShape[] = [];
  const borders: RoadShapes['borders'] = [];
  let bounds: RoadShapes['bounds'];
  for (const section of scene.sections) {
    section.lanes.forEach((lane, index) => {
      const outer = section.borders[index];
      borders.push({ xy: outer, center: lane.id === 0 });
      bounds = extend(bounds, outer);
      if (lane.id === 0) return;
      const inner = lane.id > 0 ? section.borders[index + 1] : section.borders[index - 1];
      if (!inner || !outer) return;
      const polygon = new Float64Array(inner.length + outer.length);
      polygon.set(inner, 0);
      for (let i = outer.length - 2, j = inner.length; i >= 0; i -= 2, j += 2) {
        polygon[j] = outer[i];
        polygon[j + 1] = outer[i + 1];
      }
      lanes.push({
        road: section.road,
        section: section.section,
        lane: lane.id,
        type: lane.type,
        driving: lane.driving,
        junction: section.junction,
        polygon,
        box: extend(undefined, polygon)!,
      });
    });
  }
  return { lanes, borders, bounds };
}

/**
 * What the picture frames: with `focus`, where the entities start and drive (with `margin` metres
 * around, the roads clipped to it), else everything including the whole road network.
 */
export function sceneBounds(
  shapes: RoadShapes,
  scene: SceneResult | undefined,
  run: RunTracks | undefined,
  focus = false,
  margin = 40,
): [number, number, number, number] {
  let bounds = shapes.bounds && !focus ? ([...shapes.bounds] as [number, number, number, number]) : undefined;
  for (const entity of scene?.entities ?? [])
    if (entity.x !== undefined && entity.y !== undefined) bounds = extend(bounds, [entity.x - 3, entity.y - 3, entity.x + 3, entity.y + 3]);
  for (const track of run?.entities ?? []) {
    const xy: number[] = [];
    for (let i = 0; i < track.x.length; i += Math.max(1, Math.floor(track.x.length / 200))) xy.push(track.x[i], track.y[i]);
    bounds = extend(bounds, xy);
  }
  if (focus && bounds) return [bounds[0] - margin, bounds[1] - margin, bounds[2] + margin, bounds[3] + margin];
  return bounds ?? shapes.bounds ?? [-50, -50, 50, 50];
}

/** A transform that shows `bounds` whole, centred, in a `width` × `height` screen with a margin. */
export function fitTransform(bounds: [number, number, number, number], width: number, height: number, margin = 20): ViewTransform {
  const spanX = Math.max(bounds[2] - bounds[0], 1);
  const spanY = Math.max(bounds[3] - bounds[1], 1);
  const scale = Math.min((width - 2 * margin) / spanX, (height - 2 * margin) / spanY);
  const centerX = (bounds[0] + bounds[2]) / 2;
  const centerY = (bounds[1] + bounds[3]) / 2;
  return { scale, left: centerX - width / 2 / scale, top: centerY + height / 2 / scale };
}

export function toScreen(view: ViewTransform, x: number, y: number): [number, number] {
  return [(x - view.left) * view.scale, (view.top - y) * view.scale];
}

export function toWorld(view: ViewTransform, sx: number, sy: number): [number, number] {
  return [view.left + sx / view.scale, view.top - sy / view.scale];
}

function project(view: ViewTransform, xy: ArrayLike<number>): Float64Array {
  const out = new Float64Array(xy.length);
  for (let i = 0; i + 1 < xy.length; i += 2) {
    out[i] = (xy[i] - view.left) * view.scale;
    out[i + 1] = (view.top - xy[i + 1]) * view.scale;
  }
  return out;
}

function visible(view: ViewTransform, box: [number, number, number, number], width: number, height: number): boolean {
  const [x0, y0] = toScreen(view, box[0], box[3]);
  const [x1, y1] = toScreen(view, box[2], box[1]);
  return x1 >= 0 && y1 >= 0 && x0 <= width && y0 <= height;
}

/** Roads: lane areas (driving and other lanes in their colors), lane borders, lane-offset lines. */
export function drawRoads(painter: Painter, shapes: RoadShapes, view: ViewTransform, width: number, height: number): number {
  let drawn = 0;
  for (const lane of shapes.lanes) {
    if (!visible(view, lane.box, width, height)) continue;
    painter.polygon(project(view, lane.polygon), lane.driving ? (lane.junction ? COLORS.junction : COLORS.driving) : COLORS.other);
    drawn++;
  }
  // Lines only where they are more than a few pixels apart: at network scale they would paint the roads white.
  if (view.scale >= 1.5) {
    for (const border of shapes.borders)
      painter.polyline(
        project(view, border.xy),
        border.center ? COLORS.center : COLORS.border,
        border.center ? 1.2 : 0.6,
        border.center && view.scale > 3 ? [6, 4] : undefined,
      );
  }
  return drawn;
}

/** Each entity's path over the run; a compared run's dashed. */
export function drawTrajectories(
  painter: Painter,
  run: RunTracks,
  view: ViewTransform,
  colorOf: (name: string) => string,
  dashed = false,
): void {
  for (const track of run.entities) {
    const xy = new Float64Array(track.x.length * 2);
    for (let i = 0; i < track.x.length; i++) {
      xy[2 * i] = (track.x[i] - view.left) * view.scale;
      xy[2 * i + 1] = (view.top - track.y[i]) * view.scale;
    }
    painter.polyline(xy, colorOf(track.name), 2, dashed ? [8, 5] : undefined);
  }
}

/** Where an entity is at `time` in a run: linear between frames. */
export function poseAt(run: RunTracks, track: RunTracks['entities'][number], time: number): { x: number; y: number; hdg: number } {
  const times = run.times;
  if (times.length === 0) return { x: NaN, y: NaN, hdg: 0 };
  let low = 0;
  let high = times.length - 1;
  if (time <= times[0]) high = 0;
  else if (time >= times[high]) low = high;
  else {
    while (high - low > 1) {
      const middle = (low + high) >> 1;
      if (times[middle] <= time) low = middle;
      else high = middle;
    }
  }
  const span = times[high] - times[low];
  const w = span > 0 ? (time - times[low]) / span : 0;
  let dh = track.hdg[high] - track.hdg[low];
  if (dh > Math.PI) dh -= 2 * Math.PI;
  if (dh < -Math.PI) dh += 2 * Math.PI;
  return {
    x: track.x[low] + w * (track.x[high] - track.x[low]),
    y: track.y[low] + w * (track.y[high] - track.y[low]),
    hdg: track.hdg[low] + w * dh,
  };
}

export interface PlacedBox {
  name: string;
  x: number;
  y: number;
  hdg: number;
  length: number;
  width: number;
  centerX: number;
}

/** The corners of an entity's bounding box in world coordinates. */
export function boxCorners(box: PlacedBox): number[] {
  const cos = Math.cos(box.hdg);
  const sin = Math.sin(box.hdg);
  const corners: number[] = [];
  for (const [u, v] of [
    [1, 1],
    [1, -1],
    [-1, -1],
    [-1, 1],
  ] as const) {
    const du = box.centerX + (u * box.length) / 2;
    const dv = (v * box.width) / 2;
    corners.push(box.x + du * cos - dv * sin, box.y + du * sin + dv * cos);
  }
  return corners;
}

/** An entity's box on screen as an axis-aligned rectangle. */
export function screenBox(view: ViewTransform, box: PlacedBox): Bounds {
  const corners = boxCorners(box);
  let bounds: Bounds = [Infinity, Infinity, -Infinity, -Infinity];
  for (let i = 0; i < corners.length; i += 2) {
    const [sx, sy] = toScreen(view, corners[i], corners[i + 1]);
    bounds = [Math.min(bounds[0], sx), Math.min(bounds[1], sy), Math.max(bounds[2], sx), Math.max(bounds[3], sy)];
  }
  return bounds;
}

/** Smallest on-screen size of an entity's box, px (its width; the length keeps the car's proportions). */
export const MIN_ENTITY_PIXELS = 7;

/** The box as drawn: true size, but never smaller than MIN_ENTITY_PIXELS wide on screen. */
export function drawnBox(box: PlacedBox, view: ViewTransform): PlacedBox {
  const minimum = MIN_ENTITY_PIXELS / view.scale;
  if (box.width >= minimum) return box;
  const grow = minimum / Math.max(box.width, 0.1);
  return { ...box, width: minimum, length: Math.max(box.length, box.length * Math.min(grow, 2), minimum * 1.6) };
}

export interface EntityDrawing {
  /** Screen size, so that labels stay on it. */
  width?: number;
  height?: number;
  /** The entity followed and plotted: outlined in white, labelled first. */
  chosen?: string;
  /** A second run's entities (compared, overlaid): outlined and dashed, labelled after the first run's. */
  compare?: PlacedBox[];
  /** Appended to the compared entities' names. */
  compareSuffix?: string;
  /** The labels' font size, px (larger on a large exported picture). */
  labelSize?: number;
}

const LABEL_SIZE = 12;

/**
 * Entities: their box at true size (at least a few pixels), a chevron at the front showing the heading,
 * and their names placed so that no two overlap (with a leader line when moved away).
 */
export function drawEntities(
  painter: Painter,
  boxes: PlacedBox[],
  view: ViewTransform,
  colorOf: (name: string) => string,
  options: EntityDrawing = {},
): PlacedLabel[] {
  const compare = options.compare ?? [];
  const obstacles: Bounds[] = [];
  const drawOne = (box: PlacedBox, ghost: boolean) => {
    const drawn = drawnBox(box, view);
    const corners = project(view, boxCorners(drawn));
    const outline = [
      corners[0],
      corners[1],
      corners[2],
      corners[3],
      corners[4],
      corners[5],
      corners[6],
      corners[7],
      corners[0],
      corners[1],
    ];
    if (ghost) painter.polyline(outline, colorOf(box.name), 2, [4, 3]);
    else {
      painter.polygon(corners, colorOf(box.name));
      painter.polyline(outline, box.name === options.chosen ? '#ffffff' : '#000000', box.name === options.chosen ? 2.5 : 1.5);
    }
    // The heading: a chevron from the front's middle back a third of the length, across most of the width.
    const cos = Math.cos(drawn.hdg);
    const sin = Math.sin(drawn.hdg);
    const at = (u: number, v: number) => [drawn.x + u * cos - v * sin, drawn.y + u * sin + v * cos];
    const front = drawn.centerX + drawn.length / 2;
    const back = front - Math.min(drawn.length / 3, drawn.width);
    painter.polyline(
      project(view, [...at(back, drawn.width * 0.35), ...at(front, 0), ...at(back, -drawn.width * 0.35)]),
      ghost ? colorOf(box.name) : '#1b1b1b',
      2,
    );
    obstacles.push(screenBox(view, drawn));
  };
  for (const box of compare) drawOne(box, true);
  for (const box of boxes) drawOne(box, false);
  const labelSize = options.labelSize ?? LABEL_SIZE;
  const request = (box: PlacedBox, text: string, priority: number): LabelRequest => ({
    text,
    anchor: screenBox(view, drawnBox(box, view)),
    width: text.length * labelSize * 0.62 + 4,
    height: labelSize + 3,
    priority,
  });
  const requests = [
    ...boxes.map((box, index) => request(box, box.name, box.name === options.chosen ? -1 : index)),
    ...compare.map((box, index) => request(box, `${box.name}${options.compareSuffix ?? ' (2)'}`, boxes.length + index)),
  ];
  const labels = placeLabels(requests, obstacles, options.width ?? Infinity, options.height ?? Infinity);
  for (const label of labels) {
    if (label.leader) painter.polyline(label.leader, COLORS.label, 1);
    painter.text(label.x + 2, label.y, label.text, COLORS.label, labelSize);
  }
  return labels;
}

/** Start boxes of the scene's entities that have a position. */
export function startBoxes(entities: SceneEntity[]): PlacedBox[] {
  return entities
    .filter((entity) => entity.x !== undefined && entity.y !== undefined)
    .map((entity) => ({
      name: entity.name,
      x: entity.x!,
      y: entity.y!,
      hdg: entity.hdg ?? 0,
      length: entity.length,
      width: entity.width,
      centerX: entity.centerX,
    }));
}

export function pointInPolygon(xy: ArrayLike<number>, x: number, y: number): boolean {
  let inside = false;
  for (let i = 0, j = xy.length - 2; i < xy.length; j = i, i += 2) {
    const xi = xy[i];
    const yi = xy[i + 1];
    const xj = xy[j];
    const yj = xy[j + 1];
    if (yi > y !== yj > y && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

/** The lane under a world point, if any. */
export function laneAt(shapes: RoadShapes, x: number, y: number): LaneShape | undefined {
  for (const lane of shapes.lanes) {
    const box = lane.box;
    if (x < box[0] || x > box[2] || y < box[1] || y > box[3]) continue;
    if (pointInPolygon(lane.polygon, x, y)) return lane;
  }
  return undefined;
}

/** The entity box under a world point (with a few pixels of slack), if any. */
export function boxAt(boxes: PlacedBox[], view: ViewTransform, x: number, y: number): PlacedBox | undefined {
  const slack = 4 / view.scale;
  return boxes.find((box) => pointInPolygon(boxCorners({ ...box, length: box.length + 2 * slack, width: box.width + 2 * slack }), x, y));
}

function escapeXml(text: string): string {
  return text.replace(/[&<>"']/g, (character) => `&#${character.charCodeAt(0)};`);
}

const fixed = (value: number) => (Math.round(value * 10) / 10).toString();

/** Collects the drawing as an SVG document. */
export class SvgPainter implements Painter {
  private readonly parts: string[] = [];

  constructor(
    private readonly width: number,
    private readonly height: number,
    background: string,
  ) {
    this.parts.push(`<rect width="${width}" height="${height}" fill="${background}"/>`);
  }

  private points(xy: ArrayLike<number>): string {
    const pairs: string[] = [];
    for (let i = 0; i + 1 < xy.length; i += 2) pairs.push(`${fixed(xy[i])},${fixed(xy[i + 1])}`);
    return pairs.join(' ');
  }

  polygon(xy: ArrayLike<number>, fill: string): void {
    this.parts.push(`<polygon points="${this.points(xy)}" fill="${fill}"/>`);
  }

  polyline(xy: ArrayLike<number>, stroke: string, width: number, dash?: number[]): void {
    this.parts.push(
      `<polyline points="${this.points(xy)}" fill="none" stroke="${stroke}" stroke-width="${width}"${dash ? ` stroke-dasharray="${dash.join(' ')}"` : ''}/>`,
    );
  }

  private clips = 0;

  clip(x: number, y: number, width: number, height: number): void {
    const id = `pane${++this.clips}`;
    this.parts.push(
      `<clipPath id="${id}"><rect x="${fixed(x)}" y="${fixed(y)}" width="${fixed(width)}" height="${fixed(height)}"/></clipPath><g clip-path="url(#${id})">`,
    );
  }

  unclip(): void {
    this.parts.push('</g>');
  }

  text(x: number, y: number, text: string, color: string, size: number): void {
    this.parts.push(
      `<text x="${fixed(x)}" y="${fixed(y)}" fill="${color}" font-size="${size}" font-family="sans-serif">${escapeXml(text)}</text>`,
    );
  }

  toString(): string {
    return `<?xml version="1.0" encoding="UTF-8"?>\n<svg xmlns="http://www.w3.org/2000/svg" width="${this.width}" height="${this.height}" viewBox="0 0 ${this.width} ${this.height}">\n${this.parts.join('\n')}\n</svg>\n`;
  }
}

/** Where things go on an exported picture (made by exportLayout in analysis.ts, drawn by drawExportOverlay). */
export interface ExportLayout {
  width: number;
  height: number;
  /** The map's area on the picture; below it the plots, the event list, then a band with legend, time and scale bar. */
  map: { x: number; y: number; width: number; height: number };
  /** Where the chosen entity's plots go, when the picture has them. */
  plots?: { x: number; y: number; width: number; height: number };
  /** The event list's lines as the panel words them (the last may say how many more were left out). */
  events: { x: number; y: number; text: string; dim: boolean }[];
  /** The view for the map (for each pane of it): the same centre as shown, scaled so that it shows at least what was shown. */
  view: ViewTransform;
  legend: { x: number; y: number; text: string }[];
  time: { x: number; y: number; text: string };
  scale: { x: number; y: number; pixels: number; text: string };
  fontSize: number;
}

/** The band of an exported picture: the time, a legend of the entities (a compared run's dashed) and a scale bar. */
export function drawExportOverlay(
  painter: Painter,
  layout: ExportLayout,
  colorOf: (name: string) => string,
  compared: Set<string> = new Set(),
): void {
  const { width, height, map, fontSize } = layout;
  painter.polygon([0, map.height, width, map.height, width, height, 0, height], '#1e1e1e');
  for (const line of layout.events) painter.text(line.x, line.y, line.text, line.dim ? '#9e9e9e' : COLORS.label, fontSize * 0.9);
  painter.text(layout.time.x, layout.time.y, layout.time.text, COLORS.label, fontSize);
  for (const item of layout.legend) {
    const top = item.y - fontSize * 0.8;
    if (compared.has(item.text))
      painter.polyline(
        [item.x, top, item.x + fontSize, top, item.x + fontSize, top + fontSize, item.x, top + fontSize, item.x, top],
        colorOf(item.text.replace(/ \(2\)$/, '')),
        2,
        [3, 2],
      );
    else
      painter.polygon([item.x, top, item.x + fontSize, top, item.x + fontSize, top + fontSize, item.x, top + fontSize], colorOf(item.text));
    painter.text(item.x + fontSize * 1.4, item.y, item.text, COLORS.label, fontSize);
  }
  const { x, y, pixels, text } = layout.scale;
  const tick = fontSize * 0.4;
  painter.polyline([x, y - tick, x, y, x + pixels, y, x + pixels, y - tick], COLORS.label, 2);
  painter.text(x + pixels / 2 - text.length * fontSize * 0.3, y - tick - 2, text, COLORS.label, fontSize * 0.9);
}

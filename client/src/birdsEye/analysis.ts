/**
 * The pure parts of analysing a run in the bird's-eye view: framing and following, zoom steps, the
 * tooltip's place, the speed/gap/time-to-collision series and the export's layout.
 * No DOM, so that it runs (and is tested) in Node too.
 */
import { boxCorners, type ExportLayout, type PlacedBox, type ViewTransform, toWorld } from './draw';
import type { Bounds } from './labels';
import type { RunTracks } from './messages';

export type { Bounds };

/** One wheel notch zooms by this factor, whatever the zoom level. */
export const ZOOM_STEP = 1.15;
export const MIN_SCALE = 0.01;
export const MAX_SCALE = 500;

/**
 * Notches a wheel event stands for: Chromium reports 100 px (or 3 lines, or 1 page) per notch; a
 * touchpad's small deltas give fractions of a notch.
 */
export function wheelNotches(deltaY: number, deltaMode: number): number {
  if (deltaMode === 1) return deltaY / 3;
  if (deltaMode === 2) return deltaY;
  return deltaY / 100;
}

/** Zooms by `ZOOM_STEP` per notch (wheel down zooms out), keeping the world point under (sx, sy) there. */
export function zoomAbout(view: ViewTransform, notches: number, sx: number, sy: number): ViewTransform {
  const [x, y] = toWorld(view, sx, sy);
  const scale = Math.min(Math.max(view.scale * ZOOM_STEP ** -notches, MIN_SCALE), MAX_SCALE);
  return { scale, left: x - sx / scale, top: y + sy / scale };
}

/** The same scale, the world point (x, y) in the middle of a `width` × `height` screen. */
export function centredOn(view: ViewTransform, x: number, y: number, width: number, height: number): ViewTransform {
  return { scale: view.scale, left: x - width / 2 / view.scale, top: y + height / 2 / view.scale };
}

/**
 * What *Entities* frames: the entities where they are now, `margin` metres around and at least
 * `minimumSpan` metres across (a lone car is not blown up to fill the screen).
 */
export function entitiesBounds(boxes: PlacedBox[], margin = 15, minimumSpan = 80): Bounds | undefined {
  let bounds: Bounds | undefined;
  for (const box of boxes) {
    const corners = boxCorners(box);
    for (let i = 0; i < corners.length; i += 2) {
      const x = corners[i];
      const y = corners[i + 1];
      if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
      if (!bounds) bounds = [x, y, x, y];
      else bounds = [Math.min(bounds[0], x), Math.min(bounds[1], y), Math.max(bounds[2], x), Math.max(bounds[3], y)];
    }
  }
  if (!bounds) return undefined;
  const grow = (low: number, high: number): [number, number] => {
    const half = Math.max((high - low) / 2 + margin, minimumSpan / 2);
    const middle = (low + high) / 2;
    return [middle - half, middle + half];
  };
  const [x0, x1] = grow(bounds[0], bounds[2]);
  const [y0, y1] = grow(bounds[1], bounds[3]);
  return [x0, y0, x1, y1];
}

/** The tooltip's top-left corner: beside the pointer, flipped and clamped so that it stays inside the panel. */
export function tooltipPlace(
  pointerX: number,
  pointerY: number,
  width: number,
  height: number,
  panelWidth: number,
  panelHeight: number,
  offset = 14,
): [number, number] {
  let x = pointerX + offset;
  let y = pointerY + offset;
  if (x + width > panelWidth) x = pointerX - offset - width;
  if (y + height > panelHeight) y = pointerY - offset - height;
  return [Math.max(0, Math.min(x, panelWidth - width)), Math.max(0, Math.min(y, panelHeight - height))];
}

function segmentDistance(px: number, py: number, ax: number, ay: number, bx: number, by: number): number {
  const dx = bx - ax;
  const dy = by - ay;
  const length2 = dx * dx + dy * dy;
  const t = length2 > 0 ? Math.min(Math.max(((px - ax) * dx + (py - ay) * dy) / length2, 0), 1) : 0;
  return Math.hypot(px - ax - t * dx, py - ay - t * dy);
}

function inside(corners: number[], x: number, y: number): boolean {
  // Convex, counter-clockwise or clockwise: the point is on the same side of every edge.
  let sign = 0;
  for (let i = 0; i < corners.length; i += 2) {
    const j = (i + 2) % corners.length;
    const cross = (corners[j] - corners[i]) * (y - corners[i + 1]) - (corners[j + 1] - corners[i + 1]) * (x - corners[i]);
    if (cross === 0) continue;
    if (sign === 0) sign = Math.sign(cross);
    else if (Math.sign(cross) !== sign) return false;
  }
  return true;
}

/** The distance between two entities' bounding boxes (0 when they touch or overlap), m. */
export function boxGap(a: PlacedBox, b: PlacedBox): number {
  const ca = boxCorners(a);
  const cb = boxCorners(b);
  let gap = Infinity;
  for (const [from, to] of [
    [ca, cb],
    [cb, ca],
  ] as const) {
    for (let i = 0; i < from.length; i += 2) {
      if (inside(to, from[i], from[i + 1])) return 0;
      for (let j = 0; j < to.length; j += 2) {
        const k = (j + 2) % to.length;
        gap = Math.min(gap, segmentDistance(from[i], from[i + 1], to[j], to[j + 1], to[k], to[k + 1]));
      }
    }
  }
  return gap;
}

/** The chosen entity against one other, per frame of the run. */
export interface PairSeries {
  name: string;
  /** Distance between the bounding boxes, m. */
  gap: number[];
  /** Gap divided by the rate at which it shrinks, s; NaN while it does not shrink. */
  ttc: number[];
}

export interface RunSeries {
  times: number[];
  chosen: string;
  /** The chosen entity's speed, m/s (esmini's Current_Speed, else from its positions). */
  speed: number[];
  others: PairSeries[];
}

type Track = RunTracks['entities'][number];

const boxOf = (track: Track, i: number): PlacedBox => ({
  name: track.name,
  x: track.x[i],
  y: track.y[i],
  hdg: track.hdg[i],
  length: track.length,
  width: track.width,
  centerX: track.centerX,
});

function speedOf(run: RunTracks, track: Track): number[] {
  if (track.speed && track.speed.length === run.times.length && track.speed.some(Number.isFinite))
    return track.speed.map((value) => Math.abs(value));
  const n = run.times.length;
  return run.times.map((_, i) => {
    const a = Math.max(0, i - 1);
    const b = Math.min(n - 1, i + 1);
    const dt = run.times[b] - run.times[a];
    return dt > 0 ? Math.hypot(track.x[b] - track.x[a], track.y[b] - track.y[a]) / dt : 0;
  });
}

/**
 * Speed of `chosen`, and its gap and time-to-collision against every other entity, per frame. The gap's
 * rate of change is a central difference over neighbouring frames.
 */
export function runSeries(run: RunTracks, chosen: string): RunSeries | undefined {
  const track = run.entities.find((entity) => entity.name === chosen);
  if (!track) return undefined;
  const n = run.times.length;
  const others = run.entities
    .filter((other) => other !== track)
    .map((other): PairSeries => {
      const gap = run.times.map((_, i) => boxGap(boxOf(track, i), boxOf(other, i)));
      const ttc = gap.map((value, i) => {
        const a = Math.max(0, i - 1);
        const b = Math.min(n - 1, i + 1);
        const dt = run.times[b] - run.times[a];
        const closing = dt > 0 ? (gap[a] - gap[b]) / dt : 0;
        return closing > 1e-3 && Number.isFinite(value) ? value / closing : NaN;
      });
      return { name: other.name, gap, ttc };
    });
  return { times: run.times, chosen, speed: speedOf(run, track), others };
}

/** A round length for a scale bar at most `maxPixels` long: 1, 2 or 5 × 10^k metres. */
export function scaleBar(scale: number, maxPixels: number): { metres: number; pixels: number } {
  const most = maxPixels / scale;
  const power = 10 ** Math.floor(Math.log10(most));
  const metres = [5, 2, 1].map((step) => step * power).find((value) => value <= most) ?? power;
  return { metres, pixels: metres * scale };
}

/**
 * Where things go on an exported picture of `width` × `height`: the map above (what the panel showed,
 * `shown` of `shownWidth` × `shownHeight` px, refitted), a band below with a legend of the entities,
 * the time and a scale bar. Sizes grow with the picture.
 */
export function exportLayout(
  width: number,
  height: number,
  shown: ViewTransform,
  shownWidth: number,
  shownHeight: number,
  entities: string[],
  timeText: string,
  panes = 1,
  extras: ExportExtras = {},
): ExportLayout {
  const fontSize = Math.max(11, Math.round(Math.min(width, height) / 60));
  const band = Math.round(fontSize * 2.6);
  // Plots and events as the panel shows them below the map; the map keeps at least half the picture.
  const plotsHeight = extras.plots ? Math.round(Math.max(90, height * 0.2)) : 0;
  const lineHeight = Math.round(fontSize * 1.3);
  const events = extras.events ?? [];
  const roomForLines = Math.max(0, Math.floor((height * 0.5 - band - plotsHeight - fontSize) / lineHeight));
  const lines = Math.min(events.length, roomForLines);
  const eventsHeight = lines > 0 ? lines * lineHeight + Math.round(fontSize * 0.6) : 0;
  const map = { x: 0, y: 0, width, height: Math.max(1, height - band - plotsHeight - eventsHeight) };
  // With runs side by side, each pane is a `panes`th of the map's width and shows what its pane showed.
  const paneWidth = map.width / panes;
  const [cx, cy] = toWorld(shown, shownWidth / 2, shownHeight / 2);
  const scale = Math.min(paneWidth / (shownWidth / shown.scale), map.height / (shownHeight / shown.scale));
  const view: ViewTransform = { scale, left: cx - paneWidth / 2 / scale, top: cy + map.height / 2 / scale };
  const plots = plotsHeight > 0 ? { x: 0, y: map.height, width, height: plotsHeight } : undefined;
  const eventLines: ExportLayout['events'] = [];
  const eventsTop = map.height + plotsHeight;
  for (let index = 0; index < lines; index++) {
    const y = eventsTop + (index + 1) * lineHeight;
    const omitted = events.length - lines;
    if (index === lines - 1 && omitted > 0) eventLines.push({ x: fontSize, y, text: `… and ${omitted + 1} more events`, dim: true });
    else eventLines.push({ x: fontSize, y, text: events[index].text, dim: events[index].dim });
  }
  const infoTop = eventsTop + eventsHeight;
  const baseline = infoTop + Math.round(band * 0.62);
  const bar = scaleBar(scale, Math.min(width / 5, 240 * (fontSize / 12)));
  const barX = width - fontSize - bar.pixels;
  const time = { x: fontSize, y: baseline, text: timeText };
  let x = fontSize + Math.round(timeText.length * fontSize * 0.6) + 2 * fontSize;
  const legend: ExportLayout['legend'] = [];
  for (const text of entities) {
    const itemWidth = fontSize * 1.4 + text.length * fontSize * 0.6 + fontSize;
    if (x + itemWidth > barX - fontSize) break;
    legend.push({ x, y: baseline, text });
    x += itemWidth;
  }
  return {
    width,
    height,
    map,
    ...(plots ? { plots } : {}),
    events: eventLines,
    view,
    legend,
    time,
    scale: { x: barX, y: baseline, pixels: bar.pixels, text: bar.metres >= 1000 ? `${bar.metres / 1000} km` : `${bar.metres} m` },
    fontSize,
  };
}

/** What an exported picture shows besides the map: the plots (when an entity is followed) and the event list's lines. */
export interface ExportExtras {
  plots?: boolean;
  events?: { text: string; dim: boolean }[];
}

/** `1920x1080` (or `1920 x 1080`, `1920*1080`) → [1920, 1080]; undefined when not a size from 16 to 16384 px. */
export function parseResolution(text: string): [number, number] | undefined {
  const match = /^\s*(\d{2,5})\s*[x×*,]\s*(\d{2,5})\s*$/i.exec(text);
  if (!match) return undefined;
  const size: [number, number] = [Number(match[1]), Number(match[2])];
  return size.every((value) => value >= 16 && value <= 16384) ? size : undefined;
}

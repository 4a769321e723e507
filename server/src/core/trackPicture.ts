/**
 * A run drawn from above as SVG text: the road's lanes, each entity's path with a dot every second, its
 * bounding box where it starts (outlined) and where it ends (filled). The library's pictures are drawn by it
 * (scripts/library-pictures.ts), from esmini's own log of the module's example main.
 */
import type { EsminiRun } from '../../../common/src/esminiCsv';
import type { SectionPolylines } from '../../../common/src/sectionPolylines';

export interface TrackPictureOptions {
  title: string;
  /** Pixels per metre. */
  scale?: number;
  /** Metres of road shown around the paths. */
  margin?: number;
}

const COLORS = ['#1f6feb', '#d1242f', '#1a7f37', '#9a6700', '#8250df', '#bf3989'];
const round = (value: number) => Math.round(value * 10) / 10;
const escape = (text: string) => text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');

type Point = [number, number];
type Rect = { minX: number; minY: number; maxX: number; maxY: number };

/** A polygon cut to a rectangle (Sutherland-Hodgman): the road's lanes run far beyond what a picture shows. */
function clipPolygon(points: Point[], rect: Rect): Point[] {
  const edges: [(p: Point) => boolean, (a: Point, b: Point) => Point][] = [
    [(p) => p[0] >= rect.minX, (a, b) => at(a, b, (rect.minX - a[0]) / (b[0] - a[0]))],
    [(p) => p[0] <= rect.maxX, (a, b) => at(a, b, (rect.maxX - a[0]) / (b[0] - a[0]))],
    [(p) => p[1] >= rect.minY, (a, b) => at(a, b, (rect.minY - a[1]) / (b[1] - a[1]))],
    [(p) => p[1] <= rect.maxY, (a, b) => at(a, b, (rect.maxY - a[1]) / (b[1] - a[1]))],
  ];
  let result = points;
  for (const [isInside, cross] of edges) {
    const input = result;
    result = [];
    input.forEach((current, index) => {
      const previous = input[(index + input.length - 1) % input.length];
      if (isInside(current)) {
        if (!isInside(previous)) result.push(cross(previous, current));
        result.push(current);
      } else if (isInside(previous)) result.push(cross(previous, current));
    });
  }
  return result;
}

const at = (a: Point, b: Point, fraction: number): Point => [a[0] + (b[0] - a[0]) * fraction, a[1] + (b[1] - a[1]) * fraction];

/** A polyline's segments cut to a rectangle, as runs of points (Liang-Barsky per segment). */
function clipPolyline(points: Point[], rect: Rect): Point[][] {
  const runs: Point[][] = [];
  let run: Point[] = [];
  for (let index = 0; index + 1 < points.length; index++) {
    const [a, b] = [points[index], points[index + 1]];
    let [low, high] = [0, 1];
    const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
    const tests: [number, number][] = [
      [-dx, a[0] - rect.minX],
      [dx, rect.maxX - a[0]],
      [-dy, a[1] - rect.minY],
      [dy, rect.maxY - a[1]],
    ];
    let visible = true;
    for (const [p, q] of tests) {
      if (p === 0) {
        if (q < 0) visible = false;
      } else if (p < 0) low = Math.max(low, q / p);
      else high = Math.min(high, q / p);
    }
    if (!visible || low > high) {
      if (run.length > 1) runs.push(run);
      run = [];
      continue;
    }
    const [start, end] = [at(a, b, low), at(a, b, high)];
    if (run.length === 0) run.push(start);
    run.push(end);
    if (high < 1) {
      runs.push(run);
      run = [];
    }
  }
  if (run.length > 1) runs.push(run);
  return runs;
}

/** The corners of a bounding box at a pose, as SVG points (y down). */
function boxPoints(
  x: number,
  y: number,
  hdg: number,
  length: number,
  width: number,
  centerX: number,
  toPixel: (x: number, y: number) => string,
): string {
  const [cos, sin] = [Math.cos(hdg), Math.sin(hdg)];
  const corners = [
    [centerX + length / 2, width / 2],
    [centerX + length / 2, -width / 2],
    [centerX - length / 2, -width / 2],
    [centerX - length / 2, width / 2],
  ];
  return corners.map(([dx, dy]) => toPixel(x + dx * cos - dy * sin, y + dx * sin + dy * cos)).join(' ');
}

export function trackPicture(sections: readonly SectionPolylines[], run: EsminiRun, options: TrackPictureOptions): string {
  const scale = options.scale ?? 4;
  const margin = options.margin ?? 12;
  let [minX, minY, maxX, maxY] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const entity of run.entities)
    for (let index = 0; index < entity.x.length; index++) {
      minX = Math.min(minX, entity.x[index]);
      maxX = Math.max(maxX, entity.x[index]);
      minY = Math.min(minY, entity.y[index]);
      maxY = Math.max(maxY, entity.y[index]);
    }
  if (!Number.isFinite(minX)) throw new Error('the run logged no entity');
  [minX, minY, maxX, maxY] = [minX - margin, minY - margin, maxX + margin, maxY + margin];
  const rect: Rect = { minX, minY, maxX, maxY };
  const header = 36;
  const width = Math.max(640, Math.ceil((maxX - minX) * scale));
  const height = Math.ceil((maxY - minY) * scale) + header;
  const toPixel = (x: number, y: number) => `${round((x - minX) * scale)},${round((maxY - y) * scale + header)}`;
  const pixels = (points: Point[]) => points.map(([x, y]) => toPixel(x, y)).join(' ');
  const metres = (border: number[]): Point[] => {
    const points: Point[] = [];
    for (let index = 0; index + 1 < border.length; index += 2) points.push([border[index], border[index + 1]]);
    return points;
  };
  const parts: string[] = [
    `<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" viewBox="0 0 ${width} ${height}" font-family="sans-serif" font-size="12">`,
    `<rect width="${width}" height="${height}" fill="#f6f8fa"/>`,
    `<text x="6" y="14" font-weight="bold">${escape(options.title)}</text>`,
  ];
  for (const section of sections) {
    // Each lane between its inner and outer border, cut to what the picture shows.
    for (let lane = 0; lane + 1 < section.borders.length; lane++) {
      const laneInfo = section.lanes[lane].id > 0 ? section.lanes[lane] : section.lanes[lane + 1];
      const outline = clipPolygon([...metres(section.borders[lane]), ...metres(section.borders[lane + 1]).reverse()], rect);
      if (outline.length < 3) continue;
      const fill = laneInfo.driving ? '#d0d7de' : laneInfo.type === 'sidewalk' ? '#e6e0d4' : '#f6f8fa';
      parts.push(`<polygon points="${pixels(outline)}" fill="${fill}"/>`);
    }
    for (const border of section.borders)
      for (const run of clipPolyline(metres(border), rect))
        parts.push(`<polyline points="${pixels(run)}" fill="none" stroke="#ffffff" stroke-width="1"/>`);
  }
  const legend: string[] = [];
  run.entities.forEach((entity, entityIndex) => {
    const color = COLORS[entityIndex % COLORS.length];
    const last = entity.x.length - 1;
    const path = Array.from(entity.x, (x, index) => toPixel(x, entity.y[index]));
    parts.push(`<polyline points="${path.join(' ')}" fill="none" stroke="${color}" stroke-width="1.5"/>`);
    for (let index = 0; index <= last; index++) {
      const time = run.times[index];
      if (index > 0 && Math.abs(time - Math.round(time)) < 1e-6) {
        const [px, py] = toPixel(entity.x[index], entity.y[index]).split(',');
        parts.push(`<circle cx="${px}" cy="${py}" r="2" fill="${color}"/>`);
      }
    }
    const box = (index: number) =>
      boxPoints(entity.x[index], entity.y[index], entity.hdg[index], entity.length, entity.width, entity.centerX, toPixel);
    parts.push(`<polygon points="${box(0)}" fill="none" stroke="${color}" stroke-width="1.5"/>`);
    parts.push(`<polygon points="${box(last)}" fill="${color}" fill-opacity="0.8"/>`);
    legend.push(`<tspan fill="${color}">■ ${escape(entity.name)}</tspan>`);
  });
  parts.push(
    `<text x="6" y="29">${legend.join(' ')} <tspan fill="#57606a">outline: start, filled: end (${round(run.times[run.times.length - 1])} s), dots: every second</tspan></text>`,
  );
  parts.push('</svg>');
  return parts.join('\n') + '\n';
}

import type { EntityTrack, EsminiRun } from '../../../common/src/esminiCsv';

/** What a batch row says about one run's trajectories: the ego against every other entity. */
export interface RunMetrics {
  /** The entity measured from: the one named `Ego` (any case), else esmini's first object. */
  ego: string | undefined;
  /** Smallest gap between the ego's bounding box and another's, in metres (0 when they overlap). */
  minDistance: number | undefined;
  /**
   * Smallest time to collision in seconds: the gap divided by the speed at which it closes between two
   * rows (at least 1 cm/s), over every row where it closes; undefined when it never closes.
   */
  minTtc: number | undefined;
}

type Point = [number, number];

/** The four corners of an entity's bounding box at row `row`, in order around it. */
function corners(track: EntityTrack, row: number): Point[] | undefined {
  const x = track.x[row];
  const y = track.y[row];
  const heading = track.hdg[row];
  if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(heading)) return undefined;
  const ux = Math.cos(heading);
  const uy = Math.sin(heading);
  const cx = x + ux * track.centerX;
  const cy = y + uy * track.centerX;
  const hl = track.length / 2;
  const hw = track.width / 2;
  return [
    [cx + ux * hl - uy * hw, cy + uy * hl + ux * hw],
    [cx - ux * hl - uy * hw, cy - uy * hl + ux * hw],
    [cx - ux * hl + uy * hw, cy - uy * hl - ux * hw],
    [cx + ux * hl + uy * hw, cy + uy * hl - ux * hw],
  ];
}

/** Whether two convex polygons overlap, by the separating axis theorem. */
function overlap(a: Point[], b: Point[]): boolean {
  for (const polygon of [a, b]) {
    for (let i = 0; i < polygon.length; i++) {
      const [x1, y1] = polygon[i];
      const [x2, y2] = polygon[(i + 1) % polygon.length];
      const nx = y2 - y1;
      const ny = x1 - x2;
      let minA = Infinity,
        maxA = -Infinity,
        minB = Infinity,
        maxB = -Infinity;
      for (const [px, py] of a) {
        const d = nx * px + ny * py;
        minA = Math.min(minA, d);
        maxA = Math.max(maxA, d);
      }
      for (const [px, py] of b) {
        const d = nx * px + ny * py;
        minB = Math.min(minB, d);
        maxB = Math.max(maxB, d);
      }
      if (maxA < minB || maxB < minA) return false;
    }
  }
  return true;
}

function pointToSegment([px, py]: Point, [ax, ay]: Point, [bx, by]: Point): number {
  const dx = bx - ax;
  const dy = by - ay;
  const lengthSquared = dx * dx + dy * dy;
  const t = lengthSquared === 0 ? 0 : Math.max(0, Math.min(1, ((px - ax) * dx + (py - ay) * dy) / lengthSquared));
  return Math.hypot(px - (ax + t * dx), py - (ay + t * dy));
}

/** The gap between two convex polygons: 0 when they overlap, else the nearest corner-to-edge distance. */
export function polygonGap(a: Point[], b: Point[]): number {
  if (overlap(a, b)) return 0;
  let gap = Infinity;
  for (const [from, to] of [
    [a, b],
    [b, a],
  ]) {
    for (const point of from) {
      for (let i = 0; i < to.length; i++) gap = Math.min(gap, pointToSegment(point, to[i], to[(i + 1) % to.length]));
    }
  }
  return gap;
}

/** Closing speeds below this (m/s) are the CSV's rounding, not an approach: equal speeds have no time to collision. */
const MIN_CLOSING_SPEED = 0.01;

/** The ego: the entity named Ego in any case, else the first. */
export function egoOf(entities: EntityTrack[]): EntityTrack | undefined {
  return entities.find((entity) => entity.name.toLowerCase() === 'ego') ?? entities[0];
}

/** Minimum gap and time to collision of the ego against every other entity, over the rows up to `duration`. */
export function trajectoryMetrics(run: EsminiRun, duration: number): RunMetrics {
  const ego = egoOf(run.entities);
  if (!ego) return { ego: undefined, minDistance: undefined, minTtc: undefined };
  let minDistance: number | undefined;
  let minTtc: number | undefined;
  const rows = run.times.length;
  for (const other of run.entities) {
    if (other === ego) continue;
    let previous: { time: number; gap: number } | undefined;
    for (let row = 0; row < rows; row++) {
      const time = run.times[row];
      if (!(time <= duration + 1e-9)) break;
      const a = corners(ego, row);
      const b = corners(other, row);
      if (!a || !b) {
        previous = undefined;
        continue;
      }
      const gap = polygonGap(a, b);
      minDistance = minDistance === undefined ? gap : Math.min(minDistance, gap);
      if (previous && time > previous.time) {
        const closing = (previous.gap - gap) / (time - previous.time);
        if (closing > MIN_CLOSING_SPEED) {
          const ttc = gap / closing;
          minTtc = minTtc === undefined ? ttc : Math.min(minTtc, ttc);
        }
      }
      previous = { time, gap };
    }
  }
  return { ego: ego.name, minDistance, minTtc };
}

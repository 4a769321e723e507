/**
 * Trajectory shapes ScenarioRunner cannot follow (Clothoid, ClothoidSpline, Nurbs) sampled into the polyline
 * vertices it can, the way esmini 3.6 samples them before following them (RoadManager.cpp
 * ClothoidShape::CalculatePolyLine, ClothoidSplineShape::CalculatePolyLine, NurbsShape::CalculatePolyLine:
 * a vertex every metre, or every metre of the control polygon for a Nurbs), so that esmini runs the polyline as
 * it runs the shape. Coordinates are in the frame of the shape's start (a Clothoid) or of its control points.
 */
import { evaluateGeometry, normalizeAngle, type Pose } from '../opendrive/geometry';

export interface SampledVertex {
  x: number;
  y: number;
  /** Heading along the curve, radians. */
  h: number;
  /** Seconds, when the shape gives times (else the polyline has none). */
  time?: number;
}

/** esmini's step between sampled vertices, metres (RoadManager.cpp: stepLen 1.0, NURBS_STEPLENGTH 1.0). */
export const SAMPLE_STEP = 1;

/** Stations along a length: every SAMPLE_STEP metres, then the end (as esmini's loops: i < steps, then the length). */
function stations(length: number): number[] {
  const steps = Math.floor(length / SAMPLE_STEP);
  const result: number[] = [];
  for (let i = 0; i < steps; i++) result.push(i * SAMPLE_STEP);
  result.push(length);
  return result;
}

function spiralPose(start: Pose, curvStart: number, curvEnd: number, length: number, ds: number): Pose {
  return evaluateGeometry({ kind: 'spiral', s: 0, x: start.x, y: start.y, hdg: start.hdg, length, curvStart, curvEnd }, ds);
}

/** A Clothoid from `start`: curvature + curvaturePrime·s over `length`; times from startTime to stopTime along s when given. */
export function sampleClothoid(
  start: Pose,
  curvature: number,
  curvaturePrime: number,
  length: number,
  times?: { start: number; stop: number },
): SampledVertex[] {
  const curvEnd = curvature + curvaturePrime * length;
  return stations(length).map((s) => {
    const pose = spiralPose(start, curvature, curvEnd, length, s);
    return {
      x: pose.x,
      y: pose.y,
      h: normalizeAngle(pose.hdg),
      ...(times ? { time: times.start + (length > 0 ? (s / length) * (times.stop - times.start) : 0) } : {}),
    };
  });
}

export interface SplineSegment {
  curvStart: number;
  curvEnd: number;
  length: number;
  /** Added to the heading the segment starts with (ClothoidSplineSegment hOffset). */
  hOffset: number;
  /** timeStart of the segment, when the spline is timed. */
  time?: number;
}

/** A ClothoidSpline: its segments end to end from `start` (esmini ClothoidSplineShape::Freeze); times per segment up to `timeEnd`. */
export function sampleClothoidSpline(start: Pose, segments: SplineSegment[], timeEnd?: number): SampledVertex[] {
  const total = segments.reduce((sum, segment) => sum + segment.length, 0);
  const starts: Pose[] = [];
  let pose = start;
  for (const segment of segments) {
    const from = { ...pose, hdg: pose.hdg + segment.hOffset };
    starts.push(from);
    pose = spiralPose(from, segment.curvStart, segment.curvEnd, segment.length, segment.length);
  }
  const timed = timeEnd !== undefined && segments.every((segment) => segment.time !== undefined);
  return stations(total).map((s) => {
    let index = 0;
    let before = 0;
    while (index < segments.length - 1 && s > before + segments[index].length - 1e-9) before += segments[index++].length;
    const segment = segments[index];
    const local = Math.min(s - before, segment.length);
    const at = spiralPose(starts[index], segment.curvStart, segment.curvEnd, segment.length, local);
    const vertex: SampledVertex = { x: at.x, y: at.y, h: normalizeAngle(at.hdg) };
    if (timed) {
      const from = segment.time ?? 0;
      const to = index + 1 < segments.length ? (segments[index + 1].time ?? timeEnd) : timeEnd;
      vertex.time = from + (segment.length > 0 ? (local / segment.length) * (to - from) : 0);
    }
    return vertex;
  });
}

export interface ControlPoint {
  x: number;
  y: number;
  weight: number;
  time?: number;
}

/** The B-spline basis N(i, k) at x (Cox-de Boor, as esmini's NurbsShape::CoxDeBoor). */
function coxDeBoor(x: number, i: number, k: number, knots: readonly number[]): number {
  if (k === 1) return knots[i] <= x && x < knots[i + 1] ? 1 : 0;
  const den1 = knots[i + k - 1] - knots[i];
  const den2 = knots[i + k] - knots[i + 1];
  const eq1 = den1 > 0 ? ((x - knots[i]) / den1) * coxDeBoor(x, i, k - 1, knots) : 0;
  const eq2 = den2 > 0 ? ((knots[i + k] - x) / den2) * coxDeBoor(x, i + 1, k - 1, knots) : 0;
  return eq1 + eq2;
}

/**
 * A Nurbs of `order` over its control points and knots (control points + order knots), sampled at even steps
 * of its parameter, as many as metres of its control polygon (+1); times interpolated between the control
 * points at the parameter where each weighs most (esmini NurbsShape::CalculatePolyLine). A string says why it cannot be.
 */
export function sampleNurbs(order: number, points: ControlPoint[], knots: number[]): SampledVertex[] | string {
  if (!Number.isInteger(order) || order < 1) return `its order ${order} is not a positive whole number`;
  if (points.length < 2) return 'it has fewer than two control points';
  if (knots.length !== points.length + order)
    return `it has ${knots.length} knots where ${points.length} control points of order ${order} need ${points.length + order}`;
  let polygon = 0;
  for (let i = 1; i < points.length; i++) polygon += Math.hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
  if (polygon < 1e-9) return 'its control points all lie at one place';
  const tMax = knots[knots.length - 1];
  const steps = Math.floor(1 + polygon / SAMPLE_STEP);
  const peakValue = points.map(() => 0);
  const peakParameter = points.map(() => 0);
  const evaluate = (parameter: number, track: boolean): { x: number; y: number } => {
    const t = Math.min(Math.max(parameter, knots[0]), tMax - 1e-10);
    const basis = points.map((_, i) => coxDeBoor(t, i, order, knots));
    const rational = basis.reduce((sum, value, i) => sum + value * points[i].weight, 0);
    let x = 0;
    let y = 0;
    basis.forEach((value, i) => {
      if (value <= 1e-10 || rational <= 0) return;
      x += (value * points[i].x * points[i].weight) / rational;
      y += (value * points[i].y * points[i].weight) / rational;
      if (track && value > peakValue[i]) {
        peakValue[i] = value;
        peakParameter[i] = parameter;
      }
    });
    return { x, y };
  };
  const vertices: (SampledVertex & { parameter: number })[] = [];
  const delta = Math.min(0.001, tMax / steps);
  for (let i = 0; i <= steps; i++) {
    const parameter = (i * tMax) / steps;
    const at = evaluate(parameter, true);
    const near = i < steps ? evaluate(Math.min(parameter + delta, tMax), false) : evaluate(Math.max(parameter - delta, 0), false);
    const h = i < steps ? Math.atan2(near.y - at.y, near.x - at.x) : Math.atan2(at.y - near.y, at.x - near.x);
    vertices.push({ x: at.x, y: at.y, h: normalizeAngle(h), parameter });
  }
  if (points.every((point) => point.time !== undefined)) {
    let current = 0;
    const last = Math.max(2, points.length) - 2;
    for (const vertex of vertices) {
      if (vertex.parameter >= peakParameter[current + 1]) current = Math.min(current + 1, last);
      const span = peakParameter[current + 1] - peakParameter[current];
      const w = span > 0 ? (vertex.parameter - peakParameter[current]) / span : 0;
      vertex.time = (points[current].time ?? 0) + w * ((points[current + 1].time ?? 0) - (points[current].time ?? 0));
    }
  }
  return vertices.map(({ parameter: _parameter, ...vertex }) => vertex);
}

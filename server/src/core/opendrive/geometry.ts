/**
 * OpenDRIVE reference-line geometry (ASAM OpenDRIVE 1.6, section 7): line, arc, spiral (clothoid),
 * poly3 and paramPoly3. Each geometry is evaluated at a distance `ds` from its start, along its
 * arc length, in the road's inertial x/y frame.
 */

export interface Pose {
  x: number;
  y: number;
  /** Heading in radians, counter-clockwise from the x axis. */
  hdg: number;
}

interface GeometryStart {
  /** s of the geometry's start along the road. */
  s: number;
  x: number;
  y: number;
  hdg: number;
  length: number;
}

export type Geometry =
  | (GeometryStart & { kind: 'line' })
  | (GeometryStart & { kind: 'arc'; curvature: number })
  | (GeometryStart & { kind: 'spiral'; curvStart: number; curvEnd: number })
  | (GeometryStart & { kind: 'poly3'; a: number; b: number; c: number; d: number; arc?: ArcLengthTable })
  | (GeometryStart & {
      kind: 'paramPoly3';
      aU: number;
      bU: number;
      cU: number;
      dU: number;
      aV: number;
      bV: number;
      cV: number;
      dV: number;
      pRange: 'arcLength' | 'normalized';
      arc?: ArcLengthTable;
    });

// Gauss-Legendre nodes and weights on [-1, 1], 8 points: exact for polynomials of degree 15.
const GL_NODES = [
  -0.9602898564975363, -0.7966664774136267, -0.525532409916329, -0.1834346424956498, 0.1834346424956498, 0.525532409916329,
  0.7966664774136267, 0.9602898564975363,
];
const GL_WEIGHTS = [
  0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.362683783378362, 0.362683783378362, 0.3137066458778873, 0.2223810344533745,
  0.1012285362903763,
];

function integrate(f: (u: number) => number, from: number, to: number): number {
  const half = (to - from) / 2;
  const middle = (from + to) / 2;
  let sum = 0;
  for (let i = 0; i < GL_NODES.length; i++) sum += GL_WEIGHTS[i] * f(middle + half * GL_NODES[i]);
  return sum * half;
}

/**
 * The clothoid from the origin with heading 0 and curvature k0 + c·u: ∫cos θ, ∫sin θ with
 * θ(u) = k0·u + c·u²/2, by Gauss-Legendre on pieces short enough that θ turns at most 0.25 rad.
 */
function clothoid(k0: number, c: number, ds: number): { x: number; y: number } {
  const turn = Math.abs(k0) * ds + (Math.abs(c) * ds * ds) / 2;
  const pieces = Math.max(1, Math.ceil(Math.max(ds / 20, turn / 0.25)));
  const theta = (u: number) => k0 * u + (c * u * u) / 2;
  let x = 0;
  let y = 0;
  for (let i = 0; i < pieces; i++) {
    const from = (ds * i) / pieces;
    const to = (ds * (i + 1)) / pieces;
    x += integrate((u) => Math.cos(theta(u)), from, to);
    y += integrate((u) => Math.sin(theta(u)), from, to);
  }
  return { x, y };
}

/** Arc length as a function of a curve parameter, tabulated so that s → parameter is cheap and exact. */
export interface ArcLengthTable {
  /** Parameter values, evenly spaced from 0 to the parameter's end. */
  params: Float64Array;
  /** Arc length from the start to each parameter value. */
  lengths: Float64Array;
  /** Speed |dr/dp| of the curve. */
  speed: (p: number) => number;
}

const ARC_TABLE_STEPS = 64;

function arcLengthTable(speed: (p: number) => number, pEnd: number): ArcLengthTable {
  const params = new Float64Array(ARC_TABLE_STEPS + 1);
  const lengths = new Float64Array(ARC_TABLE_STEPS + 1);
  for (let i = 1; i <= ARC_TABLE_STEPS; i++) {
    params[i] = (pEnd * i) / ARC_TABLE_STEPS;
    lengths[i] = lengths[i - 1] + integrate(speed, params[i - 1], params[i]);
  }
  return { params, lengths, speed };
}

/** The parameter at arc length `s` (clamped to the curve): table lookup, then Newton steps on the exact integral. */
function parameterAt(table: ArcLengthTable, s: number): number {
  const { params, lengths, speed } = table;
  const last = params.length - 1;
  if (s <= 0) return 0;
  if (s >= lengths[last]) return params[last];
  let low = 0;
  let high = last;
  while (high - low > 1) {
    const middle = (low + high) >> 1;
    if (lengths[middle] <= s) low = middle;
    else high = middle;
  }
  const span = lengths[high] - lengths[low];
  let p = params[low] + (span > 0 ? ((s - lengths[low]) / span) * (params[high] - params[low]) : 0);
  for (let iteration = 0; iteration < 4; iteration++) {
    const error = lengths[low] + integrate(speed, params[low], p) - s;
    const v = speed(p);
    if (v <= 1e-12 || Math.abs(error) < 1e-9) break;
    p = Math.min(params[high], Math.max(params[low], p - error / v));
  }
  return p;
}

/**
 * The parameter at `ds` along the geometry. Arc length is scaled to the declared `length`, so that a
 * slightly inconsistent length attribute still ends the curve where the next geometry starts.
 */
function scaledParameter(table: ArcLengthTable, length: number, ds: number): number {
  const total = table.lengths[table.lengths.length - 1];
  return parameterAt(table, length > 0 ? (ds * total) / length : 0);
}

function cubic(a: number, b: number, c: number, d: number, p: number): number {
  return a + p * (b + p * (c + p * d));
}

function cubicSlope(b: number, c: number, d: number, p: number): number {
  return b + p * (2 * c + p * 3 * d);
}

function place(geometry: GeometryStart, u: number, v: number, localHeading: number): Pose {
  const cos = Math.cos(geometry.hdg);
  const sin = Math.sin(geometry.hdg);
  return { x: geometry.x + u * cos - v * sin, y: geometry.y + u * sin + v * cos, hdg: geometry.hdg + localHeading };
}

/** The pose at `ds` (0 ≤ ds ≤ length) along one geometry. */
export function evaluateGeometry(geometry: Geometry, ds: number): Pose {
  switch (geometry.kind) {
    case 'line':
      return place(geometry, ds, 0, 0);
    case 'arc': {
      const k = geometry.curvature;
      if (Math.abs(k) < 1e-15) return place(geometry, ds, 0, 0);
      // Chord form: exact for any curvature, no cancellation for small ones.
      const angle = k * ds;
      const u = Math.sin(angle) / k;
      const v = (1 - Math.cos(angle)) / k;
      return place(geometry, u, v, angle);
    }
    case 'spiral': {
      const k0 = geometry.curvStart;
      const c = geometry.length > 0 ? (geometry.curvEnd - geometry.curvStart) / geometry.length : 0;
      const { x, y } = clothoid(k0, c, ds);
      return place(geometry, x, y, k0 * ds + (c * ds * ds) / 2);
    }
    case 'poly3': {
      const { a, b, c, d } = geometry;
      geometry.arc ??= arcLengthTable((u) => Math.hypot(1, cubicSlope(b, c, d, u)), poly3End(geometry));
      const u = scaledParameter(geometry.arc, geometry.length, ds);
      return place(geometry, u, cubic(a, b, c, d, u), Math.atan(cubicSlope(b, c, d, u)));
    }
    case 'paramPoly3': {
      const g = geometry;
      const pEnd = g.pRange === 'normalized' ? 1 : g.length;
      g.arc ??= arcLengthTable((p) => Math.hypot(cubicSlope(g.bU, g.cU, g.dU, p), cubicSlope(g.bV, g.cV, g.dV, p)), pEnd);
      const p = scaledParameter(g.arc, g.length, ds);
      const du = cubicSlope(g.bU, g.cU, g.dU, p);
      const dv = cubicSlope(g.bV, g.cV, g.dV, p);
      return place(g, cubic(g.aU, g.bU, g.cU, g.dU, p), cubic(g.aV, g.bV, g.cV, g.dV, p), Math.atan2(dv, du));
    }
  }
}

/** The local u at which a poly3's arc length reaches its length (the curve ends there). */
function poly3End(geometry: Extract<Geometry, { kind: 'poly3' }>): number {
  const { b, c, d, length } = geometry;
  const speed = (u: number) => Math.hypot(1, cubicSlope(b, c, d, u));
  // Arc length grows at least as fast as u, so u ≤ length; bisect the arc-length equation.
  let low = 0;
  let high = length;
  for (let i = 0; i < 60; i++) {
    const middle = (low + high) / 2;
    let arc = 0;
    const pieces = 16;
    for (let j = 0; j < pieces; j++) arc += integrate(speed, (middle * j) / pieces, (middle * (j + 1)) / pieces);
    if (arc < length) low = middle;
    else high = middle;
  }
  return (low + high) / 2;
}

/** Curvature at `ds`, used to choose how densely a curve is sampled for drawing. */
export function curvatureBound(geometry: Geometry): number {
  switch (geometry.kind) {
    case 'line':
      return 0;
    case 'arc':
      return Math.abs(geometry.curvature);
    case 'spiral':
      return Math.max(Math.abs(geometry.curvStart), Math.abs(geometry.curvEnd));
    default: {
      // Estimate from the heading change between a few points.
      let bound = 0;
      const steps = 8;
      let previous = evaluateGeometry(geometry, 0).hdg;
      for (let i = 1; i <= steps; i++) {
        const next = evaluateGeometry(geometry, (geometry.length * i) / steps).hdg;
        bound = Math.max(bound, Math.abs(normalizeAngle(next - previous)) / (geometry.length / steps || 1));
        previous = next;
      }
      return bound * 2;
    }
  }
}

export function normalizeAngle(angle: number): number {
  let result = angle % (2 * Math.PI);
  if (result > Math.PI) result -= 2 * Math.PI;
  if (result < -Math.PI) result += 2 * Math.PI;
  return result;
}

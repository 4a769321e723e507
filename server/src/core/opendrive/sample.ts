import { curvatureBound } from './geometry';
import { besidePose, Cubic, isDrivingLane, LaneSection, outerBorderTs, referencePose, Road, RoadNetwork, roadCubicAt } from './road';
import type { SectionPolylines } from '../../../../common/src/sectionPolylines';

export interface SamplingOptions {
  /** Largest distance between a drawn chord and the curve, in metres. */
  chordError?: number;
  /** Longest step along s on a straight road whose lane widths change linearly at most. */
  maxStep?: number;
  /** Longest step where the road's superelevation changes. */
  maxCurvedStep?: number;
}

function isLinear(cubics: Cubic[]): boolean {
  return cubics.every((cubic) => cubic.c === 0 && cubic.d === 0);
}

/** The s values at which a section is sampled: its ends, every place where a geometry, width or offset record starts, and enough between. */
function sectionStations(road: Road, section: LaneSection, options: Required<SamplingOptions>): number[] {
  const start = section.s;
  const end = section.s + section.length;
  const breaks = new Set<number>([start, end]);
  for (const geometry of road.geometries) if (geometry.s > start && geometry.s < end) breaks.add(geometry.s);
  for (const offset of road.laneOffsets) if (offset.start > start && offset.start < end) breaks.add(offset.start);
  for (const lane of section.lanes)
    for (const width of lane.widths) if (width.start > 0 && width.start < section.length) breaks.add(start + width.start);
  const sorted = [...breaks].sort((a, b) => a - b);
  // How fast the borders bend sideways from cubic widths and offsets: |2c| + |6d|·L summed outward, a bound on t''.
  const bend = (cubics: Cubic[], span: number) =>
    cubics.reduce((worst, cubic) => Math.max(worst, Math.abs(2 * cubic.c) + Math.abs(6 * cubic.d) * span), 0);
  const lateralBend =
    bend(road.laneOffsets, section.length) +
    section.lanes.reduce((sum, lane) => sum + bend(lane.widths, section.length) + bend(lane.borders, section.length), 0);
  const rolling = !isLinear(road.superelevations);
  const stations: number[] = [];
  for (let i = 0; i + 1 < sorted.length; i++) {
    const from = sorted[i];
    const to = sorted[i + 1];
    const geometry = road.geometries.find(
      (candidate, index) =>
        candidate.s <= from + 1e-9 && (index + 1 === road.geometries.length || road.geometries[index + 1].s > from + 1e-9),
    );
    const curvature = geometry ? curvatureBound(geometry) : 0;
    let step = rolling ? options.maxCurvedStep : options.maxStep;
    // Chord error of a curve bending by k (1/m) over a step h is about k·h²/8.
    const bending = curvature + lateralBend;
    if (bending > 0) step = Math.min(step, Math.sqrt((8 * options.chordError) / bending));
    const count = Math.max(1, Math.ceil((to - from) / step));
    for (let k = 0; k < count; k++) stations.push(from + ((to - from) * k) / count);
  }
  stations.push(end);
  return stations;
}

const round = (value: number) => Math.round(value * 100) / 100;

/** The lane borders of every lane section of every road, as polylines ready to draw. */
export function sampleNetwork(network: RoadNetwork, options: SamplingOptions = {}): SectionPolylines[] {
  const settings: Required<SamplingOptions> = {
    chordError: options.chordError ?? 0.03,
    maxStep: options.maxStep ?? 25,
    maxCurvedStep: options.maxCurvedStep ?? 2,
  };
  const result: SectionPolylines[] = [];
  for (const road of network.roads) {
    road.laneSections.forEach((section, index) => {
      if (section.length <= 0 || section.lanes.length === 0) return;
      const stations = sectionStations(road, section, settings);
      const borders = section.lanes.map(() => new Array<number>(stations.length * 2));
      const offsets = new Float64Array(section.lanes.length);
      stations.forEach((station, k) => {
        // Just inside the section at its end, as esmini samples it, so that the next section's widths do not apply.
        const s = k === stations.length - 1 ? Math.max(section.s, station - 1e-9) : station;
        const offset = roadCubicAt(road.laneOffsets, s);
        const pose = referencePose(road, s);
        const roll = roadCubicAt(road.superelevations, s);
        outerBorderTs(section, s, offsets);
        for (let laneIndex = 0; laneIndex < offsets.length; laneIndex++) {
          const point = besidePose(pose, roll, offset + offsets[laneIndex]);
          borders[laneIndex][2 * k] = round(point.x);
          borders[laneIndex][2 * k + 1] = round(point.y);
        }
      });
      result.push({
        road: road.id,
        section: index,
        junction: road.junction !== '-1' && road.junction !== '',
        lanes: section.lanes.map((lane) => ({ id: lane.id, type: lane.type, driving: isDrivingLane(lane) })),
        borders,
      });
    });
  }
  return result;
}

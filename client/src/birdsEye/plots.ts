/**
 * Plots over a run's time for the chosen entity, drawn with a Painter (canvas or SVG): its speed, and its
 * gap and time-to-collision against each other entity, as small multiples side by side, the current
 * time marked. No DOM.
 */
import type { RunSeries } from './analysis';
import type { Painter } from './draw';

export const PLOT_COLORS = { background: '#1e1e1e', axis: '#9e9e9e', text: '#d4d4d4', cursor: '#ffffff', threshold: '#ef5350' };

/** Time-to-collision above this is not plotted (it says nothing about a near miss). */
export const TTC_CEILING_S = 10;

/** A time-to-collision below this is a near miss: its line is drawn and labelled on the TTC plot. */
export const TTC_THRESHOLD_S = 1.5;

/** Gaps beyond this say nothing about the interaction and would flatten the near ones. */
export const GAP_CEILING_M = 200;

export interface PlotSpec {
  title: string;
  unit: string;
  lines: { name: string; values: number[] }[];
  /** The value range drawn; values outside are clipped. */
  low: number;
  high: number;
  /** A value worth a line of its own (e.g. a TTC of 1.5 s). */
  threshold?: number;
}

/** A round step: 1, 2 or 5 × 10^k at or above `value`. */
export function niceCeiling(value: number): number {
  if (!(value > 0)) return 1;
  const power = 10 ** Math.floor(Math.log10(value));
  return [1, 2, 5, 10].map((step) => step * power).find((candidate) => candidate >= value - 1e-9) ?? 10 * power;
}

/**
 * The range a plot draws: its finite values up to `ceiling` (and `include`, at most `ceiling`), with a margin, on round
 * steps; never below 0 when no value is (a 10 m/s line would hug the top of a 0..20 axis, a gap of a
 * few metres vanish on a 0..200 axis).
 */
export function plotRange(lists: number[][], fallback: [number, number], ceiling = Infinity, include?: number): [number, number] {
  let least = include ?? Infinity;
  let most = include ?? -Infinity;
  for (const list of lists)
    for (const value of list) {
      if (!Number.isFinite(value) || value > ceiling) continue;
      if (value < least) least = value;
      if (value > most) most = value;
    }
  if (!(most >= least)) return fallback;
  const margin = Math.max((most - least) * 0.1, Math.abs(most) * 0.05, 0.5);
  const step = niceCeiling((most - least + 2 * margin) / 4);
  const low = Math.floor((least - margin) / step) * step;
  const high = Math.ceil((most + margin) / step) * step;
  return [least >= 0 ? Math.max(0, low) : low, Math.min(high, ceiling)];
}

/** An axis label: no float noise (0.30000000000000004). */
export function tickLabel(value: number): string {
  return String(Number(value.toPrecision(6)));
}

/** The three plots for a run's series: speed of the chosen entity, gap and TTC to each other. */
export function plotSpecs(series: RunSeries): PlotSpec[] {
  const gaps = series.others.map((other) => ({ name: other.name, values: other.gap }));
  const ttcs = series.others.map((other) => ({ name: other.name, values: other.ttc }));
  const [speedLow, speedHigh] = plotRange([series.speed], [0, 1]);
  const [gapLow, gapHigh] = plotRange(
    gaps.map((gap) => gap.values),
    [0, 10],
    GAP_CEILING_M,
  );
  const [ttcLow, ttcHigh] = plotRange(
    ttcs.map((ttc) => ttc.values),
    [0, TTC_CEILING_S],
    TTC_CEILING_S,
    TTC_THRESHOLD_S,
  );
  return [
    {
      title: `speed of ${series.chosen}`,
      unit: 'm/s',
      lines: [{ name: series.chosen, values: series.speed }],
      low: speedLow,
      high: speedHigh,
    },
    { title: `gap from ${series.chosen}`, unit: 'm', lines: gaps, low: gapLow, high: gapHigh },
    {
      title: `time to collision with ${series.chosen}`,
      unit: 's',
      lines: ttcs,
      low: ttcLow,
      high: ttcHigh,
      threshold: TTC_THRESHOLD_S,
    },
  ];
}

/** Where a plot's axes are, px, and the times they span; for marking the time on them. */
export interface PlotArea {
  left: number;
  right: number;
  top: number;
  bottom: number;
  t0: number;
  t1: number;
}

/** The current time's mark on each plot. */
export function drawPlotCursor(painter: Painter, areas: PlotArea[], time: number): void {
  for (const area of areas) {
    const x = area.left + ((Math.min(Math.max(time, area.t0), area.t1) - area.t0) / (area.t1 - area.t0)) * (area.right - area.left);
    painter.polyline([x, area.top, x, area.bottom], PLOT_COLORS.cursor, 1);
  }
}

/**
 * Draws `specs` side by side in the rectangle (x, y, width, height), the time `time` marked on each
 * (none when undefined: the view draws the mark per frame over a cached picture).
 */
export function drawPlots(
  painter: Painter,
  specs: PlotSpec[],
  times: number[],
  time: number | undefined,
  x: number,
  y: number,
  width: number,
  height: number,
  colorOf: (name: string) => string,
): PlotArea[] {
  painter.polygon([x, y, x + width, y, x + width, y + height, x, y + height], PLOT_COLORS.background);
  const areas: PlotArea[] = [];
  if (specs.length === 0 || times.length === 0) return areas;
  const gap = 10;
  const each = (width - gap * (specs.length + 1)) / specs.length;
  const t0 = times[0];
  const t1 = Math.max(times[times.length - 1], t0 + 1e-6);
  specs.forEach((spec, index) => {
    const left = x + gap + index * (each + gap) + 30;
    const right = x + gap + index * (each + gap) + each;
    const top = y + 20;
    const bottom = y + height - 18;
    if (right - left < 10 || bottom - top < 10) return;
    const sx = (t: number) => left + ((t - t0) / (t1 - t0)) * (right - left);
    const sy = (value: number) =>
      bottom - ((Math.min(Math.max(value, spec.low), spec.high) - spec.low) / (spec.high - spec.low)) * (bottom - top);
    painter.text(left - 30, y + 13, `${spec.title} (${spec.unit})`, PLOT_COLORS.text, 11);
    painter.polyline([left, top, left, bottom, right, bottom], PLOT_COLORS.axis, 1);
    painter.text(left - 28, top + 8, tickLabel(spec.high), PLOT_COLORS.axis, 10);
    painter.text(left - 28, bottom, tickLabel(spec.low), PLOT_COLORS.axis, 10);
    painter.text(left, bottom + 13, `${t0.toFixed(0)} s`, PLOT_COLORS.axis, 10);
    painter.text(right - 30, bottom + 13, `${t1.toFixed(0)} s`, PLOT_COLORS.axis, 10);
    if (spec.threshold !== undefined) {
      painter.polyline([left, sy(spec.threshold), right, sy(spec.threshold)], PLOT_COLORS.threshold, 1, [3, 3]);
      painter.text(right - 48, sy(spec.threshold) - 3, `${tickLabel(spec.threshold)} ${spec.unit}`, PLOT_COLORS.threshold, 10);
    }
    for (const line of spec.lines) {
      // A gap in the data (NaN: no TTC while not closing in) breaks the line.
      let run: number[] = [];
      const flush = () => {
        if (run.length >= 4) painter.polyline(run, colorOf(line.name), 1.5);
        run = [];
      };
      // At most about one point per pixel.
      const every = Math.max(1, Math.floor(times.length / Math.max(1, right - left)));
      for (let i = 0; i < times.length; i += every) {
        const value = line.values[i];
        if (!Number.isFinite(value) || value > spec.high * 1.5) {
          flush();
          continue;
        }
        run.push(sx(times[i]), sy(value));
      }
      flush();
    }
    areas.push({ left, right, top, bottom, t0, t1 });
  });
  if (time !== undefined) drawPlotCursor(painter, areas, time);
  return areas;
}

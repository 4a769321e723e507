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

function finiteMax(lists: number[][], fallback: number): number {
  let most = -Infinity;
  for (const list of lists) for (const value of list) if (Number.isFinite(value) && value > most) most = value;
  return Number.isFinite(most) ? most : fallback;
}

/** A round upper bound: 1, 2 or 5 × 10^k at or above `value`. */
export function niceCeiling(value: number): number {
  if (!(value > 0)) return 1;
  const power = 10 ** Math.floor(Math.log10(value));
  return [1, 2, 5, 10].map((step) => step * power).find((candidate) => candidate >= value - 1e-9) ?? 10 * power;
}

/** The three plots for a run's series: speed of the chosen entity, gap and TTC to each other. */
export function plotSpecs(series: RunSeries): PlotSpec[] {
  const gaps = series.others.map((other) => ({ name: other.name, values: other.gap }));
  return [
    {
      title: `speed of ${series.chosen}`,
      unit: 'm/s',
      lines: [{ name: series.chosen, values: series.speed }],
      low: 0,
      high: niceCeiling(finiteMax([series.speed], 1)),
    },
    {
      title: `gap from ${series.chosen}`,
      unit: 'm',
      lines: gaps,
      low: 0,
      high: niceCeiling(
        Math.min(
          finiteMax(
            gaps.map((gap) => gap.values),
            10,
          ),
          200,
        ),
      ),
    },
    {
      title: `time to collision with ${series.chosen}`,
      unit: 's',
      lines: series.others.map((other) => ({ name: other.name, values: other.ttc })),
      low: 0,
      high: TTC_CEILING_S,
      threshold: 1.5,
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
    painter.text(left - 28, top + 8, String(spec.high), PLOT_COLORS.axis, 10);
    painter.text(left - 28, bottom, String(spec.low), PLOT_COLORS.axis, 10);
    painter.text(left, bottom + 13, `${t0.toFixed(0)} s`, PLOT_COLORS.axis, 10);
    painter.text(right - 30, bottom + 13, `${t1.toFixed(0)} s`, PLOT_COLORS.axis, 10);
    if (spec.threshold !== undefined)
      painter.polyline([left, sy(spec.threshold), right, sy(spec.threshold)], PLOT_COLORS.threshold, 1, [3, 3]);
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

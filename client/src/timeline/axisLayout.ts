/**
 * The storyboard timeline's time axis: how far it reaches, and where its labels go so that none wraps, leaves the
 * track or covers another. Pure: the timeline's page (webview/main.ts) measures the text, this places it, its test checks.
 */

/** While a session runs, the current time stands at most this far along the axis: the bar just started has room. */
export const LIVE_TIME_FRACTION = 0.8;
/** Ticks aimed at: about this many along the axis, fewer where their labels do not fit. */
const TICKS = 8;
/** The least space between two labels, px. */
const LABEL_GAP = 8;

/** A round step (1, 2 or 5 times a power of ten) of at least `rough`. */
export function niceStep(rough: number): number {
  if (!(rough > 0) || !Number.isFinite(rough)) return 1;
  const power = 10 ** Math.floor(Math.log10(rough));
  return [1, 2, 5, 10].map((factor) => factor * power).find((candidate) => candidate >= rough * (1 - 1e-12)) ?? 10 * power;
}

/**
 * The time the axis reaches, s. A finished run's axis ends where the run did (`end`); a running session's reaches
 * past its current time `end` to a round tick, so that the time stands at most LIVE_TIME_FRACTION along it.
 */
export function axisEnd(end: number, live: boolean): number {
  if (!live) return end > 0 ? end : 1;
  const least = Math.max(end, 0) / LIVE_TIME_FRACTION;
  if (!(least > 0)) return 1;
  const step = niceStep(least / TICKS);
  return Math.ceil(least / step - 1e-9) * step;
}

export interface AxisLabel {
  time: number;
  text: string;
  /** The label's left end, px from the track's left end. */
  x: number;
  width: number;
  /** The tick's place, px from the track's left end (the label starts there unless that would leave the track). */
  tick: number;
}

/** Seconds as an axis label writes them: `12.5 s`. */
export const axisText = (time: number) => `${Number(time.toFixed(3))} s`;

/**
 * The labels of an axis spanning 0 to `end` s on a track `width` px wide, `measure`d in the page's font: a round
 * step wide enough for the widest label, each label starting at its tick, the last moved left to end on the track
 * (and left out when that brings it onto the one before). The page writes them without wrapping.
 */
export function axisLabels(end: number, width: number, measure: (text: string) => number): AxisLabel[] {
  if (!(end > 0) || !(width > 0)) return [];
  const pixels = (time: number) => (time / end) * width;
  // The widest a label can be: the end's (the longest number of whole seconds), with the step's decimals.
  const widest = (step: number) => Math.ceil(measure(axisText(end + step / 3))) + 1;
  let step = niceStep(end / TICKS);
  // Wider steps until a label fits between two ticks (the last one or two may still be dropped when the end is near).
  for (let tries = 0; tries < 8 && pixels(step) < widest(step) + LABEL_GAP; tries++) step = niceStep(step * 1.5);
  const labels: AxisLabel[] = [];
  for (let index = 0; index * step <= end * (1 + 1e-9); index++) {
    const time = Number((index * step).toFixed(9));
    const text = axisText(time);
    const labelWidth = Math.min(Math.ceil(measure(text)) + 1, width);
    const tick = pixels(time);
    const x = Math.max(0, Math.min(tick, width - labelWidth));
    const previous = labels[labels.length - 1];
    // Only the last label, moved left to stay on the track, can reach the one before: it is left out then.
    if (previous && x < previous.x + previous.width + LABEL_GAP) continue;
    labels.push({ time, text, x, width: labelWidth, tick });
  }
  return labels;
}

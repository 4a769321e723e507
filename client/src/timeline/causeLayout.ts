/**
 * Where the storyboard timeline writes the condition that fired each bar's start, so that no label covers a bar or
 * another label. Pure: the timeline's page (webview/main.ts) measures the text, this places it, its test checks.
 */
import { describeFiring, type TimelineRow } from '../../../common/src/storyboardTimeline';

/** A row's geometry, CSS px: the bar line on top, the label lines (lanes) below it. */
export const ROW_GEOMETRY = {
  /** A row with no label line: the bar line alone. */
  rowHeight: 22,
  barTop: 4,
  barHeight: 14,
  /** Each label line below the bar line. */
  laneHeight: 13,
  /** The least space between a label and a bar or another label. */
  gap: 4,
} as const;

/** One bar of a row, px from the track's left end. */
export interface TrackBar {
  start: number;
  end: number;
  /** The width of the label of the condition that fired its start (its text measured in the page's font); none: no label. */
  labelWidth?: number;
}

/** A bar of a timeline row with its cause's words. */
export interface CauseBar extends TrackBar {
  cause?: string;
}

/**
 * A timeline row's bars on a track `width` px wide spanning 0 to `end` s (a bar still running reaches `now`, the
 * trace's last time: the axis's end but in a running session, whose axis reaches further), each with the words of
 * the condition that fired its start, `measure`d.
 */
export function rowBars(row: TimelineRow, end: number, width: number, measure: (text: string) => number, now = end): CauseBar[] {
  const pixels = (time: number) => (end > 0 ? (Math.min(Math.max(time, 0), end) / end) * width : 0);
  return row.spans.map((span) => {
    const cause = span.cause ? describeFiring(span.cause) : undefined;
    return {
      start: pixels(span.start),
      end: pixels(span.end ?? now),
      ...(cause ? { cause, labelWidth: Math.ceil(measure(cause)) + 1 } : {}),
    };
  });
}

export interface PlacedCause {
  /** The bar's index in its row. */
  bar: number;
  /** The label's left end, px from the track's left end. */
  x: number;
  /** Its width: the text's, or less where the track is narrower (the page cuts the text with an ellipsis). */
  width: number;
  /** 0: on the bar line, just before the bar; 1, 2, ...: the label lines below it. */
  lane: number;
}

export interface RowLayout {
  labels: PlacedCause[];
  /** Label lines below the bar line. */
  lanes: number;
  /** The row's height, px. */
  height: number;
}

/** Left ends and right ends of what a line holds, px. */
type Interval = [number, number];

const free = (taken: readonly Interval[], from: number, to: number, gap: number) =>
  taken.every(([start, end]) => to + gap <= start || end + gap <= from);

/**
 * Places a row's labels, bar by bar from the earliest start: on the bar line ending just before the bar's start
 * where that stretch holds no bar and no label, else on the first label line below where it fits starting at the
 * bar's start (moved left to stay on the track). A label never overlaps a bar or another label of the row; rows
 * do not overlap, as each is as high as its lines.
 */
export function layoutRow(bars: readonly TrackBar[], trackWidth: number, geometry = ROW_GEOMETRY): RowLayout {
  const { gap } = geometry;
  const width = Math.max(0, trackWidth);
  // The bar line holds the bars; a bar narrower than a pixel still takes one (the page draws it 2 px wide).
  const lines: Interval[][] = [bars.map((bar) => [bar.start, Math.max(bar.end, bar.start + 2)])];
  const labels: PlacedCause[] = [];
  const order = bars.map((bar, index) => ({ bar, index })).sort((a, b) => a.bar.start - b.bar.start || a.index - b.index);
  for (const { bar, index } of order) {
    if (bar.labelWidth === undefined || !(bar.labelWidth > 0)) continue;
    const labelWidth = Math.min(bar.labelWidth, width);
    const before = bar.start - gap - labelWidth;
    if (before >= 0 && free(lines[0], before, before + labelWidth, gap)) {
      lines[0].push([before, before + labelWidth]);
      labels.push({ bar: index, x: before, width: labelWidth, lane: 0 });
      continue;
    }
    const x = Math.max(0, Math.min(bar.start, width - labelWidth));
    let lane = 1;
    while (lines[lane] && !free(lines[lane], x, x + labelWidth, gap)) lane++;
    (lines[lane] ??= []).push([x, x + labelWidth]);
    labels.push({ bar: index, x, width: labelWidth, lane });
  }
  const lanes = lines.length - 1;
  return { labels, lanes, height: geometry.rowHeight + lanes * geometry.laneHeight };
}

/** A placed label's top, px from its row's top: level with the bar on the bar line, else on its label line. */
export function labelTop(lane: number, geometry = ROW_GEOMETRY): number {
  return lane === 0 ? geometry.barTop : geometry.rowHeight + (lane - 1) * geometry.laneHeight;
}

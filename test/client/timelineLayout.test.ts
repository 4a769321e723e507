import * as assert from 'node:assert/strict';
import { axisEnd, axisLabels, LIVE_TIME_FRACTION } from '../../client/src/timeline/axisLayout';
import { labelTop, layoutRow, ROW_GEOMETRY, rowBars, type RowLayout, type TrackBar } from '../../client/src/timeline/causeLayout';
import { storyboardTimeline, type Timeline } from '../../common/src/storyboardTimeline';
import type { TraceRecord } from '../../common/src/trace';

/** A box on the page: left, top, right, bottom (px). */
type Box = [number, number, number, number];
const overlaps = (a: Box, b: Box) => a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];

/** What a timeline drawn `width` px wide puts on the page, rows stacked: every bar's box and every label's. */
function drawn(timeline: Timeline, width: number, measure: (text: string) => number) {
  const bars: { box: Box; row: number }[] = [];
  const labels: { box: Box; row: number; text: string; lane: number; bar: TrackBar }[] = [];
  const layouts: RowLayout[] = [];
  let top = 0;
  timeline.rows.forEach((row, index) => {
    const rowBarsOf = rowBars(row, timeline.end, width, measure);
    const layout = layoutRow(rowBarsOf, width);
    layouts.push(layout);
    for (const bar of rowBarsOf)
      bars.push({
        box: [bar.start, top + ROW_GEOMETRY.barTop, Math.max(bar.end, bar.start + 2), top + ROW_GEOMETRY.barTop + ROW_GEOMETRY.barHeight],
        row: index,
      });
    for (const label of layout.labels) {
      const labelTopPx = top + labelTop(label.lane);
      const height = label.lane === 0 ? ROW_GEOMETRY.barHeight : ROW_GEOMETRY.laneHeight;
      labels.push({
        box: [label.x, labelTopPx, label.x + label.width, labelTopPx + height],
        row: index,
        text: rowBarsOf[label.bar].cause ?? '',
        lane: label.lane,
        bar: rowBarsOf[label.bar],
      });
    }
    top += layout.height;
  });
  return { bars, labels, layouts, height: top };
}

/** Every overlap of a label with a bar or another label, in words; none is what the layout promises. */
function coverings(page: ReturnType<typeof drawn>): string[] {
  const found: string[] = [];
  page.labels.forEach((label, index) => {
    for (const bar of page.bars)
      if (overlaps(label.box, bar.box)) found.push(`'${label.text}' (row ${label.row}) covers a bar of row ${bar.row}`);
    for (const other of page.labels.slice(index + 1))
      if (overlaps(label.box, other.box)) found.push(`'${label.text}' (row ${label.row}) covers '${other.text}' (row ${other.row})`);
  });
  return found;
}

/** An Event started by a condition at `time` (the records run --trace writes), ending `length` s later. */
function firedEvent(path: string, time: number, length: number, measured: number): TraceRecord[] {
  return [
    {
      time,
      element: `${path}::Start`,
      type: 'Condition',
      state: 'true',
      condition: 'RelativeDistanceCondition',
      rule: 'greaterThan',
      threshold: 20,
      measured,
      quantity: 'rel_dist',
    },
    { time, element: path, type: 'Event', state: 'running' },
    { time: time + length, element: path, type: 'Event', state: 'complete' },
  ];
}

/** About the width of 10 px text in a sans-serif font. */
const measure = (text: string) => text.length * 5.6;
const MANEUVER = 'Story::Act::Group::Maneuver';

describe('storyboard timeline: where the firing conditions are written', () => {
  it('covers no bar and no other label when 60 events start at the same time, and none starting at 0 s', () => {
    const records: TraceRecord[] = [];
    for (let index = 0; index < 60; index++) records.push(...firedEvent(`${MANEUVER}::Cut${index}`, 4, 2 + (index % 5), 20 + index / 10));
    for (let index = 0; index < 20; index++) records.push(...firedEvent(`${MANEUVER}::Early${index}`, 0, 1, 21));
    const timeline = storyboardTimeline(records, 10);
    for (const width of [120, 400, 900]) {
      const page = drawn(timeline, width, measure);
      assert.deepEqual(coverings(page), [], `at ${width} px`);
      assert.equal(page.labels.length, 80, `every start has its label at ${width} px`);
      for (const label of page.labels) assert.ok(label.box[0] >= 0 && label.box[2] <= width + 1e-9, `'${label.text}' on the track`);
    }
    // Where there is room, the words end just before the bar they started, on its line.
    const wide = drawn(timeline, 2000, measure);
    const cut = wide.labels.filter((label) => label.text.includes('20.3'));
    assert.equal(cut.length, 1);
    assert.equal(cut[0].lane, 0);
    assert.ok(Math.abs(cut[0].box[2] + ROW_GEOMETRY.gap - cut[0].bar.start) < 1e-9, 'ends a gap before the bar');
    // A bar starting at 0 s has no room before it: its words go on a line below, the row growing to hold it.
    const earlyRows = timeline.rows.flatMap((row, index) => (row.name.startsWith('Early') ? [index] : []));
    const early = wide.labels.filter((label) => earlyRows.includes(label.row));
    assert.equal(early.length, 20);
    assert.ok(early.every((label) => label.lane === 1 && label.box[0] === 0));
    assert.ok(earlyRows.every((row) => wide.layouts[row].height === ROW_GEOMETRY.rowHeight + ROW_GEOMETRY.laneHeight));
  });

  it('covers nothing when one event starts again and again, each start fired by its own condition', () => {
    const records: TraceRecord[] = [];
    // maximumExecutionCount 40: the event fires every 0.25 s for 0.1 s; its words cannot all stand beside its bars.
    for (let index = 0; index < 40; index++) records.push(...firedEvent(`${MANEUVER}::Pulse`, 1 + index * 0.25, 0.1, 20 + index));
    const timeline = storyboardTimeline(records, 12);
    for (const width of [300, 800]) {
      const page = drawn(timeline, width, measure);
      assert.deepEqual(coverings(page), [], `at ${width} px`);
      assert.equal(page.labels.length, 40);
      const pulse = page.layouts[timeline.rows.findIndex((row) => row.name === 'Pulse')];
      assert.ok(pulse.lanes > 1, `the row grows lines for the labels: ${pulse.lanes}`);
      assert.equal(pulse.height, ROW_GEOMETRY.rowHeight + pulse.lanes * ROW_GEOMETRY.laneHeight);
    }
  });

  it('keeps a label wider than the track on the track, and writes nothing for a start no condition fired', () => {
    const wide = layoutRow(
      [
        { start: 50, end: 80, labelWidth: 500 },
        { start: 90, end: 100 },
      ],
      200,
    );
    assert.deepEqual(wide.labels, [{ bar: 0, x: 0, width: 200, lane: 1 }]);
    assert.equal(wide.lanes, 1);
    assert.deepEqual(layoutRow([], 200), { labels: [], lanes: 0, height: ROW_GEOMETRY.rowHeight });
  });
});

describe('storyboard timeline: the time axis', () => {
  it("gives a running session's current time room after it, the bar just stopped on drawn before the axis's end", () => {
    for (const now of [0.05, 1, 2.35, 6.5, 8, 9.99, 10, 37.2, 1234.5]) {
      const end = axisEnd(now, true);
      assert.ok(now / end <= LIVE_TIME_FRACTION + 1e-9, `${now} s on an axis to ${end} s`);
      // Room, not a far-off end: the time stands at least half way along.
      assert.ok(now / end >= 0.4, `${now} s on an axis to ${end} s`);
    }
    assert.equal(axisEnd(0, true), 1);
    // cut-in.xosc stopped on CutInEvent at 6.5 s: its bar (open, to the current time) starts well before the track's end.
    const records: TraceRecord[] = [
      { time: 0, element: 'Story', type: 'Story', state: 'running' },
      { time: 6.5, element: 'Story::Act::G::M::CutInEvent', type: 'Event', state: 'running' },
    ];
    const timeline = storyboardTimeline(records, 6.5);
    const row = timeline.rows.find((candidate) => candidate.name === 'CutInEvent');
    assert.ok(row);
    const [bar] = rowBars(row, axisEnd(timeline.end, true), 600, measure, timeline.end);
    assert.ok(bar.start <= 600 * LIVE_TIME_FRACTION && bar.start > 300, `the bar starts at ${bar.start} px of 600`);
    assert.equal(bar.end, bar.start, 'a bar still running reaches the current time, not the axis end');
    // A finished run's axis ends where the run did.
    assert.equal(axisEnd(20.05, false), 20.05);
  });

  it('writes every axis label whole on the track, none over another, the first at 0 s, at any width and end', () => {
    for (const width of [60, 150, 333, 600, 1400])
      for (const end of [0.3, 1, 6.5, 8.125, 10, 20.05, 99.9, 3600]) {
        for (const live of [false, true]) {
          const axis = axisEnd(end, live);
          const labels = axisLabels(axis, width, measure);
          const where = `${width} px, axis to ${axis} s`;
          assert.ok(labels.length >= 1, where);
          assert.equal(labels[0].time, 0, where);
          for (const [index, label] of labels.entries()) {
            // Whole: as wide as its text (the page writes it without wrapping), unless the track is narrower.
            assert.ok(label.width >= Math.min(measure(label.text), width), `${where}: '${label.text}' ${label.width} px`);
            assert.ok(label.x >= 0 && label.x + label.width <= width + 1e-9, `${where}: '${label.text}' on the track`);
            const next = labels[index + 1];
            if (next) assert.ok(label.x + label.width < next.x, `${where}: '${label.text}' covers '${next.text}'`);
            // At its tick, but the last, moved left to end on the track.
            if (next) assert.ok(Math.abs(label.x - label.tick) < 1e-9, `${where}: '${label.text}' at its tick`);
            assert.ok(label.time <= axis * (1 + 1e-9), where);
          }
        }
      }
    // A running session stopped at 8 s: the axis to 10 s, its label kept whole at the right end.
    const labels = axisLabels(axisEnd(8, true), 600, measure);
    const last = labels[labels.length - 1];
    assert.equal(last.text, '10 s');
    assert.equal(last.x + last.width, 600);
  });
});

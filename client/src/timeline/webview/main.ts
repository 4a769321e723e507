/**
 * The storyboard timeline's page: one row per storyboard element, a bar per start (the condition that fired it
 * written at its start), elements that never started with what they waited for, and the current time's cursor. A
 * click on a row's name asks the extension to open its source; a click on the bars sets the time (the bird's-eye
 * view follows).
 */
import { describeCondition, describeFiring, describeRow, type Timeline, type TimelineRow } from '../../../../common/src/storyboardTimeline';
import { axisEnd, axisLabels } from '../axisLayout';
import { labelTop, layoutRow, ROW_GEOMETRY, rowBars } from '../causeLayout';
import type { FromView, ToView } from '../messages';

declare function acquireVsCodeApi(): { postMessage(message: FromView): void };
const vscode = acquireVsCodeApi();

const rowsElement = document.getElementById('rows') as HTMLDivElement;
const title = document.getElementById('title') as HTMLSpanElement;
const timeLabel = document.getElementById('time') as HTMLSpanElement;

let timeline: Timeline | undefined;
let time = 0;
/** The time the axis reaches: the run's end, or past the current time while a session runs (axisLayout.ts). */
let end = 1;
let live = false;
/** The tracks' horizontal span: the rows' track elements share it. */
let tracks: HTMLDivElement[] = [];

const percent = (value: number) => `${end > 0 ? (Math.min(Math.max(value, 0), end) / end) * 100 : 0}%`;

function render(label: string): void {
  title.textContent = `${label}${live ? ' (running)' : ''}`;
  // Cut with an ellipsis where the panel is narrow: the whole title on hover.
  title.title = title.textContent;
  rowsElement.replaceChildren();
  tracks = [];
  if (!timeline || timeline.rows.length === 0) {
    rowsElement.append(Object.assign(document.createElement('div'), { id: 'empty', textContent: 'No storyboard transitions yet.' }));
    report();
    return;
  }
  /** Each row with its line and track: the words of its firing conditions placed once the tracks' width is known. */
  const placements: { line: HTMLDivElement; track: HTMLDivElement; row: TimelineRow }[] = [];
  for (const row of timeline.rows) {
    const line = document.createElement('div');
    line.className = 'row';
    line.dataset.element = row.element;
    const name = document.createElement('div');
    name.className = 'label';
    name.style.paddingLeft = `${row.depth * 12}px`;
    name.title = `${row.element}${row.file ? `\n${row.file}${row.line ? `:${row.line}` : ''}` : ''}\n${describeRow(row)}`;
    name.append(Object.assign(document.createElement('span'), { className: 'kind', textContent: row.type }), row.name);
    if (row.group && row.type !== 'ManeuverGroup' && row.depth === 3)
      name.append(Object.assign(document.createElement('span'), { className: 'group', textContent: `(${row.group})` }));
    name.addEventListener('click', () => vscode.postMessage({ type: 'open', element: row.element }));
    const track = document.createElement('div');
    track.className = 'track';
    track.addEventListener('click', (event) => {
      const box = track.getBoundingClientRect();
      if (box.width > 0) vscode.postMessage({ type: 'time', time: ((event.clientX - box.left) / box.width) * end });
    });
    for (const span of row.spans) {
      const bar = document.createElement('div');
      bar.className = `bar ${row.type}${span.end === undefined ? ' open' : ''}`;
      bar.style.left = percent(span.start);
      bar.style.width = `calc(${percent(span.end ?? timeline.end)} - ${percent(span.start)})`;
      bar.title = `${row.type} ${row.name}: ${span.start.toFixed(2)} s to ${span.end === undefined ? 'the end' : `${span.end.toFixed(2)} s`}${span.cause ? `\nstarted by ${describeFiring(span.cause)}${span.cause.esmini ? `\nesmini: ${span.cause.esmini}` : ''}` : ''}`;
      track.append(bar);
    }
    placements.push({ line, track, row });
    if (!row.started) {
      const never = document.createElement('div');
      never.className = 'never';
      never.textContent = `never started${row.waitsFor?.length ? `: ${row.waitsFor.map(describeCondition).join(' or ')} never became true` : ''}`;
      track.append(never);
    }
    tracks.push(track);
    line.append(name, track);
    rowsElement.append(line);
  }
  const axis = document.createElement('div');
  axis.id = 'axis';
  const spacer = document.createElement('div');
  spacer.className = 'label';
  spacer.style.cursor = 'default';
  const labels = document.createElement('div');
  labels.id = 'axisLabels';
  axis.append(spacer, labels);
  rowsElement.append(axis);
  const width = labels.getBoundingClientRect().width;
  const measure = textMeasure(labels, 'axisLabel');
  for (const placed of axisLabels(end, width, measure))
    labels.append(
      Object.assign(document.createElement('span'), {
        className: 'axisLabel',
        textContent: placed.text,
        style: `left:${placed.x}px;width:${placed.width}px`,
      }),
    );
  placeCauses(placements);
  placeCursor();
}

/** The firing conditions' words, each where causeLayout.ts puts it: beside its bar's start or on a line below, covering nothing. */
function placeCauses(rows: { line: HTMLDivElement; track: HTMLDivElement; row: TimelineRow }[]): void {
  const now = timeline?.end ?? 0;
  const width = rows[0]?.track.getBoundingClientRect().width ?? 0;
  if (!(end > 0) || !(width > 0)) return;
  const measure = textMeasure(rows[0].track, 'cause');
  for (const { line, track, row } of rows) {
    const bars = rowBars(row, end, width, measure, now);
    const layout = layoutRow(bars, width);
    line.style.height = `${layout.height}px`;
    for (const placed of layout.labels) {
      const cause = document.createElement('div');
      cause.className = 'cause';
      cause.textContent = bars[placed.bar].cause ?? '';
      cause.title = cause.textContent;
      cause.style.left = `${placed.x}px`;
      cause.style.width = `${placed.width}px`;
      cause.style.top = `${labelTop(placed.lane)}px`;
      cause.style.height = `${placed.lane === 0 ? ROW_GEOMETRY.barHeight : ROW_GEOMETRY.laneHeight}px`;
      cause.style.lineHeight = cause.style.height;
      track.append(cause);
    }
  }
}

/** The width of a text in the font the page writes elements of `className` in (inside `parent`), px. */
function textMeasure(parent: HTMLDivElement, className: string): (text: string) => number {
  const probe = Object.assign(document.createElement('div'), { className });
  parent.append(probe);
  const style = getComputedStyle(probe);
  const font = `${style.fontStyle} ${style.fontWeight} ${style.fontSize} ${style.fontFamily}`;
  const size = parseFloat(style.fontSize) || 10;
  probe.remove();
  const context = document.createElement('canvas').getContext('2d');
  // No canvas: a width no text of that size exceeds (an average glyph is about half the size).
  if (!context) return (text) => text.length * size * 0.7;
  context.font = font;
  return (text) => context.measureText(text).width;
}

/** The cursor: one line over the tracks at the current time. */
function placeCursor(): void {
  // A running session's axis reaches past its time: the header says so rather than give it as the run's length.
  timeLabel.textContent = timeline ? `t = ${time.toFixed(2)} s ${live ? 'so far, axis to' : 'of'} ${end.toFixed(2)} s` : '';
  document.getElementById('cursor')?.remove();
  const first = tracks[0];
  const last = tracks[tracks.length - 1];
  if (!first || !last || !timeline) return report();
  const cursor = document.createElement('div');
  cursor.id = 'cursor';
  const top = first.offsetTop;
  cursor.style.top = `${top}px`;
  cursor.style.bottom = 'auto';
  cursor.style.height = `${last.offsetTop + last.offsetHeight - top}px`;
  cursor.style.left = `calc(${first.offsetLeft}px + ${first.offsetWidth}px * ${end > 0 ? Math.min(Math.max(time / end, 0), 1) : 0})`;
  rowsElement.append(cursor);
  report();
}

function report(): void {
  vscode.postMessage({
    type: 'rendered',
    stats: {
      time,
      rows: (timeline?.rows ?? []).map((row) => ({
        element: row.element,
        text: describeRow(row),
        bars: row.spans.length,
        started: row.started,
      })),
    },
  });
}

let lastLabel = '';
window.addEventListener('message', (event: MessageEvent<ToView>) => {
  const message = event.data;
  if (message.type === 'timeline') {
    timeline = message.timeline;
    lastLabel = message.label;
    live = message.live;
    end = axisEnd(timeline.end, live);
    render(message.label);
  } else if (message.type === 'time') {
    time = message.time;
    placeCursor();
  }
});
window.addEventListener('resize', () => timeline && render(lastLabel));
vscode.postMessage({ type: 'ready' });

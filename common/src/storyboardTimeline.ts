/**
 * A storyboard trace as a timeline: one row per storyboard element (Story to Action) in storyboard order, a bar
 * from each start to its end, the condition that fired each start, and for an element that never started the
 * conditions it waited for. Pure: the timeline panel, the bird's-eye view's event list and their tests use it.
 */
import type { ConditionFiring, TraceCondition, TraceRecord } from './trace';

/** The condition whose firing started an element, with what esmini measured. */
export interface FiringCondition extends ConditionFiring {
  name: string;
  time: number;
}

export interface TimelineSpan {
  start: number;
  /** Undefined while it runs (to the end of the trace). */
  end?: number;
  cause?: FiringCondition;
}

export interface TimelineRow {
  /** esmini's path (`Story::Act::ManeuverGroup::Maneuver::Event::Action`), flattened names. */
  element: string;
  type: string;
  name: string;
  /** 0 for a Story, 1 for an Act, ... */
  depth: number;
  /** The ManeuverGroup it belongs to (its flattened name: which copy of an imported group), when below one. */
  group?: string;
  file?: string;
  line?: number;
  spans: TimelineSpan[];
  /** For an element that never started: the conditions of its StartTrigger, none of which became true. */
  waitsFor?: TraceCondition[];
  started: boolean;
}

export interface Timeline {
  rows: TimelineRow[];
  /** The last time the trace reaches, s. */
  end: number;
}

const ELEMENT_TYPES = new Set(['Story', 'Act', 'ManeuverGroup', 'Maneuver', 'Event', 'Action']);

const parentOf = (path: string) => {
  const cut = path.lastIndexOf('::');
  return cut < 0 ? undefined : path.slice(0, cut);
};

function firing(record: TraceRecord): FiringCondition {
  const cause: FiringCondition = { name: record.element.slice(record.element.lastIndexOf('::') + 2), time: record.time };
  for (const key of ['condition', 'rule', 'threshold', 'measured', 'quantity', 'esmini'] as const)
    if (record[key] !== undefined) Object.assign(cause, { [key]: record[key] });
  return cause;
}

/** The timeline of a trace; `end`, when given, is the run's end (the trace's last record otherwise). */
export function storyboardTimeline(records: readonly TraceRecord[], end?: number): Timeline {
  const rows = new Map<string, TimelineRow>();
  /** Conditions fired for each owner since its last start, not yet given to a start. */
  const fired = new Map<string, FiringCondition[]>();
  let last = 0;
  const sorted = records.map((record, index) => ({ record, index })).sort((a, b) => a.record.time - b.record.time || a.index - b.index);
  for (const { record } of sorted) {
    last = Math.max(last, record.time);
    if (record.type === 'Condition') {
      const owner = parentOf(record.element);
      // A condition firing while its owner runs belongs to a StopTrigger: it starts nothing.
      if (owner !== undefined && !rows.get(owner)?.spans.some((span) => span.end === undefined)) {
        const list = fired.get(owner) ?? [];
        list.push(firing(record));
        fired.set(owner, list);
      }
      continue;
    }
    if (!ELEMENT_TYPES.has(record.type)) continue;
    let row = rows.get(record.element);
    if (!row) {
      const parts = record.element.split('::');
      row = {
        element: record.element,
        type: record.type,
        name: parts[parts.length - 1],
        depth: parts.length - 1,
        ...(parts.length > 3 ? { group: parts[2] } : record.type === 'ManeuverGroup' ? { group: parts[2] } : {}),
        ...(record.file !== undefined ? { file: record.file } : {}),
        ...(record.line !== undefined ? { line: record.line } : {}),
        spans: [],
        started: false,
      };
      rows.set(record.element, row);
    }
    const open = row.spans.find((span) => span.end === undefined);
    if (record.state === 'running') {
      if (open) continue;
      const causes = fired.get(record.element);
      const cause = causes?.pop();
      fired.delete(record.element);
      row.spans.push({ start: record.time, ...(cause ? { cause } : {}) });
      row.started = true;
    } else {
      if (open) open.end = record.time;
      if (record.state === 'standby' && record.waitsFor) row.waitsFor = record.waitsFor;
    }
  }
  for (const row of rows.values()) if (row.started) delete row.waitsFor;
  return { rows: treeOrder([...rows.values()]), end: Math.max(end ?? 0, last) };
}

/** Each row followed by its children, children in the order they first appear in the trace. */
function treeOrder(rows: TimelineRow[]): TimelineRow[] {
  const children = new Map<string | undefined, TimelineRow[]>();
  const known = new Set(rows.map((row) => row.element));
  for (const row of rows) {
    let parent = parentOf(row.element);
    while (parent !== undefined && !known.has(parent)) parent = parentOf(parent);
    const list = children.get(parent) ?? [];
    list.push(row);
    children.set(parent, list);
  }
  const ordered: TimelineRow[] = [];
  const visit = (key: string | undefined) => {
    for (const row of children.get(key) ?? []) {
      ordered.push(row);
      visit(row.element);
    }
  };
  visit(undefined);
  return ordered;
}

/** A firing condition in words: `RelativeDistanceCondition rel_dist 20.27 > 20` (what was measured against what). */
export function describeFiring(cause: FiringCondition): string {
  const kind = cause.condition ?? cause.name;
  if (cause.measured !== undefined && cause.threshold !== undefined)
    return `${kind}: ${cause.quantity ? `${cause.quantity} ` : ''}${cause.measured} ${ruleSign(cause.rule)} ${cause.threshold}`;
  return cause.esmini ? `${kind}: ${cause.esmini}` : kind;
}

/** A waited-for condition in words: `RelativeDistanceCondition greaterThan 20`. */
export function describeCondition(condition: TraceCondition): string {
  return [condition.condition ?? condition.name, condition.rule, condition.threshold].filter((part) => part !== undefined).join(' ');
}

const SIGNS: Record<string, string> = {
  greaterThan: '>',
  lessThan: '<',
  equalTo: '==',
  greaterOrEqual: '>=',
  lessOrEqual: '<=',
  notEqualTo: '!=',
};

function ruleSign(rule: string | undefined): string {
  return rule === undefined ? 'vs' : (SIGNS[rule] ?? rule);
}

/** A row in words: `Event ChangeLane (CutInLead.CutIn): 2.35–3.80 s, RelativeDistanceCondition: rel_dist 30.12 > 30`. */
export function describeRow(row: TimelineRow): string {
  const head = `${row.type} ${row.name}${row.group && row.type !== 'ManeuverGroup' ? ` (${row.group})` : ''}`;
  if (!row.started)
    return `${head}: never started${row.waitsFor?.length ? `, waited for ${row.waitsFor.map(describeCondition).join(' or ')}` : ''}`;
  const spans = row.spans.map(
    (span) =>
      `${span.start.toFixed(2)}–${span.end === undefined ? 'end' : `${span.end.toFixed(2)} s`}${span.cause ? `, ${describeFiring(span.cause)}` : ''}`,
  );
  return `${head}: ${spans.join('; ')}`;
}

/**
 * The bird's-eye view's event list: one row per Event of the scenario shown (per flattened copy of a reused group),
 * naming its actor and its group, with when the run started it, in time order, the events that never started after.
 * Pure (no DOM, no VS Code), so that it is tested on real esmini runs in Node.
 */
import type { SceneEvent, SourceLocation } from '../../../common/src/sceneProtocol';
import { describeFiring, storyboardTimeline } from '../../../common/src/storyboardTimeline';
import type { TraceRecord } from '../../../common/src/trace';
import type { RunTracks } from './messages';

/** When each element of a run started, by esmini's path (flattened names), and the condition that started it, in words. */
export interface RunStarts {
  starts: Record<string, number>;
  causes: Record<string, string>;
}

/** The first start of every element a trace shows starting, and what fired it (from the storyboard timeline, as the timeline panel reads it). */
export function startsOfTrace(records: readonly TraceRecord[]): RunStarts {
  const starts: Record<string, number> = {};
  const causes: Record<string, string> = {};
  for (const row of storyboardTimeline(records).rows) {
    const first = row.spans[0];
    if (!first) continue;
    starts[row.element] = first.start;
    if (first.cause) causes[row.element] = describeFiring(first.cause);
  }
  return { starts, causes };
}

/** `run` with the event starts of `records`, its trace. */
export function withTrace(run: RunTracks, records: readonly TraceRecord[]): RunTracks {
  return { ...run, ...startsOfTrace(records) };
}

export type EventState = 'started' | 'planned' | 'waiting' | 'never' | 'unknown';

export interface EventRow {
  name: string;
  /** esmini's path, the key of its start; undefined when the scenario could not be mapped (not flattened). */
  path?: string;
  /** The entities of its group's Actors, joined: `lead`. */
  actor: string;
  /** The ManeuverGroup as written (for a copy of an imported group, the simple scenario's group). */
  group: string;
  /** For a copy of an imported group: the simple scenario's file and the main's group that imports it. */
  groupFile?: string;
  importedBy?: string;
  /** When the run started it, s. */
  start?: number;
  /** What fired the start, in words (`RelativeDistanceCondition: rel_dist 20.27 > 20`). */
  cause?: string;
  plannedTime?: number;
  state: EventState;
  /** The state in words: `started 5.55 s`, `never started`, `planned 2 s`. */
  when: string;
  running: boolean;
  trigger: string;
  source?: SourceLocation;
}

/** Where the run stands: none yet, a finished run, or a debug session still running. */
export type RunPhase = 'none' | 'finished' | 'live';

const order: Record<EventState, number> = { started: 0, planned: 1, waiting: 2, unknown: 3, never: 4 };

/**
 * The rows of the event list: with a run, the started events by their start time (ties in storyboard order), then
 * the events not started (`never started` after a finished run, `not started yet` while a debug session runs); before
 * a run, the events by their planned time, then those a condition starts.
 */
export function eventRows(
  events: readonly SceneEvent[],
  run: Pick<RunTracks, 'starts' | 'causes'> | undefined,
  phase: RunPhase,
  running?: ReadonlySet<string>,
): EventRow[] {
  const rows = events.map((event, index) => {
    const start = run && event.path !== undefined ? run.starts[event.path] : undefined;
    let state: EventState;
    let when: string;
    if (start !== undefined) {
      state = 'started';
      when = `started ${start.toFixed(2)} s`;
    } else if (phase !== 'none' && event.path === undefined) {
      state = 'unknown';
      when = 'start not known (the scenario could not be flattened)';
    } else if (phase === 'finished') {
      state = 'never';
      when = 'never started';
    } else if (event.plannedTime !== undefined) {
      state = 'planned';
      when = `planned ${event.plannedTime} s`;
    } else {
      state = 'waiting';
      when = phase === 'live' ? 'not started yet' : 'starts on its condition';
    }
    const imported = event.sourceGroup;
    const importedBy = imported && event.group.endsWith(`.${imported.name}`) ? event.group.slice(0, -imported.name.length - 1) : undefined;
    const row: EventRow = {
      name: event.name,
      actor: event.actors.join(', ') || 'no actor',
      group: imported?.name ?? event.group,
      state,
      when,
      running: event.path !== undefined && running?.has(event.path) === true,
      trigger: event.trigger,
      ...(event.path !== undefined ? { path: event.path } : {}),
      ...(imported ? { groupFile: imported.file, importedBy: importedBy ?? event.group } : {}),
      ...(start !== undefined ? { start } : {}),
      ...(event.plannedTime !== undefined ? { plannedTime: event.plannedTime } : {}),
      ...(event.source ? { source: event.source } : {}),
    };
    const cause = event.path !== undefined ? run?.causes?.[event.path] : undefined;
    if (cause !== undefined && start !== undefined) row.cause = cause;
    return { row, index };
  });
  const time = (row: EventRow) => row.start ?? row.plannedTime ?? Infinity;
  rows.sort((a, b) => order[a.row.state] - order[b.row.state] || time(a.row) - time(b.row) || a.index - b.index);
  return rows.map(({ row }) => row);
}

/** The group in words: `CutIn (lane_change.xosc, imported by CutInLead)` for a copy, the group's name otherwise. */
export function groupText(row: EventRow): string {
  return row.groupFile ? `${row.group} (${row.groupFile}, imported by ${row.importedBy})` : row.group;
}

/** A row in words, as the list and an exported picture show it: `ChangeLane · lead · CutIn (lane_change.xosc, imported by CutInLead) · started 5.55 s`. */
export function eventRowText(row: EventRow): string {
  const why = row.state === 'started' ? (row.cause ? ` · ${row.cause}` : '') : ` · ${row.trigger}`;
  return `${row.name} · ${row.actor} · ${groupText(row)} · ${row.when}${row.running ? ' · running' : ''}${why}`;
}

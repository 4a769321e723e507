/**
 * The storyboard trace: one record per storyboard transition or condition firing, the lines of `run --trace
 * OUT.jsonl` (docs/debugging.md), the debug adapter's transition events and what the timeline draws. Plain data:
 * the server writes it, the client reads it.
 */

/** A condition an element waits for (its StartTrigger), as the flattened scenario writes it. */
export interface TraceCondition {
  name: string;
  /** `SimulationTimeCondition`, `RelativeDistanceCondition`, ... */
  condition?: string;
  rule?: string;
  threshold?: number | string;
}

/** For a condition that fired: its kind and rule as written, the threshold and the value esmini measured (its log line for it). */
export interface ConditionFiring {
  condition?: string;
  rule?: string;
  threshold?: number | string;
  measured?: number;
  quantity?: string;
  esmini?: string;
}

/** One line of `run --trace OUT.jsonl`: a storyboard transition or a condition firing. */
export interface TraceRecord extends ConditionFiring {
  /** Simulated seconds. */
  time: number;
  /** esmini's path of the element (`Story::Act::ManeuverGroup::Maneuver::Event`), flattened names. */
  element: string;
  type: string;
  /** `standby`, `running`, `complete`; `true` for a condition that fired. */
  state: string;
  /** Where the element is written in the modular sources (the simple scenario for an imported group); 1-based line. */
  file?: string;
  line?: number;
  /** On a `standby` record: the conditions of the element's StartTrigger, what it waits for. */
  waitsFor?: TraceCondition[];
}

/**
 * The debug adapter's custom DAP event: the trace records of a step (none on a stop, and none at the session's end,
 * which sends the time the run reached), the simulation time. Custom events are named as the protocol's own (`loadedSource`, `progressStart`) and other adapters' (debugpy's
 * `debugpyAttach`, js-debug's `revealLocationRequested`): camelCase, here with the adapter's name first so that no
 * future protocol event can clash; the bird's-eye view's is DEBUG_STATE_EVENT (common/src/debugState.ts).
 */
export const STORYBOARD_EVENT = 'modular2simpleStoryboard';

export interface StoryboardEventBody {
  records: TraceRecord[];
  time: number;
  /**
   * Which run of the session the records belong to: 1 from the launch, one more at each restart. A restarted session
   * keeps its id in the editor, and its new run starts again at 0 s: its records never join the last run's.
   */
  run: number;
}

/** A debug session's trace as its storyboard events build it: the records of its current run. */
export interface LiveTrace {
  run: number;
  records: TraceRecord[];
  /** The simulation time the session last gave, s. */
  time: number;
}

/**
 * The trace with one more storyboard event: the records added to the run they belong to, or, for an event of
 * another run (the session restarted), that run's trace alone, the earlier run's records dropped. An event from an
 * adapter that numbers no run belongs to the current run.
 */
export function followStoryboard(trace: LiveTrace | undefined, body: StoryboardEventBody): LiveTrace {
  const run = typeof body.run === 'number' ? body.run : (trace?.run ?? 1);
  const current = trace && trace.run === run ? trace : { run, records: [], time: 0 };
  current.records.push(...body.records);
  if (typeof body.time === 'number' && Number.isFinite(body.time)) current.time = body.time;
  return current;
}

/** A trace file that is not one JSON trace record a line: names the line and what is wrong. */
export class TraceFormatError extends Error {}

/** Reads `run --trace` output; throws TraceFormatError naming the file's line that is not a trace record. */
export function parseTrace(text: string, file = 'the trace'): TraceRecord[] {
  const records: TraceRecord[] = [];
  const lines = text.split('\n');
  lines.forEach((line, index) => {
    if (line.trim() === '') return;
    const where = `${file}:${index + 1}`;
    let value: unknown;
    try {
      value = JSON.parse(line);
    } catch (error) {
      throw new TraceFormatError(
        `${where}: not JSON (${(error as Error).message}); a trace has one JSON object a line, as run --trace writes it`,
      );
    }
    const record = value as Partial<TraceRecord> | null;
    if (
      typeof record !== 'object' ||
      record === null ||
      typeof record.time !== 'number' ||
      !Number.isFinite(record.time) ||
      typeof record.element !== 'string' ||
      typeof record.type !== 'string' ||
      typeof record.state !== 'string'
    )
      throw new TraceFormatError(`${where}: not a trace record (it needs a numeric time and element, type and state strings)`);
    records.push(record as TraceRecord);
  });
  return records;
}

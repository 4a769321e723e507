import { displayRef } from '../core/sources';
import { Simulation, StoryboardEvent } from './simulation';

/** One line of `run --trace OUT.jsonl`: a storyboard transition or a condition firing (docs/debugging.md). */
export interface TraceRecord {
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
  /** For a condition: its kind and rule as written, the threshold and the value esmini measured (its log line for it). */
  condition?: string;
  rule?: string;
  threshold?: number | string;
  measured?: number;
  quantity?: string;
  esmini?: string;
}

export function traceRecord(event: StoryboardEvent, base?: string): TraceRecord {
  const record: TraceRecord = { time: Number(event.time.toFixed(6)), element: event.element, type: event.type, state: event.state };
  if (event.mapped) {
    record.file = displayRef(event.mapped.source, base);
    record.line = event.mapped.range.start.line + 1;
  }
  if (event.type === 'Condition') {
    const spec = event.mapped?.condition;
    record.condition = spec?.type;
    record.rule = spec?.rule ?? event.reason?.rule;
    record.threshold = event.reason?.threshold ?? spec?.value;
    if (event.reason?.measured !== undefined) record.measured = event.reason.measured;
    if (event.reason?.quantity !== undefined) record.quantity = event.reason.quantity;
    if (event.reason) record.esmini = event.reason.detail;
  }
  return record;
}

/** A Debug Console line for an event: `Event CutInEvent running`, a condition with what esmini measured. */
export function describeEvent(event: StoryboardEvent): string {
  if (event.type !== 'Condition') return `${event.type} ${event.name} ${event.state} (${event.element})`;
  const spec = event.mapped?.condition;
  const written = spec ? ` ${spec.type}${spec.rule ? ` ${spec.rule}` : ''}${spec.value !== undefined ? ` ${spec.value}` : ''}` : '';
  const measured = event.reason ? `: esmini ${event.reason.detail}` : '';
  return `Condition ${event.name} true${written ? ` (${written.trim()})` : ''}${measured}`;
}

/** Runs a started simulation to its end, every event as a trace record. */
export function traceToEnd(simulation: Simulation, started: StoryboardEvent[], base?: string): TraceRecord[] {
  const records = started.map((event) => traceRecord(event, base));
  while (!simulation.ended) for (const event of simulation.step()) records.push(traceRecord(event, base));
  return records;
}

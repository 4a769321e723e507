import type { TraceCondition, TraceRecord } from '../../../common/src/trace';
import type { MappedElement, StoryboardMap } from '../core/flatten/storyboardMap';
import { displayRef } from '../core/sources';
import { Simulation, StoryboardEvent } from './simulation';

export type { TraceRecord };

/** A condition as the flattened scenario writes it, for a `waitsFor`. */
function writtenCondition(condition: MappedElement): TraceCondition {
  const spec = condition.condition;
  const written: TraceCondition = { name: condition.name };
  if (spec?.type !== undefined) written.condition = spec.type;
  if (spec?.rule !== undefined) written.rule = spec.rule;
  if (spec?.value !== undefined)
    written.threshold = Number.isFinite(Number(spec.value)) && spec.value.trim() !== '' ? Number(spec.value) : spec.value;
  return written;
}

/** The trace record of an event; with the scenario's map, a `standby` record says which conditions the element waits for. */
export function traceRecord(event: StoryboardEvent, base?: string, map?: StoryboardMap): TraceRecord {
  const record: TraceRecord = { time: Number(event.time.toFixed(6)), element: event.element, type: event.type, state: event.state };
  if (event.mapped) {
    record.file = displayRef(event.mapped.source, base);
    record.line = event.mapped.range.start.line + 1;
  }
  if (event.state === 'standby' && event.mapped && map) {
    const waitsFor = map.startConditions(event.mapped).map(writtenCondition);
    if (waitsFor.length > 0) record.waitsFor = waitsFor;
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
  const map = simulation.scenario.map;
  const records = started.map((event) => traceRecord(event, base, map));
  while (!simulation.ended) for (const event of simulation.step()) records.push(traceRecord(event, base, map));
  return records;
}

import type { TraceRecord } from '../../../common/src/trace';
import { traceRecord } from '../esmini/storyboardTrace';
import { Simulation, StoryboardEvent } from './simulation';

export type { TraceRecord };
export { traceRecord };

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

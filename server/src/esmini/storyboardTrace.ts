import type { TraceCondition, TraceRecord } from '../../../common/src/trace';
import type { FlatSource } from '../core/flatten';
import { MappedElement, StoryboardMap } from '../core/flatten/storyboardMap';
import { Evaluator, semanticModelOf } from '../core/semantics';
import { displayRef } from '../core/sources';
import { attribute } from '../core/xml';

/*
 * Storyboard trace records (common/src/trace.ts) from what esmini reports: the library's callbacks (debug/simulation.ts)
 * or, for a run of esmini's program, its log, whose lines name an element only by its own name.
 */

/** Why a condition became true, from esmini's own log line for it (`HWT: 0.41 > 0.40`). */
export interface ConditionReason {
  /** esmini's words after `delay: D, ` (`HWT: 0.41 > 0.40, edge rising`). */
  detail: string;
  /** What esmini measured (`HWT`, `rel_dist`, `speed`, the time for a SimulationTimeCondition). */
  quantity?: string;
  measured?: number;
  /** esmini's rule sign: `>`, `<`, `==`, `>=`, `<=`, `!=`. */
  rule?: string;
  threshold?: number;
}

// esmini 3.6 OSCCondition::Log: `<name>: true, delay: <d>, <GetAdditionalLogInfo()>`.
export const CONDITION_LOG = /^\[[^\]]*\] \[info\] (.+?): true, delay: [-\d.]+, (.*)$/;
// The additional info of the conditions that compare one measure with a value (OSCCondition.cpp): `HWT: 0.41 > 0.40, edge ...`.
const MEASURE = /^(?:([A-Za-z_ ]+): )?(-?[\d.]+|Inf) (>=|<=|==|!=|>|<) (-?[\d.]+)/;

/** Reads what esmini's log says about a condition it found true. */
export function conditionReason(detail: string): ConditionReason {
  const match = MEASURE.exec(detail);
  if (!match) return { detail };
  return {
    detail,
    quantity: match[1] ?? 'time',
    measured: match[2] === 'Inf' ? Infinity : Number(match[2]),
    rule: match[3],
    threshold: Number(match[4]),
  };
}

/** The storyboard map of a flattened scenario, names held in expressions evaluated as esmini evaluates them. */
export function storyboardMapOf(flat: FlatSource): StoryboardMap {
  const document = flat.model?.document;
  const evaluator = document ? new Evaluator(semanticModelOf(document)) : undefined;
  return new StoryboardMap(flat, (element) => evaluator?.textOf(element, attribute(element, 'name')));
}

/** One transition or condition firing, as the library or the log reports it. */
export interface StoryboardTransition {
  time: number;
  element: string;
  type: string;
  state: string;
  mapped: MappedElement | undefined;
  reason?: ConditionReason;
}

/** A condition as the flattened scenario writes it, for a `waitsFor`. */
function writtenCondition(condition: MappedElement): TraceCondition {
  const spec = condition.condition;
  const written: TraceCondition = { name: condition.name };
  if (spec?.type !== undefined) written.condition = spec.type;
  if (spec?.rule !== undefined) written.rule = spec.rule;
  if (spec?.value !== undefined) written.threshold = numberOrText(spec.value);
  return written;
}

const numberOrText = (value: string) => (value.trim() !== '' && Number.isFinite(Number(value)) ? Number(value) : value);

/** The trace record of a transition; with the scenario's map, a `standby` record says which conditions the element waits for. */
export function traceRecord(event: StoryboardTransition, base?: string, map?: StoryboardMap): TraceRecord {
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

// esmini 3.6 StoryBoardElement::SetState: `[t] [info] <name> <from>State -> <transition> -> <to>State`.
const TRANSITION_LOG =
  /^\[(\d+(?:\.\d+)?)\] \[info\] (.+?) (init|standby|running|complete)State -> \w+ -> (init|standby|running|complete)State\s*$/;
const TIMED_LINE = /^\[(\d+(?:\.\d+)?)\] \[info\] (.*)$/;
const TRIGGERING_ENTITY = /^Triggering entity \d+: (.+?)\s*$/;

interface LogLine {
  time: number;
  kind: 'transition' | 'condition';
  name: string;
  from?: string;
  to?: string;
  reason?: ConditionReason;
  /** For a condition: the entities esmini says triggered it. */
  entities: string[];
}

function readLogLines(log: string): LogLine[] {
  const lines: LogLine[] = [];
  for (const text of log.split('\n')) {
    const transition = TRANSITION_LOG.exec(text);
    if (transition) {
      lines.push({
        time: Number(transition[1]),
        kind: 'transition',
        name: transition[2],
        from: transition[3],
        to: transition[4],
        entities: [],
      });
      continue;
    }
    const condition = CONDITION_LOG.exec(text);
    const time = TIMED_LINE.exec(text);
    if (condition && time) {
      lines.push({ time: Number(time[1]), kind: 'condition', name: condition[1], reason: conditionReason(condition[2]), entities: [] });
      continue;
    }
    const triggering = time ? TRIGGERING_ENTITY.exec(time[2]) : null;
    const last = lines[lines.length - 1];
    if (triggering && last?.kind === 'condition') last.entities.push(triggering[1]);
  }
  return lines;
}

const TRIGGERED_KINDS = new Set(['Act', 'Event']);

const commonDepth = (a: string, b: string) => {
  const x = a.split('::');
  const y = b.split('::');
  let depth = 0;
  while (depth < x.length && depth < y.length && x[depth] === y[depth]) depth++;
  return depth;
};

/**
 * The trace of a run of esmini's program, from its log. The log names each element by its own name only, which the
 * flattened copies of an imported group share: a line goes to the element of that name in the state the line leaves,
 * preferring, in order, the one whose start condition fired in the same step (matched by the threshold and the
 * triggering entities esmini logs), the one whose parent started last, and the one nearest in the storyboard to the
 * elements the step names unambiguously (a group's flattened name, the conditions that fired).
 */
export function traceFromLog(map: StoryboardMap, log: string, base?: string): TraceRecord[] {
  const lines = readLogLines(log);
  const states = new Map<MappedElement, string>();
  const stateOf = (element: MappedElement) => states.get(element) ?? 'init';
  const byName = new Map<string, MappedElement[]>();
  for (const element of map.elements) {
    if (element.kind === 'Condition') continue;
    const list = byName.get(element.name) ?? [];
    list.push(element);
    byName.set(element.name, list);
  }
  const records: TraceRecord[] = [];
  let index = 0;
  while (index < lines.length) {
    // One simulation step at a time: the lines of one timestamp.
    const time = lines[index].time;
    let stop = index;
    while (stop < lines.length && lines[stop].time === time) stop++;
    const step = lines.slice(index, stop);
    index = stop;
    const anchors: string[] = step
      .filter((line) => line.kind === 'transition' && (byName.get(line.name)?.length ?? 0) === 1)
      .map((line) => byName.get(line.name)![0].path);
    /** Elements whose start condition fired in this step and that have not started since. */
    const triggered = new Set<MappedElement>();
    const firedConditions = new Set<MappedElement>();
    let lastStarted: MappedElement | undefined;
    for (const line of step) {
      if (line.kind === 'condition') {
        const condition = chooseCondition(map.conditionsNamed(line.name), line, firedConditions, stateOf);
        if (condition) {
          firedConditions.add(condition);
          if (condition.parent && condition.trigger === 'start') triggered.add(condition.parent);
          anchors.push(condition.path);
        }
        records.push(
          traceRecord(
            { time, element: condition?.path ?? line.name, type: 'Condition', state: 'true', mapped: condition, reason: line.reason },
            base,
            map,
          ),
        );
        continue;
      }
      const named = byName.get(line.name);
      if (!named) continue;
      const to = line.to!;
      // Only an element with a StartTrigger (Act, Event) waits in standby; the others start as their parent does.
      const waits = line.from === 'standby' || line.to === 'standby';
      const startsWithParent = line.from === 'init' && line.to === 'running';
      const ofKind = named.filter((element) =>
        waits ? TRIGGERED_KINDS.has(element.kind) : startsWithParent ? !TRIGGERED_KINDS.has(element.kind) : true,
      );
      let candidates = ofKind.filter((element) => stateOf(element) === line.from);
      if (candidates.length === 0) candidates = ofKind.length > 0 ? ofKind : named;
      if (to === 'running') {
        const underRunning = candidates.filter((element) => !element.parent || stateOf(element.parent) === 'running');
        if (underRunning.length > 0) candidates = underRunning;
        const fired = candidates.filter((element) => triggered.has(element));
        if (fired.length > 0) candidates = fired;
        const children = candidates.filter((element) => element.parent !== undefined && element.parent === lastStarted);
        if (children.length > 0) candidates = children;
      } else {
        // An element ends after its children: one with a child still running is not the one ending.
        const done = candidates.filter(
          (element) => !map.elements.some((child) => child.parent === element && stateOf(child) === 'running'),
        );
        if (done.length > 0) candidates = done;
      }
      if (candidates.length > 1) {
        const score = (element: MappedElement) => Math.max(0, ...anchors.map((anchor) => commonDepth(anchor, element.path)));
        const best = Math.max(...candidates.map(score));
        candidates = candidates.filter((element) => score(element) === best);
      }
      const element = candidates[0];
      states.set(element, to);
      if (to === 'running') {
        triggered.delete(element);
        lastStarted = element;
      }
      if (to === 'init') continue;
      records.push(traceRecord({ time, element: element.path, type: element.kind, state: to, mapped: element }, base, map));
    }
  }
  return records;
}

/** The copy of a condition a log line speaks of: its threshold and triggering entities as logged, its owner not yet running. */
function chooseCondition(
  candidates: MappedElement[],
  line: LogLine,
  fired: Set<MappedElement>,
  stateOf: (element: MappedElement) => string,
): MappedElement | undefined {
  let left = candidates.filter((candidate) => !fired.has(candidate));
  if (left.length === 0) left = candidates;
  const keep = (test: (candidate: MappedElement) => boolean) => {
    const kept = left.filter(test);
    if (kept.length > 0) left = kept;
  };
  const threshold = line.reason?.threshold;
  if (threshold !== undefined) keep((candidate) => Math.abs(Number(candidate.condition?.value) - threshold) < 0.006);
  if (line.entities.length > 0)
    keep((candidate) => line.entities.every((entity) => candidate.condition?.triggeringEntities.includes(entity) ?? false));
  keep((candidate) => candidate.trigger !== 'start' || !candidate.parent || stateOf(candidate.parent) !== 'running');
  return left[0];
}

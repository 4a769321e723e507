import { Evaluator, semanticModelOf } from '../core/semantics';
import { detectEol } from '../core/text';
import { attribute, endTagStart, parseXml, XmlElement } from '../core/xml';

/**
 * Simulated seconds after which a run with no limit set is stopped as a runaway although its StopTrigger has
 * conditions: they have not ended it. esmini itself goes on for ever then (esmini 3.6 playerbase.cpp logs
 * "Simulation time > 1 hour. Put a stopTrigger for automatic ending" and runs on).
 */
export const RUNAWAY_SECONDS = 3600;
/** Simulated seconds a scenario with no stop condition at all (an empty StopTrigger) runs when no limit is set: it has no end of its own. */
export const NO_END_SECONDS = 30;

/**
 * The limit a run gets: the user's (`user`); else, the scenario's own end standing, the runaway guard (`runaway`);
 * or, for a scenario whose StopTrigger has no condition, the default length (`no-end`).
 */
export type LimitKind = 'user' | 'no-end' | 'runaway';

/** A run's added time limit; `setBy` names where the user sets one (`EsminiRunOptions.durationSetBy`). */
export type RunLimit = { seconds: number; kind: LimitKind; setBy?: string };

export function runLimit(text: string, duration: number | undefined, setBy?: string): RunLimit {
  if (duration !== undefined) return { seconds: duration, kind: 'user', setBy };
  const stop = child(child(parseXml(text).root, 'Storyboard'), 'StopTrigger');
  const conditions = stop?.children.some(
    (group) => group.name === 'ConditionGroup' && group.children.some((each) => each.name === 'Condition'),
  );
  if (!conditions) return { seconds: NO_END_SECONDS, kind: 'no-end', setBy };
  // A StopTrigger that ends the scenario by time at or past the guard (ALKS free driving at 5 km/h: 5000 m in 3600 s) is not a runaway until then.
  const end = scenarioEnd(text)?.seconds;
  const seconds =
    end !== undefined && end + OWN_END_MARGIN_SECONDS > RUNAWAY_SECONDS
      ? Math.min(end + OWN_END_MARGIN_SECONDS, LONGEST_OWN_END_SECONDS)
      : RUNAWAY_SECONDS;
  return { seconds, kind: 'runaway', setBy };
}

/** How far past a scenario's own time end the runaway guard lies, so that the step it ends at is its own and not the guard's. */
const OWN_END_MARGIN_SECONDS = 1;
/** The longest a scenario's own time end moves the runaway guard: a day of simulated time (a few seconds to minutes of esmini). */
const LONGEST_OWN_END_SECONDS = 24 * RUNAWAY_SECONDS;

/** The condition name the runner adds; a run whose last step passes the limit was ended by it. */
export const TIME_LIMIT_CONDITION = 'modular2simple_time_limit';

/**
 * The condition group that ends a run at the first step past `seconds` of simulated time
 * (esmini 3.6 has no duration option; its README in the shared source package gives this form).
 */
function limitGroup(seconds: number): string {
  return (
    `<ConditionGroup><Condition name="${TIME_LIMIT_CONDITION}" delay="0" conditionEdge="none"><ByValueCondition>` +
    `<SimulationTimeCondition value="${seconds}" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup>`
  );
}

function child(element: XmlElement | undefined, name: string): XmlElement | undefined {
  return element?.children.find((candidate) => candidate.name === name);
}

/**
 * The scenario text with a time limit added to the Storyboard's StopTrigger (an OR: the scenario's
 * own stop conditions still apply). Only the end of the Storyboard changes, so every element before
 * the StopTrigger keeps its offset. Undefined when the text has no Storyboard to add it to.
 */
export function withTimeLimit(text: string, seconds: number): string | undefined {
  if (!(seconds > 0) || !Number.isFinite(seconds)) throw new Error(`the time limit must be a positive number of seconds, not ${seconds}`);
  const document = parseXml(text);
  const storyboard = child(document.root, 'Storyboard');
  if (!storyboard || !storyboard.closed || storyboard.selfClosing) return undefined;
  const eol = detectEol(text);
  const group = limitGroup(seconds);
  const stop = child(storyboard, 'StopTrigger');
  if (!stop) {
    const closing = endTagStart(text, storyboard);
    return `${text.slice(0, closing)}  <StopTrigger>${group}</StopTrigger>${eol}  ${text.slice(closing)}`;
  }
  if (stop.selfClosing) return `${text.slice(0, stop.start)}<StopTrigger>${group}</StopTrigger>${text.slice(stop.end)}`;
  const closing = endTagStart(text, stop);
  return `${text.slice(0, closing)}${group}${text.slice(closing)}`;
}

/** When a scenario's Storyboard StopTrigger ends it by simulated time alone. */
export interface ScenarioEnd {
  /** Simulated seconds at which a condition group made of SimulationTimeConditions alone fires first. */
  seconds: number;
  /** False when other condition groups could end it earlier (they are ORed with this one). */
  only: boolean;
}

/** SimulationTimeCondition rules that fire once the time passes the value; `lessThan` fires at the start, not at an end. */
const ENDING_RULES = new Set(['greaterThan', 'greaterOrEqual', 'equalTo']);

/**
 * The simulated time at which the scenario's own StopTrigger ends it, read as esmini evaluates its parameters and
 * expressions: the earliest condition group whose conditions are all SimulationTimeConditions (each fires at its
 * value plus its delay; a group fires when all have). Undefined when no group ends it by time alone.
 */
export function scenarioEnd(text: string): ScenarioEnd | undefined {
  const document = parseXml(text);
  const stop = child(child(document.root, 'Storyboard'), 'StopTrigger');
  const groups = stop?.children.filter((each) => each.name === 'ConditionGroup') ?? [];
  if (groups.length === 0) return undefined;
  const evaluator = new Evaluator(semanticModelOf(document), undefined, 'esmini');
  const number = (element: XmlElement, name: string): number | undefined => {
    const found = attribute(element, name);
    if (!found) return name === 'delay' ? 0 : undefined;
    const result = evaluator.attributeValue(element, found);
    const value = result.ok ? Number(result.value) : NaN;
    return Number.isFinite(value) ? value : undefined;
  };
  let earliest: number | undefined;
  let timeOnly = 0;
  for (const group of groups) {
    let groupEnd: number | undefined = -Infinity;
    for (const condition of group.children.filter((each) => each.name === 'Condition')) {
      const time = child(child(condition, 'ByValueCondition'), 'SimulationTimeCondition');
      const value = time && ENDING_RULES.has(attribute(time, 'rule')?.value ?? '') ? number(time, 'value') : undefined;
      const delay = number(condition, 'delay');
      if (value === undefined || delay === undefined || groupEnd === undefined) groupEnd = undefined;
      else groupEnd = Math.max(groupEnd, value + delay);
    }
    if (groupEnd === undefined || groupEnd === -Infinity) continue;
    timeOnly++;
    earliest = earliest === undefined ? groupEnd : Math.min(earliest, groupEnd);
  }
  return earliest === undefined ? undefined : { seconds: earliest, only: timeOnly === groups.length };
}

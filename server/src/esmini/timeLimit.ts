import { detectEol } from '../core/text';
import { parseXml, XmlElement } from '../core/xml';

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
    const closing = text.lastIndexOf('</', storyboard.end - 1);
    return `${text.slice(0, closing)}  <StopTrigger>${group}</StopTrigger>${eol}  ${text.slice(closing)}`;
  }
  if (stop.selfClosing) return `${text.slice(0, stop.start)}<StopTrigger>${group}</StopTrigger>${text.slice(stop.end)}`;
  const closing = text.lastIndexOf('</', stop.end - 1);
  return `${text.slice(0, closing)}${group}${text.slice(closing)}`;
}

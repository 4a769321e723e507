import * as path from 'node:path';
import type { RelatedProblemLocation, SimulatorFixData } from '../../problems';
import { carlaFactWording } from '../../diagnostics/simulator';
import type { CarlaFactName } from '../../profiles/carla';
import type { SourceRef } from '../../sources';
import type { LineIndex } from '../../text';
import { attribute, descendants, XmlAttribute, XmlElement } from '../../xml';
import { isTestCriterion, XML_SHAPE } from '../storyboardStop';
import { at } from './support';
import type { Finding, SemanticContext } from './types';

/*
 * ParameterConditions as CARLA's ScenarioRunner ticks them. It keeps a declared parameter as its text
 * (SR_CONFIGURATION:234) until a ParameterAction writes a number (SR_ATOMICS ChangeParameter), and its
 * CheckParameter compares the parameter with the condition's value converted to a number at every tick
 * (SR_PARSER:189-214 ParameterRef): text against a number raises TypeError for lessThan and greaterThan and
 * never holds for equalTo; a value that is no number raises ValueError. Whether a ParameterAction of a story
 * runs before the condition's first tick is read from where both stand in the tree, ticked in document
 * order (SR_SCENARIO:369-385, 425-454, 482-503); ../shared/carla's harness, ticking the built tree, shows it.
 */

/** A Condition ScenarioRunner builds as one of its test criteria (semantics/storyboardStop.ts isTestCriterion). */
export function isCriterion(condition: XmlElement): boolean {
  return isTestCriterion(condition, XML_SHAPE);
}

/** Where an element of an Act stands in ScenarioRunner's tick order. */
interface StoryPlace {
  act: XmlElement;
  /** The StartTrigger (ticked first, from the stories' first tick), or the StopTrigger the element is in; undefined: in a maneuver. */
  actTrigger: XmlElement | undefined;
  event: XmlElement | undefined;
  /** The Event's StartTrigger, ticked before its actions, when the element is in it. */
  eventTrigger: XmlElement | undefined;
  /** Compared in order: which of two elements is ticked first within one tick. */
  order: number[];
}

function storyPlace(element: XmlElement): StoryPlace | undefined {
  let act: XmlElement | undefined;
  let event: XmlElement | undefined;
  let trigger: XmlElement | undefined;
  let actTrigger: XmlElement | undefined;
  let eventTrigger: XmlElement | undefined;
  for (let node: XmlElement | undefined = element; node; node = node.parent) {
    if ((node.name === 'StartTrigger' || node.name === 'StopTrigger') && !trigger) trigger = node;
    if (node.name === 'Event' && !event) {
      event = node;
      if (trigger?.parent === node) eventTrigger = trigger;
    }
    if (node.name === 'Act') {
      act = node;
      if (trigger?.parent === node) actTrigger = trigger;
      break;
    }
  }
  if (!act) return undefined;
  // An Act: StartTrigger, then its maneuvers (each Event: StartTrigger, then actions), then its StopTrigger (SR_SCENARIO:482-503).
  const part = actTrigger?.name === 'StartTrigger' ? 0 : actTrigger ? 2 : 1;
  const order = [act.start, part, event?.start ?? 0, eventTrigger ? 0 : 1, element.start];
  return { act, actTrigger, event, eventTrigger, order };
}

function tickedBefore(first: StoryPlace, second: StoryPlace): boolean {
  for (let index = 0; index < first.order.length; index++)
    if (first.order[index] !== second.order[index]) return first.order[index] < second.order[index];
  return false;
}

/**
 * Whether ScenarioRunner certainly ticks the condition before the action can have run: the action waits for the
 * condition (it is in the Act or Event the condition starts), or both are first ticked on the same tick
 * (the condition starts an Act, ticked from the stories' first tick; or both are in one Act) and the condition
 * comes first in the tick order.
 */
function tickedBeforeAction(condition: StoryPlace, action: StoryPlace): boolean {
  const startsAct = condition.actTrigger?.name === 'StartTrigger';
  if (startsAct && action.act === condition.act) return true;
  if (condition.eventTrigger && action.event === condition.event) return true;
  return (startsAct || action.act === condition.act) && tickedBefore(condition, action);
}

interface Setter {
  action: XmlElement;
  /** Where it is ticked; undefined for one in a catalog entry, whose place in the tree this file does not show. */
  place: StoryPlace | undefined;
  /** Where it is written, for the message ("line 12", "line 4 of ManeuverCatalog.xosc") and as a related place. */
  where: string;
  related: RelatedProblemLocation;
}

/** ParameterActions by the parameter they set: those of the Init, and those of the stories (also in the catalog entries the file uses). */
function parameterSetters(context: SemanticContext, elements: XmlElement[]): { init: Set<string>; story: Map<string, Setter[]> } {
  const init = new Set<string>();
  const story = new Map<string, Setter[]>();
  const add = (action: XmlElement, place: StoryPlace | undefined, source: SourceRef, lines: LineIndex): void => {
    const name = parameterName(attribute(action, 'parameterRef'));
    const line = lines.positionAt(action.start).line + 1;
    const where = source === context.ref ? `line ${line}` : `line ${line} of ${path.basename(source.disk)}`;
    const related = { source, range: lines.range(action.start, action.nameEnd), message: `this ParameterAction sets '${name}' in a story` };
    story.set(name, [...(story.get(name) ?? []), { action, place, where, related }]);
  };
  for (const action of elements) {
    if (action.name !== 'ParameterAction') continue;
    const place = storyPlace(action);
    if (place) add(action, place, context.ref, context.model.document.lines);
    else init.add(parameterName(attribute(action, 'parameterRef')));
  }
  for (const resolution of context.catalogs.references) {
    const entry = resolution.entry;
    for (const action of entry ? descendants(entry.element) : [])
      if (entry && action.name === 'ParameterAction') add(action, undefined, entry.file.ref, entry.file.model.document.lines);
  }
  return { init, story };
}

function parameterName(ref: XmlAttribute | undefined): string {
  return ref?.value.trim().replace(/^\$/, '') ?? '';
}

/** The value of an attribute as a number, if it has one (a $parameter or ${...} evaluated). */
function numericValue(context: SemanticContext, element: XmlElement, name: string): number | undefined {
  const attr = attribute(element, name);
  const result = attr ? context.evaluator.attributeValue(element, attr) : undefined;
  if (!result?.ok) return undefined;
  const value = typeof result.value === 'number' ? result.value : Number(String(result.value).trim() || 'x');
  return Number.isFinite(value) ? value : undefined;
}

/** Whether the standard's equalTo holds on the declared value: undefined where either is not known as a number. */
function equalAsDeclared(context: SemanticContext, declaration: XmlElement, condition: XmlElement): boolean | undefined {
  const declared = numericValue(context, declaration, 'value');
  const compared = numericValue(context, condition, 'value');
  return declared === undefined || compared === undefined ? undefined : declared === compared;
}

/**
 * A ParameterCondition on a declared parameter where ScenarioRunner compares it as text: none of its
 * ParameterActions sets it (an error where the comparison raises, a warning for equalTo a number, which never
 * holds), only the stories' do (an error where none of them can run before the condition's first tick, a
 * warning naming the order where that depends on when they run), and a value that is no number, whatever
 * sets the parameter. A criteria_ condition names a test criterion, and the Storyboard's StopTrigger is
 * never ticked (storyboardStopTrigger says so).
 */
export const parametersComparedAsText = (context: SemanticContext, elements: XmlElement[]): Finding[] => {
  const root = context.model.document.root;
  const declarations = root?.children.find((child) => child.name === 'ParameterDeclarations');
  if (!declarations) return [];
  const declared = new Map(
    declarations.children
      .filter((child) => child.name === 'ParameterDeclaration')
      .map((declaration) => [attribute(declaration, 'name')?.value ?? '', declaration]),
  );
  const setters = parameterSetters(context, elements);
  const findings: Finding[] = [];
  const data: SimulatorFixData = { exportMaps: true };
  for (const element of elements) {
    if (element.name !== 'ParameterCondition') continue;
    const condition = element.parent?.parent;
    if (condition?.name === 'Condition' && isCriterion(condition)) continue;
    if (condition?.parent?.parent?.name === 'StopTrigger' && condition.parent.parent.parent?.name === 'Storyboard') continue;
    const ref = attribute(element, 'parameterRef');
    const name = parameterName(ref);
    const declaration = declared.get(name);
    if (!ref || !declaration) continue;
    const value = attribute(element, 'value')?.value.trim() ?? '';
    const rule = attribute(element, 'rule')?.value ?? '';
    const number = value.startsWith('$') || (value !== '' && Number.isFinite(Number(value)));
    const inStories = setters.story.get(name) ?? [];
    const set = setters.init.has(name) || inStories.length > 0;
    const finding = (fact: CarlaFactName, detail: string, related: Setter[] = []): Finding => ({
      ...at(element, ref),
      ...carlaFactWording(fact, detail),
      data,
      ...(related.length > 0 ? { related: related.map((setter) => setter.related) } : {}),
    });
    const compared = `'${name}' is declared as '${attribute(declaration, 'value')?.value ?? ''}' and compared ${rule} ${value}`;
    const initFix = 'a ParameterAction in the Init that sets it makes it a number';
    const lines = (list: Setter[]): string => list.map((setter) => setter.where).join(', ');
    // equalTo a number (or a $parameter holding one) compares text with a float: false, not an exception. That runs
    // otherwise than written where the declared value is the one compared with: unless known to differ for a parameter
    // nothing sets, where known equal for one a story sets.
    const equalTo = rule === 'equalTo' && number;
    const equality = equalTo ? equalAsDeclared(context, declaration, element) : undefined;
    if (!set) {
      if (!equalTo || equality !== false)
        findings.push(finding(equalTo ? 'parameterNeverEqual' : 'parameterComparedAsText', `${compared}; ${initFix}`));
      continue;
    }
    if (!number) {
      findings.push(
        finding('parameterValueNotNumber', `${rule} '${value}' on '${name}'; compare with a number (1 and 0 for true and false)`),
      );
      continue;
    }
    if (setters.init.has(name)) continue;
    if (equality === true) {
      findings.push(finding('parameterNotEqualAsDeclared', `${compared}, and set only at ${lines(inStories)}; ${initFix}`, inStories));
      continue;
    }
    // Text against a number: equalTo (and 1.1's notEqualTo) compare without raising, and hold once an action ran.
    if (rule === 'equalTo' || rule === 'notEqualTo') continue;
    const place = storyPlace(element);
    if (!place) continue;
    const mayRunFirst = inStories.filter((setter) => !setter.place || !tickedBeforeAction(place, setter.place));
    if (mayRunFirst.length === 0) {
      findings.push(finding('parameterSetAfterCondition', `${compared}, and set only at ${lines(inStories)}; ${initFix}`, inStories));
      continue;
    }
    const order = mayRunFirst
      .map(({ place: setterPlace, where }) =>
        !setterPlace
          ? `${where} is in a catalog entry`
          : `${where} comes ${tickedBefore(setterPlace, place) ? 'before' : 'after'} it in that order${setterPlace.act === place.act ? '' : ', in another Act'}`,
      )
      .join('; ');
    findings.push(
      finding(
        'parameterSetInStoryOrder',
        `${compared}; it raises unless a ParameterAction has set it by this condition's first tick: ${order}; ${initFix}`,
        inStories,
      ),
    );
  }
  return findings;
};

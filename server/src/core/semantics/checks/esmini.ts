import { esminiFactWording } from '../../diagnostics/simulator';
import { ESMINI_SMALL_NUMBER } from '../../profiles/esmini';
import { attribute, descendants, XmlAttribute, XmlElement } from '../../xml';
import { assignmentsOf } from '../catalogs';
import { formatValue } from '../values';
import { Evaluator } from '../model';
import { at, inCatalogEntry, onCatalogReferences } from './support';
import type { Finding, SemanticCheck, SemanticContext } from './types';

/*
 * What esmini refuses (an error) or runs otherwise than written (a warning) beyond one element or attribute at a
 * time (those are the profile's tables, core/profiles/esmini.ts), each finding stating its fact's source lines.
 */

/** The ScenarioObjects after an ExternalObjectReference that the document references: esmini never reads them, and refuses the reference. */
function entitiesAfterExternal(context: SemanticContext, root: XmlElement): Finding[] {
  const objects =
    root.children.find((child) => child.name === 'Entities')?.children.filter((child) => child.name === 'ScenarioObject') ?? [];
  const external = objects.findIndex((object) => object.children.some((child) => child.name === 'ExternalObjectReference'));
  if (external < 0) return [];
  const referenced = new Set(context.model.entityReferences.map((reference) => reference.attribute.value));
  const externalName = attribute(objects[external], 'name')?.value ?? '';
  return objects.slice(external + 1).flatMap((object) => {
    const name = attribute(object, 'name');
    if (!name || !referenced.has(name.value)) return [];
    return [
      {
        ...at(object, name),
        ...esminiFactWording('entitiesAfterExternal', `'${name.value}' comes after '${externalName}', and the scenario references it`),
      },
    ];
  });
}

/** Each RoutePosition among `elements` whose Orientation comes after its InRoutePosition, which esmini drops (Euro NCAP's CBFA turns its obstruction so: the second one then stands 9 m away). */
function routeOrientationsAfterPosition(elements: readonly XmlElement[]): Finding[] {
  return elements.flatMap((route) => {
    if (route.name !== 'RoutePosition') return [];
    const orientation = route.children.findIndex((child) => child.name === 'Orientation');
    const position = route.children.findIndex((child) => child.name === 'InRoutePosition');
    if (orientation < 0 || position < 0 || orientation < position) return [];
    const element = route.children[orientation];
    return [
      {
        ...at(element, undefined),
        ...esminiFactWording('routeOrientationOrder', `this <Orientation> comes after <InRoutePosition>`),
        data: { orientationFirst: true },
      },
    ];
  });
}

/** A SynchronizeAction's final AbsoluteSpeed of 0 or less followed by a steady state, among `elements`, read by `textOf`. */
function steadyStateStops(
  elements: readonly XmlElement[],
  textOf: (element: XmlElement, value: XmlAttribute) => string | undefined,
): Finding[] {
  const findings: Finding[] = [];
  for (const speed of elements) {
    if (speed.name !== 'AbsoluteSpeed' || speed.parent?.name !== 'FinalSpeed' || speed.children.length === 0) continue;
    const value = attribute(speed, 'value');
    const text = value && textOf(speed, value);
    // esmini compares with SMALL_NUMBER; a value it cannot read is another check's.
    if (text === undefined || text.trim() === '' || !(Number(text) < ESMINI_SMALL_NUMBER)) continue;
    findings.push({
      ...at(speed, value),
      ...esminiFactWording('steadyStateStop', `a final speed of ${text.trim()} with <${speed.children[0].name}>`),
    });
  }
  return findings;
}

type TextOf = (element: XmlElement, value: XmlAttribute) => string | undefined;

/** A SimulationTimeCondition's rule and value as esmini reads them, or undefined when either cannot be read. */
function simulationTimeRule(condition: XmlElement, textOf: TextOf): { rule: string; value: number } | undefined {
  const rule = attribute(condition, 'rule');
  const value = attribute(condition, 'value');
  const ruleText = rule && textOf(condition, rule)?.trim();
  const valueText = value && textOf(condition, value)?.trim();
  if (!ruleText || !valueText || !Number.isFinite(Number(valueText))) return undefined;
  return { rule: ruleText, value: Number(valueText) };
}

/** Whether SimulationTime 0 meets the rule, within esmini's SMALL_NUMBER (OSCCondition.cpp EvaluateRule). */
function holdsAtZero({ rule, value }: { rule: string; value: number }): boolean {
  switch (rule) {
    case 'equalTo':
      return Math.abs(value) < ESMINI_SMALL_NUMBER;
    case 'notEqualTo':
      return Math.abs(value) >= ESMINI_SMALL_NUMBER;
    case 'greaterThan':
      return 0 > value + ESMINI_SMALL_NUMBER;
    case 'greaterOrEqual':
      return 0 >= value - ESMINI_SMALL_NUMBER;
    case 'lessThan':
      return 0 < value - ESMINI_SMALL_NUMBER;
    case 'lessOrEqual':
      return 0 <= value + ESMINI_SMALL_NUMBER;
    default:
      return false;
  }
}

/** A Condition's text attribute as esmini reads it ('none' for an absent conditionEdge, '0' for an absent delay). */
function conditionText(condition: XmlElement, name: string, fallback: string, textOf: TextOf): string | undefined {
  const written = attribute(condition, name);
  return written ? textOf(condition, written)?.trim() : fallback;
}

/** Whether an Act starts at time 0 in esmini: no StartTrigger, or a group of SimulationTimeConditions that hold at 0, without edge or delay. */
function actStartsAtZero(act: XmlElement, textOf: TextOf): boolean {
  const trigger = act.children.find((child) => child.name === 'StartTrigger');
  if (!trigger) return true;
  return trigger.children.some(
    (group) =>
      group.name === 'ConditionGroup' &&
      group.children.length > 0 &&
      group.children.every((condition) => {
        const time = descendants(condition).find((each) => each.name === 'SimulationTimeCondition');
        const rule = time && simulationTimeRule(time, textOf);
        return (
          rule !== undefined &&
          holdsAtZero(rule) &&
          conditionText(condition, 'conditionEdge', 'none', textOf) === 'none' &&
          Number(conditionText(condition, 'delay', '0', textOf)) === 0
        );
      }),
  );
}

/**
 * SimulationTimeConditions of StartTriggers that esmini never fires: a rising edge of one that holds when its trigger
 * is first evaluated (a Story's Act at time 0, an Event of an Act that starts then) and never turns from false to true
 * after it; an equalTo 0 in an Event whose Act starts later. The paper's library has both in every scenario, so in
 * esmini nothing of it moves.
 */
function simulationTimesMissed(elements: readonly XmlElement[], textOf: TextOf): Finding[] {
  const findings: Finding[] = [];
  for (const time of elements) {
    if (time.name !== 'SimulationTimeCondition') continue;
    const condition = time.parent?.parent;
    const trigger = condition?.parent?.parent;
    const owner = trigger?.parent;
    if (condition?.name !== 'Condition' || trigger?.name !== 'StartTrigger' || (owner?.name !== 'Act' && owner?.name !== 'Event')) continue;
    const rule = simulationTimeRule(time, textOf);
    const edge = conditionText(condition, 'conditionEdge', 'none', textOf);
    if (!rule || edge === undefined) continue;
    const act = owner.name === 'Act' ? owner : owner.parent?.parent?.parent;
    const atZero = owner.name === 'Act' || (act?.name === 'Act' && actStartsAtZero(act, textOf));
    const written = `SimulationTime ${rule.rule} ${formatValue(rule.value)}`;
    if (atZero && edge === 'rising' && holdsAtZero(rule) && rule.rule !== 'notEqualTo') {
      findings.push({
        ...at(condition, attribute(condition, 'conditionEdge')),
        ...esminiFactWording(
          'edgeAtFirstEvaluation',
          `${written} with edge rising already holds when this ${owner.name}'s StartTrigger is first evaluated, at time 0: the ${owner.name} never starts`,
          'edge',
        ),
        data: { simulationTimeFix: 'edge' },
      });
    } else if (!atZero && owner.name === 'Event' && rule.rule === 'equalTo' && Math.abs(rule.value) < ESMINI_SMALL_NUMBER) {
      findings.push({
        ...at(time, attribute(time, 'rule')),
        ...esminiFactWording(
          'simulationTimeZeroAfterStart',
          `${written}: this Event's Act does not start at time 0, so the Event never starts`,
          'after-zero',
        ),
        data: { simulationTimeFix: 'after-zero' },
      });
    }
  }
  return findings;
}

/**
 * What esmini refuses at load: a ScenarioObject after an ExternalObjectReference that is referenced, a SynchronizeAction's
 * steady state to a stop; what it drops: a RoutePosition's Orientation after its position. In a catalog entry, each is
 * found on each reference that uses the entry (with its values, as esmini reads it there), not in the catalog.
 */
export const esminiScenario: SemanticCheck = (context) => {
  const root = context.model.document.root;
  if (context.simulator !== 'esmini' || !root) return [];
  const own = descendants(root).filter((element) => !inCatalogEntry(context, element));
  const textOf = (evaluator: Evaluator) => (element: XmlElement, value: XmlAttribute) => evaluator.textOf(element, value);
  return [
    ...entitiesAfterExternal(context, root),
    ...routeOrientationsAfterPosition(own),
    ...steadyStateStops(own, textOf(context.evaluator)),
    ...simulationTimesMissed(own, textOf(context.evaluator)),
    ...onCatalogReferences(context, (entry, resolution) => {
      const evaluator = new Evaluator(entry.file.model, assignmentsOf(resolution.reference, context.evaluator), context.evaluator.reading);
      const elements = [entry.element, ...descendants(entry.element)];
      return [...routeOrientationsAfterPosition(elements), ...steadyStateStops(elements, textOf(evaluator))];
    }),
  ];
};

/**
 * Whether the Storyboard's stop conditions are kept in its Acts: ScenarioRunner ignores the Storyboard's
 * StopTrigger but ends the scenario when its acts end, so a Storyboard ConditionGroup that every Act's StopTrigger
 * also holds still stops the scenario there. The CARLA export copies the groups that are not (export/carlaRules.ts
 * storyboardStop), and the CARLA check warns of them (semantics/checks/carla.ts): one answer for both.
 */
import type { XmlElement } from '../xml';

/** What this module reads of an element: the parser's XmlElement and the export's Node both answer it. */
export interface ElementShape<E> {
  name(element: E): string;
  attributes(element: E): Iterable<readonly [string, string]>;
  children(element: E): readonly E[];
}

/** The parser's element as ElementShape reads it. */
export const XML_SHAPE: ElementShape<XmlElement> = {
  name: (element) => element.name,
  attributes: (element) => element.attributes.map((each) => [each.name, each.value] as const),
  children: (element) => element.children,
};

/** An element as a text that two elements share exactly when they have the same name, attributes (in any order) and children. */
function structureKey<E>(element: E, shape: ElementShape<E>, children: readonly E[] = shape.children(element)): string {
  const attributes = [...shape.attributes(element)].map(([name, value]) => [name, value]).sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0));
  return JSON.stringify([shape.name(element), attributes, children.map((child) => structureKey(child, shape))]);
}

/**
 * A Condition ScenarioRunner builds as one of its test criteria: a ParameterCondition named criteria_*. It makes one
 * of each in every StopTrigger of the Storyboard (open_scenario.py _create_test_criteria), and in an Act's StopTrigger
 * one that never succeeds (openscenario_parser.py convert_condition_to_atomic).
 */
export function isTestCriterion<E>(condition: E, shape: ElementShape<E>): boolean {
  if (shape.name(condition) !== 'Condition') return false;
  const name = [...shape.attributes(condition)].find(([attribute]) => attribute === 'name')?.[1] ?? '';
  const holdsParameterCondition = (element: E): boolean =>
    shape.children(element).some((child) => shape.name(child) === 'ParameterCondition' || holdsParameterCondition(child));
  return name.startsWith('criteria_') && holdsParameterCondition(condition);
}

function childrenNamed<E>(element: E, name: string, shape: ElementShape<E>): E[] {
  return shape.children(element).filter((child) => shape.name(child) === name);
}

/** The Acts of a Storyboard (Storyboard/Story/Act). */
export function actsOf<E>(storyboard: E, shape: ElementShape<E>): E[] {
  return childrenNamed(storyboard, 'Story', shape).flatMap((story) => childrenNamed(story, 'Act', shape));
}

/**
 * A ConditionGroup of the Storyboard's StopTrigger, its conditions that stop the scenario (all but test criteria,
 * which ScenarioRunner reads from the Storyboard's once) and the Acts whose StopTrigger lacks a group of those.
 */
export interface StoryboardStopGroup<E> {
  group: E;
  stopping: E[];
  missingFrom: E[];
}

/** The ConditionGroups of the Storyboard's StopTrigger, each with the Acts whose StopTrigger does not hold its stopping conditions. */
export function storyboardStopGroups<E>(storyboard: E, shape: ElementShape<E>): StoryboardStopGroup<E>[] {
  const stop = childrenNamed(storyboard, 'StopTrigger', shape)[0];
  if (!stop) return [];
  const acts = actsOf(storyboard, shape).map((act) => ({
    act,
    groups: new Set(
      childrenNamed(act, 'StopTrigger', shape).flatMap((trigger) =>
        childrenNamed(trigger, 'ConditionGroup', shape).map((group) => structureKey(group, shape)),
      ),
    ),
  }));
  return childrenNamed(stop, 'ConditionGroup', shape).map((group) => {
    const stopping = shape.children(group).filter((child) => !isTestCriterion(child, shape));
    const key = structureKey(group, shape, stopping);
    return { group, stopping, missingFrom: acts.filter(({ groups }) => !groups.has(key)).map(({ act }) => act) };
  });
}

/**
 * The ConditionGroups of the Storyboard's StopTrigger that the StopTrigger of every one of its Acts holds too (a
 * group of the same conditions, test criteria aside): ScenarioRunner stops the scenario on them. None when it has no Act.
 */
export function stopGroupsKeptInActs<E>(storyboard: E, shape: ElementShape<E>): Set<E> {
  if (actsOf(storyboard, shape).length === 0) return new Set();
  return new Set(
    storyboardStopGroups(storyboard, shape)
      .filter(({ missingFrom }) => missingFrom.length === 0)
      .map(({ group }) => group),
  );
}

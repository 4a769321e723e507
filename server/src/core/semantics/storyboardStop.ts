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
function structureKey<E>(element: E, shape: ElementShape<E>): string {
  const attributes = [...shape.attributes(element)].map(([name, value]) => [name, value]).sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0));
  return JSON.stringify([shape.name(element), attributes, shape.children(element).map((child) => structureKey(child, shape))]);
}

function childrenNamed<E>(element: E, name: string, shape: ElementShape<E>): E[] {
  return shape.children(element).filter((child) => shape.name(child) === name);
}

/** The Acts of a Storyboard (Storyboard/Story/Act). */
export function actsOf<E>(storyboard: E, shape: ElementShape<E>): E[] {
  return childrenNamed(storyboard, 'Story', shape).flatMap((story) => childrenNamed(story, 'Act', shape));
}

/** A ConditionGroup of the Storyboard's StopTrigger and the Acts whose StopTrigger lacks a group of the same conditions. */
export interface StoryboardStopGroup<E> {
  group: E;
  missingFrom: E[];
}

/** The ConditionGroups of the Storyboard's StopTrigger, each with the Acts whose StopTrigger does not hold it. */
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
    const key = structureKey(group, shape);
    return { group, missingFrom: acts.filter(({ groups }) => !groups.has(key)).map(({ act }) => act) };
  });
}

/**
 * The ConditionGroups of the Storyboard's StopTrigger that the StopTrigger of every one of its Acts holds too (a
 * group of the same conditions): ScenarioRunner stops the scenario on them. None when it has no Act.
 */
export function stopGroupsKeptInActs<E>(storyboard: E, shape: ElementShape<E>): Set<E> {
  if (actsOf(storyboard, shape).length === 0) return new Set();
  return new Set(
    storyboardStopGroups(storyboard, shape)
      .filter(({ missingFrom }) => missingFrom.length === 0)
      .map(({ group }) => group),
  );
}

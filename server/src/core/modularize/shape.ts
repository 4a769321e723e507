import { ManeuverGroupInfo } from '../model';
import { descendants, endTagStart, XmlDocument, XmlElement } from '../xml';

/** One attribute of a group, addressed by its element's place in document order and its name. */
export interface Slot {
  /** Index of the element in the group's elements, document order, the group itself at 0. */
  element: number;
  name: string;
}

/** A ManeuverGroup of one input, read for comparison with the groups of the others. */
export interface GroupOccurrence {
  /** Index of the input the group stands in. */
  input: number;
  document: XmlDocument;
  group: ManeuverGroupInfo;
  /** The group element and every element below it, in document order. */
  elements: XmlElement[];
  /** Values of `slots`, in the same order. */
  values: string[];
  /** Index (in `elements`) of the actor's EntityRef, which the outer group of a reference sets. */
  actorElement: number;
}

/** The structure two groups must share to be one behaviour: elements, attribute names and text, in order. */
export interface GroupShape {
  key: string;
  slots: Slot[];
}

const COMMENT = /<!--[\s\S]*?-->/g;

/** The character data of an element outside its children and comments, trimmed (text values are not parameters). */
function ownText(text: string, element: XmlElement): string {
  if (element.selfClosing) return '';
  const closeTag = endTagStart(text, element);
  let from = element.startTagEnd;
  let result = '';
  for (const child of element.children) {
    result += text.slice(from, child.start);
    from = child.end;
  }
  result += text.slice(from, Math.max(from, closeTag));
  return result.replace(COMMENT, '').trim();
}

/**
 * The shape of a group and its attribute values; undefined for a group that cannot be imported:
 * one without a name, without an actor in its Actors (the outer group gives the actor), or already
 * holding a ScenarioReference.
 */
export function readOccurrence(
  input: number,
  document: XmlDocument,
  group: ManeuverGroupInfo,
): { shape: GroupShape; occurrence: GroupOccurrence } | undefined {
  if (!group.nameAttribute || group.references.length > 0) return undefined;
  if (!group.actor || group.actor.parent?.name !== 'Actors' || group.actor.parent.parent !== group.element) return undefined;
  const elements = [group.element, ...descendants(group.element)];
  const indexOf = new Map(elements.map((element, index) => [element, index]));
  const slots: Slot[] = [];
  const values: string[] = [];
  const parts: string[] = [];
  for (const [index, element] of elements.entries()) {
    if (element.name === 'ScenarioReference' || element.attributes.some((item) => item.name === 'parameterAttributes')) return undefined;
    const depth = depthBelow(element, group.element);
    const names = element.attributes.map((item) => item.name);
    parts.push(`${depth}<${element.name} ${names.join(' ')}>${JSON.stringify(ownText(document.text, element))}`);
    for (const item of element.attributes) {
      slots.push({ element: index, name: item.name });
      values.push(item.value);
    }
  }
  const actorElement = indexOf.get(group.actor) as number;
  return { shape: { key: parts.join('\n'), slots }, occurrence: { input, document, group, elements, values, actorElement } };
}

function depthBelow(element: XmlElement, ancestor: XmlElement): number {
  let depth = 0;
  for (let current: XmlElement | undefined = element; current && current !== ancestor; current = current.parent) depth++;
  return depth;
}

import { TextEdit } from '../flatten/edits';
import { ManeuverGroupInfo, PARAMETER_ATTRIBUTES, parseParameterAttributeNames } from '../model';
import { attribute, XmlAttribute, XmlElement } from '../xml';

/** The ManeuverGroup an element stands in (itself included), if any. */
export function groupOf(groups: readonly ManeuverGroupInfo[], element: XmlElement | undefined): ManeuverGroupInfo | undefined {
  for (let current = element; current; current = current.parent) {
    if (current.name === 'ManeuverGroup') return groups.find((group) => group.element === current);
  }
  return undefined;
}

/**
 * The edit that lists `target` in its element's `parameterAttributes` (the attribute added when the
 * element has none); undefined when it is listed already or is `parameterAttributes` itself.
 */
export function makeOverridableEdit(element: XmlElement, target: XmlAttribute): TextEdit | undefined {
  if (target.name === PARAMETER_ATTRIBUTES) return undefined;
  const declaration = attribute(element, PARAMETER_ATTRIBUTES);
  if (!declaration) return { start: element.nameEnd, end: element.nameEnd, text: ` ${PARAMETER_ATTRIBUTES}="${target.name}"` };
  const names = parseParameterAttributeNames(element, declaration);
  if (names.some((entry) => entry.name === target.name)) return undefined;
  const last = names[names.length - 1];
  return last
    ? { start: last.end, end: last.end, text: `,${target.name}` }
    : { start: declaration.valueStart, end: declaration.valueEnd, text: target.name };
}

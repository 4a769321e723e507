import type { RelatedProblemLocation } from '../../problems';
import { XmlAttribute, XmlElement } from '../../xml';
import type { Finding, SemanticContext } from './types';

/** A finding's place: an attribute's value, or the element's start tag name. */
export function at(element: XmlElement, attr: XmlAttribute | undefined): Pick<Finding, 'element' | 'attribute' | 'start' | 'end'> {
  return attr
    ? { element, attribute: attr, start: attr.valueStart, end: attr.valueEnd }
    : { element, attribute: undefined, start: element.start, end: element.nameEnd };
}

export function relatedAt(context: SemanticContext, start: number, end: number, message: string): RelatedProblemLocation {
  return { source: context.ref, range: context.model.document.lines.range(start, end), message };
}

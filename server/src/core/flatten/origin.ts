import { listedName } from '../model';
import { RelatedProblemLocation, ZERO_RANGE } from '../problems';
import { elementStartingAt, selfAndDescendants, XmlElement } from '../xml';
import { FlatSource, Insertion } from './types';

/**
 * Where an element of a flattened text was written: the file and element it was copied from,
 * followed through every nested package. Elements outside imported groups map to the file itself.
 */
export function originOf(source: FlatSource, element: XmlElement): { source: FlatSource; element: XmlElement } {
  if (!source.model || !source.original || source.model === source.original) return { source, element };
  const insertion = source.insertions.find((candidate) => element.start >= candidate.start && element.end <= candidate.end);
  const addition = insertion
    ? undefined
    : source.additions.find((candidate) => element.start >= candidate.start && element.end <= candidate.end);
  const part = addition?.parts.find((candidate) => element.start === candidate.start && element.end === candidate.end);
  if (part) return originOf(part.source, part.element);
  if (!insertion) return { source, element: originalOutsideCopies(source, element) };
  const copied = copiedFrom(source, insertion, element);
  return copied ? originOf(copied.source, copied.element) : { source, element };
}

/** Outside imported groups the flattened text is the original text, shifted by each replaced region. */
function originalOutsideCopies(source: FlatSource, element: XmlElement): XmlElement {
  const regions = new Map<number, { outStart: number; outEnd: number; inStart: number; inEnd: number }>();
  for (const candidate of source.additions) {
    regions.set(-1 - candidate.replacedStart, {
      outStart: candidate.start,
      outEnd: candidate.end,
      inStart: candidate.replacedStart,
      inEnd: candidate.replacedEnd,
    });
  }
  for (const candidate of source.insertions) {
    const region = regions.get(candidate.replacedStart);
    if (region) region.outEnd = Math.max(region.outEnd, candidate.end);
    else
      regions.set(candidate.replacedStart, {
        outStart: candidate.start,
        outEnd: candidate.end,
        inStart: candidate.replacedStart,
        inEnd: candidate.replacedEnd,
      });
  }
  let shift = 0;
  for (const region of regions.values()) {
    if (region.outEnd <= element.start) shift += region.inEnd - region.inStart - (region.outEnd - region.outStart);
  }
  const original = elementStartingAt(source.original?.document.root, element.start + shift);
  return original && original.name === element.name ? original : element;
}

/** The element of the imported group (in the referenced file's flattened model) that `element` of an insertion copies. */
export function copiedFrom(
  source: FlatSource,
  insertion: Insertion,
  element: XmlElement,
): { source: FlatSource; element: XmlElement } | undefined {
  const copyRoot = source.model?.groups.find((group) => group.element.start === insertion.start)?.element;
  const sourceOfCopy = insertion.link.source;
  const targetGroup = insertion.group.target;
  if (!copyRoot || !sourceOfCopy || !targetGroup) return undefined;
  const index = selfAndDescendants(copyRoot).indexOf(element);
  const counterpart = selfAndDescendants(targetGroup.element)[index];
  return counterpart ? { source: sourceOfCopy, element: counterpart } : undefined;
}

/** The location of a name inside the `parameterAttributes` of an element, in the file it was written in. */
export function declarationLocation(
  origin: { source: FlatSource; element: XmlElement },
  name: string,
  message: string,
): RelatedProblemLocation {
  const model = origin.source.original ?? origin.source.model;
  const listed = listedName(origin.element, name);
  const start = listed?.start ?? origin.element.start;
  const end = listed?.end ?? origin.element.nameEnd;
  return { source: origin.source.ref, range: model ? model.document.lines.range(start, end) : ZERO_RANGE, message };
}

import { FlatSource } from '../flatten';
import { applyEdits, parameterAttributeSpans, TextEdit } from '../flatten/edits';
import { XmlElement } from '../xml';

/**
 * The edits that replace one referencing group of a rendered main by its flattened form, in place:
 * the copies flattening inserted for it (their `parameterAttributes` removed, as flattening does at the
 * end), with whatever carrying added to the main's root for the imported groups (SPEC 11). Undefined
 * when the main was not rendered or flattening inserted nothing for the group.
 */
export function inlineEdits(main: FlatSource, outerGroup: XmlElement): TextEdit[] | undefined {
  const flattened = main.text;
  const model = main.model;
  if (flattened === undefined || !model) return undefined;
  const copies = main.insertions.filter((insertion) => insertion.outerGroup.element === outerGroup);
  if (copies.length === 0) return undefined;
  const start = Math.min(...copies.map((copy) => copy.start));
  const end = Math.max(...copies.map((copy) => copy.end));
  const stripped = parameterAttributeSpans(model)
    .filter((span) => span.start >= start && span.end <= end)
    .map((span) => ({ ...span, text: '' }));
  const edits: TextEdit[] = [
    { start: copies[0].replacedStart, end: copies[0].replacedEnd, text: applyEdits(flattened, stripped, start, end) },
  ];
  for (const addition of main.additions)
    edits.push({ start: addition.replacedStart, end: addition.replacedEnd, text: flattened.slice(addition.start, addition.end) });
  return edits;
}

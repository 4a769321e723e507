import { elementAt, XmlAttribute, XmlDocument, XmlElement } from './xml';

/**
 * Where the cursor stands, read from the tolerant parse (core/xml), which keeps the offsets of a
 * half-typed tag or value: the questions completion and navigation ask before they look anything up.
 */

/** An attribute value around the cursor. */
export interface ValueContext {
  element: string;
  attribute: string;
  /** Offsets of the value's content (inside the quotes). */
  valueStart: number;
  valueEnd: number;
  /** What is typed between the opening quote and the cursor. */
  prefix: string;
  /** Start offset of the tag (`<`). */
  tagStart: number;
  /** Attribute names written in the same tag, with their values. */
  siblings: { name: string; value: string }[];
}

export function ancestor(element: XmlElement | undefined, name: string): XmlElement | undefined {
  for (let current = element; current; current = current.parent) if (current.name === name) return current;
  return undefined;
}

/** The element whose start tag holds the offset (past its `<`), if any. */
function startTagAt(document: XmlDocument, offset: number): XmlElement | undefined {
  const element = elementAt(document, offset);
  if (!element || offset <= element.start) return undefined;
  const terminated = document.text[element.startTagEnd - 1] === '>';
  return offset < element.startTagEnd || (!terminated && offset === element.startTagEnd) ? element : undefined;
}

/** Whether the cursor stands in markup the tree holds no element for: an end tag, a comment, a declaration being typed. */
function inOtherMarkup(document: XmlDocument, offset: number): boolean {
  return offset > 0 && document.text.lastIndexOf('<', offset - 1) > document.text.lastIndexOf('>', offset - 1);
}

/** The attribute of the document whose name or value holds the offset. */
export function attributeAt(document: XmlDocument, offset: number): { element: XmlElement; attribute: XmlAttribute } | undefined {
  const element = elementAt(document, offset);
  if (!element || offset > element.startTagEnd) return undefined;
  for (const candidate of element.attributes) {
    if (
      (offset >= candidate.nameStart && offset <= candidate.nameEnd) ||
      (offset >= candidate.valueStart && offset <= candidate.valueEnd)
    ) {
      return { element, attribute: candidate };
    }
  }
  return undefined;
}

/**
 * Where a value being typed (its closing quote missing, so the parse ran it to the line end) ends: at a
 * quote after the cursor on the same line, else at the cursor, so that completion replaces only what is typed.
 */
function typedValueEnd(text: string, quote: string, offset: number): number {
  const close = text.indexOf(quote, offset);
  const rest = text.slice(offset, close < 0 ? undefined : close);
  return close >= 0 && !/[<>\n]/.test(rest) ? close : offset;
}

/** The attribute value the cursor stands in, if any (also while the value is still being typed). */
export function valueContextAt(document: XmlDocument, offset: number): ValueContext | undefined {
  const element = startTagAt(document, offset);
  const value = element?.attributes.find((candidate) => offset >= candidate.valueStart && offset <= candidate.valueEnd);
  if (!element || !value) return undefined;
  return {
    element: element.name,
    attribute: value.name,
    valueStart: value.valueStart,
    valueEnd: document.text[value.valueEnd] === value.quote ? value.valueEnd : typedValueEnd(document.text, value.quote, offset),
    prefix: document.text.slice(value.valueStart, offset),
    tagStart: element.start,
    siblings: element.attributes.map((entry) => ({ name: entry.name, value: entry.value })),
  };
}

/** The element name being typed right after `<`, or an empty name where the cursor stands in element content. */
export function elementNameContextAt(document: XmlDocument, offset: number): { start: number; prefix: string } | undefined {
  const text = document.text;
  let start = offset;
  while (start > 0 && /[-\w.:]/.test(text[start - 1])) start--;
  if (text[start - 1] === '<') return { start: start - 1, prefix: text.slice(start, offset) };
  if (start === offset && !startTagAt(document, offset) && !inOtherMarkup(document, offset)) return { start: offset, prefix: '' };
  return undefined;
}

/** The start tag the cursor stands in, outside any attribute value: for attribute-name completion. */
export function attributeNameContextAt(
  document: XmlDocument,
  offset: number,
): { tagStart: number; element: string; written: string[]; start: number; prefix: string } | undefined {
  const element = startTagAt(document, offset);
  if (!element || offset <= element.nameEnd || valueContextAt(document, offset)) return undefined;
  const text = document.text;
  let start = offset;
  while (start > 0 && /[-\w.:]/.test(text[start - 1])) start--;
  if (!/\s/.test(text[start - 1] ?? '')) return undefined;
  return {
    tagStart: element.start,
    element: element.name,
    written: element.attributes.map((entry) => entry.name),
    start,
    prefix: text.slice(start, offset),
  };
}

/** The innermost element still open at `start`, where a child typed there goes (a half-typed `<Nam` parses as an element of its own). */
export function openElementAt(document: XmlDocument, start: number, offset: number): XmlElement | undefined {
  let parent = elementAt(document, offset);
  while (parent && (parent.start >= start || (parent.closed && parent.end <= start))) parent = parent.parent;
  return parent && start >= parent.startTagEnd ? parent : undefined;
}

/** The last `<elementName` element that starts before `before`, in document order. */
export function lastElementBefore(document: XmlDocument, elementName: string, before: number): XmlElement | undefined {
  let found: XmlElement | undefined;
  const visit = (element: XmlElement) => {
    if (element.start >= before) return false;
    if (element.name === elementName) found = element;
    for (const child of element.children) if (visit(child) === false) return false;
    return true;
  };
  if (document.root) visit(document.root);
  return found;
}

/** Every `<elementName` element that starts in [from, to). */
export function elementsBetween(document: XmlDocument, elementName: string, from: number, to: number): XmlElement[] {
  const found: XmlElement[] = [];
  const visit = (element: XmlElement) => {
    if (element.start >= to || element.end < from) return;
    if (element.name === elementName && element.start >= from) found.push(element);
    for (const child of element.children) visit(child);
  };
  if (document.root) visit(document.root);
  return found;
}

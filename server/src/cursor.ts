import { attribute, elementAt, XmlAttribute, XmlDocument, XmlElement } from './core/xml';

/** An attribute value around the cursor, read from the text alone so that it works while typing. */
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

const NAME = /[A-Za-z_:][-\w.:]*/y;
const SCAN_LIMIT = 20_000;

/** Where the tag holding `offset` starts, or undefined when the cursor stands in element content. */
function tagStartBefore(text: string, offset: number): number | undefined {
  let quote: string | undefined;
  // Scanning backwards cannot tell quotes apart, so find the last '<' and check forwards from it.
  const floor = Math.max(0, offset - SCAN_LIMIT);
  for (let i = offset - 1; i >= floor; i--) {
    const char = text[i];
    if (char === '<') return i;
    if (char === '>' && quote === undefined) {
      // A '>' inside a quoted value is legal; the forward scan below decides.
      const candidate = text.lastIndexOf('<', i);
      if (candidate < 0 || candidate < floor) return undefined;
      const state = scanTag(text, candidate, offset);
      return state && state.open ? candidate : undefined;
    }
  }
  return undefined;
}

interface TagScan {
  element: string;
  open: boolean;
  attributes: { name: string; value: string; valueStart: number; valueEnd: number | undefined; quote: string }[];
}

/** Reads a start tag from `<` up to `limit`; `open` is false when the tag ended before `limit`. */
function scanTag(text: string, start: number, limit: number): TagScan | undefined {
  NAME.lastIndex = start + 1;
  const nameMatch = NAME.exec(text);
  if (!nameMatch) return undefined;
  const scan: TagScan = { element: nameMatch[0], open: true, attributes: [] };
  let i = start + 1 + nameMatch[0].length;
  while (i < limit) {
    const char = text[i];
    if (char === '>' || char === '<') {
      scan.open = false;
      return scan;
    }
    NAME.lastIndex = i;
    const attributeName = /[A-Za-z_:]/.test(char) ? NAME.exec(text) : null;
    if (!attributeName) {
      i++;
      continue;
    }
    i += attributeName[0].length;
    while (i < limit && /\s/.test(text[i])) i++;
    if (text[i] !== '=') continue;
    i++;
    while (i < limit && /\s/.test(text[i])) i++;
    const quote = text[i];
    if (quote !== '"' && quote !== "'") continue;
    const valueStart = i + 1;
    const close = text.indexOf(quote, valueStart);
    const lineEnd = text.slice(valueStart, close < 0 ? undefined : close).search(/[<>\n]/);
    const valueEnd = close >= 0 && lineEnd < 0 ? close : undefined;
    scan.attributes.push({ name: attributeName[0], value: text.slice(valueStart, valueEnd ?? limit), valueStart, valueEnd, quote });
    if (valueEnd === undefined || valueEnd >= limit) return scan;
    i = valueEnd + 1;
  }
  return scan;
}

/** The attribute value the cursor stands in, if any, from the text around it. */
export function valueContextAt(text: string, offset: number): ValueContext | undefined {
  const tagStart = tagStartBefore(text, offset);
  if (tagStart === undefined) return undefined;
  const scan = scanTag(text, tagStart, offset);
  if (!scan || !scan.open) return undefined;
  const last = scan.attributes[scan.attributes.length - 1];
  if (!last || last.valueStart > offset || (last.valueEnd !== undefined && last.valueEnd < offset)) return undefined;
  // The value ends at its closing quote, or at the cursor when it is not yet closed.
  let valueEnd = last.valueEnd ?? offset;
  if (last.valueEnd === undefined) {
    const close = text.indexOf(last.quote, offset);
    const stop = text.slice(offset, close < 0 ? undefined : close).search(/[<>\n]/);
    if (close >= 0 && stop < 0) valueEnd = close;
  }
  const whole = scanTag(text, tagStart, text.length);
  return {
    element: scan.element,
    attribute: last.name,
    valueStart: last.valueStart,
    valueEnd,
    prefix: text.slice(last.valueStart, offset),
    tagStart,
    siblings: (whole ?? scan).attributes.map((entry) => ({ name: entry.name, value: entry.value })),
  };
}

/** The element name being typed right after `<`, when the cursor stands in element content. */
export function elementNameContextAt(text: string, offset: number): { start: number; prefix: string } | undefined {
  let start = offset;
  while (start > 0 && /[-\w.:]/.test(text[start - 1])) start--;
  if (text[start - 1] === '<') return { start: start - 1, prefix: text.slice(start, offset) };
  if (start === offset && tagStartBefore(text, offset) === undefined) return { start: offset, prefix: '' };
  return undefined;
}

/** The last value of `attributeName` written in a `<elementName` tag that starts in [from, to). */
export function lastAttributeValueBefore(text: string, elementName: string, attributeName: string, from: number, to: number): { value: string; tagStart: number } | undefined {
  let tagStart = text.lastIndexOf(`<${elementName}`, to - 1);
  while (tagStart >= from) {
    const scan = scanTag(text, tagStart, text.length);
    if (scan && scan.element === elementName) {
      const found = scan.attributes.find((entry) => entry.name === attributeName);
      return found ? { value: found.value, tagStart } : { value: '', tagStart };
    }
    tagStart = text.lastIndexOf(`<${elementName}`, tagStart - 1);
  }
  return undefined;
}

/** Every value of `attributeName` in `<elementName` tags between the offsets. */
export function attributeValuesBetween(text: string, elementName: string, attributeName: string, from: number, to: number): { value: string; valueStart: number }[] {
  const values: { value: string; valueStart: number }[] = [];
  for (let tagStart = text.indexOf(`<${elementName}`, from); tagStart >= 0 && tagStart < to; tagStart = text.indexOf(`<${elementName}`, tagStart + 1)) {
    const scan = scanTag(text, tagStart, text.length);
    const found = scan?.element === elementName ? scan.attributes.find((entry) => entry.name === attributeName) : undefined;
    if (found) values.push({ value: found.value, valueStart: found.valueStart });
  }
  return values;
}

const MARKUP = /<!--[\s\S]*?(?:-->|$)|<!\[CDATA\[[\s\S]*?(?:\]\]>|$)|<[?!][^>]*>?|<\/([^\s>]*)[^>]*>?|<([A-Za-z_:][-\w.:]*)(?:"[^"]*"|'[^']*'|[^'">])*>?/g;

/**
 * The names of the elements open at `offset`, outermost first, read from the text so that it works
 * while the document is not well-formed: a closing tag closes up to the nearest element of its name.
 */
export function openElementsAt(text: string, offset: number): string[] {
  const open: string[] = [];
  const before = text.slice(0, offset);
  MARKUP.lastIndex = 0;
  for (let match = MARKUP.exec(before); match; match = MARKUP.exec(before)) {
    const [tag, closing, opening] = match;
    if (closing !== undefined) {
      const index = open.lastIndexOf(closing);
      if (index >= 0) open.length = index;
    } else if (opening !== undefined && tag.endsWith('>') && !tag.endsWith('/>')) {
      open.push(opening);
    }
  }
  return open;
}

/** The attribute of the parsed document whose name or value holds the offset. */
export function attributeAt(document: XmlDocument, offset: number): { element: XmlElement; attribute: XmlAttribute } | undefined {
  const element = elementAt(document, offset);
  if (!element || offset > element.startTagEnd) return undefined;
  for (const candidate of element.attributes) {
    if ((offset >= candidate.nameStart && offset <= candidate.nameEnd) || (offset >= candidate.valueStart && offset <= candidate.valueEnd)) {
      return { element, attribute: candidate };
    }
  }
  return undefined;
}

export function ancestor(element: XmlElement | undefined, name: string): XmlElement | undefined {
  for (let current = element; current; current = current.parent) if (current.name === name) return current;
  return undefined;
}

export { attribute };

/** The start tag the cursor stands in, outside any attribute value: for attribute-name completion. */
export function attributeNameContextAt(text: string, offset: number): { tagStart: number; element: string; written: string[]; start: number; prefix: string } | undefined {
  const tagStart = tagStartBefore(text, offset);
  if (tagStart === undefined || valueContextAt(text, offset)) return undefined;
  const scan = scanTag(text, tagStart, offset);
  if (!scan || !scan.open || tagStart + 1 + scan.element.length >= offset) return undefined;
  let start = offset;
  while (start > 0 && /[-\w.:]/.test(text[start - 1])) start--;
  if (!/\s/.test(text[start - 1] ?? '')) return undefined;
  const whole = scanTag(text, tagStart, text.length) ?? scan;
  return { tagStart, element: scan.element, written: whole.attributes.map((entry) => entry.name), start, prefix: text.slice(start, offset) };
}

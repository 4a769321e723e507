import { LineIndex } from './text';

/** An attribute with the offsets of its name and of its raw value (inside the quotes). */
export interface XmlAttribute {
  name: string;
  /** The value with entity and character references decoded. */
  value: string;
  nameStart: number;
  nameEnd: number;
  valueStart: number;
  valueEnd: number;
  quote: '"' | "'";
}

export interface XmlElement {
  name: string;
  /** Offset of `<`. */
  start: number;
  nameEnd: number;
  /** Offset just after the start tag's `>` (or where the broken tag ends). */
  startTagEnd: number;
  /** Offset just after the end tag's `>`, or after `/>`. */
  end: number;
  selfClosing: boolean;
  /** False when the element was never closed (the document is not well-formed). */
  closed: boolean;
  attributes: XmlAttribute[];
  children: XmlElement[];
  parent: XmlElement | undefined;
}

export interface XmlProblem {
  message: string;
  start: number;
  end: number;
  severity: 'error' | 'warning';
}

export interface XmlDocument {
  text: string;
  root: XmlElement | undefined;
  problems: XmlProblem[];
  lines: LineIndex;
  /** The internal general entities of the DOCTYPE, expanded; absent when none is declared. */
  entities?: ReadonlyMap<string, string>;
}

export interface XmlParseOptions {
  /** Upper bound on characters produced by expanding internal entities, per document. */
  maxEntityExpansion?: number;
  /** Upper bound on element nesting; deeper content is reported and skipped. */
  maxDepth?: number;
}

/** A raw attribute value that decodes to itself: no references, no white space to normalize. */
const PLAIN_VALUE = /^[^&\x00-\x1F\uD800-\uDFFF\uFFFE\uFFFF]*$/;

const LINE_END = /[\r\n>]/g;

const PREDEFINED_ENTITIES: Record<string, string> = { lt: '<', gt: '>', amp: '&', quot: '"', apos: "'" };

export function attribute(element: XmlElement, name: string): XmlAttribute | undefined {
  for (const candidate of element.attributes) if (candidate.name === name) return candidate;
  return undefined;
}

export function attributeValue(element: XmlElement, name: string): string | undefined {
  return attribute(element, name)?.value;
}

/** Every element below `element`, in document order (an array: generators are slow on hot paths). */
export function descendants(element: XmlElement): XmlElement[] {
  const result: XmlElement[] = [];
  const stack: XmlElement[] = [];
  for (let i = element.children.length - 1; i >= 0; i--) stack.push(element.children[i]);
  while (stack.length > 0) {
    const next = stack.pop() as XmlElement;
    result.push(next);
    for (let i = next.children.length - 1; i >= 0; i--) stack.push(next.children[i]);
  }
  return result;
}

export function firstDescendant(element: XmlElement, name: string): XmlElement | undefined {
  for (const candidate of descendants(element)) if (candidate.name === name) return candidate;
  return undefined;
}

/** The innermost element whose tag range contains the offset. */
export function elementAt(document: XmlDocument, offset: number): XmlElement | undefined {
  let current = document.root;
  if (!current || offset < current.start || offset > current.end) return undefined;
  for (;;) {
    const child: XmlElement | undefined = current.children.find((c) => offset >= c.start && offset <= c.end);
    if (!child) return current;
    current = child;
  }
}

/** Escapes text for use inside an attribute value delimited by `quote`. */
export function escapeAttributeValue(value: string, quote: '"' | "'" = '"'): string {
  let escaped = value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
  escaped = quote === '"' ? escaped.replace(/"/g, '&quot;') : escaped.replace(/'/g, '&apos;');
  return escaped.replace(/\t/g, '&#9;').replace(/\n/g, '&#10;').replace(/\r/g, '&#13;');
}

function isNameStart(code: number): boolean {
  return (
    (code >= 65 && code <= 90) || (code >= 97 && code <= 122) || code === 95 || code === 58 || code >= 0xc0
  );
}

/** Whether a code point is a Char of XML 1.0: no NUL, no other C0 control but tab and line ends, no U+FFFE/U+FFFF. */
export function isXmlChar(code: number): boolean {
  return code === 9 || code === 10 || code === 13 || (code >= 0x20 && code <= 0xd7ff) || (code >= 0xe000 && code <= 0xfffd) || (code >= 0x10000 && code <= 0x10ffff);
}

/** Characters that may not occur in an XML document, lone surrogates included. */
const NOT_XML_CHAR = /[\x00-\x08\x0B\x0C\x0E-\x1F\uFFFE\uFFFF\uD800-\uDFFF]/g;

function codePointName(code: number): string {
  return `U+${code.toString(16).toUpperCase().padStart(4, '0')}`;
}

function isSpace(code: number): boolean {
  return code === 32 || code === 9 || code === 10 || code === 13;
}

/**
 * A tolerant XML parser that records the offsets of every element and attribute. It never reads
 * anything outside the text: external entities are reported, not resolved, and internal entity
 * expansion is bounded. On malformed input it reports each problem and recovers, so that an editor
 * can still work with a document that is being typed.
 */
export function parseXml(input: string, options: XmlParseOptions = {}): XmlDocument {
  const text = input;
  const maxExpansion = options.maxEntityExpansion ?? 1_000_000;
  const maxDepth = options.maxDepth ?? 2000;
  const problems: XmlProblem[] = [];
  const entities = new Map<string, string>();
  const externalEntities = new Set<string>();
  let expanded = 0;
  let expansionReported = false;
  let root: XmlElement | undefined;
  const stack: XmlElement[] = [];
  let position = text.charCodeAt(0) === 0xfeff ? 1 : 0;
  let seenDoctype = false;

  const report = (message: string, start: number, end = start + 1, severity: 'error' | 'warning' = 'error') => {
    if (problems.length < 1000) problems.push({ message, start, end: Math.max(end, start), severity });
  };

  const expandEntity = (name: string, start: number, end: number, depth: number): string => {
    const predefined = PREDEFINED_ENTITIES[name];
    if (predefined !== undefined) return predefined;
    if (externalEntities.has(name)) {
      report(`external entity '&${name};' is never resolved; its reference is left empty`, start, end);
      return '';
    }
    const replacement = entities.get(name);
    if (replacement === undefined) {
      report(`undefined entity '&${name};' (escape a literal '&' as '&amp;')`, start, end);
      return '';
    }
    // Each expansion costs at least one unit, so that empty or failing entities cannot recurse without bound.
    expanded++;
    if (depth > 16) {
      report(`entity '&${name};' nests too deeply; expansion stopped`, start, end);
      return '';
    }
    if (expanded > maxExpansion) {
      if (!expansionReported) report(`entity expansion exceeds ${maxExpansion} characters; expansion stopped`, start, end);
      expansionReported = true;
      return '';
    }
    const value = decodeReferences(replacement, start, end, depth + 1);
    if (depth === 0) expanded += value.length;
    if (expanded > maxExpansion) {
      if (!expansionReported) report(`entity expansion exceeds ${maxExpansion} characters; expansion stopped`, start, end);
      expansionReported = true;
      return '';
    }
    return value;
  };

  /** Decodes references in raw text; offsets are those of the raw text in the document, for messages. */
  const decodeReferences = (raw: string, rawStart: number, rawEnd: number, depth: number): string => {
    if (raw.indexOf('&') < 0) return raw;
    let out = '';
    let i = 0;
    while (i < raw.length) {
      const amp = raw.indexOf('&', i);
      if (amp < 0) {
        out += raw.slice(i);
        if (depth > 0) expanded += raw.length - i;
        break;
      }
      out += raw.slice(i, amp);
      if (depth > 0) {
        expanded += amp - i;
        if (expanded > maxExpansion) return out;
      }
      const semicolon = raw.indexOf(';', amp);
      const at = depth === 0 ? rawStart + amp : rawStart;
      const refEnd = depth === 0 && semicolon >= 0 ? rawStart + semicolon + 1 : rawEnd;
      if (semicolon < 0 || semicolon - amp > 40) {
        report(`'&' must start an entity reference; write '&amp;' for a literal '&'`, at, at + 1);
        out += '&';
        i = amp + 1;
        continue;
      }
      const reference = raw.slice(amp + 1, semicolon);
      if (reference.startsWith('#')) {
        const code = reference.startsWith('#x') ? parseInt(reference.slice(2), 16) : parseInt(reference.slice(1), 10);
        if (!Number.isFinite(code) || !/^#(x[0-9a-fA-F]+|[0-9]+)$/.test(reference)) {
          report(`invalid character reference '&${reference};'`, at, refEnd);
        } else if (!isXmlChar(code)) {
          report(`the character reference '&${reference};' names ${code > 0x10ffff ? 'no character' : codePointName(code)}, which XML does not allow`, at, refEnd);
        } else {
          out += String.fromCodePoint(code);
        }
      } else if (/^[A-Za-z_:][\w.:-]*$/.test(reference)) {
        out += expandEntity(reference, at, refEnd, depth);
      } else {
        report(`'&' must start an entity reference; write '&amp;' for a literal '&'`, at, at + 1);
        out += '&' + reference + ';';
      }
      i = semicolon + 1;
    }
    return out;
  };

  // Sticky regular expressions run as native code, which matters in a short-lived process.
  const namePattern = /[A-Za-z_:\u00C0-\uFFFF][A-Za-z0-9_:.\-\u00B7\u00C0-\uFFFF]*/y;
  const spacePattern = /[ \t\r\n]*/y;
  const readName = (): string => {
    namePattern.lastIndex = position;
    const match = namePattern.exec(text);
    if (!match) return '';
    position += match[0].length;
    return match[0];
  };

  const skipSpace = () => {
    spacePattern.lastIndex = position;
    spacePattern.exec(text);
    position = spacePattern.lastIndex;
  };

  const parseDoctype = (start: number) => {
    if (seenDoctype || root) report('misplaced DOCTYPE', start, start + 9);
    seenDoctype = true;
    position = start + 9;
    let depth = 0;
    let subsetStart = -1;
    let subsetEnd = -1;
    while (position < text.length) {
      const code = text.charCodeAt(position);
      if (code === 34 || code === 39) {
        const close = text.indexOf(String.fromCharCode(code), position + 1);
        position = close < 0 ? text.length : close + 1;
        continue;
      }
      if (code === 91) {
        if (depth === 0) subsetStart = position + 1;
        depth++;
      } else if (code === 93) {
        depth--;
        if (depth === 0) subsetEnd = position;
      } else if (code === 62 && depth <= 0) {
        position++;
        break;
      }
      position++;
    }
    if (position >= text.length && text.charCodeAt(text.length - 1) !== 62) report('unterminated DOCTYPE', start, text.length);
    if (subsetStart >= 0 && subsetEnd > subsetStart) {
      const subset = text.slice(subsetStart, subsetEnd);
      const declaration = /<!ENTITY\s+(%\s+)?([^\s"'>]+)\s+(?:(SYSTEM|PUBLIC)\b[^>]*|"([^"]*)"|'([^']*)')\s*>/g;
      for (let match = declaration.exec(subset); match; match = declaration.exec(subset)) {
        const offset = subsetStart + match.index;
        if (match[1]) continue;
        if (match[3]) {
          externalEntities.add(match[2]);
          report(`external entity '${match[2]}' is declared; it is never resolved`, offset, offset + match[0].length, 'warning');
        } else {
          entities.set(match[2], match[4] ?? match[5] ?? '');
        }
      }
    }
  };

  const parseStartTag = (start: number) => {
    position = start + 1;
    const name = readName();
    if (!name) {
      report(`'<' must start a tag; write '&lt;' for a literal '<'`, start, start + 1);
      position = start + 1;
      return;
    }
    const element: XmlElement = {
      name,
      start,
      nameEnd: position,
      startTagEnd: position,
      end: position,
      selfClosing: false,
      closed: false,
      attributes: [],
      children: [],
      parent: stack[stack.length - 1],
    };
    let terminated = false;
    let attributeNames: Set<string> | undefined;
    for (;;) {
      const beforeSpace = position;
      skipSpace();
      if (position >= text.length) break;
      const code = text.charCodeAt(position);
      if (code === 62) {
        position++;
        terminated = true;
        break;
      }
      if (code === 47 && text.charCodeAt(position + 1) === 62) {
        position += 2;
        element.selfClosing = true;
        terminated = true;
        break;
      }
      if (code === 60) {
        report(`tag <${name}> is not closed with '>'`, start, position);
        break;
      }
      if (!isNameStart(code)) {
        report(`unexpected '${text[position]}' in tag <${name}>`, position, position + 1);
        position++;
        continue;
      }
      if (beforeSpace === position && element.attributes.length > 0) {
        report(`attributes must be separated by white space`, position, position + 1);
      }
      const nameStart = position;
      const attributeName = readName();
      const nameEnd = position;
      skipSpace();
      if (text.charCodeAt(position) !== 61) {
        report(`attribute '${attributeName}' has no value (write ${attributeName}="...")`, nameStart, nameEnd);
        continue;
      }
      position++;
      skipSpace();
      const quoteCode = text.charCodeAt(position);
      if (quoteCode !== 34 && quoteCode !== 39) {
        report(`the value of attribute '${attributeName}' must be quoted`, nameStart, position);
        continue;
      }
      const quote = quoteCode === 34 ? '"' : "'";
      const valueStart = position + 1;
      let valueEnd = text.indexOf(quote, valueStart);
      // The next '<' is found once and reused by every attribute before it (a tag may hold thousands).
      if (nextOpen < valueStart) nextOpen = indexOrEnd('<', valueStart);
      if (valueEnd < 0 || nextOpen < valueEnd) {
        // Recover at the line end so a value being typed does not swallow the rest of the file.
        LINE_END.lastIndex = valueStart;
        const lineEnd = LINE_END.exec(text);
        valueEnd = lineEnd ? lineEnd.index : text.length;
        report(`the value of attribute '${attributeName}' is not closed with ${quote}`, nameStart, valueEnd);
        position = valueEnd;
      } else {
        position = valueEnd + 1;
      }
      const raw = text.slice(valueStart, valueEnd);
      // Most values hold neither references nor line breaks: no copy is made for them.
      const value = PLAIN_VALUE.test(raw) ? raw : decodeReferences(raw.replace(/[\t\n\r]/g, ' '), valueStart, valueEnd, 0);
      // A linear scan for the usual handful of attributes, a set beyond: a tag with 40,000 attributes stays linear.
      if (element.attributes.length < 16 ? element.attributes.some((existing) => existing.name === attributeName) : (attributeNames ??= new Set(element.attributes.map((a) => a.name))).has(attributeName)) {
        report(`attribute '${attributeName}' appears twice`, nameStart, nameEnd);
      }
      attributeNames?.add(attributeName);
      element.attributes.push({ name: attributeName, value, nameStart, nameEnd, valueStart, valueEnd, quote });
    }
    if (!terminated && position >= text.length) report(`tag <${name}> is not closed with '>'`, start, text.length);
    element.startTagEnd = position;
    element.end = position;
    if (stack.length === 0) {
      if (root) report(`a document has one root element; <${name}> is a second one`, start, element.nameEnd);
      else root = element;
    } else {
      stack[stack.length - 1].children.push(element);
    }
    if (element.selfClosing || !terminated) {
      element.closed = element.selfClosing;
      return;
    }
    if (stack.length >= maxDepth) {
      report(`elements nest deeper than ${maxDepth} levels`, start, element.nameEnd);
      element.closed = true;
      return;
    }
    stack.push(element);
    openByName.set(name, (openByName.get(name) ?? 0) + 1);
  };
  /** How many elements of each name are open: an end tag that matches none is known at once. */
  const openByName = new Map<string, number>();
  const popElement = (): XmlElement => {
    const element = stack.pop() as XmlElement;
    openByName.set(element.name, (openByName.get(element.name) ?? 1) - 1);
    return element;
  };

  const parseEndTag = (start: number) => {
    position = start + 2;
    const name = readName();
    skipSpace();
    if (text.charCodeAt(position) === 62) position++;
    else report(`end tag </${name}> is not closed with '>'`, start, position);
    if (!openByName.get(name)) {
      report(`end tag </${name}> has no matching start tag`, start, position);
      return;
    }
    // The search costs as many steps as elements it closes, so each element is passed once.
    let matchIndex = stack.length - 1;
    while (stack[matchIndex].name !== name) matchIndex--;
    while (stack.length - 1 > matchIndex) {
      const unclosed = popElement();
      unclosed.end = start;
      report(`element <${unclosed.name}> is not closed (expected </${unclosed.name}> before </${name}>)`, unclosed.start, unclosed.nameEnd);
    }
    const element = popElement();
    element.end = position;
    element.closed = true;
  };

  const checkText = (from: number, to: number) => {
    if (to <= from) return;
    if (stack.length === 0) {
      for (let i = from; i < to; i++) {
        if (!isSpace(text.charCodeAt(i))) {
          report('text is not allowed outside the root element', i, Math.min(to, i + 1));
          return;
        }
      }
      return;
    }
    // The next '&' and ']]>' are found once and reused, so each text run costs only its own length.
    if (nextAmpersand < from) nextAmpersand = indexOrEnd('&', from);
    if (nextAmpersand < to) decodeReferences(text.slice(from, to), from, to, 0);
    if (nextCdataEnd < from) nextCdataEnd = indexOrEnd(']]>', from);
    if (nextCdataEnd < to) report(`']]>' is not allowed in text`, nextCdataEnd, nextCdataEnd + 3);
  };
  const indexOrEnd = (needle: string, from: number) => {
    const found = text.indexOf(needle, from);
    return found < 0 ? text.length : found;
  };
  let nextAmpersand = -1;
  let nextOpen = -1;
  let nextCdataEnd = -1;

  for (let match = NOT_XML_CHAR.exec(text); match; match = NOT_XML_CHAR.exec(text)) {
    if (problems.length >= 1000) break;
    const code = match[0].charCodeAt(0);
    // A surrogate pair is one character beyond U+FFFF; only a lone half is an error.
    if (code >= 0xd800 && code <= 0xdbff && (text.charCodeAt(match.index + 1) & 0xfc00) === 0xdc00) {
      NOT_XML_CHAR.lastIndex = match.index + 2;
      continue;
    }
    report(`the character ${codePointName(match[0].charCodeAt(0))} is not allowed in XML; remove it or write it another way`, match.index, match.index + 1);
  }
  NOT_XML_CHAR.lastIndex = 0;

  while (position < text.length) {
    const open = text.indexOf('<', position);
    const textEnd = open < 0 ? text.length : open;
    checkText(position, textEnd);
    if (open < 0) {
      position = text.length;
      break;
    }
    if (text.startsWith('<!--', open)) {
      const close = text.indexOf('-->', open + 4);
      if (close < 0) {
        report('comment is not closed with -->', open, text.length);
        position = text.length;
      } else position = close + 3;
    } else if (text.startsWith('<![CDATA[', open)) {
      const close = text.indexOf(']]>', open + 9);
      if (stack.length === 0) report('CDATA is not allowed outside the root element', open, open + 9);
      if (close < 0) {
        report('CDATA section is not closed with ]]>', open, text.length);
        position = text.length;
      } else position = close + 3;
    } else if (text.startsWith('<?', open)) {
      const close = text.indexOf('?>', open + 2);
      const target = /^<\?([^\s?]*)/.exec(text.slice(open, open + 64))?.[1] ?? '';
      if (target.toLowerCase() === 'xml' && open !== (text.charCodeAt(0) === 0xfeff ? 1 : 0)) {
        report('the XML declaration must be at the very start of the file', open, open + 5);
      }
      if (close < 0) {
        report('processing instruction is not closed with ?>', open, text.length);
        position = text.length;
      } else position = close + 2;
    } else if (text.startsWith('<!DOCTYPE', open)) {
      parseDoctype(open);
    } else if (text.startsWith('</', open)) {
      parseEndTag(open);
    } else {
      parseStartTag(open);
    }
  }
  while (stack.length > 0) {
    const unclosed = stack.pop() as XmlElement;
    unclosed.end = text.length;
    report(`element <${unclosed.name}> is not closed (expected </${unclosed.name}>)`, unclosed.start, unclosed.nameEnd);
  }
  if (!root) report('the file holds no XML element', 0, Math.min(text.length, 1));
  let expandedEntities: Map<string, string> | undefined;
  if (entities.size > 0) {
    expandedEntities = new Map();
    // Expanded for flattening, which copies groups out of this document; problems were reported where used.
    const reported = problems.length;
    for (const name of entities.keys()) expandedEntities.set(name, expandEntity(name, 0, 0, 0));
    problems.length = reported;
  }
  let lines: LineIndex | undefined;
  return {
    text,
    root,
    problems,
    entities: expandedEntities,
    // Built on first use: most parses never need line numbers.
    get lines() {
      lines ??= new LineIndex(text);
      return lines;
    },
  };
}

export function isWellFormed(document: XmlDocument): boolean {
  return !document.problems.some((problem) => problem.severity === 'error');
}

/**
 * Parses `text` knowing `previous`, the same document before one edit. When the edit lies inside a
 * single attribute value and changes no markup, the tree is copied with shifted offsets instead of
 * scanning the text again (typing a value in a large file); otherwise this is `parseXml(text)`.
 */
export function reparseXml(previous: XmlDocument, text: string): XmlDocument {
  return reparseValueEdit(previous, text) ?? parseXml(text);
}

const MARKUP = /["'<>&\r\n]/;
const COMPARED_CHUNK = 1024;

/** The one region in which two texts differ (`[prefix, removedEnd)` of the old, `[prefix, insertedEnd)` of the new), when it holds no markup. */
export function markupFreeEdit(old: string, text: string): { prefix: number; removedEnd: number; insertedEnd: number } | undefined {
  const shorter = Math.min(old.length, text.length);
  // Equal chunks are skipped by the engine's string comparison, far faster than a loop over characters.
  let prefix = 0;
  while (prefix + COMPARED_CHUNK <= shorter && old.slice(prefix, prefix + COMPARED_CHUNK) === text.slice(prefix, prefix + COMPARED_CHUNK)) prefix += COMPARED_CHUNK;
  while (prefix < shorter && old.charCodeAt(prefix) === text.charCodeAt(prefix)) prefix++;
  let suffix = 0;
  const sameChunkBefore = (end: number) => old.slice(old.length - end - COMPARED_CHUNK, old.length - end) === text.slice(text.length - end - COMPARED_CHUNK, text.length - end);
  while (suffix + COMPARED_CHUNK <= shorter - prefix && sameChunkBefore(suffix)) suffix += COMPARED_CHUNK;
  while (suffix < shorter - prefix && old.charCodeAt(old.length - 1 - suffix) === text.charCodeAt(text.length - 1 - suffix)) suffix++;
  const removedEnd = old.length - suffix;
  const insertedEnd = text.length - suffix;
  if (MARKUP.test(old.slice(prefix, removedEnd)) || MARKUP.test(text.slice(prefix, insertedEnd))) return undefined;
  return { prefix, removedEnd, insertedEnd };
}

/** The fast path of reparseXml: undefined unless the edit lies inside one attribute value. */
export function reparseValueEdit(previous: XmlDocument, text: string): XmlDocument | undefined {
  const old = previous.text;
  if (!previous.root || previous.problems.length > 0) return undefined;
  if (old === text) return previous;
  const edit = markupFreeEdit(old, text);
  if (!edit) return undefined;
  const { prefix, removedEnd, insertedEnd } = edit;
  // The attribute whose value holds the whole edit (its ends may touch the quotes, not cross them).
  let element: XmlElement | undefined = previous.root;
  let edited: XmlAttribute | undefined;
  while (element && !edited) {
    edited = element.attributes.find((candidate) => candidate.valueStart <= prefix && removedEnd <= candidate.valueEnd);
    if (edited) break;
    if (prefix < element.startTagEnd) return undefined;
    element = element.children.find((child) => child.start <= prefix && removedEnd <= child.end);
  }
  if (!edited) return undefined;
  const delta = insertedEnd - removedEnd;
  const raw = text.slice(edited.valueStart, edited.valueEnd + delta);
  if (!PLAIN_VALUE.test(raw)) return undefined;
  const shift = (offset: number) => (offset >= removedEnd && offset > prefix ? offset + delta : offset);
  const target = edited;
  const copy = (source: XmlElement, parent: XmlElement | undefined): XmlElement => {
    const result: XmlElement = {
      name: source.name,
      start: shift(source.start),
      nameEnd: shift(source.nameEnd),
      startTagEnd: shift(source.startTagEnd),
      end: shift(source.end),
      selfClosing: source.selfClosing,
      closed: source.closed,
      attributes: source.attributes.map((attribute) =>
        attribute === target
          ? { ...attribute, value: raw, valueEnd: attribute.valueEnd + delta }
          : {
              name: attribute.name,
              value: attribute.value,
              nameStart: shift(attribute.nameStart),
              nameEnd: shift(attribute.nameEnd),
              valueStart: shift(attribute.valueStart),
              valueEnd: shift(attribute.valueEnd),
              quote: attribute.quote,
            },
      ),
      children: [],
      parent,
    };
    for (const child of source.children) result.children.push(copy(child, result));
    return result;
  };
  const root = copy(previous.root, undefined);
  let lines: LineIndex | undefined;
  return {
    text,
    root,
    problems: [],
    entities: previous.entities,
    get lines() {
      lines ??= new LineIndex(text);
      return lines;
    },
  };
}

/** The element and every element below it, in document order. */
export function selfAndDescendants(element: XmlElement): XmlElement[] {
  return [element, ...descendants(element)];
}

/** The element of the tree that starts exactly at an offset. */
export function elementStartingAt(root: XmlElement | undefined, offset: number): XmlElement | undefined {
  let current = root;
  while (current) {
    if (current.start === offset) return current;
    current = current.children.find((child) => offset >= child.start && offset < child.end);
  }
  return undefined;
}

/** Whether `element` is `ancestor` or lies below it. */
export function isWithin(element: XmlElement, ancestor: XmlElement): boolean {
  for (let current: XmlElement | undefined = element; current; current = current.parent) if (current === ancestor) return true;
  return false;
}

import { LineIndex } from '../text';
import { codePointName, isNameChar, isNameStart, isSpace, LINE_END, NOT_XML_CHAR, PLAIN_VALUE } from './characters';
import { EntityDecoder } from './entities';
import { XmlAttribute, XmlDocument, XmlElement, XmlParseOptions, XmlProblem } from './types';

/**
 * A tolerant XML parser that records the offsets of every element and attribute. It never reads
 * anything outside the text: external entities are reported, not resolved, and internal entity
 * expansion is bounded. On malformed input it reports each problem and recovers, so that an editor
 * can still work with a document that is being typed.
 */
export function parseXml(input: string, options: XmlParseOptions = {}): XmlDocument {
  return new XmlScanner(input, options).scan();
}

/** One pass over one text: the state of parseXml, each construct scanned by its own method. */
class XmlScanner {
  private readonly maxDepth: number;
  private readonly problems: XmlProblem[] = [];
  private readonly decoder: EntityDecoder;
  private root: XmlElement | undefined;
  private readonly stack: XmlElement[] = [];
  private position: number;
  private seenDoctype = false;
  /**
   * How many elements of each name are open: an end tag that matches none is known at once. Built at the
   * first end tag that does not close the innermost element (none, in a well-formed document), kept after.
   */
  private openByName: Map<string, number> | undefined;
  // The next '&', '<' and ']]>' are found once and reused, so each text run costs only its own length.
  private nextAmpersand = -1;
  private nextOpen = -1;
  private nextCdataEnd = -1;
  // Sticky regular expressions run as native code, which matters in a short-lived process.
  private readonly namePattern = /[A-Za-z_:\u00C0-\uFFFF][A-Za-z0-9_:.\-\u00B7\u00C0-\uFFFF]*/y;
  private readonly spacePattern = /[ \t\r\n]*/y;

  constructor(
    private readonly text: string,
    options: XmlParseOptions,
  ) {
    this.maxDepth = options.maxDepth ?? 2000;
    this.decoder = new EntityDecoder(options.maxEntityExpansion ?? 1_000_000, this.report);
    this.position = text.charCodeAt(0) === 0xfeff ? 1 : 0;
  }

  private readonly report = (message: string, start: number, end = start + 1, severity: 'error' | 'warning' = 'error'): void => {
    if (this.problems.length < 1000) this.problems.push({ message, start, end: Math.max(end, start), severity });
  };

  scan(): XmlDocument {
    const text = this.text;
    this.checkCharacters();
    while (this.position < text.length) {
      const open = text.indexOf('<', this.position);
      const textEnd = open < 0 ? text.length : open;
      this.checkText(this.position, textEnd);
      if (open < 0) {
        this.position = text.length;
        break;
      }
      // The character after '<' tells most constructs apart without comparing strings.
      const next = text.charCodeAt(open + 1);
      if (next === 33 && text.startsWith('<!--', open)) this.skipComment(open);
      else if (next === 33 && text.startsWith('<![CDATA[', open)) this.skipCdata(open);
      else if (next === 63) this.skipProcessingInstruction(open);
      else if (next === 33 && text.startsWith('<!DOCTYPE', open)) this.parseDoctype(open);
      else if (next === 47) this.parseEndTag(open);
      else this.parseStartTag(open);
    }
    while (this.stack.length > 0) {
      const unclosed = this.stack.pop() as XmlElement;
      unclosed.end = text.length;
      this.report(`element <${unclosed.name}> is not closed (expected </${unclosed.name}>)`, unclosed.start, unclosed.nameEnd);
    }
    if (!this.root) this.report('the file holds no XML element', 0, Math.min(text.length, 1));
    const entities = this.expandedEntities();
    let lines: LineIndex | undefined;
    return {
      text,
      root: this.root,
      problems: this.problems,
      entities,
      // Built on first use: most parses never need line numbers.
      get lines() {
        lines ??= new LineIndex(text);
        return lines;
      },
    };
  }

  /** The DOCTYPE's entities expanded, for flattening, which copies groups out of this document. */
  private expandedEntities(): Map<string, string> | undefined {
    if (this.decoder.entities.size === 0) return undefined;
    const expanded = new Map<string, string>();
    // Problems were reported where each entity is used, not again here.
    const reported = this.problems.length;
    for (const name of this.decoder.entities.keys()) expanded.set(name, this.decoder.expandEntity(name, 0, 0, 0));
    this.problems.length = reported;
    return expanded;
  }

  private checkCharacters(): void {
    const text = this.text;
    for (let match = NOT_XML_CHAR.exec(text); match; match = NOT_XML_CHAR.exec(text)) {
      if (this.problems.length >= 1000) break;
      const code = match[0].charCodeAt(0);
      // A surrogate pair is one character beyond U+FFFF; only a lone half is an error.
      if (code >= 0xd800 && code <= 0xdbff && (text.charCodeAt(match.index + 1) & 0xfc00) === 0xdc00) {
        NOT_XML_CHAR.lastIndex = match.index + 2;
        continue;
      }
      this.report(
        `the character ${codePointName(match[0].charCodeAt(0))} is not allowed in XML; remove it or write it another way`,
        match.index,
        match.index + 1,
      );
    }
    NOT_XML_CHAR.lastIndex = 0;
  }

  private skipComment(open: number): void {
    const close = this.text.indexOf('-->', open + 4);
    if (close < 0) {
      this.report('comment is not closed with -->', open, this.text.length);
      this.position = this.text.length;
    } else this.position = close + 3;
  }

  private skipCdata(open: number): void {
    const close = this.text.indexOf(']]>', open + 9);
    if (this.stack.length === 0) this.report('CDATA is not allowed outside the root element', open, open + 9);
    if (close < 0) {
      this.report('CDATA section is not closed with ]]>', open, this.text.length);
      this.position = this.text.length;
    } else this.position = close + 3;
  }

  private skipProcessingInstruction(open: number): void {
    const text = this.text;
    const close = text.indexOf('?>', open + 2);
    const target = /^<\?([^\s?]*)/.exec(text.slice(open, open + 64))?.[1] ?? '';
    if (target.toLowerCase() === 'xml' && open !== (text.charCodeAt(0) === 0xfeff ? 1 : 0)) {
      this.report('the XML declaration must be at the very start of the file', open, open + 5);
    }
    if (close < 0) {
      this.report('processing instruction is not closed with ?>', open, text.length);
      this.position = text.length;
    } else this.position = close + 2;
  }

  // test() rather than exec(): no match array is made, which was most of a flatten's garbage from parsing.
  private readName(): string {
    const start = this.position;
    this.namePattern.lastIndex = start;
    if (!this.namePattern.test(this.text)) return '';
    this.position = this.namePattern.lastIndex;
    return this.text.slice(start, this.position);
  }

  private skipSpace(): void {
    this.spacePattern.lastIndex = this.position;
    this.spacePattern.test(this.text);
    this.position = this.spacePattern.lastIndex;
  }

  private indexOrEnd(needle: string, from: number): number {
    const found = this.text.indexOf(needle, from);
    return found < 0 ? this.text.length : found;
  }

  private parseDoctype(start: number): void {
    const text = this.text;
    if (this.seenDoctype || this.root) this.report('misplaced DOCTYPE', start, start + 9);
    this.seenDoctype = true;
    this.position = start + 9;
    let depth = 0;
    let subsetStart = -1;
    let subsetEnd = -1;
    while (this.position < text.length) {
      const code = text.charCodeAt(this.position);
      if (code === 34 || code === 39) {
        const close = text.indexOf(String.fromCharCode(code), this.position + 1);
        this.position = close < 0 ? text.length : close + 1;
        continue;
      }
      if (code === 91) {
        if (depth === 0) subsetStart = this.position + 1;
        depth++;
      } else if (code === 93) {
        depth--;
        if (depth === 0) subsetEnd = this.position;
      } else if (code === 62 && depth <= 0) {
        this.position++;
        break;
      }
      this.position++;
    }
    if (this.position >= text.length && text.charCodeAt(text.length - 1) !== 62) this.report('unterminated DOCTYPE', start, text.length);
    if (subsetStart >= 0 && subsetEnd > subsetStart) this.declareEntities(subsetStart, subsetEnd);
  }

  /** Records the general entities declared in the internal subset `[subsetStart, subsetEnd)`. */
  private declareEntities(subsetStart: number, subsetEnd: number): void {
    const subset = this.text.slice(subsetStart, subsetEnd);
    const declaration = /<!ENTITY\s+(%\s+)?([^\s"'>]+)\s+(?:(SYSTEM|PUBLIC)\b[^>]*|"([^"]*)"|'([^']*)')\s*>/g;
    for (let match = declaration.exec(subset); match; match = declaration.exec(subset)) {
      const offset = subsetStart + match.index;
      if (match[1]) continue;
      if (match[3]) {
        this.decoder.externalEntities.add(match[2]);
        this.report(`external entity '${match[2]}' is declared; it is never resolved`, offset, offset + match[0].length, 'warning');
      } else {
        this.decoder.entities.set(match[2], match[4] ?? match[5] ?? '');
      }
    }
  }

  private parseStartTag(start: number): void {
    const text = this.text;
    const stack = this.stack;
    this.position = start + 1;
    const name = this.readName();
    if (!name) {
      this.report(`'<' must start a tag; write '&lt;' for a literal '<'`, start, start + 1);
      this.position = start + 1;
      return;
    }
    const element: XmlElement = {
      name,
      start,
      nameEnd: this.position,
      startTagEnd: this.position,
      end: this.position,
      selfClosing: false,
      closed: false,
      attributes: [],
      children: [],
      parent: stack[stack.length - 1],
    };
    const terminated = this.parseAttributes(element);
    if (!terminated && this.position >= text.length) this.report(`tag <${name}> is not closed with '>'`, start, text.length);
    element.startTagEnd = this.position;
    element.end = this.position;
    if (stack.length === 0) {
      if (this.root) this.report(`a document has one root element; <${name}> is a second one`, start, element.nameEnd);
      else this.root = element;
    } else {
      stack[stack.length - 1].children.push(element);
    }
    if (element.selfClosing || !terminated) {
      element.closed = element.selfClosing;
      return;
    }
    if (stack.length >= this.maxDepth) {
      this.report(`elements nest deeper than ${this.maxDepth} levels`, start, element.nameEnd);
      element.closed = true;
      return;
    }
    stack.push(element);
    if (this.openByName) this.openByName.set(name, (this.openByName.get(name) ?? 0) + 1);
  }

  /** Reads the attributes of a start tag up to its `>` or `/>`; false when the tag is not terminated. */
  private parseAttributes(element: XmlElement): boolean {
    const text = this.text;
    const { name, start } = element;
    let attributeNames: Set<string> | undefined;
    for (;;) {
      const beforeSpace = this.position;
      this.skipSpace();
      if (this.position >= text.length) return false;
      const code = text.charCodeAt(this.position);
      if (code === 62) {
        this.position++;
        return true;
      }
      if (code === 47 && text.charCodeAt(this.position + 1) === 62) {
        this.position += 2;
        element.selfClosing = true;
        return true;
      }
      if (code === 60) {
        this.report(`tag <${name}> is not closed with '>'`, start, this.position);
        return false;
      }
      if (!isNameStart(code)) {
        this.report(`unexpected '${text[this.position]}' in tag <${name}>`, this.position, this.position + 1);
        this.position++;
        continue;
      }
      if (beforeSpace === this.position && element.attributes.length > 0) {
        this.report(`attributes must be separated by white space`, this.position, this.position + 1);
      }
      const nameStart = this.position;
      const attributeName = this.readName();
      const nameEnd = this.position;
      this.skipSpace();
      if (text.charCodeAt(this.position) !== 61) {
        this.report(`attribute '${attributeName}' has no value (write ${attributeName}="...")`, nameStart, nameEnd);
        continue;
      }
      this.position++;
      this.skipSpace();
      const quoteCode = text.charCodeAt(this.position);
      if (quoteCode !== 34 && quoteCode !== 39) {
        this.report(`the value of attribute '${attributeName}' must be quoted`, nameStart, this.position);
        continue;
      }
      const quote = quoteCode === 34 ? '"' : "'";
      const valueStart = this.position + 1;
      let valueEnd = text.indexOf(quote, valueStart);
      // The next '<' is found once and reused by every attribute before it (a tag may hold thousands).
      if (this.nextOpen < valueStart) this.nextOpen = this.indexOrEnd('<', valueStart);
      if (valueEnd < 0 || this.nextOpen < valueEnd) {
        // Recover at the line end so a value being typed does not swallow the rest of the file.
        LINE_END.lastIndex = valueStart;
        const lineEnd = LINE_END.exec(text);
        valueEnd = lineEnd ? lineEnd.index : text.length;
        this.report(`the value of attribute '${attributeName}' is not closed with ${quote}`, nameStart, valueEnd);
        this.position = valueEnd;
      } else {
        this.position = valueEnd + 1;
      }
      const raw = text.slice(valueStart, valueEnd);
      // Most values hold neither references nor line breaks: no copy is made for them.
      const value = PLAIN_VALUE.test(raw) ? raw : this.decoder.decodeReferences(raw.replace(/[\t\n\r]/g, ' '), valueStart, valueEnd, 0);
      // A linear scan for the usual handful of attributes, a set beyond: a tag with 40,000 attributes stays linear.
      if (
        element.attributes.length < 16
          ? hasAttributeNamed(element.attributes, attributeName)
          : (attributeNames ??= new Set(element.attributes.map((a) => a.name))).has(attributeName)
      ) {
        this.report(`attribute '${attributeName}' appears twice`, nameStart, nameEnd);
      }
      attributeNames?.add(attributeName);
      element.attributes.push({ name: attributeName, value, nameStart, nameEnd, valueStart, valueEnd, quote });
    }
  }

  private popElement(): XmlElement {
    const element = this.stack.pop() as XmlElement;
    if (this.openByName) this.openByName.set(element.name, (this.openByName.get(element.name) ?? 1) - 1);
    return element;
  }

  private isOpen(name: string): boolean {
    if (!this.openByName) {
      this.openByName = new Map();
      for (const open of this.stack) this.openByName.set(open.name, (this.openByName.get(open.name) ?? 0) + 1);
    }
    return (this.openByName.get(name) ?? 0) > 0;
  }

  /** Whether the name at the position is `name` entire; if so, moves past it. */
  private readsName(name: string): boolean {
    const end = this.position + name.length;
    if (!this.text.startsWith(name, this.position) || isNameChar(this.text.charCodeAt(end))) return false;
    this.position = end;
    return true;
  }

  private parseEndTag(start: number): void {
    const stack = this.stack;
    this.position = start + 2;
    // Nearly every end tag closes the innermost element: its name is compared in place, not read out.
    const innermost = stack.length > 0 ? stack[stack.length - 1].name : undefined;
    const closesInnermost = innermost !== undefined && this.readsName(innermost);
    const name = closesInnermost ? innermost : this.readName();
    this.skipSpace();
    if (this.text.charCodeAt(this.position) === 62) this.position++;
    else this.report(`end tag </${name}> is not closed with '>'`, start, this.position);
    if (!closesInnermost && !this.isOpen(name)) {
      this.report(`end tag </${name}> has no matching start tag`, start, this.position);
      return;
    }
    // The search costs as many steps as elements it closes, so each element is passed once.
    let matchIndex = stack.length - 1;
    while (stack[matchIndex].name !== name) matchIndex--;
    while (stack.length - 1 > matchIndex) {
      const unclosed = this.popElement();
      unclosed.end = start;
      this.report(
        `element <${unclosed.name}> is not closed (expected </${unclosed.name}> before </${name}>)`,
        unclosed.start,
        unclosed.nameEnd,
      );
    }
    const element = this.popElement();
    element.end = this.position;
    element.closed = true;
  }

  private checkText(from: number, to: number): void {
    if (to <= from) return;
    const text = this.text;
    if (this.stack.length === 0) {
      for (let i = from; i < to; i++) {
        if (!isSpace(text.charCodeAt(i))) {
          this.report('text is not allowed outside the root element', i, Math.min(to, i + 1));
          return;
        }
      }
      return;
    }
    if (this.nextAmpersand < from) this.nextAmpersand = this.indexOrEnd('&', from);
    if (this.nextAmpersand < to) this.decoder.decodeReferences(text.slice(from, to), from, to, 0);
    if (this.nextCdataEnd < from) this.nextCdataEnd = this.indexOrEnd(']]>', from);
    if (this.nextCdataEnd < to) this.report(`']]>' is not allowed in text`, this.nextCdataEnd, this.nextCdataEnd + 3);
  }
}

/** A loop rather than some(): no closure per attribute read. */
function hasAttributeNamed(attributes: readonly XmlAttribute[], name: string): boolean {
  for (let i = 0; i < attributes.length; i++) if (attributes[i].name === name) return true;
  return false;
}

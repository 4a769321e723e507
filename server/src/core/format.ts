import { cutEdit } from '../../../common/src/whitespaceEdits';
import { detectEol, LineIndex } from './text';
import { attributeValue, endTagStart, isWellFormed, parseXml, XmlDocument, XmlElement } from './xml';

export interface FormatOptions {
  /** Columns of one indentation level (and of a tab when measuring a line). */
  tabSize: number;
  insertSpaces: boolean;
  /** A start tag longer than this (indentation included) puts each attribute on its own line. */
  maxLineWidth: number;
}

export const DEFAULT_FORMAT_OPTIONS: FormatOptions = { tabSize: 2, insertSpaces: true, maxLineWidth: 120 };

/** Replace the text between offsets `start` and `end` by `newText`. Edits are sorted and disjoint. */
export interface FormatEdit {
  start: number;
  end: number;
  newText: string;
}

export type FormatResult = { ok: true; edits: FormatEdit[]; text: string } | { ok: false; message: string; line: number; column: number };

/** A node of element content that the element tree does not hold: comment, CDATA, PI, DOCTYPE or text. */
interface Misc {
  kind: 'comment' | 'cdata' | 'pi' | 'doctype' | 'text';
  start: number;
  end: number;
}

// An element is its own item (it has `start` and `end`): no object is made per element of a large file.
type Item = XmlElement | Misc;

function isBlank(text: string, start: number, end: number): boolean {
  for (let i = start; i < end; i++) {
    const code = text.charCodeAt(i);
    if (code !== 32 && code !== 10 && code !== 13 && code !== 9) return false;
  }
  return true;
}

function newlines(text: string, start: number, end: number): number {
  let count = 0;
  for (let i = start; i < end; i++) {
    const code = text.charCodeAt(i);
    if (code === 10) count++;
    else if (code === 13 && text.charCodeAt(i + 1) !== 10) count++;
  }
  return count;
}

/** The end of a DOCTYPE that starts at `start`: its `>` outside quotes and the internal subset. */
function doctypeEnd(text: string, start: number, limit: number): number {
  let depth = 0;
  for (let i = start + 9; i < limit; i++) {
    const code = text.charCodeAt(i);
    if (code === 34 || code === 39) {
      const close = text.indexOf(String.fromCharCode(code), i + 1);
      i = close < 0 ? limit : close;
    } else if (code === 91) depth++;
    else if (code === 93) depth--;
    else if (code === 62 && depth <= 0) return i + 1;
  }
  return limit;
}

/** Comments, CDATA, PIs, DOCTYPEs and non-blank text between `start` and `limit` (no elements there). */
function miscNodes(text: string, start: number, limit: number, into: Item[]): void {
  let position = start;
  while (position < limit) {
    const open = text.indexOf('<', position);
    const textEnd = open < 0 || open >= limit ? limit : open;
    if (textEnd > position && !isBlank(text, position, textEnd)) into.push({ kind: 'text', start: position, end: textEnd });
    if (textEnd >= limit) return;
    let end: number;
    let kind: Misc['kind'];
    if (text.startsWith('<!--', open)) {
      kind = 'comment';
      end = text.indexOf('-->', open + 4) + 3;
    } else if (text.startsWith('<![CDATA[', open)) {
      kind = 'cdata';
      end = text.indexOf(']]>', open + 9) + 3;
    } else if (text.startsWith('<?', open)) {
      kind = 'pi';
      end = text.indexOf('?>', open + 2) + 2;
    } else {
      kind = 'doctype';
      end = doctypeEnd(text, open, limit);
    }
    // A well-formed document closes each of these; a failed search would loop, so stop instead.
    if (end <= open) throw new Error(`unterminated markup at offset ${open}`);
    into.push({ kind, start: open, end });
    position = end;
  }
}

/**
 * Formats an XML document by changing only the white space between markup: indentation from the
 * options, one start tag per line, attributes wrapped one per line past the width, one blank line
 * kept where several stood. Comments, CDATA, processing instructions, attribute values and the
 * content of elements holding text are left byte for byte. A document that is not well-formed is
 * refused. With `range` (offsets), only white space overlapping those lines is changed. A parse of
 * `text` that the caller already holds may be given, to save parsing it again.
 */
export function formatXml(
  text: string,
  options: FormatOptions,
  range?: { start: number; end: number },
  parsed?: XmlDocument,
): FormatResult {
  const document = parsed && parsed.text === text ? parsed : parseXml(text);
  if (!isWellFormed(document) || !document.root) {
    const problem = document.problems.find((candidate) => candidate.severity === 'error');
    const where = document.lines.positionAt(problem?.start ?? 0);
    return {
      ok: false,
      message: `not formatted: the XML is not well-formed at line ${where.line + 1}, column ${where.character + 1} (${problem?.message ?? 'no root element'}); fix it first`,
      line: where.line,
      column: where.character,
    };
  }
  // Gaps are built with '\n' and given the file's line end at the end: the first line break in a gap
  // decides it, so a second pass (whose gaps all carry that line end) decides the same.
  let firstBreak: '\n' | '\r\n' | undefined;
  const tabSize = Math.max(1, Math.floor(options.tabSize) || 1);
  const unit = options.insertSpaces ? ' '.repeat(tabSize) : '\t';
  const unitWidth = tabSize;
  const indents: string[] = [''];
  const indent = (depth: number): string => {
    while (indents.length <= depth) indents.push(indents[indents.length - 1] + unit);
    return indents[depth];
  };
  // The white space wanted before a line at each depth, built once per depth rather than once per gap.
  const lineBreaks: string[] = [];
  const blankLineBreaks: string[] = [];
  const lineBreak = (depth: number): string => (lineBreaks[depth] ??= '\n' + indent(depth));
  const blankLineBreak = (depth: number): string => (blankLineBreaks[depth] ??= '\n\n' + indent(depth));
  const edits: FormatEdit[] = [];
  // Gaps met before the file's line end is known (no line break in any gap yet) wait here, in document order.
  const pending: FormatEdit[] = [];
  // A wanted text is one of a few strings (one per depth), so each is given the file's line end once.
  const withLineEnd = new Map<string, string>();
  let lowest = 0;
  let highest = text.length;
  if (range) {
    const lines = new LineIndex(text);
    lowest = lines.lineStart(lines.positionAt(range.start).line);
    // A selection that ends at the start of a line does not take that line in.
    const last = lines.positionAt(range.end > range.start ? range.end - 1 : range.end);
    highest = last.line + 1 < lines.lineCount ? lines.lineStart(last.line + 1) : text.length;
    while (highest > lowest && (text.charCodeAt(highest - 1) === 10 || text.charCodeAt(highest - 1) === 13)) highest--;
  }

  /** Makes the white space between `start` and `end` read `wanted`, with line breaks written as `lineEnd`. */
  const edit = (start: number, end: number, wanted: string, lineEnd: '\n' | '\r\n') => {
    if (lineEnd !== '\n' && wanted.length > 0) {
      let converted = withLineEnd.get(wanted);
      if (converted === undefined) withLineEnd.set(wanted, (converted = wanted.replace(/\n/g, lineEnd)));
      wanted = converted;
    }
    if (end - start === wanted.length && text.startsWith(wanted, start)) return;
    // A gap that ends where a selected line starts sets that line's indentation, so it belongs to the selection.
    if (range && !(start === end ? start >= lowest && start <= highest : end >= lowest && start < highest)) return;
    // Only white space is ever replaced: this is what guarantees that content cannot change.
    if (!isBlank(text, start, end)) throw new Error(`formatter would replace content at offset ${start}`);
    edits.push({ start, end, newText: wanted });
  };

  /** Records that the white space between `start` and `end` should read `wanted` (in document order). */
  const gap = (start: number, end: number, wanted: string) => {
    // Most gaps are empty inside tags, or already as wanted in a file with LF line ends: nothing to record.
    if (end - start === wanted.length && (wanted.length === 0 || (firstBreak === '\n' && text.startsWith(wanted, start)))) return;
    recordGap(start, end, wanted);
  };

  const recordGap = (start: number, end: number, wanted: string) => {
    if (firstBreak === undefined) {
      // Only the gap itself is searched: a file without line breaks between markup must stay linear.
      for (let i = start; firstBreak === undefined && i < end; i++) {
        if (text.charCodeAt(i) === 10) firstBreak = i > start && text.charCodeAt(i - 1) === 13 ? '\r\n' : '\n';
      }
      if (firstBreak === undefined) {
        pending.push({ start, end, newText: wanted });
        return;
      }
      for (const waiting of pending) edit(waiting.start, waiting.end, waiting.newText, firstBreak);
      pending.length = 0;
    }
    edit(start, end, wanted, firstBreak);
  };

  const startTag = (element: XmlElement, depth: number) => {
    const closeStart = element.selfClosing ? element.startTagEnd - 2 : element.startTagEnd - 1;
    const attributes = element.attributes;
    let width =
      indent(depth).length + (options.insertSpaces ? 0 : depth * (unitWidth - 1)) + 1 + element.name.length + (element.selfClosing ? 2 : 1);
    for (const attribute of attributes)
      width += 1 + attribute.nameEnd - attribute.nameStart + 1 + attribute.valueEnd - attribute.valueStart + 2;
    const separator = attributes.length >= 2 && width > options.maxLineWidth ? lineBreak(depth + 1) : ' ';
    let previous = element.nameEnd;
    for (const attribute of attributes) {
      gap(previous, attribute.nameStart, separator);
      const equals = text.indexOf('=', attribute.nameEnd);
      gap(attribute.nameEnd, equals, '');
      gap(equals + 1, attribute.valueStart - 1, '');
      previous = attribute.valueEnd + 1;
    }
    gap(previous, closeStart, '');
  };

  const preservesSpace = (element: XmlElement) => attributeValue(element, 'xml:space') === 'preserve';

  /** Formats a sequence of items at `depth`, between offsets `from` and `to` of the enclosing content. */
  const sequence = (items: Item[], depth: number, from: number, to: number, atTop: boolean) => {
    let previousEnd = from;
    for (let index = 0; index < items.length; index++) {
      const item = items[index];
      const breaks = newlines(text, previousEnd, item.start);
      let wanted: string;
      if (atTop && index === 0) wanted = '';
      else if ('kind' in item && item.kind === 'comment' && breaks === 0 && !atTop) wanted = ' ';
      else if (breaks >= 2 && index > 0) wanted = blankLineBreak(depth);
      else wanted = lineBreak(depth);
      gap(previousEnd, item.start, wanted);
      if (!('kind' in item)) element(item, depth);
      previousEnd = item.end;
    }
    gap(previousEnd, to, lineBreak(atTop ? 0 : Math.max(0, depth - 1)));
  };

  const element = (node: XmlElement, depth: number) => {
    startTag(node, depth);
    if (node.selfClosing) return;
    const contentStart = node.startTagEnd;
    const contentEnd = endTagStart(text, node);
    content(node, depth, contentStart, contentEnd);
    gap(contentEnd + 2 + node.name.length, node.end - 1, '');
  };

  const content = (node: XmlElement, depth: number, contentStart: number, contentEnd: number) => {
    const items: Item[] = [];
    let position = contentStart;
    for (const child of node.children) {
      miscNodes(text, position, child.start, items);
      items.push(child);
      position = child.end;
    }
    miscNodes(text, position, contentEnd, items);
    // Text or CDATA makes white space significant to a reader: such content is left as written.
    if (preservesSpace(node) || items.some((item) => 'kind' in item && (item.kind === 'text' || item.kind === 'cdata'))) return;
    if (items.length === 0) {
      gap(contentStart, contentEnd, '');
      return;
    }
    sequence(items, depth + 1, contentStart, contentEnd, false);
  };

  const root = document.root;
  const topItems: Item[] = [];
  const bom = text.charCodeAt(0) === 0xfeff ? 1 : 0;
  miscNodes(text, bom, root.start, topItems);
  topItems.push(root);
  miscNodes(text, root.end, text.length, topItems);
  sequence(topItems, 0, bom, text.length, true);

  // No gap held a line break: the file's own line end decides the gaps still waiting.
  const lineEnd = firstBreak ?? detectEol(text);
  for (const waiting of pending) edit(waiting.start, waiting.end, waiting.newText, lineEnd);
  edits.sort((a, b) => a.start - b.start);
  // The text is made only when read: the editor takes the edits alone.
  let output: string | undefined;
  return {
    ok: true,
    edits,
    get text() {
      return (output ??= applyEdits(text, edits));
    },
  };
}

export function applyEdits(text: string, edits: FormatEdit[]): string {
  let result = '';
  let position = 0;
  for (const edit of edits) {
    result += text.slice(position, edit.start) + edit.newText;
    position = edit.end;
  }
  return result + text.slice(position);
}

/**
 * Up to this many changed spaces, an editor gets one edit each; past it, one edit from the first to the last, which
 * our client splits again (`whitespaceEdits`): 30,877 edits were 3.6 MB of JSON to write and read for 15,000 lines.
 */
export const SEPARATE_EDITS_UP_TO = 1000;

/**
 * The edits to send an editor for a format of `text`: each cut to the characters that change (`cutEdit`); past
 * `SEPARATE_EDITS_UP_TO` of them, one edit from the first change to the last, read from the formatted text.
 */
export function editorEdits(text: string, format: { edits: readonly FormatEdit[]; text: string }): FormatEdit[] {
  const edits = format.edits;
  if (edits.length <= SEPARATE_EDITS_UP_TO) {
    const cut: FormatEdit[] = [];
    for (const edit of edits) {
      const changed = cutEdit(text, edit.start, edit.end, edit.newText);
      if (changed) cut.push(changed);
    }
    return cut;
  }
  // The formatter records only gaps that change, so the first and last of them are changes.
  const cut = (edit: FormatEdit): FormatEdit => cutEdit(text, edit.start, edit.end, edit.newText) ?? edit;
  const first = cut(edits[0]);
  const last = cut(edits[edits.length - 1]);
  const formatted = format.text;
  return [{ start: first.start, end: last.end, newText: formatted.slice(first.start, formatted.length - (text.length - last.end)) }];
}

/**
 * The indentation a file already uses, from the first line below the root that is indented:
 * a tab, or its number of spaces (2 when nothing is indented).
 */
export function detectIndentation(text: string): { tabSize: number; insertSpaces: boolean } {
  const pattern = /\n([ \t]+)</g;
  for (let match = pattern.exec(text); match; match = pattern.exec(text)) {
    const leading = match[1];
    if (leading.startsWith('\t')) return { tabSize: 4, insertSpaces: false };
    if (leading.length >= 1 && leading.length <= 8) return { tabSize: leading.length, insertSpaces: true };
  }
  return { tabSize: 2, insertSpaces: true };
}

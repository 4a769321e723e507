import { TextEdit } from 'vscode-languageserver/node';
import { positionAt } from './cursor';

export type Position = { line: number; character: number };

/** The offset of an LSP position in a text with `\n` line ends. */
export function offsetOf(text: string, position: Position): number {
  const lines = text.split('\n');
  return lines.slice(0, position.line).reduce((sum, line) => sum + line.length + 1, 0) + position.character;
}

/** The text a range covers. */
export function textAt(text: string, range: { start: Position; end: Position }): string {
  return text.slice(offsetOf(text, range.start), offsetOf(text, range.end));
}

/** The text after the edits (all relative to the original text), applied from the end backwards. */
export function applyEdits(text: string, edits: TextEdit[]): string {
  const sorted = [...edits].sort((a, b) => offsetOf(text, b.range.start) - offsetOf(text, a.range.start));
  let result = text;
  for (const edit of sorted)
    result = result.slice(0, offsetOf(text, edit.range.start)) + edit.newText + result.slice(offsetOf(text, edit.range.end));
  return result;
}

/** The position inside the nth occurrence of `needle`, `into` characters after its start. */
export function inside(text: string, needle: string, into: number, nth = 0): Position {
  let index = -1;
  for (let i = 0; i <= nth; i++) {
    index = text.indexOf(needle, index + 1);
    if (index < 0) throw new Error(`'${needle}' not found`);
  }
  return positionAt(text, index + into);
}

/**
 * The text after `edits`, read as the LSP specification reads a TextEdit[]: every range refers to the original text,
 * lines end at CR LF, CR or LF, ranges must not overlap (an error here), and inserts at one position keep the array's
 * order. Linear, for replies of tens of thousands of edits.
 */
export function applyTextEditsAsSpecified(text: string, edits: readonly TextEdit[]): string {
  const starts = [0];
  for (let i = 0; i < text.length; i++) {
    const code = text.charCodeAt(i);
    if (code === 13 && text.charCodeAt(i + 1) === 10) i++;
    if (code === 10 || code === 13) starts.push(i + 1);
  }
  const offset = ({ line, character }: Position): number => {
    if (line >= starts.length) throw new Error(`line ${line} is past the text's ${starts.length} lines`);
    const lineEnd = line + 1 < starts.length ? starts[line + 1] : text.length;
    const content = text.slice(starts[line], lineEnd).replace(/\r?\n$|\r$/, '').length;
    if (character > content) throw new Error(`position ${line}:${character} is past its line's ${content} characters (inside a line end)`);
    return starts[line] + character;
  };
  const spans = edits.map((edit, index) => ({
    start: offset(edit.range.start),
    end: offset(edit.range.end),
    newText: edit.newText,
    index,
  }));
  spans.sort((a, b) => a.start - b.start || a.index - b.index);
  const parts: string[] = [];
  let position = 0;
  for (const span of spans) {
    if (span.end < span.start) throw new Error(`edit ${span.index} ends before it starts`);
    if (span.start < position) throw new Error(`edit ${span.index} overlaps the one before it`);
    parts.push(text.slice(position, span.start), span.newText);
    position = span.end;
  }
  return parts.join('') + text.slice(position);
}

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

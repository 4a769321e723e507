/**
 * The edits of a change that touches only white space, by offsets: the formatter's edits cut to what changes (the
 * server), and one large format edit split back into those edits (the client, so the editor keeps its cursor,
 * folding and markers outside the changed spaces).
 */

/** Replace the text between offsets `start` and `end` of the original by `newText`. */
export interface OffsetEdit {
  start: number;
  end: number;
  newText: string;
}

const isSpace = (code: number) => code === 32 || code === 10 || code === 13 || code === 9;

/**
 * `text` between `start` and `end` replaced by `newText`, cut to the characters that change (an indentation after a
 * line break it keeps becomes an insertion at the line's start); never a position between a CR and its LF, which
 * LSP has no name for. Undefined when nothing changes.
 */
export function cutEdit(text: string, start: number, end: number, newText: string): OffsetEdit | undefined {
  const longest = Math.min(end - start, newText.length);
  let head = 0;
  while (head < longest && text.charCodeAt(start + head) === newText.charCodeAt(head)) head++;
  let tail = 0;
  while (tail < longest - head && text.charCodeAt(end - 1 - tail) === newText.charCodeAt(newText.length - 1 - tail)) tail++;
  if (head > 0 && text.charCodeAt(start + head - 1) === 13 && text.charCodeAt(start + head) === 10) head--;
  if (tail > 0 && text.charCodeAt(end - tail - 1) === 13 && text.charCodeAt(end - tail) === 10) tail--;
  if (head + tail === end - start && head + tail === newText.length) return undefined;
  return { start: start + head, end: end - tail, newText: newText.slice(head, newText.length - tail) };
}

function sameRun(a: string, aStart: number, aEnd: number, b: string, bStart: number, bEnd: number): boolean {
  if (aEnd - aStart !== bEnd - bStart) return false;
  for (let k = 0; k < aEnd - aStart; k++) if (a.charCodeAt(aStart + k) !== b.charCodeAt(bStart + k)) return false;
  return true;
}

/**
 * The edits that make `original` read `changed` when the two differ only in white space (space, tab, CR, LF)
 * between the same other characters: each run of white space that differs, cut as `cutEdit` cuts it, in order.
 * Undefined when any other character differs. Linear in the texts' length.
 */
export function whitespaceEdits(original: string, changed: string): OffsetEdit[] | undefined {
  const edits: OffsetEdit[] = [];
  let i = 0;
  let j = 0;
  for (;;) {
    // A run of white space in each (either may be empty: a line break put between two tags).
    const runStart = i;
    const changedStart = j;
    while (i < original.length && isSpace(original.charCodeAt(i))) i++;
    while (j < changed.length && isSpace(changed.charCodeAt(j))) j++;
    if (!sameRun(original, runStart, i, changed, changedStart, j)) {
      const edit = cutEdit(original, runStart, i, changed.slice(changedStart, j));
      if (edit) edits.push(edit);
    }
    if (i >= original.length || j >= changed.length) return i >= original.length && j >= changed.length ? edits : undefined;
    // Then the same other characters, up to white space in either.
    while (i < original.length && j < changed.length) {
      const code = original.charCodeAt(i);
      if (isSpace(code) || isSpace(changed.charCodeAt(j))) break;
      if (code !== changed.charCodeAt(j)) return undefined;
      i++;
      j++;
    }
  }
}

/**
 * A format's reply of one edit split into an edit per changed run of white space (`whitespaceEdits`), positions from
 * `document`; any other reply (several edits, or a change of other characters) as it came.
 */
export function splitFormatReply<P, R extends { start: P; end: P }, E extends { range: R; newText: string }>(
  document: { getText(range: R): string; offsetAt(position: P): number; positionAt(offset: number): P },
  edits: E[] | null | undefined,
  make: (start: P, end: P, newText: string) => E,
): E[] | null | undefined {
  if (!edits || edits.length !== 1) return edits;
  const [edit] = edits;
  const changes = whitespaceEdits(document.getText(edit.range), edit.newText);
  if (!changes) return edits;
  const base = document.offsetAt(edit.range.start);
  return changes.map((change) => make(document.positionAt(base + change.start), document.positionAt(base + change.end), change.newText));
}

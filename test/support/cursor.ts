// Cursor markers as yaml-language-server's tests write them: a `|` in the text stands where the cursor is.

export interface Position {
  line: number;
  character: number;
}

/** Text with `|` cursor markers removed, and the offsets where they stood. */
export function markers(marked: string): { text: string; offsets: number[] } {
  const offsets: number[] = [];
  let text = '';
  for (const char of marked) {
    if (char === '|') offsets.push(text.length);
    else text += char;
  }
  return { text, offsets };
}

/** Text with its one `|` cursor marker removed, and the marker's offset and position. */
export function cursor(marked: string): { text: string; offset: number; position: Position } {
  const { text, offsets } = markers(marked);
  if (offsets.length !== 1) throw new Error(`expected one '|' cursor marker, found ${offsets.length}`);
  return { text, offset: offsets[0], position: positionAt(text, offsets[0]) };
}

/**
 * The offset of the `|` in `markedSnippet` once the snippet (without its marker) is found in `text`: its one
 * occurrence, or with `after` its first occurrence after the first `after` (`'name="Fourth"'`: in group Fourth).
 */
export function offsetAt(text: string, markedSnippet: string, after?: string): number {
  const marker = markedSnippet.indexOf('|');
  if (marker < 0 || markedSnippet.indexOf('|', marker + 1) >= 0) throw new Error(`'${markedSnippet}' needs exactly one '|' cursor marker`);
  const snippet = markedSnippet.slice(0, marker) + markedSnippet.slice(marker + 1);
  let from = 0;
  if (after !== undefined) {
    from = text.indexOf(after);
    if (from < 0) throw new Error(`'${after}' not found`);
  }
  const index = text.indexOf(snippet, from);
  if (index < 0) throw new Error(`'${snippet}' not found${after === undefined ? '' : ` after '${after}'`}`);
  if (after === undefined && text.indexOf(snippet, index + 1) >= 0) throw new Error(`'${snippet}' occurs more than once: say after what`);
  return index + marker;
}

/** The position of the `|` in `markedSnippet` in a text shared by many tests: `at(MAIN, 'maneuverGroupName="Br|ake"')` (see `offsetAt`). */
export function at(text: string, markedSnippet: string, after?: string): Position {
  return positionAt(text, offsetAt(text, markedSnippet, after));
}

export function positionAt(text: string, offset: number): Position {
  const before = text.slice(0, offset);
  const line = before.split('\n').length - 1;
  return { line, character: offset - (before.lastIndexOf('\n') + 1) };
}

/** The position just after the first occurrence of `needle` (after `nth` earlier ones). */
export function positionAfter(text: string, needle: string, nth = 0): Position {
  let index = -1;
  for (let i = 0; i <= nth; i++) {
    index = text.indexOf(needle, index + 1);
    if (index < 0) throw new Error(`'${needle}' not found`);
  }
  return positionAt(text, index + needle.length);
}

/** Zero-based line and UTF-16 column, as LSP counts them. */
export interface Position {
  line: number;
  character: number;
}

export interface Range {
  start: Position;
  end: Position;
}

/** Maps between offsets and line/column positions of one text. */
export class LineIndex {
  private readonly lineStarts: number[];

  constructor(readonly text: string) {
    const starts = [0];
    // Without a CR, native searches find the lines: the character loop is slow before V8 has compiled it (a CLI run).
    if (!text.includes('\r')) {
      for (let at = text.indexOf('\n'); at !== -1; at = text.indexOf('\n', at + 1)) starts.push(at + 1);
      this.lineStarts = starts;
      return;
    }
    for (let i = 0; i < text.length; i++) {
      const code = text.charCodeAt(i);
      if (code === 10) {
        starts.push(i + 1);
      } else if (code === 13) {
        if (text.charCodeAt(i + 1) === 10) i++;
        starts.push(i + 1);
      }
    }
    this.lineStarts = starts;
  }

  get lineCount(): number {
    return this.lineStarts.length;
  }

  positionAt(offset: number): Position {
    const clamped = Math.max(0, Math.min(offset, this.text.length));
    let low = 0;
    let high = this.lineStarts.length - 1;
    while (low < high) {
      const middle = (low + high + 1) >> 1;
      if (this.lineStarts[middle] <= clamped) low = middle;
      else high = middle - 1;
    }
    return { line: low, character: clamped - this.lineStarts[low] };
  }

  offsetAt(position: Position): number {
    if (position.line < 0) return 0;
    if (position.line >= this.lineStarts.length) return this.text.length;
    const lineStart = this.lineStarts[position.line];
    const nextStart = position.line + 1 < this.lineStarts.length ? this.lineStarts[position.line + 1] : this.text.length;
    return Math.min(lineStart + Math.max(0, position.character), nextStart);
  }

  lineStart(line: number): number {
    return this.lineStarts[Math.max(0, Math.min(line, this.lineStarts.length - 1))];
  }

  range(start: number, end: number): Range {
    return { start: this.positionAt(start), end: this.positionAt(end) };
  }

  /**
   * The ranges of spans that are sorted and disjoint (each starts at or after the previous one's end), as `range`
   * gives them: one walk forward through the lines instead of two searches per span (a format's tens of thousands).
   */
  rangesInOrder(spans: readonly { start: number; end: number }[]): Range[] {
    const starts = this.lineStarts;
    const length = this.text.length;
    let line = 0;
    const positionAt = (offset: number): Position => {
      const clamped = Math.max(0, Math.min(offset, length));
      // An offset before the walk's line (spans out of order) is searched for, so the answer is always `positionAt`'s.
      if (clamped < starts[line]) return this.positionAt(clamped);
      while (line + 1 < starts.length && starts[line + 1] <= clamped) line++;
      return { line, character: clamped - starts[line] };
    };
    const ranges: Range[] = new Array<Range>(spans.length);
    for (let i = 0; i < spans.length; i++) ranges[i] = { start: positionAt(spans[i].start), end: positionAt(spans[i].end) };
    return ranges;
  }
}

/**
 * The same characters in a string of their own. A value read from a file is a slice of the file's text, and V8
 * keeps a slice of 13 characters or more as a view that holds the whole text: a memo that outlives the parse
 * (keyed by an imported group) would keep every version of the main file's text that wrote one of its keys.
 */
/** The first index of `[0, count)` at which `before` turns false, by halves (`before` holds for a run of indexes from 0, then never). */
export function partitionPoint(count: number, before: (index: number) => boolean): number {
  let low = 0;
  let high = count;
  while (low < high) {
    const middle = (low + high) >> 1;
    if (before(middle)) low = middle + 1;
    else high = middle;
  }
  return low;
}

export function ownString(text: string): string {
  // Read back from its JSON, a string is made anew (concatenating and slicing again gives V8 a view of the text once more).
  return text.length < 13 ? text : (JSON.parse(JSON.stringify(text)) as string);
}

/** Lines as an editor shows them: a last line without a newline counts, an empty file has none. */
export function countEditorLines(text: string): number {
  if (text.length === 0) return 0;
  // LineIndex's count, found by native searches: a CLI run counts its output once, before V8 has compiled the character loop.
  let lineCount = 1;
  for (let at = text.indexOf('\n'); at !== -1; at = text.indexOf('\n', at + 1)) lineCount++;
  for (let at = text.indexOf('\r'); at !== -1; at = text.indexOf('\r', at + 1)) if (text.charCodeAt(at + 1) !== 10) lineCount++;
  const endsWithNewline = text.endsWith('\n') || text.endsWith('\r');
  return endsWithNewline ? lineCount - 1 : lineCount;
}

/** Decodes file bytes as UTF-8, accepting and dropping a byte-order mark. */
export function decodeUtf8(bytes: Uint8Array): string {
  return new TextDecoder('utf-8', { fatal: false }).decode(bytes);
}

export function detectEol(text: string): '\n' | '\r\n' {
  const index = text.indexOf('\n');
  return index > 0 && text.charCodeAt(index - 1) === 13 ? '\r\n' : '\n';
}

/** Levenshtein distance, for "did you mean" hints. */
export function editDistance(a: string, b: string): number {
  if (a === b) return 0;
  const previous = new Array<number>(b.length + 1);
  for (let j = 0; j <= b.length; j++) previous[j] = j;
  for (let i = 1; i <= a.length; i++) {
    let diagonal = previous[0];
    previous[0] = i;
    for (let j = 1; j <= b.length; j++) {
      const above = previous[j];
      const cost = a.charCodeAt(i - 1) === b.charCodeAt(j - 1) ? 0 : 1;
      previous[j] = Math.min(previous[j] + 1, previous[j - 1] + 1, diagonal + cost);
      diagonal = above;
    }
  }
  return previous[b.length];
}

/** The candidate closest to `wanted`, or undefined when none is reasonably close. */
export function closestMatch(wanted: string, candidates: Iterable<string>): string | undefined {
  let best: string | undefined;
  let bestDistance = Infinity;
  const lowered = wanted.toLowerCase();
  for (const candidate of candidates) {
    const distance = editDistance(lowered, candidate.toLowerCase());
    if (distance < bestDistance || (distance === bestDistance && best !== undefined && candidate.length < best.length)) {
      best = candidate;
      bestDistance = distance;
    }
  }
  if (best === undefined) return undefined;
  const limit = Math.max(3, Math.ceil(Math.max(wanted.length, best.length) * 0.5));
  return bestDistance <= limit ? best : undefined;
}

/** Leading white space of the line where `offset` stands, when only white space precedes it there. */
export function indentationAt(text: string, offset: number): string {
  let lineStart = offset;
  while (lineStart > 0 && text[lineStart - 1] !== '\n' && text[lineStart - 1] !== '\r') lineStart--;
  const prefix = text.slice(lineStart, offset);
  return /^[ \t]*$/.test(prefix) ? prefix : '';
}

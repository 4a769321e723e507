/** Source-to-preview line maps: plain data and one lookup, so that the client bundle can use them without the flattener. */

/**
 * Lines `sourceLine .. sourceLine + lineCount - 1` of a scenario shown in its flattened text from
 * `previewLine` on: one line each when `step` is 1, all on that one line when it is 0 (a
 * referencing group, shown as the groups imported in its place).
 */
export interface LineSegment {
  sourceLine: number;
  previewLine: number;
  lineCount: number;
  step: 0 | 1;
}

/** The preview line that shows `line` of the source, by a map of `previewLineMap`. */
export function previewLineOf(segments: readonly LineSegment[], line: number): number | undefined {
  let low = 0;
  let high = segments.length - 1;
  while (low <= high) {
    const middle = (low + high) >> 1;
    const segment = segments[middle];
    if (line < segment.sourceLine) high = middle - 1;
    else if (line >= segment.sourceLine + segment.lineCount) low = middle + 1;
    else return segment.previewLine + segment.step * (line - segment.sourceLine);
  }
  return undefined;
}

import { Addition, FlatSource, Insertion, parameterAttributeSpans } from './flatten';
import type { LineSegment } from '../../../common/src/lineSegments';
import { partitionPoint } from './text';

/** An outer group of the original text and the copies that replaced it in the flattened text. */
interface ReplacedRegion {
  inStart: number;
  inEnd: number;
  outStart: number;
  outEnd: number;
  insertions: Insertion[];
}

function replacedRegions(insertions: Insertion[], additions: Addition[]): ReplacedRegion[] {
  const regions = new Map<number, ReplacedRegion>();
  // Text carried into the root (SPEC 11.5) replaces a region of its own; its lines show where it starts.
  const carried: ReplacedRegion[] = additions.map((addition) => ({
    inStart: addition.replacedStart,
    inEnd: addition.replacedEnd,
    outStart: addition.start,
    outEnd: addition.end,
    insertions: [],
  }));
  for (const insertion of insertions) {
    const region = regions.get(insertion.replacedStart);
    if (region) {
      region.outStart = Math.min(region.outStart, insertion.start);
      region.outEnd = Math.max(region.outEnd, insertion.end);
      region.insertions.push(insertion);
    } else {
      regions.set(insertion.replacedStart, {
        inStart: insertion.replacedStart,
        inEnd: insertion.replacedEnd,
        outStart: insertion.start,
        outEnd: insertion.end,
        insertions: [insertion],
      });
    }
  }
  return [...carried, ...regions.values()].sort((a, b) => a.inStart - b.inStart);
}

function countNewlines(text: string, start: number, end: number): number {
  let count = 0;
  for (let i = start; i < end; i++) {
    const code = text.charCodeAt(i);
    if (code === 10 || (code === 13 && text.charCodeAt(i + 1) !== 10)) count++;
  }
  return count;
}

/**
 * Where the flattened text of `source` (as `Flattener.flatten` writes it, `parameterAttributes`
 * stripped) shows each line of the file itself, from the flattener's insertion records: lines
 * outside replaced regions are the file's own, shifted; a referencing group's lines show at the
 * group imported for the ManeuverGroupReference on that line, or else at the first one imported;
 * lines that carried text replaced show where that text starts.
 */
export function previewLineMap(source: FlatSource): LineSegment[] {
  const original = source.original;
  const model = source.model;
  if (!original || !model) return [];
  const inLines = original.document.lines;
  const outLines = model.document.lines;
  const outText = model.document.text;
  // Stripping parameterAttributes may join lines: count the newlines each removed span held.
  const spans = parameterAttributeSpans(model).sort((a, b) => a.start - b.start);
  const removedBefore: number[] = [0];
  for (const span of spans) removedBefore.push(removedBefore[removedBefore.length - 1] + countNewlines(outText, span.start, span.end));
  const previewLineAt = (offset: number): number => {
    const spansBefore = partitionPoint(spans.length, (index) => spans[index].end <= offset);
    return outLines.positionAt(offset).line - removedBefore[spansBefore];
  };
  const regions = model === original ? [] : replacedRegions(source.insertions, source.additions);
  const lineOf = (offset: number): number => inLines.positionAt(offset).line;

  const lines: number[] = [];
  let next = 0;
  let shift = 0;
  for (let line = 0; line < inLines.lineCount; line++) {
    while (next < regions.length && lineOf(regions[next].inEnd) < line) {
      shift += regions[next].outEnd - regions[next].outStart - (regions[next].inEnd - regions[next].inStart);
      next++;
    }
    const region = regions[next];
    if (region && lineOf(region.inStart) <= line) {
      const insertion =
        region.insertions.find(
          (candidate) => lineOf(candidate.reference.element.start) <= line && line <= lineOf(candidate.reference.element.end),
        ) ?? region.insertions[0];
      lines.push(previewLineAt(insertion?.start ?? region.outStart));
    } else {
      lines.push(previewLineAt(inLines.lineStart(line) + shift));
    }
  }
  return compress(lines);
}

function compress(lines: number[]): LineSegment[] {
  const segments: LineSegment[] = [];
  for (let line = 0; line < lines.length; line++) {
    const last = segments[segments.length - 1];
    if (last) {
      const expected = last.previewLine + last.step * last.lineCount;
      if (last.lineCount === 1 && (lines[line] === last.previewLine || lines[line] === last.previewLine + 1)) {
        last.step = lines[line] === last.previewLine ? 0 : 1;
        last.lineCount++;
        continue;
      }
      if (lines[line] === expected) {
        last.lineCount++;
        continue;
      }
    }
    segments.push({ sourceLine: line, previewLine: lines[line], lineCount: 1, step: 1 });
  }
  return segments;
}

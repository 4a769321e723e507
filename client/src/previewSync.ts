/**
 * Where the flattened preview shows a line of its source, so that the preview follows the cursor
 * as the Markdown preview does. Pure text logic: the flattened text keeps the main file's lines as
 * written outside the replaced groups (SPEC 8), and names each imported group `OUTER.INNER`.
 */

const GROUP_OPEN = /<ManeuverGroup\b[^>]*?\bname\s*=\s*(["'])(.*?)\1/;
const GROUP_CLOSE = /<\/ManeuverGroup\s*>/;
const REFERENCE = /<ScenarioReference\b/;

/** The name of the outer group around `line` when that group holds a ScenarioReference. */
function referencingGroupAt(lines: string[], line: number): string | undefined {
  let depth = 0;
  for (let index = line; index >= 0; index--) {
    const text = lines[index];
    if (index !== line && GROUP_CLOSE.test(text)) depth++;
    const open = GROUP_OPEN.exec(text);
    if (!open) continue;
    if (depth > 0) {
      depth--;
      continue;
    }
    for (let after = index; after < lines.length; after++) {
      if (REFERENCE.test(lines[after])) return open[2];
      if (after > index && (GROUP_CLOSE.test(lines[after]) || GROUP_OPEN.test(lines[after]))) return undefined;
    }
    return undefined;
  }
  return undefined;
}

/** Lines that occur exactly once in a text, by their trimmed content. */
function uniqueLines(lines: string[]): Map<string, number> {
  const seen = new Map<string, number>();
  lines.forEach((text, index) => {
    const key = text.trim();
    if (key) seen.set(key, seen.has(key) ? -1 : index);
  });
  return seen;
}

/** The preview line that shows source line `line`, or undefined when nothing anchors it. */
export function previewLineFor(source: string, preview: string, line: number): number | undefined {
  const sourceLines = source.split(/\r?\n/);
  const previewLines = preview.split(/\r?\n/);
  if (line < 0 || line >= sourceLines.length) return undefined;
  const group = referencingGroupAt(sourceLines, line);
  if (group !== undefined) {
    const prefix = `name="${group}.`;
    const found = previewLines.findIndex((text) => GROUP_OPEN.test(text) && text.includes(prefix));
    if (found >= 0) return found;
  }
  // Otherwise the nearest line above that occurs once in each text fixes the offset.
  const inSource = uniqueLines(sourceLines);
  const inPreview = uniqueLines(previewLines);
  for (let anchor = line; anchor >= 0; anchor--) {
    const key = sourceLines[anchor].trim();
    if (!key || inSource.get(key) !== anchor) continue;
    const target = inPreview.get(key);
    if (target !== undefined && target >= 0) return Math.min(previewLines.length - 1, target + (line - anchor));
  }
  return undefined;
}

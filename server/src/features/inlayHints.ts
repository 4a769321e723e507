import { InlayHint, InlayHintKind } from 'vscode-languageserver/node';
import { DocumentSemantics, formatValue } from '../core/semantics';
import { serverMemo } from '../database';
import { partitionPoint } from '../core/text';

interface ExpressionHint {
  /** Offset of the attribute value's end (the hint goes after its closing quote). */
  offset: number;
  hint: InlayHint;
}

// A model never changes once built, so the hints of one analysis are computed once, for every range asked.
const hintsOf = serverMemo<DocumentSemantics, ExpressionHint[]>('inlayHints');

function allHints(semantics: DocumentSemantics): ExpressionHint[] {
  const known = hintsOf.get(semantics);
  if (known) return known;
  const lines = semantics.model.document.lines;
  const hints: ExpressionHint[] = [];
  for (const site of semantics.model.sites) {
    if (site.form.kind !== 'expression') continue;
    const result = semantics.evaluator.attributeValue(site.element, site.attribute);
    // An expression that cannot be evaluated has a diagnostic instead.
    if (!result.ok) continue;
    // Where esmini computes another value, the hint gives both: the selected reading's first (SPEC 12).
    const differs = result.differs;
    const other = differs
      ? semantics.evaluator.reading === 'esmini'
        ? ` (standard ${differs.standard})`
        : ` (esmini ${differs.esmini})`
      : '';
    const why = differs
      ? `; by the standard ${differs.standard}, by esmini ${differs.esmini}${differs.reasons.length ? `: ${differs.reasons.join('; ')}` : ''}`
      : '';
    hints.push({
      offset: site.attribute.valueEnd,
      hint: {
        position: lines.positionAt(site.attribute.valueEnd + 1),
        label: `= ${formatValue(result.value)}${other}`,
        kind: InlayHintKind.Parameter,
        paddingLeft: true,
        tooltip: `${site.attribute.value.trim()} evaluates to ${formatValue(result.value)} (${result.type})${why}`,
      },
    });
  }
  hints.sort((a, b) => a.offset - b.offset);
  hintsOf.set(semantics, hints);
  return hints;
}

/** The value of every `${...}` attribute between two offsets, shown after its closing quote. */
export function expressionHints(semantics: DocumentSemantics, start: number, end: number): InlayHint[] {
  const hints = allHints(semantics);
  // The first hint at or after `start`, by binary search: an editor asks for one screen at a time.
  const first = partitionPoint(hints.length, (index) => hints[index].offset < start);
  const result: InlayHint[] = [];
  for (let index = first; index < hints.length && hints[index].offset <= end; index++) result.push(hints[index].hint);
  return result;
}

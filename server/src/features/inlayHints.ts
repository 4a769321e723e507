import { InlayHint, InlayHintKind } from 'vscode-languageserver/node';
import { DocumentSemantics, formatValue } from '../core/semantics';

/** The value of every `${...}` attribute between two offsets, shown after its closing quote. */
export function expressionHints(semantics: DocumentSemantics, start: number, end: number): InlayHint[] {
  const lines = semantics.model.document.lines;
  const hints: InlayHint[] = [];
  for (const site of semantics.model.sites) {
    if (site.form.kind !== 'expression' || site.attribute.valueEnd < start || site.attribute.valueStart > end) continue;
    const result = semantics.evaluator.attributeValue(site.element, site.attribute);
    // An expression that cannot be evaluated has a diagnostic instead.
    if (!result.ok) continue;
    hints.push({
      position: lines.positionAt(site.attribute.valueEnd + 1),
      label: `= ${formatValue(result.value)}`,
      kind: InlayHintKind.Parameter,
      paddingLeft: true,
      tooltip: `${site.attribute.value.trim()} evaluates to ${formatValue(result.value)} (${result.type})`,
    });
  }
  return hints;
}

import { defineDiagnostic } from './definition';
import { QC } from './qcRules';

/** A reference that resolves to more than one element. */
export const AMBIGUOUS_REFERENCE = defineDiagnostic({
  code: 'ambiguous-reference',
  rule: { description: 'A reference resolves to exactly one element.', qcRule: QC.uniqueEntityReferences },
  severity: 'warning',
});

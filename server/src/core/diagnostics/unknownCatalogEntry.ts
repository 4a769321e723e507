import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isSuggestion } from './definition';

/** An entryName naming no entry of its catalog: the closest entry. */
export const UNKNOWN_CATALOG_ENTRY = defineDiagnostic({
  code: 'unknown-catalog-entry',
  rule: { description: 'An entryName names an entry of its catalog.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['unknown-catalog-entry'] => isSuggestion(value),
});

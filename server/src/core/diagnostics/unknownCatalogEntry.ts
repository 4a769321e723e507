import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, didYouMean, isSuggestion, ProblemWording } from './definition';

/** The entries named in the message, at most. */
const ENTRIES_NAMED = 30;

export function unknownCatalogEntryWording(
  catalog: string,
  entry: string,
  entries: readonly string[],
  suggestion: string | undefined,
): ProblemWording<'unknown-catalog-entry'> {
  return {
    severity: 'error',
    code: 'unknown-catalog-entry',
    message: `catalog '${catalog}' has no entry named '${entry}'; it has: ${entries.slice(0, ENTRIES_NAMED).join(', ')}${entries.length > ENTRIES_NAMED ? ', ...' : ''}`,
    hint: didYouMean(suggestion),
  };
}

/** An entryName naming no entry of its catalog: the closest entry. */
export const UNKNOWN_CATALOG_ENTRY = defineDiagnostic({
  code: 'unknown-catalog-entry',
  rule: { description: 'An entryName names an entry of its catalog.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['unknown-catalog-entry'] => isSuggestion(value),
});

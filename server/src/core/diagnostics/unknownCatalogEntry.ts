import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, didYouMean, isSuggestion, ProblemWording } from './definition';

/** The entries named in the message, at most. */
const ENTRIES_NAMED = 30;

/**
 * The catalog `catalog`, the file `loaded` (`entries`: its entries), has no entry `entry`. `shadowed`: another file holding a
 * catalog of that name has it (`holder`), but `loaded` is the first `catalog`.xosc esmini finds (core/semantics/catalogs.ts
 * `loadedFirst`), and esmini looks entries up in that file alone.
 */
export function unknownCatalogEntryWording(
  catalog: string,
  loaded: string,
  entry: string,
  entries: readonly string[],
  suggestion: string | undefined,
  shadowed?: { holder: string },
): ProblemWording<'unknown-catalog-entry'> {
  const listed = `${entries.slice(0, ENTRIES_NAMED).join(', ')}${entries.length > ENTRIES_NAMED ? ', ...' : ''}`;
  if (shadowed)
    return {
      severity: 'error',
      code: 'unknown-catalog-entry',
      message: `catalog '${catalog}' (${loaded}, the first file of that catalog esmini finds, the only one it reads) has no entry named '${entry}'; ${shadowed.holder} has one, which esmini never reads; ${loaded} has: ${listed}`,
      hint: suggestion ? didYouMean(suggestion) : `move the entry into ${loaded}, or give the other catalog another name`,
    };
  // The file is named: a catalog found through SCENARIO_PATH or the road path may not be the one the author meant.
  return {
    severity: 'error',
    code: 'unknown-catalog-entry',
    message: `catalog '${catalog}' (${loaded}) has no entry named '${entry}'; it has: ${listed}`,
    hint: suggestion
      ? didYouMean(suggestion)
      : `name one of its entries, add an entry '${entry}' to ${loaded}, or point the CatalogLocations at the catalog that has it`,
  };
}

/** The note at the entry that a catalog of the same name, found first, hides from esmini. */
export const SHADOWED_ENTRY_NOTE = 'the entry of that name, in a catalog file esmini does not read';

/** An entryName naming no entry of its catalog: the closest entry. */
export const UNKNOWN_CATALOG_ENTRY = defineDiagnostic({
  code: 'unknown-catalog-entry',
  rule: { description: 'An entryName names an entry of its catalog.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['unknown-catalog-entry'] => isSuggestion(value),
});

import { defineDiagnostic, ProblemWording } from './definition';
import { valueOfWords } from './duplicateName';
import { QC } from './qcRules';

/** Two entries of catalog `catalog` named `name` (`written` as the file writes it); a warning where esmini runs it (it takes the first). */
export function duplicateCatalogEntryWording(
  catalog: string,
  name: string,
  written: string,
  esmini: boolean,
): ProblemWording<'duplicate-catalog-entry'> {
  return {
    severity: esmini ? 'warning' : 'error',
    code: 'duplicate-catalog-entry',
    message: `catalog '${catalog}' has two entries named '${name}'${valueOfWords(name, written)}; a CatalogReference to '${name}' does not name one entry`,
    hint: `rename one of them`,
  };
}

/** Two entries of one catalog with one name. */
export const DUPLICATE_CATALOG_ENTRY = defineDiagnostic({
  code: 'duplicate-catalog-entry',
  rule: {
    description: 'The entries of a catalog have unique names, so that a CatalogReference names exactly one.',
    qcRule: QC.uniqueEntityReferences,
  },
  severity: 'warning',
});

import { defineDiagnostic } from './definition';
import { QC } from './qcRules';

/** Two entries of one catalog with one name. */
export const DUPLICATE_CATALOG_ENTRY = defineDiagnostic({
  code: 'duplicate-catalog-entry',
  rule: {
    description: 'The entries of a catalog have unique names, so that a CatalogReference names exactly one.',
    qcRule: QC.uniqueEntityReferences,
  },
  severity: 'warning',
});

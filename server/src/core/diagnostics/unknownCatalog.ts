import { defineDiagnostic } from './definition';

/** A catalogName naming no catalog of the CatalogLocations. */
export const UNKNOWN_CATALOG = defineDiagnostic({
  code: 'unknown-catalog',
  rule: { description: 'A catalogName names a catalog found in the CatalogLocations.' },
  severity: 'error',
});

import { defineDiagnostic, ProblemWording } from './definition';

/** No catalog of that name in the directories searched (a directory as written; the package root as ''). */
export function unknownCatalogWording(catalog: string, directories: readonly string[]): ProblemWording<'unknown-catalog'> {
  return {
    severity: 'error',
    code: 'unknown-catalog',
    message: `no catalog named '${catalog}' in the catalog directories of this file`,
    hint: `the directories searched: ${directories.map((directory) => directory || '(package root)').join(', ')}`,
  };
}

/** No Catalog is named `catalog`, but esmini takes the file `catalog`.xosc, whose Catalog is named `named`. */
export function catalogFoundByFileNameWording(catalog: string, named: string): ProblemWording<'unknown-catalog'> {
  return {
    severity: 'warning',
    code: 'unknown-catalog',
    message: `no Catalog is named '${catalog}'; esmini takes the file ${catalog}.xosc, whose Catalog is named '${named}', and other simulators do not`,
    hint: `name the Catalog in ${catalog}.xosc '${catalog}'`,
  };
}

/** A catalogName naming no catalog of the CatalogLocations. */
export const UNKNOWN_CATALOG = defineDiagnostic({
  code: 'unknown-catalog',
  rule: { description: 'A catalogName names a catalog found in the CatalogLocations.' },
  severity: 'error',
});

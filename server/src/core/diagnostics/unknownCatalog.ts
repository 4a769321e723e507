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

/**
 * The Catalog `catalog` is in `holder`, a file of another name, and esmini looks a catalog up as the file `catalog`.xosc
 * alone (esmini 3.6 ScenarioReader.cpp LoadCatalog, which never reads the Catalog's name): it reads `esminiReads`, a
 * Catalog of another name, or stops ("Couldn't locate OpenSCENARIO file"). An error with `simulator = esmini`, a warning
 * otherwise: the standard finds a catalog by its name.
 */
export function catalogFileNameWording(
  catalog: string,
  holder: string,
  esminiReads: { file: string; catalog: string } | undefined,
  severity: 'error' | 'warning',
): ProblemWording<'unknown-catalog'> {
  const esmini = esminiReads
    ? `esmini reads ${esminiReads.file} instead, whose Catalog is named '${esminiReads.catalog}'`
    : `esmini stops at it ("Couldn't locate OpenSCENARIO file ${catalog}")`;
  return {
    severity,
    code: 'unknown-catalog',
    message: `the Catalog '${catalog}' is in ${holder}, but esmini looks a catalog up as the file ${catalog}.xosc: ${esmini}`,
    hint: esminiReads
      ? `rename ${holder} to ${catalog}.xosc, and ${esminiReads.file} to the name of its own Catalog`
      : `rename ${holder} to ${catalog}.xosc`,
  };
}

/** A catalogName naming no catalog of the CatalogLocations. */
export const UNKNOWN_CATALOG = defineDiagnostic({
  code: 'unknown-catalog',
  rule: { description: 'A catalogName names a catalog found in the CatalogLocations.' },
  severity: 'error',
});

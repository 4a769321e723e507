import { defineDiagnostic, ProblemWording } from './definition';

/**
 * A CatalogLocations directory of `kind`, written `written`, that a CatalogReference of the file needs, found neither
 * beside the file nor in SCENARIO_PATH; `searched`: the SCENARIO_PATH folders that stood for it and hold no catalog a
 * reference of the file needs (none without a scenario path).
 *
 * An error with a scenario path or without one (SPEC 12, an unresolvable reference): the references that need the
 * directory resolve nowhere, and esmini 3.6 refuses the file either way ("Couldn't locate OpenSCENARIO file
 * VehicleCatalog", exit code 255, run without `--path` and with a `--path` folder that lacks the catalog alike).
 */
const CATALOG_HINT =
  'correct the path, or add the folder that holds the catalogs to SCENARIO_PATH (--scenario-path, the modular2simple.scenarioPath setting)';

export function catalogDirectoryWording(
  kind: string,
  written: string,
  searched: readonly string[] = [],
): ProblemWording<'catalog-directory'> {
  const hint = CATALOG_HINT;
  if (searched.length > 0)
    return {
      severity: 'error',
      code: 'catalog-directory',
      message: `the ${kind} directory '${written}' does not exist beside this file, and the SCENARIO_PATH folders searched for it (${searched.join(', ')}) hold no catalog its references name`,
      hint,
    };
  return {
    severity: 'error',
    code: 'catalog-directory',
    message: `the ${kind} directory '${written}' does not exist beside this file nor in SCENARIO_PATH, so the catalog references that need it resolve nowhere`,
    hint,
  };
}

/**
 * Several CatalogLocations directories that references of the file need (`kinds`), all missing because the folder
 * `written` does not exist beside the file (a `Catalogs/` folder not copied along): one problem, on the first, naming the
 * folder and the kinds; `itself`: every one of them is that folder. `searched`: the SCENARIO_PATH folders that stood for them.
 */
export function catalogFolderWording(
  written: string,
  kinds: readonly string[],
  itself: boolean,
  searched: readonly string[] = [],
): ProblemWording<'catalog-directory'> {
  const listed = kinds.length === 2 ? kinds.join(' and ') : `${kinds.slice(0, -1).join(', ')} and ${kinds.at(-1)}`;
  const where =
    searched.length > 0
      ? `, and the SCENARIO_PATH folders searched for it (${searched.join(', ')}) hold no catalog its references name`
      : ' nor in SCENARIO_PATH';
  const what = itself
    ? `the ${listed} directory '${written}' does not exist beside this file${where}`
    : `the folder '${written}' does not exist beside this file${where}, so neither do the ${listed} directories in it`;
  return {
    severity: 'error',
    code: 'catalog-directory',
    message: `${what}: the catalog references that need them resolve nowhere`,
    hint: CATALOG_HINT,
  };
}

/** The related location of each further directory of a missing folder. */
export const CATALOG_FOLDER_ALSO_NOTE = 'in the same missing folder';

export const CATALOG_DIRECTORY = defineDiagnostic({
  code: 'catalog-directory',
  rule: { description: 'A CatalogLocations directory that a CatalogReference needs exists.' },
  severity: 'error',
});

import { defineDiagnostic, ProblemWording } from './definition';

/**
 * A CatalogLocations directory of `kind`, written `written`, found neither beside the file nor in SCENARIO_PATH;
 * `searched`: the SCENARIO_PATH folders that stood for it and hold no catalog a reference of the file needs.
 */
export function catalogDirectoryWording(
  kind: string,
  written: string,
  searched: readonly string[] = [],
): ProblemWording<'catalog-directory'> {
  // An error: its references resolve nowhere (what unknown-catalog said at each of them before), so esmini refuses the file.
  if (searched.length > 0)
    return {
      severity: 'error',
      code: 'catalog-directory',
      message: `the ${kind} directory '${written}' does not exist beside this file, and the SCENARIO_PATH folders searched for it (${searched.join(', ')}) hold no catalog its references name`,
      hint: 'correct the path, or add the folder that holds the catalogs to SCENARIO_PATH (--scenario-path, the modular2simple.scenarioPath setting)',
    };
  return {
    severity: 'warning',
    code: 'catalog-directory',
    message: `the ${kind} directory '${written}' does not exist (relative to this file, or in SCENARIO_PATH)`,
    hint: 'correct the path, or add the folder that holds the catalogs to SCENARIO_PATH (the modular2simple.scenarioPath setting)',
  };
}

export const CATALOG_DIRECTORY = defineDiagnostic({
  code: 'catalog-directory',
  rule: { description: 'A CatalogLocations directory exists.' },
  severity: 'warning',
});

import { defineDiagnostic, ProblemWording } from './definition';

/** A CatalogLocations directory of `kind`, written `written`, found neither beside the file nor in SCENARIO_PATH. */
export function catalogDirectoryWording(kind: string, written: string): ProblemWording<'catalog-directory'> {
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

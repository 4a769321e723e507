import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRecord, isString, ProblemWording } from './definition';

/**
 * An imported group needs the `kind` catalogs in `needed`, where the main file's location of that kind is
 * `own` (as written): one directory per kind, the main file's kept. Its data's key names the kind, so that
 * each kind is reported once.
 */
export function catalogLocationConflictWording(
  kind: string,
  needed: string,
  own: string | undefined,
): ProblemWording<'catalog-location-conflict'> & { data: ProblemDataByCode['catalog-location-conflict'] } {
  return {
    severity: 'warning',
    code: 'catalog-location-conflict',
    message: `an imported group needs the ${kind} directory ${needed}, but this file's ${kind} is ${own ?? '(none)'}; OpenSCENARIO allows one directory per catalog kind, so the output keeps this one`,
    hint: `put the catalogs the imported group uses into ${own}, or point ${kind} at ${needed}`,
    data: { key: catalogLocationConflictKey(kind) },
  };
}

/** The key of the conflict of one catalog kind. */
export function catalogLocationConflictKey(kind: string): string {
  return `location:${kind}`;
}

export const CATALOG_LOCATION_CONFLICT = defineDiagnostic({
  code: 'catalog-location-conflict',
  rule: { description: "A carried catalog location agrees with the main file's (SPEC 11)." },
  severity: 'warning',
  isData: (value: unknown): value is ProblemDataByCode['catalog-location-conflict'] => isRecord(value) && isString(value.key),
});

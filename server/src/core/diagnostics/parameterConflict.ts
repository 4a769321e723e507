import { defineDiagnostic, ProblemWording } from './definition';

function conflictWording(message: string): ProblemWording<'parameter-conflict'> {
  return { severity: 'warning', code: 'parameter-conflict', message };
}

/**
 * The main file declares `name` with `mainValue`, where the imported group `group` uses the declaration at
 * `sourcePlace` (file, and line where known) with `value`: the output keeps the main file's.
 */
export function mainDeclarationKeptWording(
  name: string,
  mainValue: string,
  group: string,
  sourcePlace: string,
  value: string,
): ProblemWording<'parameter-conflict'> {
  return conflictWording(
    `parameter '${name}' is declared here with value '${mainValue}', but the imported group '${group}' uses the declaration of ${sourcePlace} with value '${value}'; the output keeps this one`,
  );
}

/** Imported groups use two declarations of `name`, the first carried (`keptValue`) kept and this one (`value`) dropped. */
export function firstCarriedKeptWording(name: string, keptValue: string, value: string): ProblemWording<'parameter-conflict'> {
  return conflictWording(
    `imported groups use two declarations of parameter '${name}' with different values; the output keeps the first one carried (value '${keptValue}'), not this one (value '${value}')`,
  );
}

/** The imported group `group` uses `name`, declared with `value` in its source, where this file declares it around the group with `hereValue`. */
export function declaredAroundGroupWording(
  group: string,
  name: string,
  value: string,
  hereValue: string,
): ProblemWording<'parameter-conflict'> {
  return conflictWording(
    `the imported group '${group}' uses parameter '${name}' declared with value '${value}' in its source, but in this file it takes the value '${hereValue}' of a declaration around the group`,
  );
}

/** The related note on the source's declaration the output drops. */
export function sourceDeclarationNote(value: string): string {
  return `the source's declaration (value '${value}')`;
}

/** The related note on the declaration the output keeps. */
export function keptDeclarationNote(value: string): string {
  return `the declaration the output keeps (value '${value}')`;
}

export const PARAMETER_CONFLICT = defineDiagnostic({
  code: 'parameter-conflict',
  rule: { description: "A carried declaration agrees with the main file's declaration of the same name (SPEC 11)." },
  severity: 'warning',
});

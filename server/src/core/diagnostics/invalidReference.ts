import { defineDiagnostic, ProblemWording } from './definition';

/** A scenarioFileName that SPEC 2 does not allow: `message` is the resolver's reason. */
export function invalidReferenceWording(message: string, hint?: string): ProblemWording<'invalid-reference'> {
  return { severity: 'error', code: 'invalid-reference', message, hint };
}

/** An input of pack that is neither a scenario nor a package (a road file, most often: --self-contained is how to store it). */
export function notPackableWording(name: string): ProblemWording<'invalid-reference'> {
  return invalidReferenceWording(
    `'${name}' is neither a .xosc scenario nor a .mosc package`,
    'pack only .xosc and .mosc files; with --self-contained, pack stores the road files, catalogs and other files the scenarios name inside the package',
  );
}

/** Two inputs of pack of one name. */
export function duplicateInputWording(name: string, other: string): ProblemWording<'invalid-reference'> {
  return invalidReferenceWording(
    `two inputs are named '${name}' (the other is ${other}); names must be unique in a package`,
    'rename one of them',
  );
}

/** The inputs of pack name `mains` main.xosc files, where a package needs one. */
export function mainCountWording(mains: number): ProblemWording<'invalid-reference'> {
  return invalidReferenceWording(
    mains === 0
      ? 'a package needs exactly one input named main.xosc; none was given'
      : `a package needs exactly one main.xosc; ${mains} were given`,
    'name the modular main file main.xosc',
  );
}

/** Two different files a self-contained package would store under one entry name. */
export function entryClashWording(name: string, existing: string, origin: string): ProblemWording<'invalid-reference'> {
  return invalidReferenceWording(`two different files would be stored as '${name}': ${existing} and ${origin}`);
}

/** A reference of a file being packed that names a file outside the package. */
export function outsidePackageWording(fileName: string): ProblemWording<'invalid-reference'> {
  return invalidReferenceWording(`'${fileName}' points outside the package`);
}

export const INVALID_REFERENCE = defineDiagnostic({
  code: 'invalid-reference',
  rule: { description: 'A ScenarioReference is written as SPEC 2 says.' },
  severity: 'error',
});

import { changeToSuggestion, defineDiagnostic, isSuggestion, ProblemWording } from './definition';

/** A scenarioFileName that names no file where it was looked up (`searched`); the hint names the closest file there, else `hint`. */
export function missingFileWording(
  fileName: string,
  searched: readonly string[],
  suggestion: string | undefined,
  hint: string | undefined,
): ProblemWording<'missing-file'> {
  return {
    severity: 'error',
    code: 'missing-file',
    message: `cannot find '${fileName}'; searched ${searched.join(', ')}`,
    hint: suggestion ? `did you mean '${suggestion}'?` : hint,
  };
}

/** Pack: a file found only through SCENARIO_PATH, which the package does not store unless asked to. */
export function leftOutOfPackageWording(fileName: string): ProblemWording<'missing-file'> {
  return {
    severity: 'information',
    code: 'missing-file',
    message: `'${fileName}' was found through SCENARIO_PATH and is left out of the package`,
    hint: 'pass --include-scenario-path to store it too',
  };
}

/** A misspelt `scenarioFileName`: name the closest file that exists where it was looked up. */
export const MISSING_FILE = defineDiagnostic({
  code: 'missing-file',
  rule: { description: 'A scenarioFileName resolves to a file (SPEC 3).' },
  severity: 'error',
  isData: isSuggestion,
  fixes: changeToSuggestion,
});

import { defineDiagnostic, ProblemWording } from './definition';

/** The related location's note: the declaration references use. */
export const DUPLICATE_PARAMETER_FIRST_NOTE = 'the first declaration';

/** Parameter `name` declared a second time in `<scope>`. */
export function duplicateParameterWording(name: string, scope: string): ProblemWording<'duplicate-parameter'> {
  return {
    severity: 'warning',
    code: 'duplicate-parameter',
    message: `parameter '${name}' is declared twice in <${scope}>; references use the first declaration`,
  };
}

/** A parameter declared twice in one scope. */
export const DUPLICATE_PARAMETER = defineDiagnostic({
  code: 'duplicate-parameter',
  rule: { description: 'A parameter is declared once in its scope.' },
  severity: 'warning',
});

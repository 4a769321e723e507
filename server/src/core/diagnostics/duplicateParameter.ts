import { esminiRule } from './simulatorValue';
import { defineDiagnostic, ProblemWording } from './definition';

/** The related location's note: the declaration references use. */
export const DUPLICATE_PARAMETER_FIRST_NOTE = 'the first declaration';

/**
 * Parameter `name` declared a second time in `<scope>`; with `esmini` (the selected simulator), the values of the first
 * and the last declaration, as esmini takes the last.
 */
export function duplicateParameterWording(
  name: string,
  scope: string,
  esmini?: { first: string; last: string },
): ProblemWording<'duplicate-parameter'> {
  const reading = esmini ? ` (value '${esmini.first}'); ${esminiRule('redeclaration')}, here value '${esmini.last}'` : '';
  return {
    severity: 'warning',
    code: 'duplicate-parameter',
    message: `parameter '${name}' is declared twice in <${scope}>; references use the first declaration${reading}`,
  };
}

/** A parameter declared twice in one scope. */
export const DUPLICATE_PARAMETER = defineDiagnostic({
  code: 'duplicate-parameter',
  rule: { description: 'A parameter is declared once in its scope.' },
  severity: 'warning',
});

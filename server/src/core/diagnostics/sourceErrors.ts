import { Problem, ProblemCause } from '../problems';
import { defineDiagnostic, ProblemWording } from './definition';

/** A referenced file (`fileName` as the reference writes it) with errors of its own: how many, and the first. */
export function sourceErrorsWording(fileName: string, errors: readonly Problem[]): ProblemWording<'source-errors'> {
  return {
    severity: 'error',
    code: 'source-errors',
    message: `'${fileName}' has ${errors.length} error${errors.length === 1 ? '' : 's'}: ${errors[0].message}`,
  };
}

/** What stands behind the errors of a referenced file: its first error, followed through the files it references in turn. */
export function sourceErrorsCause(errors: readonly Problem[]): ProblemCause {
  const first = errors[0];
  return first.cause ?? { code: first.code, among: errors.length };
}

/** Whether a source-errors problem stands only for a cycle (which the editor already shows as one diagnostic). */
export function standsForCycleOnly(problem: Problem): boolean {
  return problem.code === 'source-errors' && problem.cause?.code === 'cycle' && problem.cause.among === 1;
}

/** A referenced file with errors: flattening stops at it; its first error is quoted, the others related. */
export const SOURCE_ERRORS = defineDiagnostic({
  code: 'source-errors',
  rule: { description: 'A referenced file has no errors of its own.' },
  severity: 'error',
});

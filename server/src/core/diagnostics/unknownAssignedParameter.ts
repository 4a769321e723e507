import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, didYouMean, isSuggestion, ProblemWording } from './definition';

/** A ParameterAssignment naming `name`, which catalog entry `entry` does not declare among `declared`. */
export function unknownAssignedParameterWording(
  entry: string,
  name: string,
  declared: readonly string[],
  suggestion: string | undefined,
): ProblemWording<'unknown-assigned-parameter'> {
  return {
    severity: 'error',
    code: 'unknown-assigned-parameter',
    message:
      `catalog entry '${entry}' declares no parameter '${name}'` +
      (declared.length ? `; it declares: ${declared.join(', ')}` : '; it declares none'),
    hint: didYouMean(suggestion),
  };
}

/** A ParameterAssignment naming no parameter of the catalog entry: the closest one. */
export const UNKNOWN_ASSIGNED_PARAMETER = defineDiagnostic({
  code: 'unknown-assigned-parameter',
  rule: { description: 'A ParameterAssignment names a parameter the catalog entry declares.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['unknown-assigned-parameter'] => isSuggestion(value),
});

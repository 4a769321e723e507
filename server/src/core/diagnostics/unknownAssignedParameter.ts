import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isSuggestion } from './definition';

/** A ParameterAssignment naming no parameter of the catalog entry: the closest one. */
export const UNKNOWN_ASSIGNED_PARAMETER = defineDiagnostic({
  code: 'unknown-assigned-parameter',
  rule: { description: 'A ParameterAssignment names a parameter the catalog entry declares.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['unknown-assigned-parameter'] => isSuggestion(value),
});

import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRecord, isString } from './definition';

/** A `$name` naming no declared parameter. Its quick fix (declare it, with the value of a source's declaration) needs the file's analysis: features/fixes/undeclaredParameter.ts. */
export const UNDECLARED_PARAMETER = defineDiagnostic({
  code: 'undeclared-parameter',
  rule: { description: 'A $name names a declared parameter.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['undeclared-parameter'] => isRecord(value) && isString(value.parameter),
});

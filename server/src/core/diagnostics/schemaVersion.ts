import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isSuggestion } from './definition';

/** A FileHeader naming a version the project has no schema of, or a form that version lacks: the file is checked against another. */
export const SCHEMA_VERSION = defineDiagnostic({
  code: 'schema-version',
  rule: { description: 'The FileHeader names an OpenSCENARIO version the project knows.' },
  severity: 'information',
  isData: (value): value is ProblemDataByCode['schema-version'] => isSuggestion(value),
});

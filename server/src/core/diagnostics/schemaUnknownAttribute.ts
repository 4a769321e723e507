import { ProblemDataByCode } from '../problems';
import { changeToSuggestion, defineDiagnostic, isSuggestion } from './definition';
import { QC } from './qcRules';

/** An attribute the schema does not know on its element: the closest name it does. */
export const SCHEMA_UNKNOWN_ATTRIBUTE = defineDiagnostic({
  code: 'schema-unknown-attribute',
  rule: { description: 'Every attribute is one the ASAM schema allows on its element.', qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-unknown-attribute'] => isSuggestion(value),
  fixes: changeToSuggestion,
});

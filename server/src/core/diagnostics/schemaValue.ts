import { ProblemDataByCode } from '../problems';
import { changeToSuggestion, defineDiagnostic, isSuggestion } from './definition';
import { QC } from './qcRules';

/** A value that does not fit its attribute's type: the closest value it allows, where one is near. */
export const SCHEMA_VALUE = defineDiagnostic({
  code: 'schema-value',
  rule: { description: "An attribute's value fits its ASAM schema type.", qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-value'] => isSuggestion(value),
  fixes: changeToSuggestion,
});

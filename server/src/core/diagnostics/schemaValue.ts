import { ProblemDataByCode } from '../problems';
import { SchemaFactsByCode } from '../schema/facts';
import { changeToSuggestion, defineDiagnostic, didYouMean, isSuggestion, Words } from './definition';
import { QC } from './qcRules';
import { otherVersionsWords } from './schemaVersion';

export function schemaValueWording({
  element,
  attribute,
  value,
  type,
  expected,
  validIn,
  suggestion,
}: SchemaFactsByCode['schema-value']): Words {
  return {
    message: `'${value}' is not a valid value of ${element}.${attribute} (${type}): expected ${expected}`,
    hint: validIn ? otherVersionsWords(`'${value}'`, validIn, 'is a value of') : didYouMean(suggestion),
  };
}

/** A value that does not fit its attribute's type: the closest value it allows, where one is near. */
export const SCHEMA_VALUE = defineDiagnostic({
  code: 'schema-value',
  rule: { description: "An attribute's value fits its ASAM schema type.", qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-value'] => isSuggestion(value),
  fixes: changeToSuggestion,
});

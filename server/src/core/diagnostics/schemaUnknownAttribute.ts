import { ProblemDataByCode } from '../problems';
import { SchemaFactsByCode } from '../schema/facts';
import { changeToSuggestion, defineDiagnostic, didYouMean, isSuggestion, Words } from './definition';
import { QC } from './qcRules';
import { otherVersionsWords } from './schemaVersion';

export function schemaUnknownAttributeWording({
  element,
  attribute,
  version,
  introducedIn,
  suggestion,
  candidates,
}: SchemaFactsByCode['schema-unknown-attribute']): Words {
  const orMeant = suggestion ? `; or did you mean '${suggestion}'?` : '';
  return {
    message: `<${element}> has no attribute '${attribute}' in OpenSCENARIO ${version}`,
    hint: introducedIn
      ? otherVersionsWords(`'${attribute}'`, introducedIn) + orMeant
      : (didYouMean(suggestion) ?? (candidates.length > 0 ? `its attributes: ${candidates.join(', ')}` : undefined)),
  };
}

/** An attribute the schema does not know on its element: the closest name it does. */
export const SCHEMA_UNKNOWN_ATTRIBUTE = defineDiagnostic({
  code: 'schema-unknown-attribute',
  rule: { description: 'Every attribute is one the ASAM schema allows on its element.', qcRule: QC.validSchema },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['schema-unknown-attribute'] => isSuggestion(value),
  fixes: changeToSuggestion,
});

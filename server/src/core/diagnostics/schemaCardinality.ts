import { defineDiagnostic } from './definition';
import { QC } from './qcRules';

export const SCHEMA_CARDINALITY = defineDiagnostic({
  code: 'schema-cardinality',
  rule: { description: 'Child elements occur as often as the ASAM schema allows.', qcRule: QC.validSchema },
  severity: 'error',
});

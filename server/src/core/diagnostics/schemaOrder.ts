import { defineDiagnostic } from './definition';
import { QC } from './qcRules';

export const SCHEMA_ORDER = defineDiagnostic({
  code: 'schema-order',
  rule: { description: 'Child elements stand in the order the ASAM schema gives.', qcRule: QC.validSchema },
  severity: 'error',
});

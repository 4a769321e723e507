import { defineDiagnostic } from './definition';
import { QC } from './qcRules';

/** An operator or function the standard lacks, which esmini accepts: a warning (SPEC 12). */
export const NONSTANDARD_EXPRESSION = defineDiagnostic({
  code: 'nonstandard-expression',
  rule: { description: 'An expression uses only what the standard defines.', qcRule: QC.allowedOperators },
  severity: 'warning',
});

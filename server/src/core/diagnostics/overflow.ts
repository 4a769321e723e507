import { defineDiagnostic } from './definition';

/** A number beyond its type's range (worded by the expression evaluator). */
export const OVERFLOW = defineDiagnostic({
  code: 'overflow',
  rule: { description: "A number stays within its type's range (IEEE double, int, unsignedInt, unsignedShort)." },
  severity: 'error',
});

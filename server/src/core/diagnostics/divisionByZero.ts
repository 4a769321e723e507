import { defineDiagnostic } from './definition';

/** An expression dividing by zero (worded by the expression evaluator). */
export const DIVISION_BY_ZERO = defineDiagnostic({
  code: 'division-by-zero',
  rule: { description: 'An expression does not divide by zero.' },
  severity: 'error',
});

import { defineDiagnostic } from './definition';
import { DivisionByZeroFact } from './expressionFacts';

export function divisionByZeroMessage(fact: DivisionByZeroFact): string {
  return `division by zero: the right side of '${fact.operator}' is 0`;
}

/** An expression dividing by zero (found by the expression evaluator). */
export const DIVISION_BY_ZERO = defineDiagnostic({
  code: 'division-by-zero',
  rule: { description: 'An expression does not divide by zero.' },
  severity: 'error',
});

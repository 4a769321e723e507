import { defineDiagnostic } from './definition';
import { OverflowFact } from './expressionFacts';

export function overflowMessage(fact: OverflowFact): string {
  return `${fact.fact === 'number' ? 'this number' : 'the result'} is beyond the range of a double (at most 1.7976931348623157E308)`;
}

/** A number beyond its type's range (found by the expression evaluator). */
export const OVERFLOW = defineDiagnostic({
  code: 'overflow',
  rule: { description: "A number stays within its type's range (IEEE double, int, unsignedInt, unsignedShort)." },
  severity: 'error',
});

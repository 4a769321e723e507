import { defineDiagnostic } from './definition';
import { NonstandardFact } from './expressionFacts';
import { QC } from './qcRules';

/**
 * Why a constant is not standard here: `pi` came with OpenSCENARIO 1.4, after every version the project reads (1.0-1.3)
 * (ASAM OpenSCENARIO XML v1.4.0, 5 Backward compatibility: "The math constant 'pi' is introduced"; asked for by the Euro NCAP
 * scenarios' authors, who use it in 1.3 files: openscenario-xml issue 672).
 */
const CONSTANT_MESSAGES: Record<NonstandardFact['constant'], string> = {
  pi: "'pi' is a constant from OpenSCENARIO 1.4 on, not of 1.3 and the versions before it (esmini knows it); a simulator of an earlier version rejects it",
  e: "'e' is an esmini constant, not part of the OpenSCENARIO standard; other simulators reject it",
};

export function nonstandardExpressionMessage(fact: NonstandardFact): string {
  return CONSTANT_MESSAGES[fact.constant];
}

/** An operator or function the standard lacks, which esmini accepts: a warning (SPEC 12). */
export const NONSTANDARD_EXPRESSION = defineDiagnostic({
  code: 'nonstandard-expression',
  rule: { description: 'An expression uses only what the standard defines.', qcRule: QC.allowedOperators },
  severity: 'warning',
});

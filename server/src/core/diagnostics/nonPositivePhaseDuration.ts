import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A Phase of duration `seconds`: zero is a warning (within the standard's range), below zero an error. */
export function nonPositivePhaseDurationWording(seconds: number): ProblemWording<'non-positive-phase-duration'> {
  const zero = seconds === 0;
  return {
    severity: zero ? 'warning' : 'error',
    code: 'non-positive-phase-duration',
    message: zero
      ? "a Phase of duration 0 is within the standard's range [0..inf[, but ASAM's Quality Checker requires a positive duration"
      : `the duration of a Phase must be positive; it is ${seconds} s`,
  };
}

export const NON_POSITIVE_PHASE_DURATION = defineDiagnostic({
  code: 'non-positive-phase-duration',
  rule: { description: "A Phase duration is positive (zero: a warning, within the standard's range).", qcRule: QC.phaseDuration },
  severity: 'error',
});

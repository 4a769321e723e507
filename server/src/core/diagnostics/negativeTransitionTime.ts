import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A LightStateAction's transitionTime of `seconds`, below zero. */
export function negativeTransitionTimeWording(seconds: number): ProblemWording<'negative-transition-time'> {
  return {
    severity: 'error',
    code: 'negative-transition-time',
    message: `the transition time of a LightStateAction must not be negative; it is ${seconds} s`,
  };
}

export const NEGATIVE_TRANSITION_TIME = defineDiagnostic({
  code: 'negative-transition-time',
  rule: { description: 'A LightStateAction transitionTime is not negative.', qcRule: QC.transitionTime },
  severity: 'error',
});

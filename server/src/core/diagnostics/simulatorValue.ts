import { defineDiagnostic } from './definition';

/** A value the selected simulator computes otherwise than the standard (SPEC 12). */
export const SIMULATOR_VALUE = defineDiagnostic({
  code: 'simulator-value',
  rule: { description: 'A value is the same in the standard and in the selected simulator.' },
  severity: 'warning',
});

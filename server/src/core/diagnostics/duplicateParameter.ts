import { defineDiagnostic } from './definition';

/** A parameter declared twice in one scope. */
export const DUPLICATE_PARAMETER = defineDiagnostic({
  code: 'duplicate-parameter',
  rule: { description: 'A parameter is declared once in its scope.' },
  severity: 'warning',
});

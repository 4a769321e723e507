import { defineDiagnostic } from './definition';

/** A declared parameter nothing uses: shown faded. */
export const UNUSED_PARAMETER = defineDiagnostic({
  code: 'unused-parameter',
  rule: { description: 'A declared parameter is used.' },
  severity: 'hint',
  unnecessary: true,
});

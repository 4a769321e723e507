import { defineDiagnostic } from './definition';

/** A value that does not convert to the type that uses it (worded where the conversion fails). */
export const TYPE_MISMATCH = defineDiagnostic({
  code: 'type-mismatch',
  rule: { description: 'A value converts to the type that uses it.' },
  severity: 'error',
});

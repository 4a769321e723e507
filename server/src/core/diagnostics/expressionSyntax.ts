import { defineDiagnostic } from './definition';

/** A `${...}` that does not parse (the expression parser words it, core/semantics/expressionParser.ts). */
export const EXPRESSION_SYNTAX = defineDiagnostic({
  code: 'expression-syntax',
  rule: { description: "A ${...} expression follows the standard's grammar." },
  severity: 'error',
});

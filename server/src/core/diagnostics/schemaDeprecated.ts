import { ProblemDataByCode } from '../problems';
import { changeToSuggestion, defineDiagnostic, isSuggestion } from './definition';

/** A deprecated element, attribute or value: a warning, struck through, whose fix writes the standard's replacement. */
export const SCHEMA_DEPRECATED = defineDiagnostic({
  code: 'schema-deprecated',
  rule: {
    description: 'No deprecated element, attribute or value is used (a warning, as in both official checkers); the replacement is named.',
  },
  severity: 'warning',
  deprecated: true,
  isData: (value): value is ProblemDataByCode['schema-deprecated'] => isSuggestion(value),
  fixes: changeToSuggestion,
});

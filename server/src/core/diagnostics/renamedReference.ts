import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isSuggestion } from './definition';

/** A reference to a group that flattening renames: the new name. */
export const RENAMED_REFERENCE = defineDiagnostic({
  code: 'renamed-reference',
  rule: { description: 'A reference to a group that flattening renames is updated.' },
  severity: 'error',
  isData: (value): value is ProblemDataByCode['renamed-reference'] => isSuggestion(value),
});

import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isSuggestion } from './definition';
import { QC } from './qcRules';

/** A storyboardElementRef naming no storyboard element: the closest one. */
export const UNKNOWN_STORYBOARD_ELEMENT = defineDiagnostic({
  code: 'unknown-storyboard-element',
  rule: { description: 'A storyboardElementRef names a storyboard element.', qcRule: QC.storyboardReference },
  severity: 'warning',
  isData: (value): value is ProblemDataByCode['unknown-storyboard-element'] => isSuggestion(value),
});

import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, didYouMean, isSuggestion, ProblemWording } from './definition';
import { QC } from './qcRules';

/**
 * A storyboardElementRef naming no element (of type `elementType` where it says one): a warning in a file of
 * its own (a simple scenario may name an element of the main it is composed into), an error in a flattened output.
 */
export function unknownStoryboardElementWording(
  written: string,
  elementType: string | undefined,
  suggestion: string | undefined,
  flattened: boolean,
): ProblemWording<'unknown-storyboard-element'> {
  return {
    severity: flattened ? 'error' : 'warning',
    code: 'unknown-storyboard-element',
    message: `no ${elementType ?? 'storyboard element'} named '${written}'`,
    hint: didYouMean(suggestion),
  };
}

/** A storyboardElementRef naming no storyboard element: the closest one. */
export const UNKNOWN_STORYBOARD_ELEMENT = defineDiagnostic({
  code: 'unknown-storyboard-element',
  rule: { description: 'A storyboardElementRef names a storyboard element.', qcRule: QC.storyboardReference },
  severity: 'warning',
  isData: (value): value is ProblemDataByCode['unknown-storyboard-element'] => isSuggestion(value),
});

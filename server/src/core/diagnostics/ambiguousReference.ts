import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** `count` elements of the flattened scenario (of type `elementType` where the reference says one) are named `written`. */
export function ambiguousReferenceWording(
  count: number,
  written: string,
  elementType: string | undefined,
): ProblemWording<'ambiguous-reference'> {
  return {
    severity: 'warning',
    code: 'ambiguous-reference',
    message: `${count} elements of the flattened scenario are named '${written}'${elementType ? ` (${elementType})` : ''}; a simulator takes one of them`,
    hint: 'give the elements unique names, or qualify the reference with its ancestors (Story::Act::...)',
  };
}

/** A reference that resolves to more than one element. */
export const AMBIGUOUS_REFERENCE = defineDiagnostic({
  code: 'ambiguous-reference',
  rule: { description: 'A reference resolves to exactly one element.', qcRule: QC.uniqueEntityReferences },
  severity: 'warning',
});
